/* fit.c - fits the weights of AUTO's confidence (meshfix.h,
   meshfix__confidence_weights) on rows the evaluation programs write

   Each row is a patch after AUTO's repair (tests/eval/calibration.h):
       case right wrong f0 f1 ...
   The decision does not depend on these weights, so the rows are fixed and
   one fit suffices: a logistic regression of "a triangle of this patch faces
   the right way" on the features, each patch weighing its triangles, each
   case (one call) at most --case-cap triangles in all so that one large
   model does not speak for the corpus, with a small ridge. Newton's method
   on the weights.

   Printed: the weights as the header's table, and on the same rows the
   reliability of the margin (the weighing's bound, the confidence before
   this fit) and of the fitted probability. Fit on the tune halves only
   (tests/corpus/split.sh); the held-out halves are scored by the
   evaluation programs with the header built from the table.

   Build:  cc -std=c99 -O2 -I. tests/eval/fit.c -lm
   Usage:  fit [--case-cap N] [--ridge R] [--validate] [--table meshfix.h] ROWS...
           --validate: fit on half of the cases, print the reliability on
           the other half (to choose features without the held-out data)
           --table: write the weights into that file between its
           "fitted: begin" and "fitted: end" lines
   Exit:   0; 1 for bad usage or unreadable rows. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAXF 64
static int F; /* features per row: the first row's */

typedef struct row {
    unsigned long id; /* the case, unique over files */
    double right, wrong, f[MAXF];
} row;

typedef struct rows {
    row *r;
    size_t count, capacity;
} rows;

static int read_rows(const char *path, unsigned long file, rows *out)
{
    FILE *in = fopen(path, "r");
    row x;
    unsigned long id;
    if (in == NULL)
        return 0;
    char line[4096];
    while (fgets(line, sizeof(line), in) != NULL) {
        char *p = line, *end;
        int k = 0;
        id = strtoul(p, &end, 10);
        x.right = strtod(end, &p);
        x.wrong = strtod(p, &end);
        if (end == p)
            break;
        for (p = end; k < MAXF; ++k, p = end) {
            x.f[k] = strtod(p, &end);
            if (end == p)
                break;
        }
        if (F == 0)
            F = k;
        if (k != F) {
            fprintf(stderr, "fit: %s: a row of %d features, not %d\n", path, k, F);
            fclose(in);
            return 0;
        }
        x.id = id * 64 + file;
        if (out->count == out->capacity) {
            size_t capacity = out->capacity ? 2 * out->capacity : 4096;
            row *grown = (row *)realloc(out->r, capacity * sizeof(row));
            if (grown == NULL)
                break;
            out->r = grown, out->capacity = capacity;
        }
        out->r[out->count++] = x;
    }
    fclose(in);
    return 1;
}

/* Each row's weight: its triangles, scaled so that no case weighs more
   than cap triangles. Rows of a case are contiguous in a file. */
static void case_scales(const rows *d, double cap, double *scale)
{
    size_t i = 0;
    while (i < d->count) {
        size_t j = i;
        double total = 0;
        while (j < d->count && d->r[j].id == d->r[i].id)
            total += d->r[j].right + d->r[j].wrong, ++j;
        for (; i < j; ++i)
            scale[i] = total > cap ? cap / total : 1.0;
    }
}

static double logistic(const double *w, const double *f)
{
    double z = 0;
    int k;
    for (k = 0; k < F; ++k)
        z += w[k] * f[k];
    return 1.0 / (1.0 + exp(-z));
}

/* Solves a x = b (a symmetric positive definite, F x F) in place. */
static int solve(double a[MAXF][MAXF], double b[MAXF])
{
    int i, j, k;
    for (i = 0; i < F; ++i) {
        int pivot = i;
        for (k = i + 1; k < F; ++k)
            if (fabs(a[k][i]) > fabs(a[pivot][i]))
                pivot = k;
        if (fabs(a[pivot][i]) < 1e-300)
            return 0;
        for (k = 0; k < F; ++k) {
            double t = a[i][k];
            a[i][k] = a[pivot][k], a[pivot][k] = t;
        }
        {
            double t = b[i];
            b[i] = b[pivot], b[pivot] = t;
        }
        for (j = i + 1; j < F; ++j) {
            double factor = a[j][i] / a[i][i];
            for (k = i; k < F; ++k)
                a[j][k] -= factor * a[i][k];
            b[j] -= factor * b[i];
        }
    }
    for (i = F - 1; i >= 0; --i) {
        for (k = i + 1; k < F; ++k)
            b[i] -= a[i][k] * b[k];
        b[i] /= a[i][i];
    }
    return 1;
}

/* Newton's method on the weighted log-loss plus ridge * |w|^2 (the bias too:
   a feature never seen stays at 0). */
static void fit(const rows *d, const double *scale, double ridge, double *w)
{
    int iteration, k, l;
    memset(w, 0, MAXF * sizeof(double));
    for (iteration = 0; iteration < 50; ++iteration) {
        double h[MAXF][MAXF], g[MAXF], step = 0;
        size_t i;
        memset(h, 0, sizeof(h));
        for (k = 0; k < F; ++k)
            g[k] = -2 * ridge * w[k], h[k][k] = 2 * ridge;
        for (i = 0; i < d->count; ++i) {
            const row *x = &d->r[i];
            double p = logistic(w, x->f), n = (x->right + x->wrong) * scale[i];
            double y = x->right * scale[i], v = n * p * (1 - p);
            for (k = 0; k < F; ++k) {
                g[k] += (y - n * p) * x->f[k];
                for (l = 0; l < F; ++l)
                    h[k][l] += v * x->f[k] * x->f[l];
            }
        }
        if (!solve(h, g))
            break;
        for (k = 0; k < F; ++k)
            w[k] += g[k], step += fabs(g[k]);
        if (step < 1e-9)
            break;
    }
}

#define BANDS 6
static const double band_low[BANDS] = {0.0, 0.5, 0.9, 0.99, 0.999, 1.0};
static const char *const band_name[BANDS] = {"< 0.5", "0.5-0.9", "0.9-0.99", "0.99-0.999", ">= 0.999", "1"};

/* The reliability of a confidence (column -1: the fitted probability) over
   the rows: triangles and the share wrong by band, and how many of the
   wrong triangles lie below 0.5. */
static void reliability(const char *title, const rows *d, const double *w, int column, long file)
{
    static const double bars[4] = {0.5, 0.9, 0.95, 0.99};
    double bar_wrong[4] = {0}, bar_right[4] = {0}, all_right = 0;
    double tri[BANDS] = {0}, wrong[BANDS] = {0}, patches[BANDS] = {0}, all_wrong = 0, doubtful_wrong = 0;
    size_t i;
    int b;
    for (i = 0; i < d->count; ++i) {
        const row *x = &d->r[i];
        double c;
        if (file >= 0 && (long)(x->id % 64) != file)
            continue;
        c = column < 0 ? (double)(float)logistic(w, x->f) : (double)(float)x->f[column];
        for (b = BANDS - 1; b > 0 && c < band_low[b]; --b)
            ;
        patches[b] += 1, tri[b] += x->right + x->wrong, wrong[b] += x->wrong;
        all_wrong += x->wrong;
        all_right += x->right;
        doubtful_wrong += c < 0.5 ? x->wrong : 0;
        for (b = 0; b < 4; ++b)
            if (c < bars[b])
                bar_wrong[b] += x->wrong, bar_right[b] += x->right;
    }
    printf("%s\n  confidence   patches    triangles   wrong\n", title);
    for (b = 0; b < BANDS; ++b)
        printf("  %-10s %9.0f %12.0f  %6.2f%%\n", band_name[b], patches[b], tri[b],
               tri[b] > 0 ? 100.0 * wrong[b] / tri[b] : 0.0);
    printf("  wrong triangles in doubtful patches (< 0.5): %.1f%% of %.0f\n",
           all_wrong > 0 ? 100.0 * doubtful_wrong / all_wrong : 100.0, all_wrong);
    printf("  doubtful below:");
    for (b = 0; b < 4; ++b)
        printf("  %.2f: %.1f%% of wrong, %.2f%% of right", bars[b], all_wrong > 0 ? 100 * bar_wrong[b] / all_wrong : 100.0,
               all_right > 0 ? 100 * bar_right[b] / all_right : 0.0);
    printf("\n");
}

/* Replaces the lines between "fitted: begin" and "fitted: end" of path. */
static int write_table(const char *path, const double *w)
{
    FILE *in = fopen(path, "rb"), *out;
    char *text, *begin, *end, temp[4096];
    long size;
    int k, ok;
    if (in == NULL || fseek(in, 0, SEEK_END) != 0 || (size = ftell(in)) < 0 || fseek(in, 0, SEEK_SET) != 0)
        return in != NULL ? (fclose(in), 0) : 0;
    text = (char *)malloc((size_t)size + 1);
    ok = text != NULL && fread(text, 1, (size_t)size, in) == (size_t)size;
    fclose(in);
    if (!ok)
        return free(text), 0;
    text[size] = 0;
    begin = strstr(text, "/* fitted: begin */");
    end = begin != NULL ? strstr(begin, "    /* fitted: end */") : NULL;
    if (end == NULL)
        return free(text), 0;
    begin = strchr(begin, '\n') + 1;
    snprintf(temp, sizeof(temp), "%s.fit", path);
    out = fopen(temp, "wb");
    if (out == NULL)
        return free(text), 0;
    fwrite(text, 1, (size_t)(begin - text), out);
    for (k = 0; k < F; ++k)
        fprintf(out, "%s%.4f%s", k % 8 == 0 ? "    " : "", w[k], k == F - 1 ? "\n" : k % 8 == 7 ? ",\n" : ", ");
    fputs(end, out);
    ok = fclose(out) == 0 && rename(temp, path) == 0;
    free(text);
    return ok;
}

/* --validate: the cases in two folds by a hash of their id over 16 (the
   cases of one file are consecutive: they go together); fit on one,
   score the other. */
static int fold_of(unsigned long id)
{
    unsigned long long h = (unsigned long long)(id % 64) * 0x9E3779B97F4A7C15ull ^ (id / 64 / 16);
    h *= 0xBF58476D1CE4E5B9ull;
    return (int)((h >> 31) & 1u);
}

static void take_fold(const rows *d, int fold, rows *out)
{
    size_t i;
    out->count = 0;
    for (i = 0; i < d->count; ++i)
        if (fold_of(d->r[i].id) == fold)
            out->r[out->count++] = d->r[i];
}

int main(int argc, char **argv)
{
    rows d = {NULL, 0, 0};
    double cap = 20000, ridge = 1.0, w[MAXF], *scale;
    const char *table = NULL, *paths[64];
    int validate = 0;
    unsigned long files = 0;
    int i, k;
    for (i = 1; i < argc; ++i) {
        if (strcmp(argv[i], "--case-cap") == 0 && i + 1 < argc)
            cap = atof(argv[++i]);
        else if (strcmp(argv[i], "--ridge") == 0 && i + 1 < argc)
            ridge = atof(argv[++i]);
        else if (strcmp(argv[i], "--table") == 0 && i + 1 < argc)
            table = argv[++i];
        else if (strcmp(argv[i], "--validate") == 0)
            validate = 1;
        else if (files == 64 || (paths[files] = argv[i], !read_rows(argv[i], files++, &d))) {
            fprintf(stderr, "fit: cannot read %s\n", argv[i]);
            return 1;
        }
    }
    if (d.count == 0) {
        fprintf(stderr, "usage: fit [--case-cap N] [--ridge R] [--table meshfix.h] ROWS...\n");
        return 1;
    }
    if (validate) { /* the fit's weights from one fold, the reliability on the other: the whole picture */
        rows a = {NULL, 0, d.count}, b = {NULL, 0, d.count};
        a.r = (row *)malloc(d.count * sizeof(row));
        b.r = (row *)malloc(d.count * sizeof(row));
        scale = (double *)malloc(d.count * sizeof(double));
        if (a.r == NULL || b.r == NULL || scale == NULL)
            return 1;
        take_fold(&d, 0, &a);
        take_fold(&d, 1, &b);
        case_scales(&a, cap, scale);
        fit(&a, scale, ridge, w);
        reliability("fold 1, the weights fitted on fold 0:", &b, w, -1, -1);
        for (k = 0; files > 1 && k < (int)files; ++k) {
            char title[1024];
            snprintf(title, sizeof(title), "fold 1, %s:", paths[k]);
            reliability(title, &b, w, -1, k);
        }
        free(a.r), free(b.r), free(scale), free(d.r);
        return 0;
    }
    scale = (double *)malloc(d.count * sizeof(double));
    if (scale == NULL)
        return 1;
    case_scales(&d, cap, scale);
    fit(&d, scale, ridge, w);
    printf("%lu rows; weights:\n", (unsigned long)d.count);
    for (k = 0; k < F; ++k)
        printf("%s%.4f%s", k % 8 == 0 ? "    " : "", w[k], k == F - 1 ? "\n" : k % 8 == 7 ? ",\n" : ", ");
    reliability("the margin (the confidence before the fit), these rows:", &d, w, 1, -1);
    reliability("the fitted probability, these rows:", &d, w, -1, -1);
    for (k = 0; files > 1 && k < (int)files; ++k) { /* each file's rows alone */
        char title[1024];
        snprintf(title, sizeof(title), "the fitted probability, %s:", paths[k]);
        reliability(title, &d, w, -1, k);
    }

    if (table != NULL && !write_table(table, w)) {
        fprintf(stderr, "fit: cannot write the table into %s\n", table);
        return 1;
    }
    free(scale);
    free(d.r);
    return 0;
}
