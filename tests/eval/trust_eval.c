/* trust_eval.c - the trust suite's families, cut the way real exports are
   cut, scored against their truth (tests/scenes.h)

   Each scene (solids whose every triangle's intended facing is known) is
   cut into K unwelded patches grown from K random seed triangles, each
   with its own copies of its seam vertices, the seams made one of three
   ways:

       exact    the copies stay where they were (joined again by position:
                the topology the library sees is the scene's own);
       gap      every copy moves 3% of the way to its patch's centroid
                (seams open into gaps; the project's older cuts);
       jitter   every seam copy moves by its own random offset, 0.5 to 1 x
                1e-4 x the box diagonal, in a random direction (seams gap
                and overlap by turns, as real exports' do).

   Each cut is repaired twice: as cut ("correct": every flip is damage),
   and corrupted ("corrupted": a random half of the patches reversed whole,
   then each triangle with probability 0.02). A row per scene, K, seams and
   input: right% (triangles facing the intended way after the repair),
   damaged (right before, wrong after), kept (patches decided by nothing),
   rays, ms.

   --ablation adds, per kind of evidence (outputs.patch_evidence), the
   patches it decided and how many of those ended right (a patch is right
   when most of its area faces the intended way after the repair).

   Build:  cc -std=c99 -O2 -I. tests/eval/trust_eval.c -lm
   --rows FILE writes a line per patch for tests/eval/fit.c; the output
   ends with the reliability of the reported confidence
   (tests/eval/calibration.h).

   Usage:  trust_eval [--size small|large] [--scene NAME]... [--policy NAME]
                      [--k N]... [--seams exact|gap|jitter]... [--jitter J] [--seed N]
                      [--ablation] [--csv]
           --jitter: the seam offsets' largest length, of the box diagonal (1e-4)
   Exit:   0; 1 for bad usage; 2 when a meshfix call failed. */
#define _POSIX_C_SOURCE 200809L
#define CALIBRATION_IMPLEMENTATION
#include "tests/eval/calibration.h"
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

#define COUNT(a) (sizeof(a) / sizeof((a)[0]))
#define MAX_PICKS 32
#define EVIDENCE_KINDS 6

static const char *const DEFAULT_SCENES[] = {"city",   "cavity_box",     "cavity_coarse", "crossing",
                                              "cad_part", "spider", "projection_box", "buildings"};
static const char *const SEAMS[] = {"exact", "gap", "jitter"};
static const char *const EVIDENCE_NAMES[EVIDENCE_KINDS] = {"kept", "volume", "parity", "visibility", "normals", "policy"};

typedef struct settings {
    scene_size size;
    const char *scenes[MAX_PICKS];
    size_t scene_count;
    unsigned ks[MAX_PICKS];
    size_t k_count;
    const char *seams[MAX_PICKS];
    size_t seam_count;
    meshfix_policy policy;
    unsigned long long seed;
    double jitter; /* of the diagonal: 1e-4 */
    int ablation, csv;
} settings;

/* What one repair did, against the truth. */
typedef struct score {
    size_t triangles, right, damaged, flipped, kept, patches, rays;
    double ms;
    size_t decided[EVIDENCE_KINDS], decided_right[EVIDENCE_KINDS];
} score;

static int usage(void)
{
    fprintf(stderr, "usage: trust_eval [--size small|large] [--scene NAME]... [--policy NAME] [--k N]...\n"
                    "                  [--seams exact|gap|jitter]... [--seed N] [--ablation] [--csv]\n"
                    "                  [--rows FILE]\n");
    return 1;
}

static int parse(int argc, char **argv, settings *s)
{
    int i;
    memset(s, 0, sizeof(*s));
    s->size = SCENE_SMALL;
    s->seed = 1;
    s->policy = MESHFIX_POLICY_AUTO;
    s->jitter = 1e-4;
    for (i = 1; i < argc; ++i) {
        const char *arg = argv[i], *value = i + 1 < argc ? argv[i + 1] : NULL;
        if (strcmp(arg, "--ablation") == 0) {
            s->ablation = 1;
        } else if (strcmp(arg, "--csv") == 0) {
            s->csv = 1;
        } else if (value == NULL) {
            return 0;
        } else if (strcmp(arg, "--size") == 0) {
            s->size = strcmp(value, "large") == 0 ? SCENE_LARGE : SCENE_SMALL;
            ++i;
        } else if (strcmp(arg, "--scene") == 0 && s->scene_count < MAX_PICKS) {
            s->scenes[s->scene_count++] = value, ++i;
        } else if (strcmp(arg, "--k") == 0 && s->k_count < MAX_PICKS) {
            s->ks[s->k_count++] = (unsigned)strtoul(value, NULL, 10), ++i;
        } else if (strcmp(arg, "--seams") == 0 && s->seam_count < MAX_PICKS) {
            s->seams[s->seam_count++] = value, ++i;
        } else if (strcmp(arg, "--policy") == 0) {
            s->policy = meshfix_policy_from_string(value), ++i;
            if (s->policy == MESHFIX_POLICY_COUNT)
                return 0;
        } else if (strcmp(arg, "--jitter") == 0) {
            s->jitter = strtod(value, NULL), ++i;
        } else if (strcmp(arg, "--seed") == 0) {
            s->seed = strtoull(value, NULL, 10), ++i;
        } else if (strcmp(arg, "--rows") == 0) {
            if (!calib_open_rows(value))
                return 0;
            ++i;
        } else {
            return 0;
        }
    }
    if (s->scene_count == 0)
        for (i = 0; i < (int)COUNT(DEFAULT_SCENES); ++i)
            s->scenes[s->scene_count++] = DEFAULT_SCENES[i];
    if (s->k_count == 0)
        s->ks[s->k_count++] = 16, s->ks[s->k_count++] = 256;
    if (s->seam_count == 0)
        for (i = 0; i < (int)COUNT(SEAMS); ++i)
            s->seams[s->seam_count++] = SEAMS[i];
    return 1;
}

static scene_seams seams_of(const char *name)
{
    return strcmp(name, "gap") == 0 ? SCENE_SEAMS_GAP : strcmp(name, "jitter") == 0 ? SCENE_SEAMS_JITTER : SCENE_SEAMS_EXACT;
}

static double now_ms(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec * 1e3 + (double)t.tv_nsec * 1e-6;
}

static calib_table reliability; /* of the reported confidence, over every repair */

/* Repairs `indices` (the scene's triangles as corrupted; truth as they
   stand) and scores the result. */
static int repair(const scene *s, unsigned int *indices, const unsigned char *truth, meshfix_policy policy, score *sc)
{
    size_t n = s->mesh.index_count / 3, t, p, capacity = n + 1;
    unsigned char *flipped = (unsigned char *)malloc(n + 1), *evidence = (unsigned char *)malloc(capacity);
    unsigned int *patch_ids = (unsigned int *)malloc(n * sizeof(unsigned int) + 1);
    float *confidence = (float *)malloc(capacity * sizeof(float));
    double *right_area = (double *)calloc(capacity, sizeof(double)), *all_area = (double *)calloc(capacity, sizeof(double));
    meshfix_options o;
    meshfix_outputs outputs;
    meshfix_report r;
    meshfix_result result;
    double start;
    memset(sc, 0, sizeof(*sc));
    if (!flipped || !evidence || !patch_ids || !confidence || !right_area || !all_area) {
        result = MESHFIX_ERROR_OUT_OF_MEMORY;
        goto done;
    }
    memset(&o, 0, sizeof(o));
    o.policy = policy;
    memset(&outputs, 0, sizeof(outputs));
    outputs.flipped = flipped;
    outputs.patch_ids = patch_ids;
    outputs.patch_evidence = evidence;
    outputs.patch_evidence_capacity = capacity;
    outputs.patch_confidence = confidence;
    outputs.patch_confidence_capacity = capacity;
    calib_begin();
    start = now_ms();
    result = meshfix_orient(NULL, indices, s->mesh.index_count, s->mesh.positions, s->mesh.vertex_count, 12, &o, &r,
                            &outputs);
    sc->ms = now_ms() - start;
    if (result != MESHFIX_OK)
        goto done;
    sc->patches = r.mesh.patches;
    sc->kept = r.evidence.patches_kept;
    sc->rays = r.evidence.rays_cast;
    sc->flipped = r.triangles_flipped;
    for (t = 0; t < n; ++t) {
        int after = truth[t] ^ flipped[t];
        double area = scene_triangle_area(&s->mesh, t);
        sc->triangles++;
        sc->right += (size_t)after;
        sc->damaged += (size_t)(truth[t] && !after);
        if (patch_ids[t] != 0xFFFFFFFFu && patch_ids[t] < capacity) {
            all_area[patch_ids[t]] += area;
            right_area[patch_ids[t]] += after ? area : 0.0;
        }
    }
    calib_score(&reliability, n, truth, flipped, patch_ids, confidence, r.mesh.patches);
    for (p = 0; p < r.mesh.patches && p < capacity; ++p) {
        unsigned kind = evidence[p] < EVIDENCE_KINDS ? evidence[p] : 0;
        sc->decided[kind]++;
        sc->decided_right[kind] += (size_t)(right_area[p] > 0.5 * all_area[p]);
    }
done:
    free(flipped);
    free(evidence);
    free(patch_ids);
    free(confidence);
    free(right_area);
    free(all_area);
    return result == MESHFIX_OK;
}

static void add_score(score *total, const score *s)
{
    int k;
    total->triangles += s->triangles, total->right += s->right, total->damaged += s->damaged;
    total->flipped += s->flipped, total->kept += s->kept, total->patches += s->patches, total->rays += s->rays;
    total->ms += s->ms;
    for (k = 0; k < EVIDENCE_KINDS; ++k)
        total->decided[k] += s->decided[k], total->decided_right[k] += s->decided_right[k];
}

static void print_row(const settings *st, const char *name, unsigned k, const char *seams, const char *input,
                      const score *s)
{
    double right = s->triangles ? 100.0 * (double)s->right / (double)s->triangles : 0.0;
    if (st->csv)
        printf("%s,%u,%s,%s,%zu,%zu,%zu,%zu,%zu,%zu,%.1f\n", name, k, seams, input, s->triangles, s->right, s->damaged,
               s->kept, s->patches, s->rays, s->ms);
    else
        printf("%-12s %5u %-7s %-10s %9zu %8.3f%% %9zu %6zu/%-6zu %9zu %9.1f\n", name, k, seams, input, s->triangles,
               right, s->damaged, s->kept, s->patches, s->rays, s->ms);
}

static void print_ablation(const score *s)
{
    int k;
    printf("  evidence      patches     right\n");
    for (k = 0; k < EVIDENCE_KINDS; ++k)
        if (s->decided[k] != 0)
            printf("  %-12s %8zu  %7.2f%%\n", EVIDENCE_NAMES[k], s->decided[k],
                   100.0 * (double)s->decided_right[k] / (double)s->decided[k]);
}

int main(int argc, char **argv)
{
    settings st;
    score total[2];
    size_t i, a, b;
    if (!parse(argc, argv, &st))
        return usage();
    memset(total, 0, sizeof(total));
    if (!st.csv)
        printf("%-12s %5s %-7s %-10s %9s %9s %9s %13s %9s %9s\n", "scene", "K", "seams", "input", "triangles", "right",
               "damaged", "kept/patches", "rays", "ms");
    for (i = 0; i < st.scene_count; ++i) {
        scene base;
        int built = scene_build(&base, st.scenes[i], st.size);
        if (built != 1) {
            fprintf(stderr, "trust_eval: scene '%s' %s\n", st.scenes[i], built < 0 ? "not available" : "not built");
            continue;
        }
        for (a = 0; a < st.k_count; ++a)
            for (b = 0; b < st.seam_count; ++b) {
                scene cut;
                size_t n = base.mesh.index_count / 3;
                unsigned long long seed = st.seed * 1000003ull + i * 7919ull + a * 104729ull + b;
                unsigned int *indices = (unsigned int *)malloc(base.mesh.index_count * sizeof(unsigned int) + 1);
                unsigned char *truth = (unsigned char *)malloc(n + 1);
                score sc;
                if (indices == NULL || truth == NULL ||
                    !scene_cut_as_exported(&base, &cut, st.ks[a], seams_of(st.seams[b]), st.jitter, seed)) {
                    fprintf(stderr, "trust_eval: out of memory\n");
                    return 2;
                }
                if (!repair(&cut, cut.mesh.indices, cut.truth, st.policy, &sc))
                    return 2;
                print_row(&st, st.scenes[i], st.ks[a], st.seams[b], "correct", &sc);
                if (st.ablation)
                    print_ablation(&sc);
                add_score(&total[0], &sc);
                memcpy(indices, cut.mesh.indices, base.mesh.index_count * sizeof(unsigned int));
                memcpy(truth, cut.truth, n);
                scene_corrupt_cut(&cut, indices, truth, seed);
                if (!repair(&cut, indices, truth, st.policy, &sc))
                    return 2;
                print_row(&st, st.scenes[i], st.ks[a], st.seams[b], "corrupted", &sc);
                if (st.ablation)
                    print_ablation(&sc);
                add_score(&total[1], &sc);
                free(indices);
                free(truth);
                scene_free(&cut);
            }
        scene_free(&base);
    }
    for (i = 0; i < 2; ++i) {
        printf("total %-9s right %.3f%%, damaged %zu, kept %zu of %zu patches, %zu rays, %.0f ms\n",
               i ? "corrupted" : "correct", total[i].triangles ? 100.0 * (double)total[i].right / (double)total[i].triangles : 0,
               total[i].damaged, total[i].kept, total[i].patches, total[i].rays, total[i].ms);
        if (st.ablation)
            print_ablation(&total[i]);
    }
    printf("reliability of the reported confidence (every repair):\n");
    calib_print(&reliability, stdout);
    calib_close_rows();
    return 0;
}
