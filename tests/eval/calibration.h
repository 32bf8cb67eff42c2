/* calibration.h - how honest AUTO's confidence is, and the rows that fit it

   Include before meshfix.h's implementation: it defines MESHFIX_FIT_ROW so
   that the library hands over, patch by patch, the features its confidence
   is computed from (meshfix__unit_features). After each call the program
   scores every patch against its truth with calib_score:

   - the reliability table: by band of reported confidence, the patches,
     their triangles and the share of those facing wrong, and the share of
     all wrong triangles in patches reported doubtful (below AUTO's bar,
     0.9) with the right triangles reported so;
   - with calib_open_rows, one line per patch for tests/eval/fit.c:
       case right wrong f0 f1 ... (as many as the library gives)
     (triangles facing right and wrong after the repair, then the features).

   One program, one mesh at a time: the rows of the call in flight are kept
   in static storage (this is a test program's helper, not the library). */
#ifndef CALIBRATION_H
#define CALIBRATION_H

#include <stddef.h>
#include <stdio.h>

#define CALIB_FEATURES 64 /* at most */
void calib_row(unsigned int patch, const double *features, int count);
#define MESHFIX_FIT_ROW(patch, features, count) calib_row((patch), (features), (count))

#define CALIB_BANDS 6
typedef struct calib_table {
    double patches[CALIB_BANDS], triangles[CALIB_BANDS], wrong[CALIB_BANDS];
    double wrong_total, wrong_doubtful, right_doubtful, triangles_total; /* doubtful: below AUTO's bar, 0.9 */
} calib_table;

/* Begin a call: forget the rows of the last one. */
void calib_begin(void);
/* flipped, patch_ids: the call's outputs per triangle; truth[t] 1 when
   triangle t faced the right way as given, 0 when not, 2 when unknown
   (left out); confidence: by patch id. */
void calib_score(calib_table *t, size_t triangles, const unsigned char *truth, const unsigned char *flipped,
                 const unsigned int *patch_ids, const float *confidence, size_t patch_count);
void calib_print(const calib_table *t, FILE *out);
/* Rows of every later calib_score go to path (NULL: nowhere). 0 on failure. */
int calib_open_rows(const char *path);
void calib_close_rows(void);

#endif

#ifdef CALIBRATION_IMPLEMENTATION
#include <stdlib.h>
#include <string.h>

static const double calib_band_low[CALIB_BANDS] = {0.0, 0.5, 0.9, 0.99, 0.999, 1.0};
static const char *const calib_band_name[CALIB_BANDS] = {"< 0.5", "0.5-0.9", "0.9-0.99", "0.99-0.999", ">= 0.999",
                                                         "1"};

static struct {
    double *features; /* CALIB_FEATURES per patch id */
    unsigned char *seen;
    size_t capacity;
    FILE *rows;
    unsigned long case_id;
    int count; /* features per patch, as the library gives them */
} calib;

static int calib_reserve(size_t patches)
{
    double *f;
    unsigned char *seen;
    if (patches <= calib.capacity)
        return 1;
    f = (double *)realloc(calib.features, patches * CALIB_FEATURES * sizeof(double));
    if (f == NULL)
        return 0;
    calib.features = f;
    seen = (unsigned char *)realloc(calib.seen, patches);
    if (seen == NULL)
        return 0;
    memset(seen + calib.capacity, 0, patches - calib.capacity);
    calib.seen = seen;
    calib.capacity = patches;
    return 1;
}

void calib_row(unsigned int patch, const double *features, int count)
{
    if (count > CALIB_FEATURES || !calib_reserve((size_t)patch + 1))
        return;
    calib.count = count;
    memcpy(calib.features + (size_t)patch * CALIB_FEATURES, features, (size_t)count * sizeof(double));
    calib.seen[patch] = 1;
}

void calib_begin(void)
{
    if (calib.seen != NULL)
        memset(calib.seen, 0, calib.capacity);
}

static int calib_band(double c)
{
    int b = CALIB_BANDS - 1;
    while (b > 0 && c < calib_band_low[b])
        --b;
    return b;
}

void calib_score(calib_table *t, size_t triangles, const unsigned char *truth, const unsigned char *flipped,
                 const unsigned int *patch_ids, const float *confidence, size_t patch_count)
{
    size_t *right = (size_t *)calloc(patch_count + 1, sizeof(size_t));
    size_t *wrong = (size_t *)calloc(patch_count + 1, sizeof(size_t));
    size_t i, p;
    if (right == NULL || wrong == NULL) {
        free(right);
        free(wrong);
        return;
    }
    for (i = 0; i < triangles; ++i) {
        int ok = (truth[i] != 0) != (flipped[i] != 0);
        if (patch_ids[i] >= patch_count || truth[i] > 1)
            continue; /* degenerate (never flipped, no patch), or no truth */
        if (ok)
            right[patch_ids[i]]++;
        else
            wrong[patch_ids[i]]++;
    }
    for (p = 0; p < patch_count; ++p) {
        int b = calib_band((double)confidence[p]);
        double n = (double)(right[p] + wrong[p]);
        if (n == 0)
            continue;
        t->patches[b] += 1;
        t->triangles[b] += n;
        t->wrong[b] += (double)wrong[p];
        t->triangles_total += n;
        t->wrong_total += (double)wrong[p];
        if (confidence[p] < 0.9f) {
            t->wrong_doubtful += (double)wrong[p];
            t->right_doubtful += (double)right[p];
        }
        if (calib.rows != NULL && p < calib.capacity && calib.seen[p]) {
            int k;
            fprintf(calib.rows, "%lu %lu %lu", calib.case_id, (unsigned long)right[p], (unsigned long)wrong[p]);
            for (k = 0; k < calib.count; ++k)
                fprintf(calib.rows, " %.6g", calib.features[p * CALIB_FEATURES + (size_t)k]);
            fputc('\n', calib.rows);
        }
    }
    calib.case_id++;
    free(right);
    free(wrong);
}

void calib_print(const calib_table *t, FILE *out)
{
    int b;
    fprintf(out, "confidence   patches    triangles   wrong\n");
    for (b = 0; b < CALIB_BANDS; ++b)
        fprintf(out, "%-10s %9.0f %12.0f  %6.2f%%\n", calib_band_name[b], t->patches[b], t->triangles[b],
                t->triangles[b] > 0 ? 100.0 * t->wrong[b] / t->triangles[b] : 0.0);
    fprintf(out, "wrong triangles: %.0f of %.0f; in doubtful patches (< 0.9): %.1f%%; right triangles reported "
                 "doubtful: %.0f (%.2f%%)\n",
            t->wrong_total, t->triangles_total, t->wrong_total > 0 ? 100.0 * t->wrong_doubtful / t->wrong_total : 100.0,
            t->right_doubtful,
            t->triangles_total > t->wrong_total ? 100.0 * t->right_doubtful / (t->triangles_total - t->wrong_total) : 0.0);
}

int calib_open_rows(const char *path)
{
    calib.rows = path != NULL ? fopen(path, "w") : NULL;
    return path == NULL || calib.rows != NULL;
}

void calib_close_rows(void)
{
    if (calib.rows != NULL)
        fclose(calib.rows);
    calib.rows = NULL;
    free(calib.features);
    free(calib.seen);
    calib.features = NULL;
    calib.seen = NULL;
    calib.capacity = 0;
}
#endif
