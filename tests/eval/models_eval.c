/* models_eval.c - real models under eleven corruptions, scored against the
   winding they were shipped with

   A model is taken when, as shipped (corners at equal positions joined),
   every edge is shared by exactly two triangles run opposite ways and
   every component has a positive volume: closed, consistent and outward,
   so its shipped winding is the truth and geometry can tell it (open
   sheets, where only a convention can, are the STL and asset suites'
   business). Models with fewer than 12 triangles are left out. Each is
   corrupted eleven ways and repaired with meshfix_orient (default options
   or --policy):

       correct      as shipped: every flip is damage;
       shuffled     triangles shuffled, corners rotated (winding kept);
       inside-out   every triangle reversed;
       random-0.1, random-0.3, random-0.5
                    each triangle reversed with that probability;
       soup-0.5     every triangle its own three corners (joined again by
                    position), then random-0.5;
       cut64-exact  cut into 64 regions whose seams stay welded, half the
                    regions reversed;
       cut16-jitter, cut256-jitter
                    cut into 16 / 256 unwelded patches, seams jittered by 0.5
                    to 1 x 1e-4 of the diagonal (gaps and overlaps), half
                    the patches reversed, then each triangle with p = 0.02;
       cut256-gap   cut into 256 patches shrunk 1% toward their middles,
                    half reversed.

   Printed: per model and corruption the % of triangles facing as shipped
   after the repair, then per corruption the mean over models and the
   worst model, and the mean of every (model, corruption) and the worst;
   then the reliability of the reported confidence (tests/eval/calibration.h).

   Build:  cc -std=c99 -O2 -I. tests/eval/models_eval.c -lm
   Usage:  models_eval [--policy NAME] [--seed N] [--quiet] [--rows FILE] FILE_OR_DIRECTORY...
           --rows: a line per patch for tests/eval/fit.c (tests/eval/calibration.h)
           (directories searched recursively for .stl .obj .off .ply)
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

#include <ctype.h>
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#define CORRUPTIONS 11
static const char *const NAMES[CORRUPTIONS] = {"correct",     "shuffled",     "inside-out",    "random-0.1",
                                               "random-0.3",  "random-0.5",   "soup-0.5",      "cut64-exact",
                                               "cut16-jitter", "cut256-jitter", "cut256-gap"};

typedef struct totals {
    double sum[CORRUPTIONS], worst[CORRUPTIONS];
    const char *worst_name[CORRUPTIONS];
    size_t models;
    char names[4096][256];
} totals;

static meshfix_policy policy = MESHFIX_POLICY_AUTO;
static unsigned long long base_seed = 1;
static int quiet = 0;
static calib_table reliability;

/* Whether the shipped model is closed, consistent and outward. */
static int usable(const mio_mesh *m)
{
    meshfix_report r;
    meshfix_component components[256];
    meshfix_outputs out;
    size_t c;
    memset(&out, 0, sizeof(out));
    out.components = components;
    out.components_capacity = 256;
    if (m->index_count < 36 ||
        meshfix_inspect(m->indices, m->index_count, m->positions, m->vertex_count, 12, NULL, &r, &out) != MESHFIX_OK)
        return 0;
    if (r.mesh.edges_boundary || r.mesh.edges_non_manifold || r.mesh.edges_inconsistent || r.mesh.triangles_degenerate ||
        r.mesh.components > 256 || r.mesh.components_non_orientable)
        return 0;
    for (c = 0; c < r.mesh.components; ++c)
        if (!(components[c].signed_volume > 0))
            return 0;
    return 1;
}

/* A corrupted copy of m (positions may be new: a cut or a soup) and each
   triangle's truth (1: faces as shipped). */
static int corrupt(const mio_mesh *m, int kind, unsigned long long seed, mio_mesh *out, unsigned char *truth)
{
    size_t n = m->index_count / 3, t;
    unsigned int *patch = NULL;
    memset(truth, 1, n);
    memset(out, 0, sizeof(*out));
    if (kind >= 7) { /* the cuts */
        static const unsigned k_of[] = {64, 16, 256, 256};
        patch = (unsigned int *)malloc(n * sizeof(unsigned int) + 1);
        if (patch == NULL)
            return 0;
        if (kind == 10 ? gen_cut(out, patch, m, 256, 0.01f, seed) == 0
                       : gen_cut_jittered(out, patch, m, k_of[kind - 7], kind == 7 ? 0.0 : 1e-4, seed) == 0) {
            free(patch);
            return 0;
        }
        gen_reverse_patches(out, truth, patch, 0.5, seed ^ 0xA5ull);
        if (kind == 8 || kind == 9)
            gen_reverse_random(out, truth, 0.02, seed ^ 0x5Aull);
        free(patch);
        return 1;
    }
    out->vertex_count = kind == 6 ? 3 * n : m->vertex_count;
    out->index_count = m->index_count;
    out->positions = (float *)malloc(3 * out->vertex_count * sizeof(float) + 4);
    out->indices = (unsigned int *)malloc(m->index_count * sizeof(unsigned int) + 4);
    if (out->positions == NULL || out->indices == NULL)
        return 0;
    if (kind == 6) {
        for (t = 0; t < m->index_count; ++t) {
            memcpy(out->positions + 3 * t, m->positions + 3 * (size_t)m->indices[t], 3 * sizeof(float));
            out->indices[t] = (unsigned int)t;
        }
    } else {
        memcpy(out->positions, m->positions, 3 * m->vertex_count * sizeof(float));
        memcpy(out->indices, m->indices, m->index_count * sizeof(unsigned int));
    }
    switch (kind) {
    case 1: return gen_shuffle(out, truth, NULL, seed);
    case 2: gen_reverse_all(out, truth); break;
    case 3: gen_reverse_random(out, truth, 0.1, seed); break;
    case 4: gen_reverse_random(out, truth, 0.3, seed); break;
    case 5: case 6: gen_reverse_random(out, truth, 0.5, seed); break;
    default: break;
    }
    return 1;
}

/* % of triangles facing as shipped after the repair; -1 on failure. */
static double score(const mio_mesh *m, const unsigned char *truth)
{
    size_t n = m->index_count / 3, t, right = 0;
    unsigned char *flipped = (unsigned char *)malloc(n + 1);
    unsigned int *patch_ids = (unsigned int *)malloc(n * sizeof(unsigned int) + 4);
    float *confidence = (float *)malloc(n * sizeof(float) + 4);
    meshfix_options o;
    meshfix_outputs out;
    meshfix_report r;
    meshfix_result result = MESHFIX_ERROR_OUT_OF_MEMORY;
    memset(&o, 0, sizeof(o));
    o.policy = policy;
    memset(&out, 0, sizeof(out));
    out.flipped = flipped;
    out.patch_ids = patch_ids;
    out.patch_confidence = confidence;
    out.patch_confidence_capacity = n;
    if (flipped != NULL && patch_ids != NULL && confidence != NULL) {
        calib_begin();
        result = meshfix_orient(NULL, m->indices, m->index_count, m->positions, m->vertex_count, 12, &o, &r, &out);
    }
    for (t = 0; result == MESHFIX_OK && t < n; ++t)
        right += (size_t)((truth[t] != 0) != (flipped[t] != 0));
    if (result == MESHFIX_OK)
        calib_score(&reliability, n, truth, flipped, patch_ids, confidence, r.mesh.patches);
    free(flipped);
    free(patch_ids);
    free(confidence);
    return result == MESHFIX_OK ? 100.0 * (double)right / (double)n : -1;
}

static int model(const char *path, totals *tot)
{
    mio_mesh m, c;
    char error[256];
    unsigned char *truth;
    double row[CORRUPTIONS];
    int k;
    if (!mio_load(path, &m, error, sizeof(error)))
        return 1;
    if (!usable(&m)) {
        mio_free(&m);
        return 1;
    }
    truth = (unsigned char *)malloc(m.index_count / 3 + 1);
    for (k = 0; truth != NULL && k < CORRUPTIONS; ++k) {
        unsigned long long seed = base_seed * 0x9E3779B97F4A7C15ull + (unsigned long long)k * 7919u;
        if (!corrupt(&m, k, seed, &c, truth)) {
            fprintf(stderr, "models_eval: %s: cannot make %s\n", path, NAMES[k]);
            row[k] = -1;
            continue;
        }
        row[k] = score(&c, truth);
        mio_free(&c);
        if (row[k] < 0) {
            fprintf(stderr, "models_eval: %s: meshfix_orient failed on %s\n", path, NAMES[k]);
            free(truth);
            mio_free(&m);
            return 0;
        }
    }
    free(truth);
    if (tot->models < 4096)
        snprintf(tot->names[tot->models], sizeof(tot->names[0]), "%s", path);
    for (k = 0; k < CORRUPTIONS; ++k) {
        tot->sum[k] += row[k];
        if (tot->models == 0 || row[k] < tot->worst[k]) {
            tot->worst[k] = row[k];
            tot->worst_name[k] = tot->names[tot->models < 4096 ? tot->models : 4095];
        }
    }
    tot->models++;
    if (!quiet) {
        printf("%8lu", (unsigned long)(m.index_count / 3));
        for (k = 0; k < CORRUPTIONS; ++k)
            printf(" %7.2f", row[k]);
        printf("  %s\n", path);
    }
    mio_free(&m);
    return 1;
}

static int mesh_file(const char *name)
{
    size_t n = strlen(name);
    const char *ext = n > 4 ? name + n - 4 : "";
    char lower[5];
    int i;
    for (i = 0; i < 4 && ext[i]; ++i)
        lower[i] = (char)tolower((unsigned char)ext[i]);
    lower[i] = 0;
    return strcmp(lower, ".stl") == 0 || strcmp(lower, ".obj") == 0 || strcmp(lower, ".off") == 0 || strcmp(lower, ".ply") == 0;
}

static int walk(const char *path, totals *tot)
{
    struct stat st;
    DIR *d;
    struct dirent *e;
    char **names = NULL;
    size_t count = 0, cap = 0, i;
    int ok = 1;
    if (stat(path, &st) != 0)
        return 1;
    if (!S_ISDIR(st.st_mode))
        return mesh_file(path) ? model(path, tot) : 1;
    if ((d = opendir(path)) == NULL)
        return 1;
    while ((e = readdir(d)) != NULL) {
        if (e->d_name[0] == '.')
            continue;
        if (count == cap) {
            char **grown = (char **)realloc(names, (cap = cap ? 2 * cap : 64) * sizeof(char *));
            if (grown == NULL)
                break;
            names = grown;
        }
        names[count] = (char *)malloc(strlen(path) + strlen(e->d_name) + 2);
        if (names[count] != NULL)
            sprintf(names[count++], "%s/%s", path, e->d_name);
    }
    closedir(d);
    for (i = 0; i < count; ++i) { /* sorted: the same order on every machine */
        size_t j;
        for (j = i + 1; j < count; ++j)
            if (strcmp(names[j], names[i]) < 0) {
                char *x = names[i];
                names[i] = names[j], names[j] = x;
            }
    }
    for (i = 0; i < count; ++i) {
        ok = ok && walk(names[i], tot);
        free(names[i]);
    }
    free(names);
    return ok;
}

int main(int argc, char **argv)
{
    static totals tot;
    int i, k, files = 0;
    double all = 0, worst = 101;
    for (i = 1; i < argc; ++i) {
        if (strcmp(argv[i], "--policy") == 0 && i + 1 < argc) {
            policy = meshfix_policy_from_string(argv[++i]);
            if (policy == MESHFIX_POLICY_COUNT)
                return 1;
        } else if (strcmp(argv[i], "--seed") == 0 && i + 1 < argc) {
            base_seed = strtoull(argv[++i], NULL, 10);
        } else if (strcmp(argv[i], "--quiet") == 0) {
            quiet = 1;
        } else if (strcmp(argv[i], "--rows") == 0 && i + 1 < argc) {
            if (!calib_open_rows(argv[++i]))
                return 1;
        } else {
            files++;
        }
    }
    if (files == 0) {
        fprintf(stderr, "usage: models_eval [--policy NAME] [--seed N] [--quiet] [--rows FILE] FILE_OR_DIRECTORY...\n");
        return 1;
    }
    if (!quiet) {
        printf("%8s", "tris");
        for (k = 0; k < CORRUPTIONS; ++k)
            printf(" %7.7s", NAMES[k]);
        printf("  file\n");
    }
    for (i = 1; i < argc; ++i) {
        if (strcmp(argv[i], "--policy") == 0 || strcmp(argv[i], "--seed") == 0 || strcmp(argv[i], "--rows") == 0) {
            ++i;
            continue;
        }
        if (strcmp(argv[i], "--quiet") == 0)
            continue;
        if (!walk(argv[i], &tot))
            return 2;
    }
    if (tot.models == 0) {
        printf("no closed, consistent, outward model found\n");
        return 0;
    }
    printf("%lu models; %% of triangles facing as shipped after the repair, mean over models (worst model):\n",
           (unsigned long)tot.models);
    for (k = 0; k < CORRUPTIONS; ++k) {
        printf("  %-14s %8.3f%%  (%.2f%% %s)\n", NAMES[k], tot.sum[k] / (double)tot.models, tot.worst[k],
               tot.worst_name[k]);
        all += tot.sum[k];
        worst = tot.worst[k] < worst ? tot.worst[k] : worst;
    }
    printf("all: mean %.3f%% over %lu (model, corruption), worst %.2f%%\n", all / (double)(tot.models * CORRUPTIONS),
           (unsigned long)(tot.models * CORRUPTIONS), worst);
    printf("reliability (every patch of every case):\n");
    calib_print(&reliability, stdout);
    calib_close_rows();
    return 0;
}
