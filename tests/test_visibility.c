/* Tests of the Borodin-style policies (VISIBILITY, AUTO), nested shells,
   UP, the ray caster and the weld. Prints "N passed, N failed". */
#undef NDEBUG
#define MESHFIX_IMPLEMENTATION
#include "../meshfix.h"
#define MESHIO_IMPLEMENTATION
#include "../examples/meshio.h"
#define MESHGEN_IMPLEMENTATION
#include "../examples/meshgen.h"
#define SCENES_IMPLEMENTATION
#include "scenes.h"

#include "check.h"
#include <pthread.h>
#include "internals.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *models_dir(void)
{
    const char *dir = getenv("MESHFIX_MODELS");
    return dir != NULL ? dir : "/usr/share/assimp/models";
}

static void flip(unsigned int *indices, size_t t)
{
    unsigned int x = indices[3 * t + 1];
    indices[3 * t + 1] = indices[3 * t + 2];
    indices[3 * t + 2] = x;
}

static double triangle_area(const mio_mesh *g, size_t t)
{
    const float *a = g->positions + 3 * (size_t)g->indices[3 * t], *b = g->positions + 3 * (size_t)g->indices[3 * t + 1];
    const float *c = g->positions + 3 * (size_t)g->indices[3 * t + 2];
    double u[3], v[3], n[3];
    int k;
    for (k = 0; k < 3; ++k)
        u[k] = (double)b[k] - a[k], v[k] = (double)c[k] - a[k];
    n[0] = u[1] * v[2] - u[2] * v[1];
    n[1] = u[2] * v[0] - u[0] * v[2];
    n[2] = u[0] * v[1] - u[1] * v[0];
    return 0.5 * sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
}

/* ---- cutting a model into unwelded patches ---- */

/* Region growing from `count` seed triangles over shared edges (a
   breadth-first fill from all seeds at once); returns a cluster per
   triangle. Deterministic for a seed. */
static unsigned int *grow_clusters(const mio_mesh *g, size_t count, unsigned long long seed)
{
    size_t t, triangles = g->index_count / 3, head = 0, tail = 0, i, e;
    unsigned int *cluster = (unsigned int *)malloc(triangles * sizeof(unsigned int));
    unsigned int *queue = (unsigned int *)malloc(triangles * sizeof(unsigned int));
    /* edge -> triangles by a simple sorted list of (low, high, triangle) */
    unsigned long long *edges = (unsigned long long *)malloc(3 * triangles * sizeof(unsigned long long) * 2);
    size_t n = 0;
    for (t = 0; t < triangles; ++t)
        cluster[t] = 0xFFFFFFFFu;
    for (t = 0; t < triangles; ++t)
        for (e = 0; e < 3; ++e) {
            unsigned long long a = g->indices[3 * t + e], b = g->indices[3 * t + (e + 1) % 3];
            unsigned long long lo = a < b ? a : b, hi = a < b ? b : a;
            edges[2 * n] = (lo << 32) | hi;
            edges[2 * n + 1] = t;
            n++;
        }
    /* insertion-free sort: simple shell sort on pairs */
    {
        size_t gap, j;
        for (gap = n / 2; gap > 0; gap /= 2)
            for (i = gap; i < n; ++i) {
                unsigned long long k0 = edges[2 * i], k1 = edges[2 * i + 1];
                for (j = i; j >= gap && edges[2 * (j - gap)] > k0; j -= gap) {
                    edges[2 * j] = edges[2 * (j - gap)];
                    edges[2 * j + 1] = edges[2 * (j - gap) + 1];
                }
                edges[2 * j] = k0;
                edges[2 * j + 1] = k1;
            }
    }
    for (i = 0; i < count; ++i) {
        size_t s = (size_t)(gen_random(&seed) % triangles);
        if (cluster[s] == 0xFFFFFFFFu) {
            cluster[s] = (unsigned int)i;
            queue[tail++] = (unsigned int)s;
        }
    }
    while (head < tail) {
        unsigned int cur = queue[head++];
        for (e = 0; e < 3; ++e) {
            unsigned long long a = g->indices[3 * cur + e], b = g->indices[3 * cur + (e + 1) % 3];
            unsigned long long key = ((a < b ? a : b) << 32) | (a < b ? b : a);
            size_t lo = 0, hi = n;
            while (lo < hi) {
                size_t mid = (lo + hi) / 2;
                if (edges[2 * mid] < key)
                    lo = mid + 1;
                else
                    hi = mid;
            }
            for (; lo < n && edges[2 * lo] == key; ++lo) {
                unsigned int u = (unsigned int)edges[2 * lo + 1];
                if (cluster[u] == 0xFFFFFFFFu) {
                    cluster[u] = cluster[cur];
                    queue[tail++] = u;
                }
            }
        }
    }
    for (t = 0; t < triangles; ++t) /* anything unreached (another component) is its own cluster */
        if (cluster[t] == 0xFFFFFFFFu)
            cluster[t] = (unsigned int)(count + t);
    free(queue);
    free(edges);
    return cluster;
}

/* A cut model: every cluster has its own copy of its vertices (no index
   is shared across a seam), each copy moved `gap` of the way toward its
   cluster's centroid so the seams open. `second` records, per triangle,
   the corner that follows the first one in the reference winding (flips
   keep the first corner), so outward_share can score any result. */
typedef struct cut {
    mio_mesh mesh;
    unsigned int *second;
    unsigned int *cluster;
    size_t clusters;
} cut;

static void cut_model(const mio_mesh *g, size_t clusters, float gap, double inside, unsigned long long seed, cut *out)
{
    size_t t, c, k, triangles = g->index_count / 3, size = 1, mask, used = 0;
    unsigned long long *keys;
    unsigned int *values;
    double *centroid;
    size_t *count;
    out->cluster = grow_clusters(g, clusters, seed);
    out->clusters = 0;
    for (t = 0; t < triangles; ++t)
        out->clusters = out->cluster[t] + 1 > out->clusters ? out->cluster[t] + 1 : out->clusters;
    centroid = (double *)calloc(3 * out->clusters, sizeof(double));
    count = (size_t *)calloc(out->clusters, sizeof(size_t));
    for (t = 0; t < triangles; ++t)
        for (c = 0; c < 3; ++c) {
            for (k = 0; k < 3; ++k)
                centroid[3 * out->cluster[t] + k] += g->positions[3 * (size_t)g->indices[3 * t + c] + k];
            count[out->cluster[t]]++;
        }
    while (size < 4 * g->index_count)
        size *= 2;
    mask = size - 1;
    keys = (unsigned long long *)malloc(size * sizeof(unsigned long long));
    values = (unsigned int *)malloc(size * sizeof(unsigned int));
    for (k = 0; k < size; ++k)
        keys[k] = ~0ull;
    out->mesh.positions = (float *)malloc(3 * g->index_count * sizeof(float));
    out->mesh.indices = (unsigned int *)malloc(g->index_count * sizeof(unsigned int));
    out->mesh.index_count = g->index_count;
    for (t = 0; t < triangles; ++t)
        for (c = 0; c < 3; ++c) {
            unsigned int v = g->indices[3 * t + c], cl = out->cluster[t];
            unsigned long long key = ((unsigned long long)cl << 32) | v;
            size_t i = (size_t)((key * 0x9E3779B97F4A7C15ull) >> 17) & mask;
            while (keys[i] != ~0ull && keys[i] != key)
                i = (i + 1) & mask;
            if (keys[i] == ~0ull) {
                keys[i] = key;
                values[i] = (unsigned int)used;
                for (k = 0; k < 3; ++k) {
                    double p = g->positions[3 * (size_t)v + k], mid = centroid[3 * cl + k] / (double)count[cl];
                    out->mesh.positions[3 * used + k] = (float)(p + (mid - p) * gap);
                }
                used++;
            }
            out->mesh.indices[3 * t + c] = values[i];
        }
    out->mesh.vertex_count = used;
    out->second = (unsigned int *)malloc(triangles * sizeof(unsigned int));
    for (t = 0; t < triangles; ++t)
        out->second[t] = out->mesh.indices[3 * t + 1];
    /* half of the patches reversed, and `inside` of the triangles at random */
    for (t = 0; t < triangles; ++t) {
        unsigned long long h = ((unsigned long long)out->cluster[t] + 1) * 0x9E3779B97F4A7C15ull;
        int reverse_patch = (int)((h >> 45) & 1);
        if (reverse_patch ^ (gen_uniform(&seed) < inside))
            flip(out->mesh.indices, t);
    }
    free(keys);
    free(values);
    free(centroid);
    free(count);
}

static void free_cut(cut *c)
{
    mio_free(&c->mesh);
    free(c->second);
    free(c->cluster);
}

/* The share of area wound as the reference winds it. */
static double outward_share(const cut *c, const unsigned int *result)
{
    size_t t;
    double same = 0, total = 0;
    mio_mesh view = c->mesh;
    view.indices = (unsigned int *)result;
    for (t = 0; t < c->mesh.index_count / 3; ++t) {
        double a = triangle_area(&view, t);
        total += a;
        same += result[3 * t + 1] == c->second[t] ? a : 0;
    }
    return total > 0 ? same / total : 0;
}

/* ---- closed models cut into patches ---- */

/* Repairs a cut model with `policy`; returns the outward share of area. */
static double repair_cut(const cut *c, meshfix_policy policy, unsigned int flags, meshfix_report *r)
{
    meshfix_options o;
    unsigned int *out = (unsigned int *)malloc(c->mesh.index_count * sizeof(unsigned int));
    double share;
    memset(&o, 0, sizeof(o));
    o.policy = policy;
    o.visibility.flags = flags;
    CHECK_EQ(meshfix_orient(out, c->mesh.indices, c->mesh.index_count, c->mesh.positions, c->mesh.vertex_count, 12,
                            &o, r, NULL),
             MESHFIX_OK);
    share = outward_share(c, out);
    free(out);
    return share;
}

/* The closed parts of a real model, wound outward by meshfix itself (the
   files are not all consistent), as the reference. */
static int load_closed_reference(const char *file, mio_mesh *g)
{
    char path[512], error[256];
    meshfix_report r;
    snprintf(path, sizeof(path), "%s/%s", models_dir(), file);
    if (!mio_load(path, g, error, sizeof(error))) {
        printf("    cannot load %s: %s (install Debian's assimp-testmodels)\n", path, error);
        return 0;
    }
    return meshfix_orient(g->indices, g->indices, g->index_count, g->positions, g->vertex_count, 12, NULL, &r, NULL) ==
           MESHFIX_OK;
}

static void check_cut(const char *name, const mio_mesh *g, size_t clusters)
{
    cut c;
    meshfix_report r;
    double share;
    cut_model(g, clusters, 0.002f, 0.2, 77, &c);
    CHECK_EQ(meshfix_inspect(c.mesh.indices, c.mesh.index_count, c.mesh.positions, c.mesh.vertex_count, 12, NULL, &r, NULL),
             MESHFIX_OK);
    share = repair_cut(&c, MESHFIX_POLICY_VISIBILITY, 0, &r);
    printf("    %s in %lu patches (%lu triangles): %.4f%% of the area outward; %lu rays, %lu pairs, %lu merges\n",
           name, (unsigned long)r.mesh.patches, (unsigned long)r.mesh.triangles, 100 * share, (unsigned long)r.evidence.rays_cast,
           (unsigned long)r.evidence.patch_pairs, (unsigned long)r.evidence.patches_merged);
    CHECK(r.mesh.patches >= clusters / 2);
    CHECK(share >= 0.999);
    CHECK_EQ(r.mesh.edges_inconsistent, 0);
    share = repair_cut(&c, MESHFIX_POLICY_AUTO, 0, &r);
    CHECK(share >= 0.999);
    free_cut(&c);
}

static void test_cut_generated(void)
{
    mio_mesh g, t;
    CHECK(gen_sphere(&g, 40, 60, 0, 0, 0, 1));
    check_cut("sphere", &g, 60);
    mio_free(&g);
    CHECK(gen_torus(&g, 80, 30, 2, 0.6f));
    check_cut("torus", &g, 120);
    mio_free(&g);
    CHECK(gen_sphere(&g, 30, 40, 0, 0, 0, 1));
    CHECK(gen_torus(&t, 60, 20, 3.5f, 0.5f));
    CHECK(gen_append(&g, &t));
    check_cut("sphere and torus", &g, 300);
    mio_free(&g);
    mio_free(&t);
}

static void test_cut_real(void)
{
    static const char *files[] = {"OBJ/spider.obj", "OBJ/empty_mat.obj", "STL/Spider_binary.stl"};
    size_t f;
    for (f = 0; f < sizeof(files) / sizeof(files[0]); ++f) {
        mio_mesh g;
        if (!load_closed_reference(files[f], &g)) {
            failures++;
            continue;
        }
        check_cut(files[f], &g, f == 1 ? 20 : 150);
        mio_free(&g);
    }
}


/* ---- open sheets ---- */

/* A windshield: a quarter of a cylinder, 1.2 wide, open on all sides. */
static void make_windshield(mio_mesh *g)
{
    size_t v;
    gen_grid(g, 60, 30);
    for (v = 0; v < g->vertex_count; ++v) {
        float *p = g->positions + 3 * v, angle = (p[0] - 0.5f) * 1.6f;
        float x = 2.0f * sinf(angle), z = 2.0f * cosf(angle) - 2.0f;
        p[0] = x, p[2] = z, p[1] = p[1] * 1.2f;
    }
}

static int consistent(double share)
{
    return share >= 0.999 || share <= 0.001;
}

static void test_open_sheets(void)
{
    mio_mesh g;
    cut c;
    meshfix_report r;
    double share;
    make_windshield(&g);
    cut_model(&g, 30, 0.002f, 0.2, 5, &c);
    share = repair_cut(&c, MESHFIX_POLICY_VISIBILITY, 0, &r);
    printf("    windshield in %lu patches: %.4f%% wound like the reference\n", (unsigned long)r.mesh.patches, 100 * share);
    CHECK(consistent(share));
    CHECK(repair_cut(&c, MESHFIX_POLICY_AUTO, 0, &r) == share);
    free_cut(&c);
    mio_free(&g);

    /* a terrain: UP makes every patch face up, the visibility policy one way */
    CHECK(gen_grid(&g, 80, 80));
    cut_model(&g, 40, 0.002f, 0.2, 6, &c);
    share = repair_cut(&c, MESHFIX_POLICY_UP, 0, &r);
    CHECK(share >= 0.999);
    share = repair_cut(&c, MESHFIX_POLICY_VISIBILITY, 0, &r);
    printf("    terrain in %lu patches: UP all up; VISIBILITY %.4f%% like the reference\n", (unsigned long)r.mesh.patches,
           100 * share);
    CHECK(consistent(share));
    free_cut(&c);
    mio_free(&g);
}

/* Each criterion alone fails somewhere; together they do not (the paper's
   figures 8 and 9). Coherence alone makes a cut torus consistent but has
   no outside to go by: the majority of the scrambled input wins, inside
   out. Visibility alone decides each patch of a gently waving terrain by
   itself, and both sides of a sheet see the sky: patches disagree. */
static void test_both_criteria_needed(void)
{
    mio_mesh g;
    cut c;
    meshfix_report r;
    double both, coherence, visibility;
    CHECK(gen_torus(&g, 80, 30, 2, 0.6f));
    cut_model(&g, 120, 0.002f, 0.2, 77, &c);
    both = repair_cut(&c, MESHFIX_POLICY_VISIBILITY, 0, &r);
    coherence = repair_cut(&c, MESHFIX_POLICY_VISIBILITY, MESHFIX_VISIBILITY_COHERENCE_ONLY, &r);
    printf("    torus: both %.4f%%, coherence only %.4f%% outward\n", 100 * both, 100 * coherence);
    CHECK(both >= 0.999);
    CHECK(coherence < 0.999);
    CHECK(consistent(coherence)); /* consistent, just the wrong way */
    free_cut(&c);
    mio_free(&g);

    CHECK(gen_grid(&g, 80, 80));
    cut_model(&g, 60, 0.002f, 0.2, 8, &c);
    both = repair_cut(&c, MESHFIX_POLICY_VISIBILITY, 0, &r);
    visibility = repair_cut(&c, MESHFIX_POLICY_VISIBILITY, MESHFIX_VISIBILITY_ONLY, &r);
    printf("    terrain: both %.4f%%, visibility only %.4f%% like the reference\n", 100 * both, 100 * visibility);
    CHECK(consistent(both));
    CHECK(!consistent(visibility));
    free_cut(&c);
    mio_free(&g);
}

/* ---- nested shells ---- */

static void reverse_range(mio_mesh *g, size_t first, size_t count)
{
    size_t t;
    for (t = first; t < first + count; ++t)
        flip(g->indices, t);
}

/* outer sphere out, a cavity in it facing in, an island in the cavity out */
static void make_nested(mio_mesh *g, size_t *first_cavity, size_t *first_island)
{
    mio_mesh cavity, island;
    gen_sphere(g, 24, 32, 0, 0, 0, 3);
    gen_sphere(&cavity, 20, 28, 0, 0, 0, 2);
    gen_sphere(&island, 16, 24, 0.2f, 0, 0, 1);
    *first_cavity = g->index_count / 3;
    gen_append(g, &cavity);
    *first_island = g->index_count / 3;
    gen_append(g, &island);
    reverse_range(g, *first_cavity, *first_island - *first_cavity);
    mio_free(&cavity);
    mio_free(&island);
}

static void test_nested_shells(void)
{
    mio_mesh g;
    size_t cavity, island;
    unsigned int *reference, *out;
    meshfix_report r;
    meshfix_options o;
    int policy;
    make_nested(&g, &cavity, &island);
    reference = (unsigned int *)malloc(g.index_count * sizeof(unsigned int));
    out = (unsigned int *)malloc(g.index_count * sizeof(unsigned int));
    memcpy(reference, g.indices, g.index_count * sizeof(unsigned int));
    gen_flip_random(&g, 0.4, 3, NULL);
    reverse_range(&g, 0, cavity); /* and the outer one mostly inside out */
    for (policy = MESHFIX_POLICY_AUTO; policy <= MESHFIX_POLICY_OUTWARD; policy += MESHFIX_POLICY_OUTWARD) {
        memset(&o, 0, sizeof(o));
        o.policy = (meshfix_policy)policy;
        CHECK_EQ(meshfix_orient(out, g.indices, g.index_count, g.positions, g.vertex_count, 12, &o, &r, NULL), MESHFIX_OK);
        CHECK(memcmp(out, reference, g.index_count * sizeof(unsigned int)) == 0);
        CHECK_EQ(r.evidence.shells_inward, 1);
    }
    free(reference);
    free(out);
    mio_free(&g);
}

/* The outer shell cut into unwelded patches with gaps: no closed outer
   shell any more, yet the cavity stays inward (rays from it still cross
   the outer patches an odd number of times, except through the gaps). */
static void test_cavity_in_open_shell(void)
{
    mio_mesh outer, inner, island;
    cut c;
    meshfix_options o;
    meshfix_report r;
    unsigned int *out;
    size_t t, first_inner, outer_triangles;
    double share;
    CHECK(gen_sphere(&outer, 30, 40, 0, 0, 0, 3));
    cut_model(&outer, 40, 0.002f, 0.2, 12, &c);
    outer_triangles = c.mesh.index_count / 3;
    gen_sphere(&inner, 20, 28, 0, 0, 0, 2);
    gen_sphere(&island, 16, 24, 0.2f, 0, 0, 1);
    reverse_range(&inner, 0, inner.index_count / 3); /* the cavity's reference: inward */
    first_inner = c.mesh.index_count / 3;
    gen_append(&c.mesh, &inner);
    gen_append(&c.mesh, &island);
    c.second = (unsigned int *)realloc(c.second, c.mesh.index_count / 3 * sizeof(unsigned int));
    for (t = first_inner; t < c.mesh.index_count / 3; ++t)
        c.second[t] = c.mesh.indices[3 * t + 1];
    {
        unsigned long long seed = 4;
        for (t = first_inner; t < c.mesh.index_count / 3; ++t)
            if (gen_uniform(&seed) < 0.5)
                flip(c.mesh.indices, t);
    }
    out = (unsigned int *)malloc(c.mesh.index_count * sizeof(unsigned int));
    memset(&o, 0, sizeof(o));
    CHECK_EQ(meshfix_orient(out, c.mesh.indices, c.mesh.index_count, c.mesh.positions, c.mesh.vertex_count, 12, &o, &r, NULL),
             MESHFIX_OK);
    share = outward_share(&c, out);
    printf("    outer shell in %lu open patches with gaps, cavity, island: %.4f%% as the reference\n",
           (unsigned long)(r.mesh.patches - 2), 100 * share);
    CHECK(share >= 0.999);
    CHECK_EQ(r.evidence.shells_inward, 1);
    (void)outer_triangles;
    free(out);
    free_cut(&c);
    mio_free(&outer);
    mio_free(&inner);
    mio_free(&island);
}

/* A glass sphere with two overlapping balls inside: the balls cross each
   other, so neither is a cavity; all three face out. */
static void test_intersecting_shells(void)
{
    mio_mesh g, a, b;
    meshfix_report r;
    unsigned int *reference;
    CHECK(gen_sphere(&g, 24, 32, 0, 0, 0, 3));
    CHECK(gen_sphere(&a, 16, 24, -0.5f, 0, 0, 1));
    CHECK(gen_sphere(&b, 16, 24, 0.6f, 0.1f, 0, 1));
    gen_append(&g, &a);
    gen_append(&g, &b);
    reference = (unsigned int *)malloc(g.index_count * sizeof(unsigned int));
    memcpy(reference, g.indices, g.index_count * sizeof(unsigned int));
    gen_flip_random(&g, 0.6, 10, NULL);
    CHECK_EQ(meshfix_orient(g.indices, g.indices, g.index_count, g.positions, g.vertex_count, 12, NULL, &r, NULL), MESHFIX_OK);
    CHECK(memcmp(g.indices, reference, g.index_count * sizeof(unsigned int)) == 0);
    CHECK_EQ(r.evidence.shells_inward, 0);
    free(reference);
    mio_free(&g);
    mio_free(&a);
    mio_free(&b);
}

static void test_mobius(void)
{
    mio_mesh g;
    meshfix_report r;
    meshfix_options o;
    int policy;
    CHECK(gen_mobius(&g, 40));
    gen_flip_random(&g, 0.5, 2, NULL);
    for (policy = 0; policy < 2; ++policy) {
        memset(&o, 0, sizeof(o));
        o.policy = policy ? MESHFIX_POLICY_VISIBILITY : MESHFIX_POLICY_AUTO;
        CHECK_EQ(meshfix_orient(g.indices, g.indices, g.index_count, g.positions, g.vertex_count, 12, &o, &r, NULL),
                 MESHFIX_OK);
        CHECK_EQ(r.mesh.components_non_orientable, 1);
        CHECK(r.mesh.edges_inconsistent >= 1 && r.mesh.edges_inconsistent <= 2);
    }
    mio_free(&g);
}

/* ---- independence of triangle order and of how much was flipped ---- */

static void test_order_and_flip_independence(void)
{
    mio_mesh g;
    cut c;
    meshfix_report r;
    unsigned int *out, *shuffled, *back, *perm;
    size_t t, n;
    unsigned long long seed = 99;
    double share;
    int f;
    CHECK(gen_sphere(&g, 40, 60, 0, 0, 0, 1));
    cut_model(&g, 80, 0.002f, 0.2, 21, &c);
    n = c.mesh.index_count / 3;
    out = (unsigned int *)malloc(3 * n * sizeof(unsigned int));
    shuffled = (unsigned int *)malloc(3 * n * sizeof(unsigned int));
    back = (unsigned int *)malloc(3 * n * sizeof(unsigned int));
    perm = (unsigned int *)malloc(n * sizeof(unsigned int));
    CHECK_EQ(meshfix_orient(out, c.mesh.indices, 3 * n, c.mesh.positions, c.mesh.vertex_count, 12, NULL, &r, NULL), MESHFIX_OK);
    for (t = 0; t < n; ++t)
        perm[t] = (unsigned int)t;
    for (t = n - 1; t > 0; --t) {
        size_t j = (size_t)(gen_random(&seed) % (t + 1));
        unsigned int x = perm[t];
        perm[t] = perm[j];
        perm[j] = x;
    }
    for (t = 0; t < n; ++t)
        memcpy(shuffled + 3 * t, c.mesh.indices + 3 * perm[t], 3 * sizeof(unsigned int));
    CHECK_EQ(meshfix_orient(shuffled, shuffled, 3 * n, c.mesh.positions, c.mesh.vertex_count, 12, NULL, &r, NULL), MESHFIX_OK);
    for (t = 0; t < n; ++t)
        memcpy(back + 3 * perm[t], shuffled + 3 * t, 3 * sizeof(unsigned int));
    CHECK(memcmp(back, out, 3 * n * sizeof(unsigned int)) == 0);
    /* other amounts of flipping inside the patches: the same result */
    for (f = 0; f < 3; ++f) {
        unsigned long long s2 = 500 + (unsigned long long)f;
        memcpy(shuffled, c.mesh.indices, 3 * n * sizeof(unsigned int));
        for (t = 0; t < n; ++t)
            if (gen_uniform(&s2) < 0.3 * f)
                flip(shuffled, t);
        CHECK_EQ(meshfix_orient(shuffled, shuffled, 3 * n, c.mesh.positions, c.mesh.vertex_count, 12, NULL, &r, NULL),
                 MESHFIX_OK);
        CHECK(memcmp(shuffled, out, 3 * n * sizeof(unsigned int)) == 0);
    }
    share = outward_share(&c, out);
    CHECK(share >= 0.999);
    free(out);
    free(shuffled);
    free(back);
    free(perm);
    free_cut(&c);
    mio_free(&g);
}

/* ---- parallel_for: bit-identical ---- */

static void backwards_parallel_for(void (*task)(void *, size_t), void *context, size_t count, void *user)
{
    size_t i;
    (*(int *)user)++;
    for (i = count; i-- > 0;)
        task(context, i);
}

/* A real pool: `threads` threads, thread t runs tasks t, t + threads, ... */
typedef struct thread_pool_job {
    void (*task)(void *, size_t);
    void *context;
    size_t count, first, step;
} thread_pool_job;

static void *thread_pool_run(void *argument)
{
    thread_pool_job *job = (thread_pool_job *)argument;
    size_t i;
    for (i = job->first; i < job->count; i += job->step)
        job->task(job->context, i);
    return NULL;
}

static void threaded_parallel_for(void (*task)(void *, size_t), void *context, size_t count, void *user)
{
    enum { MOST = 8 };
    size_t threads = *(const size_t *)user, t;
    pthread_t ids[MOST];
    int started[MOST];
    thread_pool_job jobs[MOST];
    threads = threads < MOST ? threads : MOST;
    for (t = 0; t < threads; ++t) {
        jobs[t].task = task, jobs[t].context = context, jobs[t].count = count, jobs[t].first = t, jobs[t].step = threads;
        started[t] = pthread_create(&ids[t], NULL, thread_pool_run, &jobs[t]) == 0;
        if (!started[t])
            thread_pool_run(&jobs[t]); /* no thread to be had: this one does it */
    }
    for (t = 0; t < threads; ++t)
        if (started[t])
            pthread_join(ids[t], NULL);
}

/* AUTO on scenes of many units (trees built and evidence gathered as
   tasks) with 2 and 4 real threads: the result of the single-threaded
   run, bit for bit. */
/* A unit large enough that its own tree is built on every thread
   (MESHFIX__PARALLEL_UNIT triangles and more) and boundary segments for
   many partner-search chunks: a 152k-triangle sphere cut into 32 patches
   with gaps, half of them reversed. */
static void test_threads_large_unit(void)
{
    mio_mesh whole, pieces;
    unsigned int *patch_of, *single, *multi;
    unsigned char *truth;
    meshfix_report r1, r2;
    size_t threads, t;
    memset(&whole, 0, sizeof(whole));
    memset(&pieces, 0, sizeof(pieces));
    CHECK(gen_sphere(&whole, 200, 380, 0, 0, 0, 1));
    patch_of = (unsigned int *)malloc(whole.index_count / 3 * sizeof(unsigned int));
    truth = (unsigned char *)malloc(whole.index_count / 3);
    CHECK(gen_cut(&pieces, patch_of, &whole, 32, 0.01f, 3) == 32);
    CHECK(pieces.index_count / 3 >= 2 * MESHFIX__PARALLEL_UNIT);
    for (t = 0; t < pieces.index_count / 3; ++t)
        truth[t] = 1;
    gen_reverse_patches(&pieces, truth, patch_of, 0.5, 11);
    single = (unsigned int *)malloc(pieces.index_count * sizeof(unsigned int));
    multi = (unsigned int *)malloc(pieces.index_count * sizeof(unsigned int));
    CHECK_EQ(meshfix_orient(single, pieces.indices, pieces.index_count, pieces.positions, pieces.vertex_count, 0, NULL, &r1, NULL),
             MESHFIX_OK);
    for (threads = 2; threads <= 4; threads += 2) {
        meshfix_options o = {0};
        o.parallel_for = threaded_parallel_for;
        o.parallel_user = &threads;
        CHECK_EQ(meshfix_orient(multi, pieces.indices, pieces.index_count, pieces.positions, pieces.vertex_count, 0, &o, &r2, NULL),
                 MESHFIX_OK);
        CHECK(memcmp(single, multi, pieces.index_count * sizeof(unsigned int)) == 0);
        CHECK(memcmp(&r1, &r2, sizeof(r1)) == 0);
    }
    printf("    %lu-triangle cut sphere: %lu flipped, the same on 1, 2 and 4 threads\n",
           (unsigned long)(pieces.index_count / 3), (unsigned long)r1.triangles_flipped);
    CHECK(r1.triangles_flipped > 0);
    free(single), free(multi), free(patch_of), free(truth);
    mio_free(&whole);
    mio_free(&pieces);
}

static void test_threads_identical(void)
{
    static const char *const names[] = {"assembly", "parts", "glass", "cavity_cut"};
    size_t n, threads;
    for (n = 0; n < sizeof(names) / sizeof(names[0]); ++n) {
        scene sc;
        scene_trial t;
        unsigned int *single, *multi;
        meshfix_report r1, r2;
        CHECK(scene_build(&sc, names[n], SCENE_SMALL) == 1);
        CHECK(scene_trial_make(&t, &sc, &SCENE_CORRUPTIONS[4], 9));
        single = (unsigned int *)malloc(t.mesh.index_count * sizeof(unsigned int));
        multi = (unsigned int *)malloc(t.mesh.index_count * sizeof(unsigned int));
        CHECK_EQ(meshfix_orient(single, t.mesh.indices, t.mesh.index_count, t.mesh.positions, t.mesh.vertex_count, 0,
                                NULL, &r1, NULL),
                 MESHFIX_OK);
        for (threads = 2; threads <= 4; threads += 2) {
            meshfix_options o = {0};
            o.parallel_for = threaded_parallel_for;
            o.parallel_user = &threads;
            CHECK_EQ(meshfix_orient(multi, t.mesh.indices, t.mesh.index_count, t.mesh.positions, t.mesh.vertex_count,
                                    0, &o, &r2, NULL),
                     MESHFIX_OK);
            CHECK(memcmp(single, multi, t.mesh.index_count * sizeof(unsigned int)) == 0);
            CHECK(memcmp(&r1, &r2, sizeof(r1)) == 0);
        }
        CHECK(r1.triangles_flipped > 0);
        free(single), free(multi);
        scene_trial_free(&t);
        scene_free(&sc);
    }
    test_threads_large_unit();
}

static void test_parallel_for_identical(void)
{
    mio_mesh g;
    cut c;
    meshfix_options o;
    meshfix_outputs outputs;
    meshfix_report r1, r2;
    float conf1[512], conf2[512];
    unsigned int *a, *b;
    int calls = 0;
    CHECK(gen_torus(&g, 60, 24, 2, 0.6f));
    cut_model(&g, 90, 0.002f, 0.3, 31, &c);
    a = (unsigned int *)malloc(c.mesh.index_count * sizeof(unsigned int));
    b = (unsigned int *)malloc(c.mesh.index_count * sizeof(unsigned int));
    memset(&o, 0, sizeof(o));
    memset(&outputs, 0, sizeof(outputs));
    o.policy = MESHFIX_POLICY_VISIBILITY;
    outputs.patch_confidence = conf1;
    outputs.patch_confidence_capacity = 512;
    CHECK_EQ(meshfix_orient(a, c.mesh.indices, c.mesh.index_count, c.mesh.positions, c.mesh.vertex_count, 12, &o, &r1, &outputs),
             MESHFIX_OK);
    o.parallel_for = backwards_parallel_for;
    o.parallel_user = &calls;
    outputs.patch_confidence = conf2;
    CHECK_EQ(meshfix_orient(b, c.mesh.indices, c.mesh.index_count, c.mesh.positions, c.mesh.vertex_count, 12, &o, &r2, &outputs),
             MESHFIX_OK);
    CHECK(calls >= 1); /* the visibility stage's; below MESHFIX__PARALLEL_UNIT, the stages in chunks call it too */
    CHECK(memcmp(a, b, c.mesh.index_count * sizeof(unsigned int)) == 0);
    CHECK(memcmp(&r1, &r2, sizeof(r1)) == 0);
    CHECK(memcmp(conf1, conf2, r1.mesh.patches * sizeof(float)) == 0);
    CHECK(r1.mesh.patches < 512);
    {
        size_t p;
        for (p = 0; p < r1.mesh.patches; ++p)
            CHECK(conf1[p] >= 0.0f && conf1[p] <= 1.0f);
    }
    free(a);
    free(b);
    free_cut(&c);
    mio_free(&g);
}

/* The stages before and after the decision (the join, the edges, the
   flood fill, the sums, the write) and the coherence stage on chunks of
   MESHFIX__PARALLEL_UNIT triangles, segments or pairs and more: on 2 and 4 real threads and in reverse order, what
   one thread gives, bit for bit, written in place or not. A Moebius strip
   (a seam: the fill runs again in order), a shuffled sphere (every chunk
   joins the others), a soup (every corner joined), 16-bit indices,
   TOPOLOGY_INDICES and no positions. */
static void same_on_threads(const char *name, const mio_mesh *g, const float *positions, meshfix_options o)
{
    size_t n = g->index_count / 3, threads, i, mode;
    unsigned int *single = (unsigned int *)malloc(g->index_count * sizeof(unsigned int) + 4);
    unsigned int *multi = (unsigned int *)malloc(g->index_count * sizeof(unsigned int) + 4);
    unsigned int *ids1 = (unsigned int *)malloc(n * sizeof(unsigned int)), *ids2 = (unsigned int *)malloc(n * sizeof(unsigned int));
    unsigned char *flipped1 = (unsigned char *)malloc(n), *flipped2 = (unsigned char *)malloc(n);
    const void *indices = g->indices;
    unsigned short *narrow = NULL;
    size_t index_bytes = o.index_size == 2 ? 2 : 4;
    meshfix_outputs out1, out2;
    meshfix_report r1, r2;
    int calls = 0;
    if (o.index_size == 2) {
        narrow = (unsigned short *)malloc(g->index_count * sizeof(unsigned short));
        for (i = 0; i < g->index_count; ++i)
            narrow[i] = (unsigned short)g->indices[i];
        indices = narrow;
    }
    memset(&out1, 0, sizeof(out1));
    out1.patch_ids = ids1;
    out1.flipped = flipped1;
    out2 = out1;
    out2.patch_ids = ids2;
    out2.flipped = flipped2;
    CHECK_EQ(meshfix_orient(single, indices, g->index_count, positions, g->vertex_count, 12, &o, &r1, &out1), MESHFIX_OK);
    for (mode = 0; mode < 4; ++mode) {
        meshfix_options t = o;
        void *destination = multi;
        threads = mode == 0 ? 2 : 4;
        t.parallel_for = mode < 2 ? threaded_parallel_for : backwards_parallel_for;
        t.parallel_user = mode < 2 ? (void *)&threads : (void *)&calls;
        if (mode == 3) { /* in place */
            memcpy(multi, indices, g->index_count * index_bytes);
            destination = multi;
            indices = multi;
        }
        memset(ids2, 0xAB, n * sizeof(unsigned int));
        memset(flipped2, 0xAB, n);
        CHECK_EQ(meshfix_orient(destination, indices, g->index_count, positions, g->vertex_count, 12, &t, &r2, &out2),
                 MESHFIX_OK);
        CHECK(memcmp(single, multi, g->index_count * index_bytes) == 0);
        CHECK(memcmp(&r1, &r2, sizeof(r1)) == 0);
        CHECK(memcmp(ids1, ids2, n * sizeof(unsigned int)) == 0);
        CHECK(memcmp(flipped1, flipped2, n) == 0);
        if (mode == 3)
            indices = narrow != NULL ? (const void *)narrow : (const void *)g->indices;
    }
    CHECK(calls > 2);
    printf("    %s: %lu triangles, %lu patches, %lu flipped, the same on 1, 2 and 4 threads\n", name,
           (unsigned long)n, (unsigned long)r1.mesh.patches, (unsigned long)r1.triangles_flipped);
    free(single), free(multi), free(ids1), free(ids2), free(flipped1), free(flipped2), free(narrow);
}

static void test_threads_stages(void)
{
    mio_mesh g, soup;
    meshfix_options o;
    memset(&g, 0, sizeof(g));
    memset(&o, 0, sizeof(o));
    CHECK(gen_mobius(&g, MESHFIX__PARALLEL_UNIT / 2 + 500));
    gen_flip_random(&g, 0.3, 5, NULL);
    same_on_threads("Moebius strip", &g, g.positions, o);
    o.policy = MESHFIX_POLICY_MAJORITY;
    same_on_threads("Moebius strip, MAJORITY, no positions", &g, NULL, o);
    mio_free(&g);

    memset(&g, 0, sizeof(g));
    CHECK(gen_sphere(&g, 180, 200, 0, 0, 0, 1));
    CHECK(g.index_count / 3 >= MESHFIX__PARALLEL_UNIT && g.vertex_count < 65536);
    CHECK(gen_shuffle(&g, NULL, NULL, 7));
    gen_flip_random(&g, 0.3, 9, NULL);
    o.policy = MESHFIX_POLICY_AUTO;
    same_on_threads("shuffled sphere", &g, g.positions, o);
    o.index_size = 2;
    same_on_threads("shuffled sphere, 16-bit indices", &g, g.positions, o);
    o.index_size = 0;
    o.topology = MESHFIX_TOPOLOGY_INDICES;
    o.policy = MESHFIX_POLICY_SEED;
    same_on_threads("shuffled sphere, TOPOLOGY_INDICES, SEED", &g, g.positions, o);
    o.topology = MESHFIX_TOPOLOGY_POSITIONS;

    /* every triangle its own corners: the join makes the sphere again */
    CHECK(gen_soup(&soup, &g));
    o.policy = MESHFIX_POLICY_OUTWARD;
    same_on_threads("soup of the sphere", &soup, soup.positions, o);
    o.policy = MESHFIX_POLICY_MAJORITY;
    same_on_threads("soup of the sphere, no positions", &soup, NULL, o);
    free(soup.indices);
    free(soup.positions);
    mio_free(&g);

    /* the coherence stage on chunks (MESHFIX__PARALLEL_UNIT segments and
       pairs and more): a smaller sphere's soup with TOPOLOGY_INDICES, a
       patch per triangle, every edge a boundary segment whose partner is
       its neighbour's */
    memset(&g, 0, sizeof(g));
    CHECK(gen_sphere(&g, 100, 120, 0, 0, 0, 1));
    CHECK(g.index_count >= MESHFIX__PARALLEL_UNIT + 1000);
    CHECK(gen_soup(&soup, &g));
    gen_flip_random(&soup, 0.3, 5, NULL);
    memset(&o, 0, sizeof(o));
    o.topology = MESHFIX_TOPOLOGY_INDICES;
    same_on_threads("soup of a sphere, TOPOLOGY_INDICES (a patch per triangle), AUTO", &soup, soup.positions, o);
    free(soup.indices);
    free(soup.positions);
    mio_free(&g);
}

/* ---- weld ---- */

static void test_weld(void)
{
    mio_mesh g;
    size_t t, corners, unique;
    float *soup, nan_soup[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    unsigned int *remap, *indices, untouched[3] = {7, 7, 7};
    meshfix_report r;
    unsigned long long seed = 3;
    CHECK(gen_sphere(&g, 20, 30, 0, 0, 0, 1));
    corners = g.index_count;
    soup = (float *)malloc(3 * corners * sizeof(float));
    remap = (unsigned int *)malloc(corners * sizeof(unsigned int));
    indices = (unsigned int *)malloc(corners * sizeof(unsigned int));
    for (t = 0; t < corners; ++t)
        memcpy(soup + 3 * t, g.positions + 3 * (size_t)g.indices[t], 3 * sizeof(float));
    /* exact: the soup becomes the sphere again */
    CHECK_EQ(meshfix_weld(remap, soup, corners, 12, 0.0f, NULL, &unique), MESHFIX_OK);
    CHECK_EQ(unique, g.vertex_count);
    for (t = 0; t < corners; ++t)
        indices[t] = remap[t];
    CHECK_EQ(meshfix_inspect(indices, corners, soup, corners, 12, NULL, &r, NULL), MESHFIX_OK);
    CHECK_EQ(r.mesh.components, 1);
    CHECK_EQ(r.mesh.edges_boundary, 0);
    CHECK_EQ(r.mesh.euler_characteristic, 2);
    /* jittered corners: welded by a tolerance, not without one */
    for (t = 0; t < 3 * corners; ++t)
        soup[t] += (float)(gen_uniform(&seed) - 0.5) * 2e-5f;
    CHECK_EQ(meshfix_weld(remap, soup, corners, 12, 0.0f, NULL, &unique), MESHFIX_OK);
    CHECK_EQ(unique, corners);
    CHECK_EQ(meshfix_weld(remap, soup, corners, 12, 1e-3f, NULL, &unique), MESHFIX_OK);
    CHECK_EQ(unique, g.vertex_count);
    for (t = 0; t < corners; ++t)
        CHECK(remap[remap[t]] == remap[t] && remap[t] <= t);
    /* -0 welds to +0; NaN is refused and remap left alone */
    nan_soup[3] = -0.0f, nan_soup[0] = 0.0f, nan_soup[6] = 0.0f, nan_soup[4] = 0.0f;
    CHECK_EQ(meshfix_weld(untouched, nan_soup, 3, 12, 0.0f, NULL, &unique), MESHFIX_OK);
    CHECK_EQ(unique, 2);
    nan_soup[7] = (float)NAN;
    untouched[0] = untouched[1] = untouched[2] = 7;
    CHECK_EQ(meshfix_weld(untouched, nan_soup, 3, 12, 0.0f, NULL, &unique), MESHFIX_ERROR_NON_FINITE);
    CHECK(untouched[0] == 7 && untouched[1] == 7 && untouched[2] == 7);
    CHECK_EQ(meshfix_weld(untouched, nan_soup, 3, 8, 0.0f, NULL, &unique), MESHFIX_ERROR_INVALID_ARGUMENT);
    CHECK_EQ(meshfix_weld(untouched, nan_soup, 3, 12, -1.0f, NULL, &unique), MESHFIX_ERROR_INVALID_ARGUMENT);
    free(soup);
    free(remap);
    free(indices);
    mio_free(&g);
}

/* ---- the ray caster ---- */

/* Rays from the centre of a closed sphere aimed exactly at its vertices and
   edge midpoints: each crosses the surface exactly once (no leak through a
   shared vertex or edge, no double hit), at the right distance. */
static void test_watertight_rays(void)
{
    mio_mesh g;
    meshfix__mesh m;
    meshfix__bvh bvh;
    meshfix__arena arena;
    meshfix_options o;
    unsigned char *block;
    unsigned int *units, root;
    size_t v, t, bad = 0, rays = 0;
    CHECK(gen_sphere(&g, 18, 26, 0.1f, -0.2f, 0.3f, 1.5f));
    memset(&o, 0, sizeof(o));
    block = bind_mesh(&m, &o, g.indices, g.index_count, g.positions, g.vertex_count);
    units = (unsigned int *)calloc(g.index_count / 3, sizeof(unsigned int));
    root = whole_tree(&bvh, &m, &arena, units);
    CHECK(root != MESHFIX__NONE);
    /* rays in the tree's frame, where its corners are */
    for (v = 0; v < g.vertex_count + g.index_count; ++v) {
        const float model_centre[3] = {0.1f, -0.2f, 0.3f};
        float centre[3], target[3], d[3], a[3], b[3];
        meshfix__ray ray;
        meshfix__query q;
        int k;
        meshfix__frame_float(&bvh, model_centre, centre);
        if (v < g.vertex_count) {
            meshfix__frame_vertex(&bvh, &m, (unsigned int)v, target);
        } else {
            size_t h = v - g.vertex_count, next = h % 3 == 2 ? h - 2 : h + 1;
            meshfix__frame_vertex(&bvh, &m, g.indices[h], a);
            meshfix__frame_vertex(&bvh, &m, g.indices[next], b);
            for (k = 0; k < 3; ++k)
                target[k] = 0.5f * (a[k] + b[k]);
        }
        for (k = 0; k < 3; ++k)
            d[k] = target[k] - centre[k];
        meshfix__setup_ray(&ray, centre, d, 0.0f, 1e30f);
        q.mode = MESHFIX__COUNT_HITS;
        q.skip = MESHFIX__NONE;
        meshfix__trace(&bvh, root, &ray, &q);
        bad += q.hits != 1;
        q.mode = MESHFIX__CLOSEST_HIT;
        meshfix__trace(&bvh, root, &ray, &q);
        bad += !(q.hits == 1 && fabsf(q.t - 1.0f) < 1e-4f);
        rays++;
    }
    for (t = 0; t < 64; ++t) { /* from outside, pointing away: nothing */
        const float far_away[3] = {5, 5, 5}, away[3] = {1, 0.5f, 0.25f};
        float from[3];
        meshfix__ray ray;
        meshfix__query q;
        meshfix__frame_float(&bvh, far_away, from);
        meshfix__setup_ray(&ray, from, away, 0.0f, 1e30f);
        q.mode = MESHFIX__ANY_HIT;
        q.skip = MESHFIX__NONE;
        bad += meshfix__trace(&bvh, root, &ray, &q);
    }
    printf("    %lu rays through vertices and edges: %lu wrong\n", (unsigned long)rays, (unsigned long)bad);
    CHECK_EQ(bad, 0);
    free_arena(&arena);
    free(units);
    free(block);
    mio_free(&g);
}

/* A tree's structure: every slot in exactly one leaf, every corner inside
   the box its parent holds for it, at most one node per slot, and the
   depth within the traversal's bound. */
typedef struct tree_facts {
    unsigned char *seen;
    size_t nodes, deepest, outside;
} tree_facts;

static void walk_tree(const meshfix__bvh *b, unsigned int node, size_t depth, tree_facts *f)
{
    const meshfix__wide *n = &b->nodes[node];
    int c, k;
    f->nodes++;
    f->deepest = depth > f->deepest ? depth : f->deepest;
    for (c = 0; c < MESHFIX__WIDE; ++c) {
        unsigned int i;
        if (n->inner & (1u << c)) {
            walk_tree(b, n->child[c], depth + 1, f);
            continue;
        }
        if (!(n->leaves & (1u << c)))
            continue;
        for (i = n->child[c]; i < n->child[c] + n->count[c]; ++i) {
            f->seen[i]++;
            for (k = 0; k < 9; ++k)
                f->outside += !(b->corners[9 * i + k] >= n->bounds[k % 3][c] &&
                                b->corners[9 * i + k] <= n->bounds[3 + k % 3][c]);
        }
    }
}

/* A tree against brute force: random rays from inside the box (every
   other one aimed at a triangle's middle), each answered by the tree and
   by every triangle in turn, for the closest hit and the number of
   crossings; and the tree's structure. */
static void check_tree(const char *builder, const meshfix__bvh *bvh, unsigned int root, unsigned long long seed)
{
    size_t wrong = 0, slot, misplaced = 0, crossed = 0;
    unsigned int i;
    tree_facts facts;
    CHECK(root != MESHFIX__NONE);
    if (root == MESHFIX__NONE)
        return;
    facts.seen = (unsigned char *)calloc(bvh->count, 1);
    facts.nodes = facts.deepest = facts.outside = 0;
    walk_tree(bvh, root, 1, &facts);
    for (slot = 0; slot < bvh->count; ++slot)
        misplaced += facts.seen[slot] != 1;
    for (i = 0; i < 3000; ++i) {
        float from[3], d[3], t_brute = 1e30f;
        unsigned int hits_brute;
        meshfix__ray ray;
        meshfix__query q;
        meshfix__crossings crossings;
        const float *aim;
        int k;
        slot = (size_t)(gen_uniform(&seed) * bvh->count);
        aim = bvh->corners + 9 * slot;
        for (k = 0; k < 3; ++k) {
            from[k] = bvh->low[k] + (float)gen_uniform(&seed) * (bvh->high[k] - bvh->low[k]);
            d[k] = i % 2 ? (aim[k] + aim[3 + k] + aim[6 + k]) / 3.0f - from[k] : (float)gen_uniform(&seed) - 0.5f;
        }
        meshfix__setup_ray(&ray, from, d, 0.0f, 1e30f);
        crossings.halves = crossings.vertex_count = 0;
        for (slot = 0; slot < bvh->count; ++slot) {
            /* the leaves' own test, one slot at a time: the same float
               operations even where -ffast-math reorders the scalar test */
            float hit_t[MESHFIX__WIDE];
            int zeros[MESHFIX__WIDE];
            unsigned int lane = (unsigned int)(slot % MESHFIX__WIDE);
            if (meshfix__lanes_simd(&ray, &bvh->blocks[slot / MESHFIX__WIDE], 1u << lane, hit_t, zeros)) {
                t_brute = hit_t[lane] < t_brute ? hit_t[lane] : t_brute;
                meshfix__count_crossing(&crossings, hit_t[lane], zeros[lane]);
            }
        }
        hits_brute = (crossings.halves + 1) / 2;
        crossed += hits_brute;
        q.skip = MESHFIX__NONE;
        q.mode = MESHFIX__CLOSEST_HIT;
        if (meshfix__trace(bvh, root, &ray, &q) != (t_brute < 1e30f) || (t_brute < 1e30f && q.t != t_brute))
            wrong++;
        q.mode = MESHFIX__COUNT_HITS;
        meshfix__trace(bvh, root, &ray, &q);
        wrong += q.hits != hits_brute;
    }
    printf("    %u triangles, %s: %lu nodes, depth %lu; 3000 rays, %lu crossings, %lu answers unlike brute force\n",
           bvh->count, builder, (unsigned long)facts.nodes, (unsigned long)facts.deepest, (unsigned long)crossed,
           (unsigned long)wrong);
    CHECK(crossed > 1500);
    CHECK_EQ(misplaced, 0);
    CHECK_EQ(facts.outside, 0);
    CHECK(facts.nodes <= bvh->count);
    CHECK(facts.deepest <= MESHFIX__BVH_LEVELS);
    CHECK_EQ(wrong, 0);
    free(facts.seen);
}

/* Both builders against brute force: the library's choice (binned SAH
   below MESHFIX__MORTON_MIN triangles, as all three models are unless the
   fuzzers' knobs lower it, Morton clusters above), binned SAH and Morton
   clusters on every model. The larger models: a sphere alone, and with
   two stacks of triangles about one point each (one Morton code a stack:
   split by halving). */
static void test_trees_against_brute_force(void)
{
    int model;
    for (model = 0; model < 3; ++model) {
        mio_mesh g;
        meshfix__mesh m;
        meshfix__bvh bvh;
        meshfix__arena arena;
        meshfix_options o;
        unsigned char *block;
        unsigned int *units;
        size_t t;
        memset(&g, 0, sizeof(g));
        if (model == 0)
            CHECK(gen_sphere(&g, 20, 30, 0, 0, 0, 1)); /* SAH */
        else if (model == 1)
            CHECK(gen_sphere(&g, 90, 140, 0.5f, 0, 0, 2)); /* Morton */
        else {
            /* a sphere and two stacks of 600 triangles turned about one
               centroid each: within a stack one code (split by halving);
               few enough that a ray through one stays within
               MESHFIX__RAY_WORK nodes */
            size_t sphere_vertices, sphere_indices, v;
            CHECK(gen_sphere(&g, 40, 60, 0, 0, 0, 0.5f));
            sphere_vertices = g.vertex_count, sphere_indices = g.index_count;
            g.vertex_count += 3600, g.index_count += 3600;
            g.positions = (float *)realloc(g.positions, 3 * g.vertex_count * sizeof(float));
            g.indices = (unsigned int *)realloc(g.indices, g.index_count * sizeof(unsigned int));
            for (t = 0; t < 1200; ++t) {
                double a = 0.01 * (double)t, b = 0.007 * (double)t, centre = t < 600 ? -1.0 : 1.0;
                double d[3], e[3];
                int k;
                d[0] = 0.05 * cos(a), d[1] = 0.05 * sin(a), d[2] = 0.015 * cos(b);
                e[0] = -0.01 * sin(b), e[1] = 0.01 * cos(a), e[2] = 0.04;
                v = sphere_vertices + 3 * t;
                for (k = 0; k < 3; ++k) {
                    double c = k == 0 ? centre : 0.0;
                    g.positions[3 * v + k] = (float)(c + d[k]);
                    g.positions[3 * v + 3 + k] = (float)(c + e[k]);
                    g.positions[3 * v + 6 + k] = (float)(c - d[k] - e[k]);
                    g.indices[sphere_indices + 3 * t + k] = (unsigned int)(v + k);
                }
            }
        }
        memset(&o, 0, sizeof(o));
        block = bind_mesh(&m, &o, g.indices, g.index_count, g.positions, g.vertex_count);
        units = (unsigned int *)calloc(g.index_count / 3, sizeof(unsigned int));
        check_tree(g.index_count / 3 < MESHFIX__MORTON_MIN ? "the library's (binned SAH)"
                                                           : "the library's (Morton clusters)",
                   &bvh, whole_tree(&bvh, &m, &arena, units), 7 + (unsigned long long)model);
        free_arena(&arena);
        check_tree("binned SAH", &bvh, whole_tree_built(&bvh, &m, &arena, units, MESHFIX__BUILD_SAH),
                   7 + (unsigned long long)model);
        free_arena(&arena);
        check_tree("Morton clusters", &bvh, whole_tree_built(&bvh, &m, &arena, units, MESHFIX__BUILD_MORTON),
                   7 + (unsigned long long)model);
        free_arena(&arena);
        free(units);
        free(block);
        mio_free(&g);
    }
}

static const test_case tests[] = {
    {"generated closed models cut into unwelded patches with gaps", test_cut_generated},
    {"real closed models cut into unwelded patches with gaps", test_cut_real},
    {"open sheets: windshield, terrain", test_open_sheets},
    {"coherence alone and visibility alone each fail; together not", test_both_criteria_needed},
    {"nested spheres: out, in, out", test_nested_shells},
    {"cavity inside an outer shell that has gaps stays inward", test_cavity_in_open_shell},
    {"intersecting shells all face out", test_intersecting_shells},
    {"Moebius strip: reported, no crash", test_mobius},
    {"independent of triangle order and of how much was flipped", test_order_and_flip_independence},
    {"parallel_for gives bit-identical results; confidence in [0, 1]", test_parallel_for_identical},
    {"AUTO with 2 and 4 real threads gives the single-threaded result", test_threads_identical},
    {"the input, edge, fill, coherence, sum and write stages on threads give one thread's result", test_threads_stages},
    {"weld: exact, tolerance, -0, NaN", test_weld},
    {"watertight rays through shared vertices and edges", test_watertight_rays},
    {"trees of both builders answer as brute force does", test_trees_against_brute_force},
};

int main(int argc, char **argv)
{
    return run_tests(tests, sizeof(tests) / sizeof(tests[0]), argc > 1 ? argv[1] : NULL);
}
