/* Hostile input: the bad-input matrix, allocation failure at every
   allocation a call makes, and adversarial meshes at sizes where anything
   quadratic would not finish. Every refusal must leave every buffer the
   caller passed byte for byte as it was. Prints "N passed, N failed". */
#undef NDEBUG
#define MESHFIX_IMPLEMENTATION
#include "../meshfix.h"
#define MESHIO_IMPLEMENTATION
#include "../examples/meshio.h"
#define MESHGEN_IMPLEMENTATION
#include "../examples/meshgen.h"

#include "check.h"
#include "internals.h"
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static float cheap_sdf(const float p[3], void *user)
{
    (void)user;
    return sqrtf(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]) - 1.0f;
}

/* every policy, SDF with a cheap function */
#define POLICIES 7
static meshfix_options policy_options(int i)
{
    static const meshfix_policy policies[POLICIES] = {MESHFIX_POLICY_AUTO,       MESHFIX_POLICY_SEED,
                                                      MESHFIX_POLICY_MAJORITY,   MESHFIX_POLICY_OUTWARD,
                                                      MESHFIX_POLICY_VISIBILITY, MESHFIX_POLICY_UP,
                                                      MESHFIX_POLICY_SDF};
    meshfix_options o;
    memset(&o, 0, sizeof(o));
    o.policy = policies[i];
    o.sdf.distance = cheap_sdf;
    o.visibility.rays = 4096;
    return o;
}

/* The caller's buffers around one call, to compare after it. */
/* Counts this large are claims the library must refuse before reading:
   the guarded buffers hold what really exists. */
#define REAL_COUNT(n) ((n) <= 10000000u ? (n) : 12u)

typedef struct guarded {
    unsigned int *indices, *indices_copy, *destination, *destination_copy, *patch_ids, *patch_copy;
    unsigned char *flipped, *flipped_copy;
    float *confidence, *confidence_copy;
    meshfix_component components[4], components_copy[4];
    meshfix_report report, report_copy;
    meshfix_outputs outputs;
    size_t index_count;
} guarded;

static void guard(guarded *g, const unsigned int *indices, size_t index_count)
{
    size_t n = REAL_COUNT(index_count) + 3, t = n / 3 + 1;
    memset(g, 0, sizeof(*g));
    g->index_count = index_count;
    g->indices = (unsigned int *)calloc(n, sizeof(unsigned int));
    g->indices_copy = (unsigned int *)calloc(n, sizeof(unsigned int));
    g->destination = (unsigned int *)calloc(n, sizeof(unsigned int));
    g->destination_copy = (unsigned int *)calloc(n, sizeof(unsigned int));
    g->patch_ids = (unsigned int *)calloc(t, sizeof(unsigned int));
    g->patch_copy = (unsigned int *)calloc(t, sizeof(unsigned int));
    g->flipped = (unsigned char *)calloc(t, 1);
    g->flipped_copy = (unsigned char *)calloc(t, 1);
    g->confidence = (float *)calloc(t, sizeof(float));
    g->confidence_copy = (float *)calloc(t, sizeof(float));
    if (indices != NULL)
        memcpy(g->indices, indices, REAL_COUNT(index_count) * sizeof(unsigned int));
    memset(g->destination, 0xA5, n * sizeof(unsigned int));
    memset(g->patch_ids, 0x5A, t * sizeof(unsigned int));
    memset(g->flipped, 0x77, t);
    memset(g->confidence, 0x33, t * sizeof(float));
    memset(g->components, 0x44, sizeof(g->components));
    memset(&g->report, 0x66, sizeof(g->report));
    memcpy(g->indices_copy, g->indices, n * sizeof(unsigned int));
    memcpy(g->destination_copy, g->destination, n * sizeof(unsigned int));
    memcpy(g->patch_copy, g->patch_ids, t * sizeof(unsigned int));
    memcpy(g->flipped_copy, g->flipped, t);
    memcpy(g->confidence_copy, g->confidence, t * sizeof(float));
    memcpy(g->components_copy, g->components, sizeof(g->components));
    g->report_copy = g->report;
}

static void attach(guarded *g)
{
    memset(&g->outputs, 0, sizeof(g->outputs));
    g->outputs.flipped = g->flipped;
    g->outputs.patch_ids = g->patch_ids;
    g->outputs.patch_confidence = g->confidence;
    g->outputs.patch_confidence_capacity = REAL_COUNT(g->index_count) / 3 + 1;
    g->outputs.components = g->components;
    g->outputs.components_capacity = 4;
}

static int untouched(const guarded *g)
{
    size_t n = REAL_COUNT(g->index_count) + 3, t = n / 3 + 1;
    return memcmp(g->indices, g->indices_copy, n * sizeof(unsigned int)) == 0 &&
           memcmp(g->destination, g->destination_copy, n * sizeof(unsigned int)) == 0 &&
           memcmp(g->patch_ids, g->patch_copy, t * sizeof(unsigned int)) == 0 &&
           memcmp(g->flipped, g->flipped_copy, t) == 0 &&
           memcmp(g->confidence, g->confidence_copy, t * sizeof(float)) == 0 &&
           memcmp(g->components, g->components_copy, sizeof(g->components)) == 0 &&
           memcmp(&g->report, &g->report_copy, sizeof(g->report)) == 0;
}

static void unguard(guarded *g)
{
    free(g->indices), free(g->indices_copy), free(g->destination), free(g->destination_copy);
    free(g->patch_ids), free(g->patch_copy), free(g->flipped), free(g->flipped_copy);
    free(g->confidence), free(g->confidence_copy);
}

/* One refused call under every policy, in place and out of place: the
   status expected, nothing written. */
static void expect_refusal(const char *what, const unsigned int *indices, size_t index_count, const float *positions,
                           size_t vertex_count, size_t stride, meshfix_result expected)
{
    int p;
    for (p = 0; p < POLICIES; ++p) {
        guarded g;
        meshfix_options o = policy_options(p);
        meshfix_result r;
        guard(&g, indices, index_count);
        attach(&g);
        r = meshfix_orient(g.destination, indices != NULL ? g.indices : NULL, index_count, positions, vertex_count,
                           stride, &o, &g.report, &g.outputs);
        if (r != expected)
            printf("    %s, policy %d: %s\n", what, (int)o.policy, meshfix_result_string(r));
        CHECK_EQ(r, expected);
        CHECK(untouched(&g));
        r = meshfix_orient(indices != NULL ? g.indices : NULL, indices != NULL ? g.indices : NULL, index_count,
                           positions, vertex_count, stride, &o, &g.report, &g.outputs);
        CHECK_EQ(r, expected);
        CHECK(untouched(&g));
        r = meshfix_inspect(indices != NULL ? g.indices : NULL, index_count, positions, vertex_count, stride, &o,
                               &g.report, &g.outputs);
        if (expected != MESHFIX_ERROR_POSITIONS_REQUIRED && expected != MESHFIX_ERROR_INVALID_ARGUMENT)
            CHECK_EQ(r, expected);
        if (r != MESHFIX_OK)
            CHECK(untouched(&g));
        unguard(&g);
    }
}

static const float tetra_p[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
static const unsigned int tetra_i[] = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};

static void test_matrix_refusals(void)
{
    unsigned int bad[12];
    float flat[12];
    memcpy(bad, tetra_i, sizeof(bad));
    bad[4] = 4;
    expect_refusal("index == vertex_count", bad, 12, tetra_p, 4, 12, MESHFIX_ERROR_INDEX_OUT_OF_RANGE);
    bad[4] = 0xFFFFFFFFu;
    expect_refusal("index 0xFFFFFFFF", bad, 12, tetra_p, 4, 12, MESHFIX_ERROR_INDEX_OUT_OF_RANGE);
    expect_refusal("11 indices", tetra_i, 11, tetra_p, 4, 12, MESHFIX_ERROR_NOT_TRIANGLES);
    expect_refusal("1 index", tetra_i, 1, tetra_p, 4, 12, MESHFIX_ERROR_NOT_TRIANGLES);
    expect_refusal("NULL indices", NULL, 12, tetra_p, 4, 12, MESHFIX_ERROR_INVALID_ARGUMENT);
    expect_refusal("stride 8", tetra_i, 12, tetra_p, 4, 8, MESHFIX_ERROR_INVALID_ARGUMENT);
    expect_refusal("stride 13", tetra_i, 12, tetra_p, 4, 13, MESHFIX_ERROR_INVALID_ARGUMENT);
    expect_refusal("no vertices", tetra_i, 12, tetra_p, 0, 12, MESHFIX_ERROR_INDEX_OUT_OF_RANGE);
    expect_refusal("index_count over 2^31", tetra_i, (size_t)0x80000001u, tetra_p, 4, 12, MESHFIX_ERROR_TOO_LARGE);
    expect_refusal("index_count near SIZE_MAX", tetra_i, ((size_t)-1) / 3 * 3, tetra_p, 4, 12, MESHFIX_ERROR_TOO_LARGE);
    if (sizeof(size_t) > 4) {
        size_t huge = (size_t)1 << 16 << 17; /* over 2^32 vertices cannot be indexed */
        expect_refusal("vertex_count over 2^32", tetra_i, 12, tetra_p, huge, 12, MESHFIX_ERROR_TOO_LARGE);
        expect_refusal("vertex_count * stride overflows", tetra_i, 12, tetra_p, 0xFFFFFFFFu, ((size_t)-1) / 8 / 4 * 4,
                       MESHFIX_ERROR_TOO_LARGE);
    }
    if (sizeof(size_t) > 4)
        CHECK_EQ(meshfix_scratch_size(12, (size_t)1 << 20 << 20, NULL), 0);
    CHECK_EQ(meshfix_scratch_size(((size_t)-1) / 3 * 3, 4, NULL), 0);
    /* positions needed */
    {
        guarded g;
        meshfix_options o = policy_options(3);
        guard(&g, tetra_i, 12);
        attach(&g);
        CHECK_EQ(meshfix_orient(g.destination, g.indices, 12, NULL, 4, 0, &o, &g.report, &g.outputs),
                 MESHFIX_ERROR_POSITIONS_REQUIRED);
        CHECK(untouched(&g));
        o = policy_options(6);
        o.sdf.distance = NULL;
        CHECK_EQ(meshfix_orient(g.destination, g.indices, 12, tetra_p, 4, 12, &o, &g.report, &g.outputs),
                 MESHFIX_ERROR_INVALID_ARGUMENT);
        o = policy_options(0);
        o.memory.alloc_func = (void *(*)(size_t, void *))0x1; /* alloc without free: refused before use */
        CHECK_EQ(meshfix_orient(g.destination, g.indices, 12, tetra_p, 4, 12, &o, &g.report, &g.outputs),
                 MESHFIX_ERROR_INVALID_ARGUMENT);
        CHECK(untouched(&g));
        unguard(&g);
    }
    /* weld refusals */
    {
        unsigned int remap[4] = {9, 9, 9, 9};
        memcpy(flat, tetra_p, sizeof(flat));
        flat[5] = INFINITY;
        CHECK_EQ(meshfix_weld(remap, flat, 4, 12, 0.0f, NULL, NULL), MESHFIX_ERROR_NON_FINITE);
        CHECK_EQ(meshfix_weld(NULL, flat, 4, 12, 0.0f, NULL, NULL), MESHFIX_ERROR_INVALID_ARGUMENT);
        CHECK_EQ(meshfix_weld(remap, NULL, 4, 12, 0.0f, NULL, NULL), MESHFIX_ERROR_INVALID_ARGUMENT);
        CHECK_EQ(meshfix_weld(remap, flat, 4, 12, NAN, NULL, NULL), MESHFIX_ERROR_INVALID_ARGUMENT);
        CHECK_EQ(meshfix_weld(remap, flat, ((size_t)-1) / 2, 12, 0.0f, NULL, NULL), MESHFIX_ERROR_TOO_LARGE);
        CHECK(remap[0] == 9 && remap[3] == 9);
    }
}

/* Accepted, odd inputs: a documented status (OK) and a sound result under
   every policy. */
static void expect_repair(const char *what, const unsigned int *indices, size_t index_count, const float *positions,
                          size_t vertex_count, meshfix_report *last)
{
    int p;
    for (p = 0; p < POLICIES; ++p) {
        meshfix_options o = policy_options(p);
        meshfix_report r, again;
        unsigned int *out = (unsigned int *)malloc(index_count * sizeof(unsigned int) + 4);
        meshfix_result result =
            meshfix_orient(out, indices, index_count, positions, vertex_count, 12, &o, &r, NULL);
        if (result != MESHFIX_OK)
            printf("    %s, policy %d: %s\n", what, p, meshfix_result_string(result));
        CHECK_EQ(result, MESHFIX_OK);
        if (result == MESHFIX_OK && o.policy != MESHFIX_POLICY_SDF) {
            /* a second pass changes nothing */
            CHECK_EQ(meshfix_orient(out, out, index_count, positions, vertex_count, 12, &o, &again, NULL), MESHFIX_OK);
            CHECK_EQ(again.triangles_flipped, 0);
        }
        *last = r;
        free(out);
    }
}

static void test_matrix_accepted(void)
{
    meshfix_report r;
    float p[12], *many;
    unsigned int *idx;
    size_t t, k;
    /* zero triangles, NULL everywhere */
    CHECK_EQ(meshfix_orient(NULL, NULL, 0, NULL, 0, 0, NULL, &r, NULL), MESHFIX_OK);
    CHECK_EQ(meshfix_weld(NULL, NULL, 0, 0, 0.0f, NULL, NULL), MESHFIX_OK);
    /* NaN and Inf positions: counted, weigh nothing, topology still repaired */
    memcpy(p, tetra_p, sizeof(p));
    p[3] = NAN, p[7] = INFINITY, p[11] = -INFINITY;
    expect_repair("NaN and Inf", tetra_i, 12, p, 4, &r);
    CHECK_EQ(r.mesh.vertices_non_finite, 3);
    CHECK_EQ(r.mesh.edges_inconsistent, 0);
    /* all degenerate: reported, nothing flipped */
    {
        static const unsigned int degenerate[] = {0, 0, 1, 1, 2, 2, 3, 3, 3, 0, 1, 0};
        expect_repair("all degenerate", degenerate, 12, tetra_p, 4, &r);
        CHECK_EQ(r.mesh.triangles_degenerate, 4);
        CHECK_EQ(r.triangles_flipped, 0);
        CHECK_EQ(r.mesh.patches, 0);
    }
    /* duplicated triangles */
    {
        static const unsigned int dup[] = {0, 1, 2, 0, 1, 2, 2, 1, 0, 1, 2, 0, 0, 1, 3};
        expect_repair("duplicates", dup, 15, tetra_p, 4, &r);
        CHECK_EQ(r.mesh.triangles_duplicate, 3);
    }
    /* an edge shared by k = 3 .. 64 triangles */
    for (k = 3; k <= 64; k = k < 8 ? k + 1 : k * 2) {
        many = (float *)malloc(3 * (k + 2) * sizeof(float));
        idx = (unsigned int *)malloc(3 * k * sizeof(unsigned int));
        many[0] = 0, many[1] = 0, many[2] = 0, many[3] = 1, many[4] = 0, many[5] = 0;
        for (t = 0; t < k; ++t) {
            double a = 6.283185307 * (double)t / (double)k;
            many[3 * (t + 2)] = 0.5f, many[3 * (t + 2) + 1] = (float)cos(a), many[3 * (t + 2) + 2] = (float)sin(a);
            idx[3 * t] = 0, idx[3 * t + 1] = 1, idx[3 * t + 2] = (unsigned int)(t + 2);
        }
        expect_repair("edge shared by k", idx, 3 * k, many, k + 2, &r);
        CHECK_EQ(r.mesh.edges_non_manifold, 1);
        CHECK_EQ(r.mesh.patches, k);
        CHECK_EQ(r.mesh.components, 1);
        free(many);
        free(idx);
    }
    /* NULL positions with the topology policies; huge vertex_count, few used */
    CHECK_EQ(meshfix_orient(NULL, tetra_i, 12, NULL, 0xFFFFFFFFu, 0, NULL, &r, NULL), MESHFIX_OK);
    CHECK_EQ(r.mesh.vertices_used, 4);
    CHECK_EQ(meshfix_inspect(tetra_i, 12, NULL, 4, 0, NULL, &r, NULL), MESHFIX_OK);
}

/* ---- allocation failure at every allocation ---- */

typedef struct failing_allocator {
    size_t calls, frees, fail_at, live;
} failing_allocator;

static void *failing_alloc(size_t size, void *user)
{
    failing_allocator *a = (failing_allocator *)user;
    if (++a->calls == a->fail_at)
        return NULL;
    a->live++;
    return malloc(size);
}

static void failing_free(void *p, void *user)
{
    failing_allocator *a = (failing_allocator *)user;
    a->frees++;
    a->live--;
    free(p);
}

static void fail_every_allocation(const char *what, const unsigned int *indices, size_t index_count,
                                  const float *positions, size_t vertex_count)
{
    int p;
    for (p = 0; p < POLICIES; ++p) {
        failing_allocator a;
        meshfix_options o = policy_options(p);
        size_t total, n;
        guarded g;
        memset(&a, 0, sizeof(a));
        o.memory.alloc_func = failing_alloc;
        o.memory.free_func = failing_free;
        o.memory.user_data = &a;
        guard(&g, indices, index_count);
        attach(&g);
        CHECK_EQ(meshfix_orient(g.destination, g.indices, index_count, positions, vertex_count, 12, &o, &g.report, &g.outputs),
                 MESHFIX_OK);
        CHECK_EQ(a.live, 0);
        total = a.calls;
        unguard(&g);
        for (n = 1; n <= total; ++n) {
            meshfix_result r;
            guard(&g, indices, index_count);
            attach(&g);
            memset(&a, 0, sizeof(a));
            a.fail_at = n;
            r = meshfix_orient(g.destination, g.indices, index_count, positions, vertex_count, 12, &o, &g.report, &g.outputs);
            if (r != MESHFIX_ERROR_OUT_OF_MEMORY || a.live != 0 || !untouched(&g))
                printf("    %s, policy %d, allocation %lu of %lu: %s, %lu live\n", what, p, (unsigned long)n,
                       (unsigned long)total, meshfix_result_string(r), (unsigned long)a.live);
            CHECK_EQ(r, MESHFIX_ERROR_OUT_OF_MEMORY);
            CHECK_EQ(a.live, 0);
            CHECK(untouched(&g));
            unguard(&g);
        }
    }
    {
        /* the weld: one allocation */
        failing_allocator a;
        meshfix_options o;
        unsigned int *remap = (unsigned int *)malloc(vertex_count * sizeof(unsigned int));
        size_t n;
        memset(&o, 0, sizeof(o));
        o.memory.alloc_func = failing_alloc;
        o.memory.free_func = failing_free;
        o.memory.user_data = &a;
        for (n = 1; n <= 1; ++n) { /* one block */
            memset(&a, 0, sizeof(a));
            memset(remap, 0x3C, vertex_count * sizeof(unsigned int));
            a.fail_at = n;
            CHECK_EQ(meshfix_weld(remap, positions, vertex_count, 12, 1e-4f, &o, NULL), MESHFIX_ERROR_OUT_OF_MEMORY);
            CHECK_EQ(a.live, 0);
            CHECK(remap[0] == 0x3C3C3C3Cu);
        }
        free(remap);
    }
}

static void test_allocation_failure(void)
{
    mio_mesh g, t;
    /* two shells and open patches, so the ray-casting stages allocate too */
    CHECK(gen_sphere(&g, 10, 14, 0, 0, 0, 2));
    CHECK(gen_sphere(&t, 8, 10, 0, 0, 0, 1)); /* a cavity */
    CHECK(gen_append(&g, &t));
    mio_free(&t);
    CHECK(gen_grid(&t, 6, 6));
    CHECK(gen_append(&g, &t));
    mio_free(&t);
    gen_flip_random(&g, 0.3, 1, NULL);
    fail_every_allocation("spheres and a sheet", g.indices, g.index_count, g.positions, g.vertex_count);
    mio_free(&g);
}

/* ---- adversarial shapes at sizes where quadratic work would not finish ---- */

/* n = 200000, or MESHFIX_ADVERSARIAL_N (the sanitizer and valgrind runs
   use less): at this size anything quadratic would take hours, so the
   suite finishing is the check; make bench measures the time. */
static void test_adversarial(void)
{
    const size_t n = getenv("MESHFIX_ADVERSARIAL_N") ? (size_t)strtoul(getenv("MESHFIX_ADVERSARIAL_N"), NULL, 10) : 200000;
    float *p = (float *)malloc(3 * (n + 2) * sizeof(float));
    unsigned int *idx = (unsigned int *)malloc(3 * n * sizeof(unsigned int));
    meshfix_report r;
    meshfix_options o;
    size_t t;
    int policy;
    unsigned long long seed = 5;
    memset(&o, 0, sizeof(o));
    o.visibility.rays = 16384;
    /* one vertex shared by n triangles: a disk fan, half of it reversed */
    p[0] = p[1] = p[2] = 0;
    for (t = 0; t < n; ++t) {
        double a = 6.283185307 * (double)t / (double)n;
        p[3 * (t + 1)] = (float)cos(a), p[3 * (t + 1) + 1] = (float)sin(a), p[3 * (t + 1) + 2] = 0;
        idx[3 * t] = 0, idx[3 * t + 1] = (unsigned int)(t + 1), idx[3 * t + 2] = (unsigned int)((t + 1) % n + 1);
        if (t % 2)
            idx[3 * t + 1] = (unsigned int)((t + 1) % n + 1), idx[3 * t + 2] = (unsigned int)(t + 1);
    }
    for (policy = 0; policy < 2; ++policy) {
        o.policy = policy ? MESHFIX_POLICY_VISIBILITY : MESHFIX_POLICY_AUTO;
        CHECK_EQ(meshfix_orient(idx, idx, 3 * n, p, n + 1, 12, &o, &r, NULL), MESHFIX_OK);
        CHECK_EQ(r.mesh.edges_inconsistent, 0);
        CHECK_EQ(r.mesh.patches, 1);
    }
    /* one edge shared by n triangles */
    p[3] = 1, p[4] = 0, p[5] = 0;
    for (t = 0; t < n; ++t) {
        idx[3 * t] = 0, idx[3 * t + 1] = 1, idx[3 * t + 2] = (unsigned int)(t % n + 2 > n ? 2 : t + 2);
        p[3 * ((t % n) + 2) - 3 + 3] = 0.5f;
    }
    for (t = 2; t < n + 2; ++t)
        p[3 * t] = 0.5f, p[3 * t + 1] = (float)gen_uniform(&seed), p[3 * t + 2] = (float)gen_uniform(&seed);
    for (t = 0; t < n; ++t)
        idx[3 * t + 2] = (unsigned int)(t + 2 <= n + 1 ? t + 2 : 2);
    for (policy = 0; policy < 2; ++policy) {
        o.policy = policy ? MESHFIX_POLICY_VISIBILITY : MESHFIX_POLICY_AUTO;
        CHECK_EQ(meshfix_orient(idx, idx, 3 * n, p, n + 2, 12, &o, &r, NULL), MESHFIX_OK);
        CHECK_EQ(r.mesh.edges_non_manifold, 1);
        CHECK_EQ(r.mesh.patches, n);
    }
    /* n coincident triangles */
    for (t = 0; t < n; ++t)
        idx[3 * t] = 0, idx[3 * t + 1] = t % 2 ? 1 : 2, idx[3 * t + 2] = t % 2 ? 2 : 1;
    for (policy = 0; policy < 2; ++policy) {
        o.policy = policy ? MESHFIX_POLICY_VISIBILITY : MESHFIX_POLICY_AUTO;
        CHECK_EQ(meshfix_orient(NULL, idx, 3 * n, p, n + 2, 12, &o, &r, NULL), MESHFIX_OK);
        CHECK_EQ(r.mesh.triangles_duplicate, n - 1);
        CHECK_EQ(r.mesh.edges, 3);
    }
    /* a soup: every triangle its own patch, random positions */
    for (t = 0; t < 3 * n; ++t)
        idx[t] = (unsigned int)t;
    free(p);
    p = (float *)malloc(9 * n * sizeof(float));
    for (t = 0; t < 9 * n; ++t)
        p[t] = (float)gen_uniform(&seed);
    for (policy = 0; policy < 2; ++policy) {
        o.policy = policy ? MESHFIX_POLICY_VISIBILITY : MESHFIX_POLICY_AUTO;
        CHECK_EQ(meshfix_orient(idx, idx, 3 * n, p, 3 * n, 12, &o, &r, NULL), MESHFIX_OK);
        CHECK_EQ(r.mesh.patches, n);
    }
    free(p);
    free(idx);
    /* many tiny closed shells: 5000 tetrahedra, nesting checks for each */
    {
        mio_mesh g;
        size_t shells = 5000, s;
        g.vertex_count = 4 * shells;
        g.index_count = 12 * shells;
        g.positions = (float *)malloc(3 * g.vertex_count * sizeof(float));
        g.indices = (unsigned int *)malloc(g.index_count * sizeof(unsigned int));
        for (s = 0; s < shells; ++s) {
            size_t k;
            for (k = 0; k < 12; ++k)
                g.positions[12 * s + k] = tetra_p[k] * 0.5f + (float)(k % 3 == 0 ? (double)(s % 100) : k % 3 == 1 ? (double)(s / 100) : 0.0);
            for (k = 0; k < 12; ++k)
                g.indices[12 * s + k] = tetra_i[k] + (unsigned int)(4 * s);
        }
        gen_flip_random(&g, 0.5, 3, NULL);
        CHECK_EQ(meshfix_orient(g.indices, g.indices, g.index_count, g.positions, g.vertex_count, 12, NULL, &r, NULL),
                 MESHFIX_OK);
        CHECK_EQ(r.mesh.patches_inside_out, 0);
        CHECK_EQ(r.evidence.shells_inward, 0);
        CHECK_EQ(r.mesh.edges_inconsistent, 0);
        mio_free(&g);
    }
}

/* ---- what an independent audit found (each reached a crash, a hang or
   quadratic time before it was fixed) ---- */

/* Triangles in the planes x, y, z = 11^-(k + axis / 3), each as small as
   its distance from the origin: the binned SAH cuts one of them off at
   each level, so a build without a depth bound made a chain as deep as
   the triangles are many (64 here with 135 of them, the traversal's stack
   size), and a ray from near the origin overflowed the traversal stack.
   The depth is bounded now; it is measured, rays are cast from every
   triangle, and every policy runs (under the sanitizers in make test). */
static size_t tree_depth(const meshfix__bvh *b, unsigned int node)
{
    size_t deepest = 0, d;
    int c;
    for (c = 0; c < MESHFIX__WIDE; ++c)
        if ((b->nodes[node].inner & (1u << c)) && (d = tree_depth(b, b->nodes[node].child[c])) > deepest)
            deepest = d;
    return 1 + deepest;
}

static void make_shrinking_planes(mio_mesh *g, unsigned int planes)
{
    unsigned int k, axis;
    memset(g, 0, sizeof(*g));
    g->vertex_count = 9 * (size_t)planes;
    g->index_count = 9 * (size_t)planes;
    g->positions = (float *)calloc(3 * g->vertex_count, sizeof(float));
    g->indices = (unsigned int *)malloc(g->index_count * sizeof(unsigned int));
    for (k = 0; k < planes; ++k)
        for (axis = 0; axis < 3; ++axis) {
            size_t v = 9 * (size_t)k + 3 * axis, c;
            float x = (float)pow(11.0, -((double)k + axis / 3.0));
            for (c = 0; c < 3; ++c) {
                g->positions[3 * (v + c) + axis] = x;
                g->positions[3 * (v + c) + (axis + 1) % 3] = c == 1 ? x : 0.0f;
                g->positions[3 * (v + c) + (axis + 2) % 3] = c == 2 ? x : 0.0f;
                g->indices[v + c] = (unsigned int)(v + c);
            }
        }
}

static void test_deep_tree(void)
{
    mio_mesh g;
    meshfix__mesh m;
    meshfix__bvh bvh;
    meshfix__arena arena;
    meshfix_options o;
    meshfix_report r;
    unsigned char *block;
    unsigned int t, i, *units, root;
    unsigned long long seed = 1;
    size_t depth;
    int p;
    make_shrinking_planes(&g, 45);
    memset(&o, 0, sizeof(o));
    block = bind_mesh(&m, &o, g.indices, g.index_count, g.positions, g.vertex_count);
    units = (unsigned int *)calloc(g.index_count / 3, sizeof(unsigned int));
    root = whole_tree(&bvh, &m, &arena, units);
    CHECK(root != MESHFIX__NONE);
    depth = tree_depth(&bvh, root);
    printf("    %u triangles shrinking toward the origin: tree depth %lu, traversal stack %d\n", bvh.count,
           (unsigned long)depth, MESHFIX__BVH_STACK);
    CHECK(depth <= MESHFIX__BVH_LEVELS);
    for (t = 0; t < bvh.count; ++t)
        for (i = 0; i < 16; ++i) {
            float from[3], d[3];
            meshfix__ray ray;
            meshfix__query q;
            int k;
            for (k = 0; k < 3; ++k) {
                from[k] = (bvh.corners[9 * t + k] + bvh.corners[9 * t + 3 + k] + bvh.corners[9 * t + 6 + k]) / 3.0f;
                d[k] = (float)gen_uniform(&seed) - 0.5f;
            }
            meshfix__setup_ray(&ray, from, d, 0.0f, 1e30f);
            q.mode = MESHFIX__COUNT_HITS;
            q.skip = MESHFIX__NONE;
            meshfix__trace(&bvh, root, &ray, &q);
        }
    free_arena(&arena);
    for (p = 0; p < POLICIES; ++p) {
        o = policy_options(p);
        CHECK_EQ(meshfix_orient(g.indices, g.indices, g.index_count, g.positions, g.vertex_count, 12, &o, &r, NULL),
                 MESHFIX_OK);
    }
    free(block);
    free(units);
    mio_free(&g);
}

/* Option values out of range are refused with nothing written (a struct
   nobody zeroed once asked for 2^32 + 64 rays). */
static void test_option_ranges(void)
{
    int field, p;
    for (field = 0; field < 15; ++field)
        for (p = 0; p < POLICIES; ++p) {
            guarded g;
            meshfix_options o = policy_options(p);
            guard(&g, tetra_i, 12);
            attach(&g);
            switch (field) {
            case 0: o.visibility.rays = sizeof(size_t) > 4 ? (size_t)0xFFFFFFFFu + 65u : (size_t)0xFFFFFFFFu; break;
            case 1: o.visibility.rays = ((size_t)1 << 24) + 1; break;
            case 2: o.visibility.min_samples = 1u << 20; break;
            case 3: o.visibility.coherence_distance = NAN; break;
            case 4: o.visibility.eps = -1.0f; break;
            case 5: o.visibility.kv = INFINITY; break;
            case 6: o.up[1] = NAN; break;
            case 7: o.sdf.step = -INFINITY; break;
            /* fuzz_stress findings 2 and 4 */
            case 8: o.evidence.sigma = INFINITY; break;
            case 9: o.evidence.min_confidence = NAN; break;
            case 10: o.evidence.min_confidence = 1.5f; break;
            case 11: o.evidence.triangle_normals = tetra_p, o.evidence.triangle_normals_stride = 13; break;
            case 12: o.evidence.vertex_normals = tetra_p, o.evidence.vertex_normals_stride = 8; break;
            case 13: o.index_size = 1; break;
            default: o.sdf.mode = (meshfix_sdf_mode)7; o.policy = MESHFIX_POLICY_SDF; break;
            }
            CHECK_EQ(meshfix_orient(g.destination, g.indices, 12, tetra_p, 4, 12, &o, &g.report, &g.outputs),
                     MESHFIX_ERROR_INVALID_ARGUMENT);
            CHECK(untouched(&g));
            unguard(&g);
        }
}

/* The report may share memory with the options that carry the caller's
   scratch: the options are read whole before the report is written. */
static void test_report_shares_options(void)
{
    union {
        meshfix_options options;
        meshfix_report report;
    } shared;
    unsigned int out[12];
    size_t size = meshfix_scratch_size(12, 4, NULL);
    void *scratch = malloc(size);
    memset(&shared, 0, sizeof(shared));
    shared.options.memory.scratch = scratch;
    shared.options.memory.scratch_size = size;
    shared.options.policy = MESHFIX_POLICY_MAJORITY;
    CHECK_EQ(meshfix_orient(out, tetra_i, 12, tetra_p, 4, 12, &shared.options, &shared.report, NULL), MESHFIX_OK);
    CHECK_EQ(shared.report.mesh.triangles, 4);
    free(scratch);
}

/* A destination that overlaps the indices at any shift gives what a
   separate buffer gets. */
static void test_overlapping_destination(void)
{
    mio_mesh g;
    unsigned int *expected, *buffer;
    int shift;
    CHECK(gen_sphere(&g, 6, 8, 0, 0, 0, 1));
    gen_flip_random(&g, 0.4, 11, NULL);
    expected = (unsigned int *)malloc(g.index_count * sizeof(unsigned int));
    buffer = (unsigned int *)malloc((g.index_count + 16) * sizeof(unsigned int));
    CHECK_EQ(meshfix_orient(expected, g.indices, g.index_count, g.positions, g.vertex_count, 12, NULL, NULL, NULL),
             MESHFIX_OK);
    for (shift = -6; shift <= 6; ++shift) {
        unsigned int *in = buffer + 8, *out = buffer + 8 + shift;
        memcpy(in, g.indices, g.index_count * sizeof(unsigned int));
        CHECK_EQ(meshfix_orient(out, in, g.index_count, g.positions, g.vertex_count, 12, NULL, NULL, NULL), MESHFIX_OK);
        CHECK(memcmp(out, expected, g.index_count * sizeof(unsigned int)) == 0);
    }
    free(expected);
    free(buffer);
    mio_free(&g);
}

/* Counts and strides where size_t has 32 bits: an index of 0xFFFFFFFE
   with 0xFFFFFFFF vertices made `vertex_range + 1` wrap, and 3 * 2^28
   indices were read before the plan refused them. */
static void test_sizes_that_wrap(void)
{
    static const unsigned int far_index[3] = {0, 1, 0xFFFFFFFEu};
    if (sizeof(size_t) == 4) {
        expect_refusal("index 0xFFFFFFFE of 0xFFFFFFFF vertices", far_index, 3, NULL, 0xFFFFFFFFu, 12,
                       MESHFIX_ERROR_TOO_LARGE);
        expect_refusal("3 * 2^28 indices", tetra_i, (size_t)3 << 28, tetra_p, 4, 12, MESHFIX_ERROR_TOO_LARGE);
        CHECK_EQ(meshfix_scratch_size(3, 0xFFFFFFFFu, NULL), 0);
    }
    /* the last vertex's 12 bytes past the end of the address space */
    expect_refusal("stride * (vertex_count - 1) + 12 overflows", tetra_i, 12, tetra_p, 4,
                   (((size_t)-1) / 3) & ~(size_t)3, MESHFIX_ERROR_TOO_LARGE);
}

/* Welding with every vertex in one hash bucket (what crafted positions
   did to the old probing table): the bucket is sorted and searched, so
   the result is the same and the time O(n log n). */
static void weld_one_bucket(const float *positions, size_t n, float tolerance, unsigned int *remap)
{
    meshfix__welder w;
    unsigned int *block = (unsigned int *)malloc((1 + 5 * n) * sizeof(unsigned int));
    memset(&w, 0, sizeof(w));
    w.positions = (const unsigned char *)positions;
    w.stride = 12;
    w.position_size = 4;
    w.cell = (double)tolerance * (1.0 + 1e-9);
    w.mask = 0;
    w.bucket_end = block;
    w.order = block + 1;
    w.home = w.order + n;
    w.rep_head = w.home + n;
    w.rep_next = w.rep_head + n;
    meshfix__weld_run(&w, n, (double)tolerance, remap);
    free(block);
}

static void test_weld_one_bucket(void)
{
    const size_t n = getenv("MESHFIX_ADVERSARIAL_N") ? (size_t)strtoul(getenv("MESHFIX_ADVERSARIAL_N"), NULL, 10) : 200000;
    float *p = (float *)malloc(3 * n * sizeof(float));
    unsigned int *normal = (unsigned int *)malloc(n * sizeof(unsigned int));
    unsigned int *crowded = (unsigned int *)malloc(n * sizeof(unsigned int));
    unsigned long long seed = 77;
    size_t v, unique;
    int pass;
    for (pass = 0; pass < 2; ++pass) {
        float tolerance = pass ? 0.004f : 0.0f;
        for (v = 0; v < 3 * n; ++v) /* on a coarse lattice, so exact copies occur too */
            p[v] = (float)(gen_random(&seed) % 64) / 64.0f + (pass ? (float)gen_uniform(&seed) * 0.003f : 0.0f);
        CHECK_EQ(meshfix_weld(normal, p, n, 12, tolerance, NULL, &unique), MESHFIX_OK);
        weld_one_bucket(p, n, tolerance, crowded);
        CHECK(memcmp(normal, crowded, n * sizeof(unsigned int)) == 0);
        printf("    %lu vertices in one bucket, tolerance %g: %lu clusters, same as spread\n", (unsigned long)n,
               (double)tolerance, (unsigned long)unique);
    }
    free(p);
    free(normal);
    free(crowded);
}

/* Every triangle of a complete 3-uniform hypergraph on k vertices (each
   edge in k - 2 triangles, so all three edges non-manifold), twice: the
   duplicates are found through edge rings, no hash to aim at. */
static void test_duplicates_on_crowded_edges(void)
{
    const unsigned int k = getenv("MESHFIX_ADVERSARIAL_N") ? 24u : 64u;
    size_t triangles = (size_t)k * (k - 1) * (k - 2) / 6, t = 0;
    unsigned int *idx = (unsigned int *)malloc(2 * 3 * triangles * sizeof(unsigned int));
    float *p = (float *)malloc(3 * k * sizeof(float));
    unsigned long long seed = 3;
    unsigned int a, b, c;
    meshfix_report r;
    for (a = 0; a < 3 * k; ++a)
        p[a] = (float)gen_uniform(&seed);
    for (a = 0; a < k; ++a)
        for (b = a + 1; b < k; ++b)
            for (c = b + 1; c < k; ++c, ++t) {
                idx[3 * t] = a, idx[3 * t + 1] = b, idx[3 * t + 2] = c;
                /* the copy, rotated and reversed */
                idx[3 * (triangles + t)] = c, idx[3 * (triangles + t) + 1] = b, idx[3 * (triangles + t) + 2] = a;
            }
    CHECK_EQ(meshfix_inspect(idx, 6 * triangles, p, k, 12, NULL, &r, NULL), MESHFIX_OK);
    CHECK_EQ(r.mesh.triangles_duplicate, triangles);
    CHECK_EQ(r.mesh.edges_non_manifold, (size_t)k * (k - 1) / 2);
    free(idx);
    free(p);
}

/* NaN, infinities and values near FLT_MAX in half the positions of a
   soup: counted by their bit patterns (a build with -ffast-math runs this
   suite too), weigh nothing, and the area stays finite. */
static void test_non_finite_soup(void)
{
    const size_t n = 2000;
    float *p = (float *)malloc(9 * n * sizeof(float));
    unsigned int *idx = (unsigned int *)malloc(3 * n * sizeof(unsigned int));
    unsigned long long seed = 9;
    size_t v, bad = 0;
    meshfix_report r;
    int policy;
    for (v = 0; v < 3 * n; ++v) {
        int kind = (int)(gen_random(&seed) % 6);
        float x = (float)gen_uniform(&seed), y = (float)gen_uniform(&seed), z = (float)gen_uniform(&seed);
        if (kind == 0)
            x = NAN;
        else if (kind == 1)
            y = -INFINITY;
        else if (kind == 2)
            z = INFINITY;
        else if (kind == 3)
            x = 3.4e38f, y = -3.4e38f;
        bad += kind < 3;
        p[3 * v] = x, p[3 * v + 1] = y, p[3 * v + 2] = z;
        idx[v] = (unsigned int)v;
    }
    for (policy = 0; policy < POLICIES; ++policy) {
        meshfix_options o = policy_options(policy);
        CHECK_EQ(meshfix_orient(idx, idx, 3 * n, p, 3 * n, 12, &o, &r, NULL), MESHFIX_OK);
        CHECK_EQ(r.mesh.vertices_non_finite, bad);
        CHECK(r.mesh.area - r.mesh.area == 0.0 && r.mesh.area > 0.0);
    }
    {
        unsigned int remap[3];
        const float nan_tolerance = NAN;
        CHECK_EQ(meshfix_weld(remap, p, 3, 12, nan_tolerance, NULL, NULL), MESHFIX_ERROR_INVALID_ARGUMENT);
        CHECK_EQ(meshfix_weld(remap, p, 3, 12, INFINITY, NULL, NULL), MESHFIX_ERROR_INVALID_ARGUMENT);
    }
    free(p);
    free(idx);
}

/* ---- what fuzz_stress found (tests/fuzz/crashes/README.md) ---- */

/* Finding 1: two fans of three triangles on one edge each are two
   components of three triangles (the renumbering walked ids as parents). */
static void test_components_of_two_fans(void)
{
    static const unsigned int idx[18] = {0, 1, 2, 0, 1, 3, 0, 1, 4, 5, 6, 7, 5, 6, 8, 5, 6, 9};
    meshfix_component c[4];
    meshfix_outputs outputs = {0};
    meshfix_report r;
    outputs.components = c, outputs.components_capacity = 4;
    CHECK_EQ(meshfix_inspect(idx, 18, NULL, 10, 0, NULL, &r, &outputs), MESHFIX_OK);
    CHECK_EQ(r.mesh.patches, 6);
    CHECK_EQ(r.mesh.components, 2);
    CHECK_EQ(r.mesh.euler_characteristic, 2);
    CHECK_EQ(c[0].triangles, 3);
    CHECK_EQ(c[1].triangles, 3);
    CHECK_EQ(c[1].first_triangle, 3);
}

/* An allocator whose fresh blocks hold a given byte: a result that reads
   memory nobody wrote changes with it. */
static void *garbage_alloc(size_t size, void *user)
{
    void *p = malloc(size);
    if (p != NULL)
        memset(p, *(const unsigned char *)user, size);
    return p;
}

static void garbage_free(void *p, void *user)
{
    (void)user;
    free(p);
}

/* Finding 5: a segment too long for the coherence grid kept an unwritten
   distance, and a neighbour that chose it compared against garbage. The
   finding's mesh, and scenes, under every policy, with fresh memory
   filled two ways: the same answer. */
static void test_no_reads_of_unwritten_memory(void)
{
    enum { TINY = 60 };
    static float p[3 * (6 + 3 * TINY)];
    static unsigned int idx[3 * (2 + TINY)];
    static const float two[18] = {0, 0, 0, 0.31f, 0, 0, 0.155f, 0.05f, 0,
                                  0.145f, -0.005f, 0, 0.155f, -0.01f, 0, 0.165f, -0.005f, 0};
    unsigned int v = 0, n = 0, i, k;
    int policy;
    for (i = 0; i < 18; ++i)
        p[i] = two[i];
    for (i = 0; i < 6; ++i)
        idx[n++] = v++;
    for (i = 0; i < TINY; ++i) { /* tiny triangles up to x = 1: a small mean edge */
        float x = 0.4f + 0.6f * (float)i / (TINY - 1);
        float q[9];
        q[0] = x, q[1] = 0.5f, q[2] = 0, q[3] = x + 0.001f, q[4] = 0.5f, q[5] = 0, q[6] = x, q[7] = 0.501f, q[8] = 0;
        for (k = 0; k < 9; ++k)
            p[3 * v + k] = q[k];
        idx[n++] = v, idx[n++] = v + 1, idx[n++] = v + 2;
        v += 3;
    }
    /* every policy, and VISIBILITY once more with coherence alone (finding 3) */
    for (policy = 0; policy <= (int)MESHFIX_POLICY_COUNT; ++policy) {
        unsigned char fill[2] = {0x00, 0xFF};
        unsigned int out[2][3 * (2 + TINY)];
        float confidence[2][64];
        meshfix_report r[2];
        int run;
        if (policy == MESHFIX_POLICY_SDF)
            continue;
        for (run = 0; run < 2; ++run) {
            meshfix_options o = {0};
            meshfix_outputs outputs = {0};
            o.policy = policy == (int)MESHFIX_POLICY_COUNT ? MESHFIX_POLICY_VISIBILITY : (meshfix_policy)policy;
            o.visibility.flags = policy == (int)MESHFIX_POLICY_COUNT ? MESHFIX_VISIBILITY_COHERENCE_ONLY : 0u;
            o.visibility.rays = o.policy == MESHFIX_POLICY_VISIBILITY ? 2000 : 0;
            o.evidence.triangle_normals = policy == MESHFIX_POLICY_NORMALS ? p : NULL;
            o.memory.alloc_func = garbage_alloc, o.memory.free_func = garbage_free, o.memory.user_data = &fill[run];
            outputs.patch_confidence = confidence[run], outputs.patch_confidence_capacity = 64;
            memset(confidence[run], 0, sizeof(confidence[run]));
            CHECK_EQ(meshfix_orient(out[run], idx, n, p, v, 0, &o, &r[run], &outputs), MESHFIX_OK);
        }
        CHECK(memcmp(out[0], out[1], n * sizeof(unsigned int)) == 0);
        CHECK(memcmp(&r[0], &r[1], sizeof(r[0])) == 0);
        CHECK(memcmp(confidence[0], confidence[1], sizeof(confidence[0])) == 0);
    }
}

/* Finding 6: the geometric stage's arena was counted short for tiny
   meshes. One triangle, a quad, two triangles apart, a tetrahedron: under
   every policy, in scratch of exactly meshfix_scratch_size() bytes, with
   an allocator that must not be called. */
static void *forbidden_alloc(size_t size, void *user)
{
    (void)size;
    ++*(int *)user;
    return NULL;
}

static void test_tiny_meshes_in_exact_scratch(void)
{
    static const float p[] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 5, 5, 5, 6, 5, 5, 5, 6, 5};
    static const unsigned int one[] = {0, 1, 2}, quad[] = {0, 1, 2, 0, 2, 3}, apart[] = {0, 1, 2, 4, 5, 6};
    static const struct {
        const unsigned int *indices;
        size_t count;
        const float *positions;
        size_t vertices;
    } meshes[] = {{one, 3, p, 3}, {quad, 6, p, 4}, {apart, 6, p, 7}, {tetra_i, 12, tetra_p, 4}};
    size_t k;
    int policy;
    for (k = 0; k < sizeof(meshes) / sizeof(meshes[0]); ++k)
        for (policy = 0; policy < (int)MESHFIX_POLICY_COUNT; ++policy) {
            meshfix_options o = {0};
            unsigned int out[12];
            size_t size;
            void *scratch;
            int calls = 0;
            if (policy == MESHFIX_POLICY_SDF)
                continue;
            o.policy = (meshfix_policy)policy;
            o.evidence.vertex_normals = meshes[k].positions;
            size = meshfix_scratch_size(meshes[k].count, meshes[k].vertices, &o);
            scratch = malloc(size);
            o.memory.scratch = scratch, o.memory.scratch_size = size;
            o.memory.alloc_func = forbidden_alloc, o.memory.free_func = garbage_free, o.memory.user_data = &calls;
            CHECK_EQ(meshfix_orient(out, meshes[k].indices, meshes[k].count, meshes[k].positions, meshes[k].vertices, 0,
                                    &o, NULL, NULL),
                     MESHFIX_OK);
            CHECK_EQ(calls, 0);
            free(scratch);
        }
}

/* A small triangle in the patch of a huge one: its areas' sum took each
   corner relative to the patch's first vertex, 10^30 away, where its
   x coordinates round together and its area to 0; meshfix_check looked
   for a triangle without an area from the positions as given and found
   none, so its failure named no triangle. The two now agree. */
static void test_small_triangle_far_from_its_patch(void)
{
    static const float positions[12] = {1e30f, 0, 0, 0, 0, 0, 0, 1e-3f, 0, 1e-3f, 0, 0};
    static const unsigned int indices[6] = {0, 1, 2, 1, 3, 2};
    meshfix_report r;
    meshfix_check_failure why;
    CHECK_EQ(meshfix_inspect(indices, 6, positions, 4, 12, NULL, &r, NULL), MESHFIX_OK);
    CHECK_EQ(r.mesh.patches, 1);
    CHECK_EQ(r.mesh.triangles_zero_area, 0);
    CHECK(meshfix_check(indices, 6, positions, 4, 12, MESHFIX_REQUIRE_NO_DEGENERATE, NULL, &why));
    CHECK(why.triangle == (size_t)-1);
}

static const test_case tests[] = {
    {"bad input refused under every policy, nothing written", test_matrix_refusals},
    {"odd input accepted: NaN/Inf, degenerate, duplicates, edges of 3..64, empty", test_matrix_accepted},
    {"allocation failure at every allocation: OOM, no leak, nothing written", test_allocation_failure},
    {"adversarial: fan of n, n on one edge, n coincident, soup of n, 5000 shells", test_adversarial},
    {"audit: triangles shrinking toward a point give a tree the traversal stack holds", test_deep_tree},
    {"audit: option values out of range refused, nothing written", test_option_ranges},
    {"audit: report sharing memory with options and scratch", test_report_shares_options},
    {"audit: destination overlapping the indices at any shift", test_overlapping_destination},
    {"audit: counts and strides that wrap size_t", test_sizes_that_wrap},
    {"audit: weld with every vertex in one hash bucket", test_weld_one_bucket},
    {"audit: duplicates among triangles whose edges are all non-manifold", test_duplicates_on_crowded_edges},
    {"audit: NaN, Inf and FLT_MAX soup classified by bits", test_non_finite_soup},
    {"fuzz: two fans on two edges are two components", test_components_of_two_fans},
    {"fuzz: fresh memory filled two ways gives the same answer under every policy", test_no_reads_of_unwritten_memory},
    {"fuzz: tiny meshes in exact scratch under every policy, no allocation", test_tiny_meshes_in_exact_scratch},
    {"fuzz: a small triangle far from its patch's first vertex has its area", test_small_triangle_far_from_its_patch},
};

int main(int argc, char **argv)
{
    return run_tests(tests, sizeof(tests) / sizeof(tests[0]), argc > 1 ? argv[1] : NULL);
}
