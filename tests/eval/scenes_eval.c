/* scenes_eval.c - scores meshfix_orient on generated scenes whose truth is
   known by construction (tests/scenes.h), under several corruptions

   Every triangle of a scene has an intended facing (solids out, hollows
   in, pipes away from their axis, U-channels away from their inside,
   sheets and terrains +z). Each scene is corrupted in turn:

       correct      as built: the repair must change nothing;
       shuffled     triangles shuffled and their corners rotated (the
                    winding kept): must change nothing either;
       inside-out   every triangle reversed;
       patches      each cut patch reversed whole with probability 0.5
                    (only scenes cut into unwelded patches);
       random-0.3   each triangle reversed with probability 0.3;
       random-0.5   ... 0.5: a vote over winding is a coin toss.

   then repaired with meshfix_orient (options NULL, or --policy), and
   scored per (scene, corruption):

       before%, after%   scored triangles facing the intended way before
                         and after the repair; area% the same by area;
       damaged           scored triangles right before and wrong after;
       flips             triangles the repair turned;
       undecided         triangles whose side nothing can tell: flat sheets
                         (their +z is a convention) when the corruption
                         left no trace of it (inside-out, patches,
                         random-0.5). Not scored; up% says how many of
                         them face +z after the repair;
       ms, ms/100k       the orient call alone, and per 100k triangles.

   The totals line adds up the counts of all rows (area% there is the mean
   of the rows' area%); "unchanged" counts the correct and shuffled inputs
   that came back with no flip. --parts lists, under each row, the parts
   that are not all right. --csv writes counts, one row per line.

   Build:  cc -std=c99 -O2 -I. tests/eval/scenes_eval.c -lm
   Usage:  scenes_eval [--policy NAME] [--size small|large] [--scene NAME]...
                       [--corruption NAME]... [--seed N] [--parts] [--csv]
           NAME of a policy: default (options NULL), auto, seed, majority,
           outward, visibility, up.
   Exit:   0; 1 for bad usage; 2 when a meshfix call failed. */
#define _POSIX_C_SOURCE 200809L
#define MESHFIX_IMPLEMENTATION
#include "meshfix.h"
#define MESHIO_IMPLEMENTATION
#include "examples/meshio.h"
#define MESHGEN_IMPLEMENTATION
#include "examples/meshgen.h"
#define SCENES_IMPLEMENTATION
#include "tests/scenes.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

/* ---- policies and corruptions ---- */

typedef struct policy_choice {
    const char *name;
    int named;             /* 0: the library default, options NULL */
    meshfix_policy policy; /* when named */
} policy_choice;

static const policy_choice POLICIES[] = {
    {"default", 0, MESHFIX_POLICY_AUTO},       {"auto", 1, MESHFIX_POLICY_AUTO},
    {"seed", 1, MESHFIX_POLICY_SEED},          {"majority", 1, MESHFIX_POLICY_MAJORITY},
    {"outward", 1, MESHFIX_POLICY_OUTWARD},    {"visibility", 1, MESHFIX_POLICY_VISIBILITY},
    {"up", 1, MESHFIX_POLICY_UP},
};

#define COUNT(a) (sizeof(a) / sizeof((a)[0]))

/* ---- command line ---- */

#define MAX_PICKS 64

typedef struct settings {
    const policy_choice *policy;
    scene_size size;
    const char *scenes[MAX_PICKS];
    size_t scene_picks;
    const char *corruptions[MAX_PICKS];
    size_t corruption_picks;
    unsigned long long seed;
    int parts, csv;
} settings;

static int usage(void)
{
    fprintf(stderr, "usage: scenes_eval [--policy default|auto|seed|majority|outward|visibility|up]\n"
                    "                   [--size small|large] [--scene NAME]... [--corruption NAME]...\n"
                    "                   [--seed N] [--parts] [--csv]\n");
    return 0;
}

static int picked(const char *const *picks, size_t count, const char *name)
{
    size_t i;
    for (i = 0; i < count; ++i)
        if (strcmp(picks[i], name) == 0)
            return 1;
    return count == 0;
}

static int parse(int argc, char **argv, settings *s)
{
    int i;
    size_t k;
    memset(s, 0, sizeof(*s));
    s->policy = &POLICIES[0];
    s->seed = 1;
    for (i = 1; i < argc; ++i) {
        const char *arg = argv[i], *value = i + 1 < argc ? argv[i + 1] : NULL;
        if (strcmp(arg, "--parts") == 0) {
            s->parts = 1;
            continue;
        }
        if (strcmp(arg, "--csv") == 0) {
            s->csv = 1;
            continue;
        }
        if (value == NULL)
            return usage();
        ++i;
        if (strcmp(arg, "--policy") == 0) {
            for (k = 0; k < COUNT(POLICIES) && strcmp(POLICIES[k].name, value) != 0; ++k)
                ;
            if (k == COUNT(POLICIES))
                return usage();
            s->policy = &POLICIES[k];
        } else if (strcmp(arg, "--size") == 0 && (strcmp(value, "small") == 0 || strcmp(value, "large") == 0)) {
            s->size = strcmp(value, "small") == 0 ? SCENE_SMALL : SCENE_LARGE;
        } else if (strcmp(arg, "--scene") == 0 && scene_find(value) != NULL && s->scene_picks < MAX_PICKS) {
            s->scenes[s->scene_picks++] = value;
        } else if (strcmp(arg, "--corruption") == 0 && s->corruption_picks < MAX_PICKS) {
            for (k = 0; k < SCENE_CORRUPTION_COUNT && strcmp(SCENE_CORRUPTIONS[k].name, value) != 0; ++k)
                ;
            if (k == SCENE_CORRUPTION_COUNT)
                return usage();
            s->corruptions[s->corruption_picks++] = value;
        } else if (strcmp(arg, "--seed") == 0) {
            s->seed = strtoull(value, NULL, 10);
        } else {
            return usage();
        }
    }
    return 1;
}

/* ---- scoring ---- */

typedef struct tally {
    size_t triangles, scored, undecided, undecided_up;
    size_t right_before, right_after, damaged, flips, changed_otherwise;
    double area, area_right;
    double ms;
} tally;

static double now_ms(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec * 1e3 + (double)t.tv_nsec * 1e-6;
}

/* 1 when the repair turned triangle i (a, b, c) into (a, c, b), 0 when it
   kept it; -1 for any other change (never expected). */
static int turned(const unsigned int *in, const unsigned int *out, size_t i)
{
    const unsigned int *a = in + 3 * i, *b = out + 3 * i;
    if (a[0] == b[0] && a[1] == b[1] && a[2] == b[2])
        return 0;
    return a[0] == b[0] && a[1] == b[2] && a[2] == b[1] ? 1 : -1;
}

/* Counts what the repair `out` did to the trial, into `total` and, by
   part, into `parts` (may be NULL). */
static void score(const scene_trial *t, const unsigned int *out, tally *total, tally *parts)
{
    size_t i, n = t->mesh.index_count / 3;
    for (i = 0; i < n; ++i) {
        int turn = turned(t->mesh.indices, out, i);
        int before = t->truth[i], after = before ^ (turn == 1);
        tally *each[2];
        size_t k;
        each[0] = total;
        each[1] = parts != NULL ? &parts[t->part[i]] : NULL;
        for (k = 0; k < 2 && each[k] != NULL; ++k) {
            tally *y = each[k];
            y->triangles++;
            y->flips += turn == 1;
            y->changed_otherwise += turn < 0;
            if (!t->scored[i]) {
                y->undecided++;
                y->undecided_up += (size_t)after; /* a flat sheet's truth is +z */
                continue;
            }
            {
                double area = scene_triangle_area(&t->mesh, i);
                y->scored++;
                y->right_before += (size_t)before;
                y->right_after += (size_t)after;
                y->damaged += before && !after;
                y->area += area;
                y->area_right += after ? area : 0;
            }
        }
    }
}

/* Repairs the trial with the chosen policy and scores it. */
static meshfix_result run(const scene_trial *t, const policy_choice *policy, size_t part_count, tally *total, tally *parts)
{
    unsigned int *out = (unsigned int *)malloc(t->mesh.index_count * sizeof(unsigned int) + 1);
    meshfix_options options;
    meshfix_result result;
    double start;
    memset(total, 0, sizeof(*total));
    memset(parts, 0, part_count * sizeof(*parts));
    if (out == NULL)
        return MESHFIX_ERROR_OUT_OF_MEMORY;
    memset(&options, 0, sizeof(options));
    options.policy = policy->policy;
    start = now_ms();
    result = meshfix_orient(out, t->mesh.indices, t->mesh.index_count, t->mesh.positions, t->mesh.vertex_count, 12,
                            policy->named ? &options : NULL, NULL, NULL);
    total->ms = now_ms() - start;
    if (result == MESHFIX_OK)
        score(t, out, total, parts);
    free(out);
    return result;
}

/* ---- output ---- */

static double percent(double part, double whole)
{
    return whole > 0 ? 100 * part / whole : 0;
}

/* "99.99" or "-" when there is nothing to divide. */
static const char *percent_text(char *buffer, size_t size, double part, double whole)
{
    if (whole > 0)
        snprintf(buffer, size, "%.2f", percent(part, whole));
    else
        snprintf(buffer, size, "-");
    return buffer;
}

static void print_header(int csv)
{
    if (csv)
        printf("scene,size,corruption,policy,triangles,scored,right_before,right_after,area_scored,area_right_after,"
               "damaged,flips,changed_otherwise,undecided,undecided_up_after,ms\n");
    else
        printf("%-16s %-11s %9s %9s %8s %8s %8s %8s %8s %9s %6s %9s %8s\n", "scene", "corruption", "triangles", "scored",
               "before%", "after%", "area%", "damaged", "flips", "undecided", "up%", "ms", "ms/100k");
}

static void print_row(const char *scene_name, const char *corruption_name, const settings *s, const tally *y)
{
    char before[16], after[16], area[16], up[16];
    if (s->csv) {
        printf("%s,%s,%s,%s,%lu,%lu,%lu,%lu,%.9g,%.9g,%lu,%lu,%lu,%lu,%lu,%.3f\n", scene_name,
               s->size == SCENE_SMALL ? "small" : "large", corruption_name, s->policy->name, (unsigned long)y->triangles,
               (unsigned long)y->scored, (unsigned long)y->right_before, (unsigned long)y->right_after, y->area,
               y->area_right, (unsigned long)y->damaged, (unsigned long)y->flips, (unsigned long)y->changed_otherwise,
               (unsigned long)y->undecided, (unsigned long)y->undecided_up, y->ms);
        return;
    }
    printf("%-16s %-11s %9lu %9lu %8s %8s %8s %8lu %8lu %9lu %6s %9.1f %8.1f\n", scene_name, corruption_name,
           (unsigned long)y->triangles, (unsigned long)y->scored,
           percent_text(before, sizeof(before), (double)y->right_before, (double)y->scored),
           percent_text(after, sizeof(after), (double)y->right_after, (double)y->scored),
           percent_text(area, sizeof(area), y->area_right, y->area), (unsigned long)y->damaged, (unsigned long)y->flips,
           (unsigned long)y->undecided, percent_text(up, sizeof(up), (double)y->undecided_up, (double)y->undecided), y->ms,
           y->triangles ? y->ms * 1e5 / (double)y->triangles : 0.0);
    if (y->changed_otherwise)
        printf("    !! %lu triangles changed otherwise than by a flip\n", (unsigned long)y->changed_otherwise);
}

/* The parts of a row that are not all right (or not scored). */
static void print_parts(const scene *sc, const tally *parts)
{
    size_t p;
    char after[16];
    for (p = 0; p < sc->part_count; ++p) {
        const tally *y = &parts[p];
        if (y->triangles == 0 || (y->undecided == 0 && y->right_after == y->scored))
            continue;
        if (y->undecided)
            printf("    part %2lu %-18s %8lu triangles, undecided, %.2f%% +z after\n", (unsigned long)p,
                   sc->parts[p].name, (unsigned long)y->triangles, percent((double)y->undecided_up, (double)y->undecided));
        else
            printf("    part %2lu %-18s %8lu triangles, %s%% right after, %lu damaged\n", (unsigned long)p,
                   sc->parts[p].name, (unsigned long)y->triangles,
                   percent_text(after, sizeof(after), (double)y->right_after, (double)y->scored),
                   (unsigned long)y->damaged);
    }
}

/* Running sums for the totals line. */
typedef struct totals {
    tally sum;
    double area_percent_sum;
    size_t rows, rows_with_area, correct_inputs, correct_unchanged, failed;
} totals;

static void add_row(totals *all, const scene_corruption *c, const tally *y)
{
    all->sum.triangles += y->triangles;
    all->sum.scored += y->scored;
    all->sum.undecided += y->undecided;
    all->sum.undecided_up += y->undecided_up;
    all->sum.right_before += y->right_before;
    all->sum.right_after += y->right_after;
    all->sum.damaged += y->damaged;
    all->sum.flips += y->flips;
    all->sum.changed_otherwise += y->changed_otherwise;
    all->sum.area += y->area;
    all->sum.area_right += y->area_right;
    all->sum.ms += y->ms;
    all->rows++;
    if (y->area > 0) {
        all->area_percent_sum += percent(y->area_right, y->area);
        all->rows_with_area++;
    }
    if (c->kind == SCENE_KEEP || c->kind == SCENE_SHUFFLE) {
        all->correct_inputs++;
        all->correct_unchanged += y->flips == 0;
    }
}

static void print_totals(const totals *all, const settings *s)
{
    char before[16], after[16], up[16];
    const tally *y = &all->sum;
    if (s->csv)
        return;
    printf("%-16s %-11s %9lu %9lu %8s %8s %8.2f %8lu %8lu %9lu %6s %9.1f %8.1f\n", "total", s->policy->name,
           (unsigned long)y->triangles, (unsigned long)y->scored,
           percent_text(before, sizeof(before), (double)y->right_before, (double)y->scored),
           percent_text(after, sizeof(after), (double)y->right_after, (double)y->scored),
           all->rows_with_area ? all->area_percent_sum / (double)all->rows_with_area : 0.0, (unsigned long)y->damaged,
           (unsigned long)y->flips, (unsigned long)y->undecided,
           percent_text(up, sizeof(up), (double)y->undecided_up, (double)y->undecided), y->ms,
           y->triangles ? y->ms * 1e5 / (double)y->triangles : 0.0);
    printf("%lu rows; correct inputs returned unchanged: %lu of %lu; meshfix calls failed: %lu\n",
           (unsigned long)all->rows, (unsigned long)all->correct_unchanged, (unsigned long)all->correct_inputs,
           (unsigned long)all->failed);
}

/* ---- driver ---- */

/* Every picked corruption of one built scene. */
static void evaluate_scene(const scene_info *info, const scene *sc, const settings *s, totals *all)
{
    tally *parts = (tally *)calloc(sc->part_count + 1, sizeof(tally));
    size_t c;
    for (c = 0; c < SCENE_CORRUPTION_COUNT; ++c) {
        const scene_corruption *k = &SCENE_CORRUPTIONS[c];
        scene_trial t;
        tally y;
        meshfix_result result;
        if (!picked(s->corruptions, s->corruption_picks, k->name) || (k->kind == SCENE_PATCHES && sc->patch == NULL))
            continue;
        if (parts == NULL || !scene_trial_make(&t, sc, k, s->seed * 1000 + c)) {
            fprintf(stderr, "%s %s: out of memory\n", info->name, k->name);
            all->failed++;
            continue;
        }
        result = run(&t, s->policy, sc->part_count, &y, parts);
        if (result != MESHFIX_OK) {
            fprintf(stderr, "%s %s: meshfix_orient failed: %s\n", info->name, k->name, meshfix_result_string(result));
            all->failed++;
        } else {
            print_row(info->name, k->name, s, &y);
            if (s->parts && !s->csv)
                print_parts(sc, parts);
            add_row(all, k, &y);
        }
        scene_trial_free(&t);
        fflush(stdout);
    }
    free(parts);
}

int main(int argc, char **argv)
{
    settings s;
    totals all;
    size_t i;
    if (!parse(argc, argv, &s))
        return 1;
    memset(&all, 0, sizeof(all));
    if (!s.csv)
        printf("policy %s, %s scenes, seed %llu\n", s.policy->name, s.size == SCENE_SMALL ? "small" : "large", s.seed);
    print_header(s.csv);
    for (i = 0; i < scene_count(); ++i) {
        const scene_info *info = scene_get(i);
        scene sc;
        int built;
        if (!picked(s.scenes, s.scene_picks, info->name))
            continue;
        built = scene_build(&sc, info->name, s.size);
        if (built < 0) {
            fprintf(stderr, "%s: skipped (model not available or not closed)\n", info->name);
            continue;
        }
        if (built == 0) {
            fprintf(stderr, "%s: cannot build (out of memory)\n", info->name);
            all.failed++;
            continue;
        }
        evaluate_scene(info, &sc, &s, &all);
        scene_free(&sc);
    }
    print_totals(&all, &s);
    return all.failed ? 2 : 0;
}
