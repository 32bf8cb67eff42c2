/* Unit, property and real-model tests of meshfix.h. Prints "N passed, N failed".
   Real models come from Debian's assimp-testmodels (/usr/share/assimp/models,
   or the folder in MESHFIX_MODELS). */
#undef NDEBUG
#define MESHFIX_IMPLEMENTATION
#include "../meshfix.h"
#define MESHIO_IMPLEMENTATION
#include "../examples/meshio.h"
#define MESHGEN_IMPLEMENTATION
#include "../examples/meshgen.h"

#include "check.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- helpers ---- */

static void flip_triangle(unsigned int *indices, size_t t)
{
    unsigned int x = indices[3 * t + 1];
    indices[3 * t + 1] = indices[3 * t + 2];
    indices[3 * t + 2] = x;
}

static unsigned int *copy_indices(const unsigned int *indices, size_t count)
{
    unsigned int *out = (unsigned int *)malloc(count * sizeof(unsigned int) + 1);
    memcpy(out, indices, count * sizeof(unsigned int));
    return out;
}

/* Each output triangle must be its input triangle or the same with its last
   two indices swapped; returns how many were swapped, or -1. */
static long count_swapped(const unsigned int *in, const unsigned int *out, size_t index_count)
{
    size_t t;
    long swapped = 0;
    for (t = 0; t < index_count / 3; ++t) {
        const unsigned int *a = in + 3 * t, *b = out + 3 * t;
        if (a[0] == b[0] && a[1] == b[1] && a[2] == b[2])
            continue;
        if (a[0] == b[0] && a[1] == b[2] && a[2] == b[1])
            swapped++;
        else
            return -1;
    }
    return swapped;
}

/* Orients, then checks the contract every call must meet: only swaps, the
   reported flip count, the flipped[] output, idempotence, in-place equal
   to out-of-place. Returns the output (caller frees). */
static unsigned int *orient_checked(const unsigned int *indices, size_t index_count, const float *positions,
                                    size_t vertex_count, size_t stride, meshfix_policy policy, meshfix_report *report)
{
    meshfix_options o;
    meshfix_outputs outputs;
    meshfix_report again;
    unsigned int *out = (unsigned int *)malloc(index_count * sizeof(unsigned int) + 1);
    unsigned int *in_place = copy_indices(indices, index_count), *second = copy_indices(indices, index_count);
    unsigned char *flipped = (unsigned char *)malloc(index_count / 3 + 1);
    size_t t, flagged = 0;
    memset(&o, 0, sizeof(o));
    memset(&outputs, 0, sizeof(outputs));
    o.policy = policy;
    outputs.flipped = flipped;
    CHECK_EQ(meshfix_orient(out, indices, index_count, positions, vertex_count, stride, &o, report, &outputs), MESHFIX_OK);
    CHECK_EQ(count_swapped(indices, out, index_count), report->triangles_flipped);
    for (t = 0; t < index_count / 3; ++t)
        flagged += flipped[t];
    CHECK_EQ(flagged, report->triangles_flipped);
    outputs.flipped = NULL;
    CHECK_EQ(meshfix_orient(in_place, in_place, index_count, positions, vertex_count, stride, &o, &again, &outputs), MESHFIX_OK);
    CHECK(memcmp(in_place, out, index_count * sizeof(unsigned int)) == 0);
    memcpy(second, out, index_count * sizeof(unsigned int));
    CHECK_EQ(meshfix_orient(second, second, index_count, positions, vertex_count, stride, &o, &again, &outputs), MESHFIX_OK);
    CHECK_EQ(again.triangles_flipped, 0);
    CHECK(memcmp(second, out, index_count * sizeof(unsigned int)) == 0);
    free(in_place);
    free(second);
    free(flipped);
    return out;
}

/* ---- hand-built meshes ---- */

static const float tetra_positions[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
static const unsigned int tetra_indices[] = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};

static const float cube_positions[] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1};
static const unsigned int cube_indices[] = {0, 2, 1, 0, 3, 2, 4, 5, 6, 4, 6, 7, 0, 1, 5, 0, 5, 4,
                                            1, 2, 6, 1, 6, 5, 2, 3, 7, 2, 7, 6, 3, 0, 4, 3, 4, 7};

static void test_quick_start(void)
{
    /* the quick start of meshfix.h, as written there */
    unsigned int indices[36];
    const float *positions = cube_positions;
    size_t index_count = 36, vertex_count = 8;
    memcpy(indices, cube_indices, sizeof(indices));
    flip_triangle(indices, 4);
    {
        meshfix_report report;
        meshfix_result r = meshfix_orient(indices, indices, index_count,
                                          positions, vertex_count, sizeof(float) * 3,
                                          NULL, &report, NULL);
        if (r != MESHFIX_OK)
            printf("meshfix: %s\n", meshfix_result_string(r));
        CHECK_EQ(r, MESHFIX_OK);
        CHECK_EQ(report.triangles_flipped, 1);
        CHECK(meshfix_check(indices, index_count, positions, vertex_count,
                            sizeof(float) * 3, MESHFIX_REQUIRE_SOLID, NULL, NULL));
    }
}

static void test_tetrahedron(void)
{
    meshfix_report r;
    unsigned int in[12], *out;
    CHECK_EQ(meshfix_inspect(tetra_indices, 12, tetra_positions, 4, 12, NULL, &r, NULL), MESHFIX_OK);
    CHECK_EQ(r.mesh.edges, 6);
    CHECK_EQ(r.mesh.edges_manifold, 6);
    CHECK_EQ(r.mesh.edges_inconsistent, 0);
    CHECK_EQ(r.mesh.euler_characteristic, 2);
    CHECK_EQ(r.mesh.components_closed, 1);
    CHECK(fabs(r.mesh.signed_volume - 1.0 / 6.0) < 1e-12);
    CHECK(meshfix_check(tetra_indices, 12, tetra_positions, 4, 12, MESHFIX_REQUIRE_SOLID, NULL, NULL));
    /* all four reversed: consistent but inside-out, which OUTWARD undoes */
    memcpy(in, tetra_indices, sizeof(in));
    flip_triangle(in, 0), flip_triangle(in, 1), flip_triangle(in, 2), flip_triangle(in, 3);
    CHECK(meshfix_check(in, 12, tetra_positions, 4, 12, MESHFIX_REQUIRE_CONSISTENT, NULL, NULL));
    CHECK(!meshfix_check(in, 12, tetra_positions, 4, 12, MESHFIX_REQUIRE_OUTWARD, NULL, NULL));
    out = orient_checked(in, 12, tetra_positions, 4, 12, MESHFIX_POLICY_OUTWARD, &r);
    CHECK_EQ(r.triangles_flipped, 4);
    CHECK(memcmp(out, tetra_indices, sizeof(in)) == 0);
    free(out);
}

static void test_cube_one_and_five_flipped(void)
{
    static const size_t five[] = {1, 4, 6, 9, 11};
    meshfix_report r;
    unsigned int in[36], *out;
    size_t i;
    memcpy(in, cube_indices, sizeof(in));
    flip_triangle(in, 7);
    CHECK_EQ(meshfix_inspect(in, 36, cube_positions, 8, 12, NULL, &r, NULL), MESHFIX_OK);
    CHECK_EQ(r.mesh.edges_inconsistent, 3);
    out = orient_checked(in, 36, cube_positions, 8, 12, MESHFIX_POLICY_AUTO, &r);
    CHECK_EQ(r.triangles_flipped, 1);
    CHECK_EQ(r.mesh.edges_inconsistent, 0);
    CHECK_EQ(r.edges_inconsistent_before, 3);
    CHECK(memcmp(out, cube_indices, sizeof(in)) == 0);
    free(out);

    memcpy(in, cube_indices, sizeof(in));
    for (i = 0; i < 5; ++i)
        flip_triangle(in, five[i]);
    out = orient_checked(in, 36, cube_positions, 8, 12, MESHFIX_POLICY_MAJORITY, &r);
    CHECK_EQ(r.triangles_flipped, 5);
    CHECK(memcmp(out, cube_indices, sizeof(in)) == 0);
    CHECK(fabs(r.mesh.signed_volume - 1.0) < 1e-9);
    free(out);
}

static void test_open_sheet(void)
{
    mio_mesh g;
    meshfix_report r;
    unsigned int *in, *out;
    CHECK(gen_grid(&g, 8, 6));
    CHECK_EQ(meshfix_inspect(g.indices, g.index_count, g.positions, g.vertex_count, 12, NULL, &r, NULL), MESHFIX_OK);
    CHECK_EQ(r.mesh.edges_boundary, 2 * (8 + 6));
    CHECK_EQ(r.mesh.euler_characteristic, 1);
    CHECK_EQ(r.mesh.patches_closed, 0);
    CHECK_EQ(r.mesh.signed_volume, 0);
    in = copy_indices(g.indices, g.index_count);
    gen_flip_random(&g, 0.3, 7, NULL);
    /* an open patch under OUTWARD falls back to the majority side */
    out = orient_checked(g.indices, g.index_count, g.positions, g.vertex_count, 12, MESHFIX_POLICY_OUTWARD, &r);
    CHECK(memcmp(out, in, g.index_count * sizeof(unsigned int)) == 0);
    CHECK_EQ(r.mesh.edges_inconsistent, 0);
    free(in);
    free(out);
    mio_free(&g);
}

static void test_mobius_strip(void)
{
    mio_mesh g;
    meshfix_report r;
    meshfix_component c[2];
    meshfix_options o;
    meshfix_outputs outputs;
    unsigned int *out;
    CHECK(gen_mobius(&g, 24));
    memset(&o, 0, sizeof(o));
    memset(&outputs, 0, sizeof(outputs));
    outputs.components = c;
    outputs.components_capacity = 2;
    CHECK_EQ(meshfix_inspect(g.indices, g.index_count, g.positions, g.vertex_count, 12, &o, &r, &outputs), MESHFIX_OK);
    CHECK_EQ(r.mesh.components, 1);
    CHECK_EQ(r.mesh.components_non_orientable, 1);
    CHECK_EQ(r.mesh.euler_characteristic, 0);
    CHECK_EQ(c[0].orientable, 0);
    CHECK_EQ(c[0].closed, 0);
    gen_flip_random(&g, 0.5, 3, NULL);
    out = orient_checked(g.indices, g.index_count, g.positions, g.vertex_count, 12, MESHFIX_POLICY_AUTO, &r);
    /* a Moebius strip cannot be consistent: at least one edge stays, and a
       one-quad-wide strip needs no more than the seam where the fill meets */
    CHECK(r.mesh.edges_inconsistent >= 1 && r.mesh.edges_inconsistent <= 2);
    CHECK_EQ(r.mesh.components_non_orientable, 1);
    free(out);
    mio_free(&g);
}

/* The seam left in a non-orientable strip depends on its topology alone:
   repaired from any scramble, every triangle comes out wound like the first
   repair, or every one reversed (the policy's turn). */
static void test_mobius_seam_independent_of_winding(void)
{
    mio_mesh g;
    meshfix_report r;
    unsigned int *clean, *first = NULL, *out;
    size_t t, triangles;
    unsigned long long seed;
    CHECK(gen_mobius(&g, 60));
    triangles = g.index_count / 3;
    clean = copy_indices(g.indices, g.index_count);
    for (seed = 1; seed <= 6; ++seed) {
        size_t same = 0;
        memcpy(g.indices, clean, g.index_count * sizeof(unsigned int));
        gen_flip_random(&g, seed / 7.0, seed, NULL);
        out = orient_checked(g.indices, g.index_count, NULL, g.vertex_count, 12, MESHFIX_POLICY_SEED, &r);
        CHECK_EQ(r.mesh.components_non_orientable, 1);
        CHECK(r.mesh.edges_inconsistent >= 1);
        if (first == NULL) {
            first = out;
            continue;
        }
        for (t = 0; t < triangles; ++t)
            same += (size_t)(out[3 * t + 1] == first[3 * t + 1]);
        CHECK(same == 0 || same == triangles);
        free(out);
    }
    free(first);
    free(clean);
    mio_free(&g);
}

static void test_two_shells(void)
{
    mio_mesh a, b;
    meshfix_report r;
    meshfix_component c[3];
    meshfix_options o;
    meshfix_outputs outputs;
    unsigned int *clean, *out;
    CHECK(gen_sphere(&a, 8, 12, 0, 0, 0, 1));
    CHECK(gen_torus(&b, 12, 8, 3, 0.5f));
    CHECK(gen_append(&a, &b));
    clean = copy_indices(a.indices, a.index_count);
    memset(&o, 0, sizeof(o));
    memset(&outputs, 0, sizeof(outputs));
    outputs.components = c;
    outputs.components_capacity = 3;
    CHECK_EQ(meshfix_inspect(a.indices, a.index_count, a.positions, a.vertex_count, 12, &o, &r, &outputs), MESHFIX_OK);
    CHECK_EQ(r.mesh.components, 2);
    CHECK_EQ(r.mesh.components_closed, 2);
    CHECK_EQ(r.mesh.euler_characteristic, 2 + 0);
    CHECK_EQ(c[0].euler_characteristic, 2);
    CHECK_EQ(c[1].euler_characteristic, 0);
    CHECK_EQ(c[1].first_triangle, 2 * 12 * 7);
    CHECK_EQ(c[0].triangles + c[1].triangles, a.index_count / 3);
    CHECK(c[0].signed_volume > 3.0 && c[0].signed_volume < 4.19);
    CHECK(c[1].signed_volume > 0.0);
    /* reverse the whole torus and part of the sphere: both come back out */
    {
        size_t t;
        for (t = 2 * 12 * 7; t < a.index_count / 3; ++t)
            flip_triangle(a.indices, t);
        flip_triangle(a.indices, 3);
    }
    out = orient_checked(a.indices, a.index_count, a.positions, a.vertex_count, 12, MESHFIX_POLICY_AUTO, &r);
    CHECK(memcmp(out, clean, a.index_count * sizeof(unsigned int)) == 0);
    CHECK_EQ(r.mesh.patches_inside_out, 0);
    free(out);
    free(clean);
    mio_free(&a);
    mio_free(&b);
}

static void test_non_manifold_fan(void)
{
    /* three triangles on edge 0-1, plus a fourth sharing an ordinary edge */
    static const float p[] = {0, 0, 0, 1, 0, 0, 0.5f, 1, 0, 0.5f, -1, 0, 0.5f, 0, 1, 1.5f, 1, 0};
    static const unsigned int idx[] = {0, 1, 2, 1, 0, 3, 0, 1, 4, 1, 2, 5};
    meshfix_report r;
    unsigned int *out;
    CHECK_EQ(meshfix_inspect(idx, 12, p, 6, 12, NULL, &r, NULL), MESHFIX_OK);
    CHECK_EQ(r.mesh.edges_non_manifold, 1);
    CHECK_EQ(r.mesh.edges_inconsistent, 2); /* 0-1 (shared by three) and 1-2 */
    CHECK_EQ(r.mesh.vertices_non_manifold, 2); /* the ends of the edge of three */
    CHECK_EQ(r.mesh.components, 1);
    CHECK_EQ(r.mesh.patches, 3);
    CHECK_EQ(r.mesh.components_closed, 0);
    CHECK(!meshfix_check(idx, 12, p, 6, 12, MESHFIX_REQUIRE_MANIFOLD, NULL, NULL));
    out = orient_checked(idx, 12, p, 6, 12, MESHFIX_POLICY_MAJORITY, &r);
    /* 1-2-5 runs 1->2 like 0-1-2 does; they tie on area, the seed stays */
    CHECK_EQ(r.triangles_flipped, 1);
    CHECK_EQ(out[10], 5);
    CHECK_EQ(out[11], 2);
    CHECK_EQ(r.mesh.edges_inconsistent, 1); /* the non-manifold edge always counts */
    free(out);
}

/* Two tetrahedra sharing one vertex: every edge manifold, one bow-tie vertex. */
static void test_bow_tie_vertex(void)
{
    static const float p[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, -1, 0, 0, 0, -1, 0, 0, 0, -1};
    static const unsigned int idx[] = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3, 0, 5, 4, 0, 4, 6, 0, 6, 5, 4, 5, 6};
    meshfix_report r;
    CHECK_EQ(meshfix_inspect(idx, 24, p, 7, 12, NULL, &r, NULL), MESHFIX_OK);
    CHECK_EQ(r.mesh.edges_non_manifold, 0);
    CHECK_EQ(r.mesh.vertices_non_manifold, 1);
    CHECK_EQ(r.mesh.components, 2);
    CHECK_EQ(r.mesh.euler_characteristic, 4);
    CHECK(!meshfix_check(idx, 24, p, 7, 12, MESHFIX_REQUIRE_MANIFOLD, NULL, NULL));
    CHECK(meshfix_check(idx, 24, p, 7, 12, MESHFIX_REQUIRE_CONSISTENT | MESHFIX_REQUIRE_CLOSED, NULL, NULL));
    CHECK_EQ(meshfix_inspect(tetra_indices, 12, tetra_positions, 4, 12, NULL, &r, NULL), MESHFIX_OK);
    CHECK_EQ(r.mesh.vertices_non_manifold, 0);
    CHECK_EQ(meshfix_inspect(idx, 12, p, 7, 12, NULL, &r, NULL), MESHFIX_OK);
    CHECK_EQ(r.mesh.vertices_non_manifold, 0);
}

static int is_reversal(const unsigned int *a, const unsigned int *b, size_t index_count)
{
    size_t t;
    for (t = 0; t < index_count / 3; ++t)
        if (a[3 * t] != b[3 * t] || a[3 * t + 1] != b[3 * t + 2] || a[3 * t + 2] != b[3 * t + 1])
            return 0;
    return 1;
}

/* A winding vote is symmetric: 90% reversed is 10% reversed of the mesh
   turned over, so MAJORITY keeps the 90% side, inside-out. Geometry decides
   it: OUTWARD (and AUTO, with positions) restores the sphere. At 10%
   reversed with a reversed seed, the plain flood fill comes out inside-out
   while MAJORITY restores it. */
static void test_ninety_percent_flipped_sphere(void)
{
    mio_mesh g;
    meshfix_report r;
    unsigned int *clean, *out;
    size_t flipped;
    CHECK(gen_sphere(&g, 24, 32, 0, 0, 0, 1));
    clean = copy_indices(g.indices, g.index_count);
    flipped = gen_flip_random(&g, 0.9, 11, NULL);
    CHECK(flipped > g.index_count / 3 * 85 / 100);
    out = orient_checked(g.indices, g.index_count, g.positions, g.vertex_count, 12, MESHFIX_POLICY_OUTWARD, &r);
    CHECK(memcmp(out, clean, g.index_count * sizeof(unsigned int)) == 0);
    CHECK_EQ(r.triangles_flipped, flipped);
    CHECK_EQ(r.mesh.patches_inside_out, 0);
    free(out);
    out = orient_checked(g.indices, g.index_count, g.positions, g.vertex_count, 12, MESHFIX_POLICY_AUTO, &r);
    CHECK(memcmp(out, clean, g.index_count * sizeof(unsigned int)) == 0);
    free(out);
    out = orient_checked(g.indices, g.index_count, g.positions, g.vertex_count, 12, MESHFIX_POLICY_MAJORITY, &r);
    CHECK(is_reversal(out, clean, g.index_count));
    CHECK_EQ(r.mesh.patches_inside_out, 1);
    free(out);

    /* 10% reversed, triangle 0 (the seed) among them */
    memcpy(g.indices, clean, g.index_count * sizeof(unsigned int));
    flipped = gen_flip_random(&g, 0.1, 12, NULL);
    if (g.indices[1] == clean[1]) {
        flip_triangle(g.indices, 0);
        flipped++;
    }
    out = orient_checked(g.indices, g.index_count, g.positions, g.vertex_count, 12, MESHFIX_POLICY_SEED, &r);
    CHECK(is_reversal(out, clean, g.index_count));
    CHECK_EQ(r.mesh.patches_inside_out, 1);
    CHECK_EQ(r.triangles_flipped, g.index_count / 3 - flipped);
    free(out);
    out = orient_checked(g.indices, g.index_count, NULL, g.vertex_count, 0, MESHFIX_POLICY_MAJORITY, &r);
    CHECK(memcmp(out, clean, g.index_count * sizeof(unsigned int)) == 0);
    CHECK_EQ(r.triangles_flipped, flipped);
    free(out);
    free(clean);
    mio_free(&g);
}

static void test_degenerate_triangles(void)
{
    /* tetrahedron + a repeated-index triangle + a zero-area sliver + a duplicate */
    static const float p[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 2, 0, 0};
    static const unsigned int idx[] = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3, 1, 1, 2, 0, 1, 4, 2, 1, 0};
    meshfix_report r;
    meshfix_options o;
    meshfix_outputs outputs;
    unsigned int patch_ids[7], *out;
    memset(&o, 0, sizeof(o));
    memset(&outputs, 0, sizeof(outputs));
    outputs.patch_ids = patch_ids;
    CHECK_EQ(meshfix_inspect(idx, 21, p, 5, 12, &o, &r, &outputs), MESHFIX_OK);
    CHECK_EQ(r.mesh.triangles_degenerate, 1);
    CHECK_EQ(r.mesh.triangles_zero_area, 1);
    CHECK_EQ(r.mesh.triangles_duplicate, 1);
    CHECK_EQ(patch_ids[4], 0xFFFFFFFFu);
    CHECK(!meshfix_check(idx, 21, p, 5, 12, MESHFIX_REQUIRE_NO_DEGENERATE, NULL, NULL));
    out = orient_checked(idx, 21, p, 5, 12, MESHFIX_POLICY_AUTO, &r);
    CHECK(memcmp(out + 12, idx + 12, 3 * sizeof(unsigned int)) == 0); /* left as it is */
    free(out);
}

static void test_nan_positions(void)
{
    float p[12];
    meshfix_report r;
    unsigned int *out, in[12];
    memcpy(p, tetra_positions, sizeof(p));
    p[9] = (float)NAN;
    memcpy(in, tetra_indices, sizeof(in));
    flip_triangle(in, 2);
    CHECK_EQ(meshfix_inspect(in, 12, p, 4, 12, NULL, &r, NULL), MESHFIX_OK);
    CHECK_EQ(r.mesh.vertices_non_finite, 1);
    CHECK_EQ(r.mesh.triangles_zero_area, 3);
    /* the one finite triangle decides by area; topology repairs the rest */
    out = orient_checked(in, 12, p, 4, 12, MESHFIX_POLICY_AUTO, &r);
    CHECK(memcmp(out, tetra_indices, sizeof(in)) == 0);
    CHECK(r.mesh.signed_volume == r.mesh.signed_volume);
    free(out);
}

static void test_empty_mesh(void)
{
    meshfix_report r;
    CHECK_EQ(meshfix_orient(NULL, NULL, 0, NULL, 0, 0, NULL, &r, NULL), MESHFIX_OK);
    CHECK_EQ(r.mesh.triangles, 0);
    CHECK_EQ(meshfix_inspect(NULL, 0, NULL, 0, 0, NULL, &r, NULL), MESHFIX_OK);
    CHECK_EQ(r.mesh.components, 0);
    CHECK(meshfix_check(NULL, 0, NULL, 0, 0, MESHFIX_REQUIRE_CONSISTENT, NULL, NULL));
}

static void test_strides(void)
{
    /* the cube inside interleaved vertices of 16 and 32 bytes */
    static const size_t strides[] = {12, 16, 32};
    unsigned int in[36], *reference = NULL;
    size_t s, v;
    memcpy(in, cube_indices, sizeof(in));
    flip_triangle(in, 2), flip_triangle(in, 3), flip_triangle(in, 8);
    for (s = 0; s < 3; ++s) {
        float buffer[8 * 8];
        meshfix_report r;
        unsigned int *out;
        size_t floats = strides[s] / 4;
        for (v = 0; v < 8 * floats; ++v)
            buffer[v] = -77.0f;
        for (v = 0; v < 8; ++v)
            memcpy(buffer + v * floats, cube_positions + 3 * v, 3 * sizeof(float));
        out = orient_checked(in, 36, buffer, 8, strides[s], MESHFIX_POLICY_OUTWARD, &r);
        CHECK(fabs(r.mesh.signed_volume - 1.0) < 1e-9);
        if (reference == NULL)
            reference = out;
        else {
            CHECK(memcmp(out, reference, sizeof(in)) == 0);
            free(out);
        }
    }
    CHECK(memcmp(reference, cube_indices, sizeof(in)) == 0);
    free(reference);
}

/* ---- errors leave everything untouched ---- */

static void test_errors_change_nothing(void)
{
    unsigned int bad[12], out[12], before[12];
    unsigned char flipped[4] = {9, 9, 9, 9};
    meshfix_report r, sentinel;
    meshfix_options o;
    meshfix_outputs outputs;
    memset(&sentinel, 0xAB, sizeof(sentinel));
    memcpy(bad, tetra_indices, sizeof(bad));
    bad[7] = 4; /* out of range for 4 vertices */
    memcpy(before, bad, sizeof(bad));
    memset(out, 0xCD, sizeof(out));
    memset(&o, 0, sizeof(o));
    memset(&outputs, 0, sizeof(outputs));
    outputs.flipped = flipped;
    r = sentinel;
    CHECK_EQ(meshfix_orient(out, bad, 12, tetra_positions, 4, 12, &o, &r, &outputs), MESHFIX_ERROR_INDEX_OUT_OF_RANGE);
    CHECK(memcmp(&r, &sentinel, sizeof(r)) == 0);
    CHECK_EQ(out[0], 0xCDCDCDCDu);
    CHECK_EQ(flipped[0], 9);
    CHECK_EQ(meshfix_orient(bad, bad, 12, tetra_positions, 4, 12, &o, &r, &outputs), MESHFIX_ERROR_INDEX_OUT_OF_RANGE);
    CHECK(memcmp(bad, before, sizeof(bad)) == 0);
    bad[7] = 0xFFFFFFFFu;
    CHECK_EQ(meshfix_orient(bad, bad, 12, NULL, 4, 0, NULL, NULL, NULL), MESHFIX_ERROR_INDEX_OUT_OF_RANGE);
    CHECK_EQ(bad[7], 0xFFFFFFFFu);
    CHECK_EQ(meshfix_orient(out, tetra_indices, 11, tetra_positions, 4, 12, NULL, &r, NULL), MESHFIX_ERROR_NOT_TRIANGLES);
    CHECK_EQ(meshfix_orient(out, NULL, 12, tetra_positions, 4, 12, NULL, &r, NULL), MESHFIX_ERROR_INVALID_ARGUMENT);
    CHECK_EQ(meshfix_orient(out, tetra_indices, 12, tetra_positions, 4, 8, NULL, &r, NULL), MESHFIX_ERROR_INVALID_ARGUMENT);
    CHECK_EQ(meshfix_orient(out, tetra_indices, 12, tetra_positions, 4, 14, NULL, &r, NULL), MESHFIX_ERROR_INVALID_ARGUMENT);
    CHECK_EQ(meshfix_orient(out, tetra_indices, 12, NULL, 4, 0, NULL, &r, NULL), MESHFIX_OK);
    o.policy = MESHFIX_POLICY_OUTWARD;
    outputs.flipped = NULL;
    CHECK_EQ(meshfix_orient(out, tetra_indices, 12, NULL, 4, 0, &o, &r, &outputs), MESHFIX_ERROR_POSITIONS_REQUIRED);
    /* NORMALS compares the caller's normals with the faces: without
       positions, or without normals, it has nothing to go on */
    {
        float normals[12] = {0, 0, -1, 0, -1, 0, -1, 0, 0, 1, 1, 1};
        o.policy = MESHFIX_POLICY_NORMALS;
        o.evidence.triangle_normals = normals;
        r = sentinel;
        memcpy(out, tetra_indices, sizeof(out));
        CHECK_EQ(meshfix_orient(out, tetra_indices, 12, NULL, 4, 0, &o, &r, &outputs), MESHFIX_ERROR_POSITIONS_REQUIRED);
        CHECK(memcmp(&r, &sentinel, sizeof(r)) == 0);
        CHECK_EQ(meshfix_orient(out, tetra_indices, 12, tetra_positions, 4, 12, &o, &r, &outputs), MESHFIX_OK);
        o.evidence.triangle_normals = NULL;
        r = sentinel;
        CHECK_EQ(meshfix_orient(out, tetra_indices, 12, tetra_positions, 4, 12, &o, &r, &outputs),
                 MESHFIX_ERROR_NORMALS_REQUIRED);
        CHECK(memcmp(&r, &sentinel, sizeof(r)) == 0);
        o.evidence.vertex_normals = normals;
        CHECK_EQ(meshfix_orient(out, tetra_indices, 12, tetra_positions, 4, 12, &o, &r, &outputs), MESHFIX_OK);
        o.evidence.vertex_normals = NULL;
    }
    {
        /* the names the tool and the bindings take, both ways */
        int p;
        for (p = 0; p < (int)MESHFIX_POLICY_COUNT; ++p)
            CHECK_EQ((int)meshfix_policy_from_string(meshfix_policy_string((meshfix_policy)p)), p);
        CHECK(strcmp(meshfix_policy_string(MESHFIX_POLICY_VISIBILITY), "visibility") == 0);
        CHECK_EQ((int)meshfix_policy_from_string("Auto"), (int)MESHFIX_POLICY_COUNT);
        CHECK_EQ((int)meshfix_policy_from_string("autox"), (int)MESHFIX_POLICY_COUNT);
        CHECK_EQ((int)meshfix_policy_from_string("aut"), (int)MESHFIX_POLICY_COUNT);
        CHECK_EQ((int)meshfix_policy_from_string(NULL), (int)MESHFIX_POLICY_COUNT);
        CHECK(strcmp(meshfix_policy_string((meshfix_policy)99), "unknown policy") == 0);
    }
    o.policy = (meshfix_policy)99;
    CHECK_EQ(meshfix_orient(out, tetra_indices, 12, NULL, 4, 0, &o, &r, &outputs), MESHFIX_ERROR_INVALID_ARGUMENT);
    CHECK_EQ(meshfix_orient(out, tetra_indices, (size_t)0x80000001, NULL, 4, 0, NULL, &r, NULL), MESHFIX_ERROR_TOO_LARGE);
    CHECK_EQ(meshfix_orient(out, tetra_indices, ((size_t)-1) / 3 * 3, NULL, 4, 0, NULL, &r, NULL), MESHFIX_ERROR_TOO_LARGE);
    CHECK_EQ(meshfix_inspect(tetra_indices, 12, NULL, 4, 0, NULL, NULL, NULL), MESHFIX_ERROR_INVALID_ARGUMENT);
    CHECK(!meshfix_check(tetra_indices, 12, NULL, 4, 0, MESHFIX_REQUIRE_OUTWARD, NULL, NULL));
    CHECK(strcmp(meshfix_result_string(MESHFIX_ERROR_OUT_OF_MEMORY), "out of memory") == 0);
    CHECK(meshfix_result_string((meshfix_result)1234) != NULL);
    CHECK_EQ(meshfix_scratch_size(0, 4, NULL), 0);
    CHECK_EQ(meshfix_scratch_size((size_t)0x7FFFFFFF + 1, 4, NULL), 0);
}

/* ---- allocators ---- */

typedef struct counting_allocator {
    size_t allocations, frees, fail_at, bytes, peak;
} counting_allocator;

static void *counting_alloc(size_t size, void *user)
{
    counting_allocator *a = (counting_allocator *)user;
    size_t *block;
    if (a->fail_at != 0 && a->allocations + 1 == a->fail_at)
        return NULL;
    block = (size_t *)malloc(size + sizeof(size_t) * 2);
    if (block == NULL)
        return NULL;
    a->allocations++;
    block[0] = size;
    a->bytes += size;
    a->peak = a->bytes > a->peak ? a->bytes : a->peak;
    return block + 2;
}

static void counting_free(void *p, void *user)
{
    counting_allocator *a = (counting_allocator *)user;
    size_t *block = (size_t *)p - 2;
    a->frees++;
    a->bytes -= block[0];
    free(block);
}

static void test_allocators(void)
{
    mio_mesh g;
    counting_allocator a;
    meshfix_options o;
    meshfix_report r;
    unsigned int *before, *out;
    void *scratch;
    size_t need;
    CHECK(gen_torus(&g, 20, 10, 2, 0.5f));
    gen_flip_random(&g, 0.4, 5, NULL);
    before = copy_indices(g.indices, g.index_count);
    out = copy_indices(g.indices, g.index_count);
    memset(&a, 0, sizeof(a));
    memset(&o, 0, sizeof(o));
    o.memory.alloc_func = counting_alloc;
    o.memory.free_func = counting_free;
    o.memory.user_data = &a;
    CHECK_EQ(meshfix_orient(out, g.indices, g.index_count, g.positions, g.vertex_count, 12, &o, &r, NULL), MESHFIX_OK);
    CHECK_EQ(a.allocations, 1);
    CHECK_EQ(a.frees, 1);
    CHECK(a.peak <= meshfix_scratch_size(g.index_count, g.vertex_count, &o));
    CHECK(a.peak <= 64 * g.index_count / 3 + 4 * g.vertex_count + 256);
    /* every allocation the call makes fails in turn: out of memory, nothing leaked or written */
    memset(&a, 0, sizeof(a));
    a.fail_at = 1;
    memcpy(out, before, g.index_count * sizeof(unsigned int));
    r.mesh.triangles = 12345;
    CHECK_EQ(meshfix_orient(out, g.indices, g.index_count, g.positions, g.vertex_count, 12, &o, &r, NULL),
             MESHFIX_ERROR_OUT_OF_MEMORY);
    CHECK_EQ(a.allocations, a.frees);
    CHECK_EQ(r.mesh.triangles, 12345);
    CHECK(memcmp(out, before, g.index_count * sizeof(unsigned int)) == 0);
    CHECK_EQ(meshfix_inspect(g.indices, g.index_count, g.positions, g.vertex_count, 12, &o, &r, NULL),
             MESHFIX_ERROR_OUT_OF_MEMORY);
    /* caller scratch: zero allocations under every policy; one byte short
       of what the mesh needs: refused */
    {
        static const meshfix_policy every[] = {MESHFIX_POLICY_AUTO, MESHFIX_POLICY_SEED, MESHFIX_POLICY_MAJORITY,
                                               MESHFIX_POLICY_OUTWARD, MESHFIX_POLICY_VISIBILITY, MESHFIX_POLICY_UP};
        mio_mesh two;
        size_t k;
        CHECK(gen_sphere(&two, 8, 10, 4, 0, 0, 1));
        gen_append(&two, &g); /* two shells: the geometric stage runs */
        gen_flip_random(&two, 0.3, 6, NULL);
        for (k = 0; k < sizeof(every) / sizeof(every[0]); ++k) {
            o.policy = every[k];
            need = meshfix_scratch_size(two.index_count, two.vertex_count, &o);
            scratch = malloc(need);
            memset(&a, 0, sizeof(a));
            o.memory.scratch = scratch;
            o.memory.scratch_size = need;
            CHECK_EQ(meshfix_orient(two.indices, two.indices, two.index_count, two.positions, two.vertex_count, 12, &o,
                                    &r, NULL), MESHFIX_OK);
            CHECK_EQ(a.allocations, 0);
            CHECK_EQ(r.mesh.edges_inconsistent, 0);
            free(scratch);
            /* without scratch: at most two allocations (topology, then the
               geometric stage), both given back */
            memset(&a, 0, sizeof(a));
            o.memory.scratch = NULL;
            o.memory.scratch_size = 0;
            CHECK_EQ(meshfix_orient(NULL, two.indices, two.index_count, two.positions, two.vertex_count, 12, &o, &r,
                                    NULL), MESHFIX_OK);
            CHECK(a.allocations >= 1 && a.allocations <= 2);
            CHECK_EQ(a.frees, a.allocations);
        }
        o.memory.scratch = NULL;
        o.policy = MESHFIX_POLICY_MAJORITY; /* the topology alone: its exact need */
        need = meshfix_scratch_size(g.index_count, g.vertex_count, &o);
        scratch = malloc(need);
        o.memory.scratch = (char *)scratch + 1; /* misaligned on purpose */
        o.memory.scratch_size = need - 1;
        CHECK_EQ(meshfix_orient(out, g.indices, g.index_count, g.positions, g.vertex_count, 12, &o, &r, NULL),
                 MESHFIX_ERROR_SCRATCH_TOO_SMALL);
        free(scratch);
        mio_free(&two);
    }
    free(before);
    free(out);
    mio_free(&g);
}

/* ---- property tests over random meshes ---- */

/* the policies that need nothing but the mesh (SDF has its own tests) */
static const meshfix_policy plain_policies[4] = {MESHFIX_POLICY_AUTO, MESHFIX_POLICY_SEED, MESHFIX_POLICY_MAJORITY,
                                                 MESHFIX_POLICY_OUTWARD};

/* A random closed mesh: sphere or torus of random resolution, sometimes
   several shells, with a random fraction of triangles reversed. */
static void random_mesh(mio_mesh *m, unsigned long long *seed, size_t *shells)
{
    size_t i, n = 1 + gen_random(seed) % 3;
    memset(m, 0, sizeof(*m));
    *shells = n;
    for (i = 0; i < n; ++i) {
        mio_mesh part;
        float at = 5.0f * (float)i;
        if (gen_random(seed) % 2)
            gen_sphere(&part, 3 + (unsigned)(gen_random(seed) % 20), 3 + (unsigned)(gen_random(seed) % 20), at, 0, 0, 1);
        else
            gen_torus(&part, 3 + (unsigned)(gen_random(seed) % 20), 3 + (unsigned)(gen_random(seed) % 20), 1.5f, 0.4f);
        if (i == 0)
            *m = part;
        else {
            size_t v;
            for (v = 0; v < part.vertex_count; ++v)
                part.positions[3 * v] += at;
            gen_append(m, &part);
            mio_free(&part);
        }
    }
}

static void test_property_random_flips(void)
{
    unsigned long long seed = 20261123;
    int round;
    for (round = 0; round < 200; ++round) {
        mio_mesh g;
        meshfix_report r, clean_report;
        unsigned int *clean, *out;
        size_t shells, flipped;
        double fraction;
        random_mesh(&g, &seed, &shells);
        CHECK_EQ(meshfix_inspect(g.indices, g.index_count, g.positions, g.vertex_count, 12, NULL, &clean_report, NULL), MESHFIX_OK);
        CHECK_EQ(clean_report.mesh.components, shells);
        CHECK_EQ(clean_report.mesh.edges_inconsistent, 0);
        clean = copy_indices(g.indices, g.index_count);
        fraction = gen_uniform(&seed);
        flipped = gen_flip_random(&g, fraction, gen_random(&seed), NULL);
        out = orient_checked(g.indices, g.index_count, g.positions, g.vertex_count, 12,
                             plain_policies[round % 4], &r);
        CHECK_EQ(r.mesh.edges_inconsistent, 0);
        CHECK_EQ(r.mesh.components, shells);
        CHECK_EQ(r.mesh.edges, clean_report.mesh.edges);
        CHECK_EQ(r.mesh.euler_characteristic, clean_report.mesh.euler_characteristic);
        if (plain_policies[round % 4] == MESHFIX_POLICY_MAJORITY && fraction > 0.6 && shells == 1) {
            CHECK(is_reversal(out, clean, g.index_count));
        } else if (plain_policies[round % 4] != MESHFIX_POLICY_SEED &&
                   (plain_policies[round % 4] != MESHFIX_POLICY_MAJORITY || fraction < 0.4)) {
            /* every closed shell faces out again: exactly the clean mesh */
            CHECK(memcmp(out, clean, g.index_count * sizeof(unsigned int)) == 0);
            CHECK_EQ(r.triangles_flipped, flipped);
            CHECK(fabs(r.mesh.signed_volume - clean_report.mesh.signed_volume) < 1e-6 * clean_report.mesh.signed_volume);
        }
        free(clean);
        free(out);
        mio_free(&g);
    }
}

/* Random index soups over a few vertices: mostly non-manifold and
   degenerate. The contract still holds, and the same call twice gives
   bit-identical results. */
/* What orient says of the mesh as given is what inspect says of it. */
static void check_before_is_inspect(const meshfix_report *orient, const meshfix_report *inspect)
{
    CHECK_EQ(orient->verdict_before, inspect->verdict);
    CHECK_EQ(orient->edges_inconsistent_before, inspect->mesh.edges_inconsistent);
    CHECK_EQ(orient->patches_inside_out_before, inspect->mesh.patches_inside_out);
    CHECK(orient->signed_volume_before == inspect->mesh.signed_volume);
    CHECK_EQ(inspect->verdict_before, inspect->verdict);
    CHECK(inspect->signed_volume_before == inspect->mesh.signed_volume);
}

static void test_property_random_soups(void)
{
    unsigned long long seed = 99;
    int round;
    for (round = 0; round < 300; ++round) {
        size_t vertices = 3 + gen_random(&seed) % 12, triangles = 1 + gen_random(&seed) % 40, i;
        unsigned int *idx = (unsigned int *)malloc(3 * triangles * sizeof(unsigned int));
        float *p = (float *)malloc(3 * vertices * sizeof(float));
        unsigned int *out, *again;
        meshfix_report r, r2;
        for (i = 0; i < 3 * triangles; ++i)
            idx[i] = (unsigned int)(gen_random(&seed) % vertices);
        for (i = 0; i < 3 * vertices; ++i)
            p[i] = (float)(gen_random(&seed) % 5);
        out = orient_checked(idx, 3 * triangles, p, vertices, 12, plain_policies[round % 4], &r);
        again = orient_checked(idx, 3 * triangles, p, vertices, 12, plain_policies[round % 4], &r2);
        CHECK(memcmp(out, again, 3 * triangles * sizeof(unsigned int)) == 0);
        CHECK(memcmp(&r, &r2, sizeof(r)) == 0);
        CHECK_EQ(meshfix_inspect(idx, 3 * triangles, p, vertices, 12, NULL, &r2, NULL), MESHFIX_OK);
        check_before_is_inspect(&r, &r2);
        CHECK(r.mesh.edges_inconsistent <= r.edges_inconsistent_before || r.mesh.components_non_orientable > 0);
        CHECK_EQ(r.mesh.edges, r.mesh.edges_boundary + r.mesh.edges_manifold + r.mesh.edges_non_manifold);
        CHECK(r.mesh.patches >= r.mesh.components);
        free(out);
        free(again);
        free(idx);
        free(p);
    }
}

/* ---- real models ---- */

static const char *models_dir(void)
{
    const char *dir = getenv("MESHFIX_MODELS");
    return dir != NULL ? dir : "/usr/share/assimp/models";
}

static double triangle_area(const mio_mesh *g, const unsigned int *indices, size_t t)
{
    const float *a = g->positions + 3 * (size_t)indices[3 * t], *b = g->positions + 3 * (size_t)indices[3 * t + 1];
    const float *c = g->positions + 3 * (size_t)indices[3 * t + 2];
    double u[3], v[3], n[3];
    int k;
    for (k = 0; k < 3; ++k) {
        u[k] = (double)b[k] - a[k];
        v[k] = (double)c[k] - a[k];
    }
    n[0] = u[1] * v[2] - u[2] * v[1];
    n[1] = u[2] * v[0] - u[0] * v[2];
    n[2] = u[0] * v[1] - u[1] * v[0];
    return 0.5 * sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
}

/* Scrambles a repaired model and repairs it again. Per patch: under
   MAJORITY it comes back as it was when less than half of its area was
   scrambled and reversed when more was; under OUTWARD a patch is always
   all as it was or all reversed, and no closed patch ends inside-out. */
static void check_scrambled_patches(const char *name, const mio_mesh *g, const unsigned int *reference,
                                    const unsigned int *patch_ids, size_t patches, int policy, unsigned long long seed)
{
    mio_mesh s = *g;
    meshfix_report r;
    unsigned char *scrambled = (unsigned char *)malloc(g->index_count / 3 + 1);
    double *area = (double *)calloc(patches + 1, sizeof(double)), *moved = (double *)calloc(patches + 1, sizeof(double));
    size_t *same = (size_t *)calloc(patches + 1, sizeof(size_t)), *size = (size_t *)calloc(patches + 1, sizeof(size_t));
    size_t t, p, wrong = 0;
    unsigned int *out;
    s.indices = copy_indices(reference, g->index_count);
    gen_flip_random(&s, 0.35, seed, scrambled);
    out = orient_checked(s.indices, s.index_count, s.positions, s.vertex_count, 12, (meshfix_policy)policy, &r);
    CHECK_EQ(r.mesh.edges_inconsistent, r.mesh.edges_non_manifold);
    if (policy == MESHFIX_POLICY_OUTWARD && r.mesh.patches_inside_out != 0)
        printf("    %s: %lu patches inside-out\n", name, (unsigned long)r.mesh.patches_inside_out);
    if (policy == MESHFIX_POLICY_OUTWARD)
        CHECK_EQ(r.mesh.patches_inside_out, 0);
    for (t = 0; t < g->index_count / 3; ++t) {
        size_t patch = patch_ids[t] == 0xFFFFFFFFu ? patches : patch_ids[t];
        double a = triangle_area(g, reference, t);
        area[patch] += a;
        moved[patch] += scrambled[t] ? a : 0.0;
        size[patch]++;
        same[patch] += memcmp(out + 3 * t, reference + 3 * t, 3 * sizeof(unsigned int)) == 0;
    }
    for (p = 0; p < patches; ++p) {
        int all_same = same[p] == size[p], all_reversed = same[p] == 0;
        if (!all_same && !all_reversed)
            wrong++;
        else if (policy == MESHFIX_POLICY_MAJORITY && area[p] > 0 && moved[p] < 0.499 * area[p] && !all_same)
            wrong++;
        else if (policy == MESHFIX_POLICY_MAJORITY && area[p] > 0 && moved[p] > 0.501 * area[p] && !all_reversed)
            wrong++;
    }
    if (wrong != 0)
        printf("    %s: %lu of %lu patches wrong after scrambling (policy %d)\n", name, (unsigned long)wrong,
               (unsigned long)patches, policy);
    CHECK_EQ(wrong, 0);
    free(out);
    free(s.indices);
    free(scrambled);
    free(area);
    free(moved);
    free(same);
    free(size);
}

static void test_real_models(void)
{
    static const char *files[] = {
        "OBJ/WusonOBJ.obj", "OBJ/spider.obj", "OBJ/box.obj", "OBJ/regr01.obj", "OBJ/empty_mat.obj",
        "OBJ/concave_polygon.obj", "OFF/Wuson.off", "OFF/Cube.off", "PLY/cube.ply", "PLY/cube_binary.ply",
        "PLY/Wuson.ply", "STL/Spider_ascii.stl", "STL/Spider_binary.stl", "STL/Wuson.stl", "STL/sphereWithHole.stl"};
    size_t f, loaded = 0;
    for (f = 0; f < sizeof(files) / sizeof(files[0]); ++f) {
        char path[512], error[256];
        mio_mesh g;
        meshfix_report input, fixed;
        meshfix_options o;
        meshfix_outputs outputs;
        unsigned int *reference, *patch_ids;
        int policy;
        snprintf(path, sizeof(path), "%s/%s", models_dir(), files[f]);
        if (!mio_load(path, &g, error, sizeof(error))) {
            printf("    cannot load %s: %s (install Debian's assimp-testmodels)\n", path, error);
            failures++;
            continue;
        }
        loaded++;
        CHECK_EQ(meshfix_inspect(g.indices, g.index_count, g.positions, g.vertex_count, 12, NULL, &input, NULL), MESHFIX_OK);
        patch_ids = (unsigned int *)malloc(g.index_count / 3 * sizeof(unsigned int) + 1);
        for (policy = MESHFIX_POLICY_MAJORITY; policy <= MESHFIX_POLICY_OUTWARD; ++policy) {
            reference = orient_checked(g.indices, g.index_count, g.positions, g.vertex_count, 12,
                                       (meshfix_policy)policy, &fixed);
            CHECK_EQ(fixed.mesh.edges_inconsistent, fixed.mesh.edges_non_manifold);
            CHECK_EQ(fixed.mesh.components_non_orientable, 0);
            CHECK_EQ(fixed.mesh.patches, input.mesh.patches);
            check_before_is_inspect(&fixed, &input);
            if (policy == MESHFIX_POLICY_OUTWARD)
                CHECK_EQ(fixed.mesh.patches_inside_out, 0);
            if (input.mesh.edges_inconsistent == 0 && policy == MESHFIX_POLICY_MAJORITY)
                CHECK_EQ(fixed.triangles_flipped, 0); /* consistent already: unchanged */
            memset(&o, 0, sizeof(o));
            memset(&outputs, 0, sizeof(outputs));
            outputs.patch_ids = patch_ids;
            CHECK_EQ(meshfix_inspect(reference, g.index_count, g.positions, g.vertex_count, 12, &o, &fixed, &outputs),
                     MESHFIX_OK);
            check_scrambled_patches(files[f], &g, reference, patch_ids, fixed.mesh.patches, policy, 1000 + f);
            free(reference);
        }
        free(patch_ids);
        mio_free(&g);
    }
    CHECK_EQ(loaded, sizeof(files) / sizeof(files[0]));
}

/* The hostile files the package ships must be refused with a message. */
static void test_hostile_files(void)
{
    static const char *files[] = {"invalid/OutOfMemory.off", "invalid/empty.obj", "invalid/empty.off",
                                  "invalid/empty.ply", "invalid/malformed.obj", "invalid/malformed2.obj",
                                  "OFF/invalid.off", "PLY/pond.0.ply"};
    static const char *truncated[] = {"PLY/cube_binary.ply", "STL/Spider_binary.stl", "OFF/Wuson.off", "OBJ/box.obj"};
    size_t f;
    for (f = 0; f < sizeof(files) / sizeof(files[0]); ++f) {
        char path[512], error[256] = "";
        mio_mesh g;
        snprintf(path, sizeof(path), "%s/%s", models_dir(), files[f]);
        CHECK(!mio_load(path, &g, error, sizeof(error)));
        CHECK(error[0] != 0);
    }
    /* every prefix of real files: loads or fails cleanly, never crashes */
    for (f = 0; f < sizeof(truncated) / sizeof(truncated[0]); ++f) {
        char path[512], error[256];
        mio_mesh g;
        FILE *in;
        char *data;
        long size, cut;
        snprintf(path, sizeof(path), "%s/%s", models_dir(), truncated[f]);
        in = fopen(path, "rb");
        CHECK(in != NULL);
        if (in == NULL)
            continue;
        fseek(in, 0, SEEK_END);
        size = ftell(in);
        fseek(in, 0, SEEK_SET);
        data = (char *)malloc((size_t)size);
        CHECK(fread(data, 1, (size_t)size, in) == (size_t)size);
        fclose(in);
        for (cut = 0; cut < size; cut += 1 + size / 300) {
            const char *ext = strrchr(truncated[f], '.') + 1;
            char lower[8];
            size_t k;
            for (k = 0; k < 4; ++k)
                lower[k] = (char)(ext[k] | 0x20);
            lower[3] = 0;
            if (mio_parse(data, (size_t)cut, lower, &g, error, sizeof(error))) {
                meshfix_report r;
                CHECK_EQ(meshfix_orient(g.indices, g.indices, g.index_count, g.positions, g.vertex_count, 12, NULL, &r, NULL),
                         MESHFIX_OK);
                mio_free(&g);
            }
        }
        free(data);
    }
}

/* ---- the header's account of itself ---- */

static float distance_to_unit_sphere(const float position[3], void *user)
{
    (void)user;
    return (float)sqrt((double)(position[0] * position[0] + position[1] * position[1] + position[2] * position[2])) -
           1.0f;
}

/* meshfix_policy_info says what each policy needs and does, and each call
   behaves as it says: refused without positions, normals or a distance
   function exactly when it needs them; rays cast only by those that cast
   them (two open sheets apart, half of one reversed: AUTO and VISIBILITY
   look). */
static void test_policy_info(void)
{
    mio_mesh g, other;
    meshfix_report r;
    meshfix_options o;
    float *normals;
    size_t t;
    int p;
    CHECK(gen_grid(&g, 12, 12));
    CHECK(gen_grid(&other, 12, 12));
    for (t = 0; t < other.vertex_count; ++t)
        other.positions[3 * t + 2] += 5.0f;
    CHECK(gen_append(&g, &other));
    for (t = 0; t < other.index_count / 3 / 2; ++t) {
        unsigned int *tri = g.indices + g.index_count - 3 * (t + 1), keep = tri[1];
        tri[1] = tri[2], tri[2] = keep;
    }
    normals = (float *)calloc(g.index_count, sizeof(float));
    CHECK(meshfix_policy_info(MESHFIX_POLICY_COUNT) == NULL);
    CHECK(meshfix_policy_info((meshfix_policy)-1) == NULL);
    for (p = 0; p < (int)MESHFIX_POLICY_COUNT; ++p) {
        const meshfix_policy_facts *f = meshfix_policy_info((meshfix_policy)p);
        meshfix_result without_positions, without_normals, without_distance;
        CHECK(f != NULL && strcmp(f->name, meshfix_policy_string((meshfix_policy)p)) == 0);
        CHECK(f->description != NULL && strlen(f->description) > 10);
        memset(&o, 0, sizeof(o));
        o.policy = (meshfix_policy)p;
        o.sdf.distance = distance_to_unit_sphere;
        o.evidence.triangle_normals = normals;
        without_positions = meshfix_orient(NULL, g.indices, g.index_count, NULL, g.vertex_count, 0, &o, &r, NULL);
        CHECK_EQ(without_positions == MESHFIX_ERROR_POSITIONS_REQUIRED, f->needs_positions);
        o.evidence.triangle_normals = NULL;
        without_normals = meshfix_orient(NULL, g.indices, g.index_count, g.positions, g.vertex_count, 12, &o, &r,
                                         NULL);
        CHECK_EQ(without_normals == MESHFIX_ERROR_NORMALS_REQUIRED, f->needs_normals);
        o.evidence.triangle_normals = normals;
        o.sdf.distance = NULL;
        without_distance = meshfix_orient(NULL, g.indices, g.index_count, g.positions, g.vertex_count, 12, &o, &r,
                                          NULL);
        CHECK_EQ(without_distance == MESHFIX_ERROR_INVALID_ARGUMENT, f->needs_distance);
        o.sdf.distance = distance_to_unit_sphere;
        CHECK_EQ(meshfix_orient(NULL, g.indices, g.index_count, g.positions, g.vertex_count, 12, &o, &r, NULL),
                 MESHFIX_OK);
        CHECK_EQ(r.evidence.rays_cast > 0, f->casts_rays && p != MESHFIX_POLICY_OUTWARD);
        if (f->casts_rays == 0)
            CHECK_EQ(r.evidence.rays_cast, 0);
    }
    CHECK(meshfix_policy_info(MESHFIX_POLICY_UP)->reads_up && !meshfix_policy_info(MESHFIX_POLICY_AUTO)->reads_up);
    free(normals);
    mio_free(&other);
    mio_free(&g);
}

/* The options are resolved and checked whole before any index is read:
   a bad option is refused as such even where the indices are bad too
   (an index out of range, a count that is no multiple of 3), and
   meshfix_scratch_size (0) and meshfix_weld refuse it the same way. */
static void test_options_before_indices(void)
{
    static const unsigned int bad_indices[] = {0, 2, 1, 0, 1, 99};
    meshfix_options o;
    meshfix_report r;
    meshfix_check_failure why;
    unsigned int remap[4];
    size_t unique = 0;
    int k;
    for (k = 0; k < 4; ++k) {
        memset(&o, 0, sizeof(o));
        if (k == 0)
            o.evidence.sigma = -1.0f;
        else if (k == 1)
            o.index_size = 3;
        else if (k == 2)
            o.evidence.triangle_normals_stride = 7;
        else
            o.visibility.rays = (size_t)1 << 30;
        CHECK_EQ(meshfix_orient(NULL, bad_indices, 6, tetra_positions, 4, 12, &o, &r, NULL),
                 MESHFIX_ERROR_INVALID_ARGUMENT);
        CHECK_EQ(meshfix_orient(NULL, bad_indices, 5, tetra_positions, 4, 12, &o, &r, NULL),
                 MESHFIX_ERROR_INVALID_ARGUMENT);
        CHECK_EQ(meshfix_inspect(bad_indices, 6, tetra_positions, 4, 12, &o, &r, NULL), MESHFIX_ERROR_INVALID_ARGUMENT);
        CHECK(!meshfix_check(bad_indices, 6, tetra_positions, 4, 12, 0, &o, &why));
        CHECK_EQ(why.result, MESHFIX_ERROR_INVALID_ARGUMENT);
        CHECK_EQ(meshfix_scratch_size(6, 4, &o), 0);
        CHECK_EQ(meshfix_weld(remap, tetra_positions, 4, 12, 0.0f, &o, &unique), MESHFIX_ERROR_INVALID_ARGUMENT);
    }
    memset(&o, 0, sizeof(o));
    CHECK_EQ(meshfix_orient(NULL, bad_indices, 6, tetra_positions, 4, 12, &o, &r, NULL),
             MESHFIX_ERROR_INDEX_OUT_OF_RANGE);
    CHECK(meshfix_scratch_size(6, 4, &o) > 0);
    CHECK_EQ(meshfix_weld(remap, tetra_positions, 4, 12, 0.0f, &o, &unique), MESHFIX_OK);
    CHECK_EQ(unique, 4);
}

/* meshfix_doubtful_below is the bar the report counts by: a patch just
   under it is doubtful, one at it is not. */
static void test_doubtful_below(void)
{
    meshfix_options o;
    meshfix_report r;
    meshfix_outputs outputs;
    float confidence[8];
    int p;
    CHECK(fabs(meshfix_doubtful_below(NULL, MESHFIX_POLICY_AUTO) - 0.9f) < 1e-6f);
    for (p = 1; p < (int)MESHFIX_POLICY_COUNT; ++p)
        CHECK(meshfix_doubtful_below(NULL, (meshfix_policy)p) == 0.5f);
    memset(&o, 0, sizeof(o));
    memset(&outputs, 0, sizeof(outputs));
    outputs.patch_confidence = confidence;
    outputs.patch_confidence_capacity = 8;
    CHECK_EQ(meshfix_orient(NULL, tetra_indices, 12, tetra_positions, 4, 12, &o, &r, &outputs), MESHFIX_OK);
    CHECK_EQ(r.mesh.patches, 1);
    CHECK(confidence[0] >= meshfix_doubtful_below(&o, MESHFIX_POLICY_AUTO));
    CHECK_EQ(r.patches_doubtful, 0);
    o.evidence.min_confidence = confidence[0];
    CHECK(meshfix_doubtful_below(&o, MESHFIX_POLICY_AUTO) == confidence[0]);
    CHECK_EQ(meshfix_orient(NULL, tetra_indices, 12, tetra_positions, 4, 12, &o, &r, &outputs), MESHFIX_OK);
    CHECK_EQ(r.patches_doubtful, 0);
    o.evidence.min_confidence = nextafterf(confidence[0], 2.0f);
    CHECK_EQ(meshfix_orient(NULL, tetra_indices, 12, tetra_positions, 4, 12, &o, &r, &outputs), MESHFIX_OK);
    CHECK_EQ(r.patches_doubtful, 1);
    CHECK_EQ(r.verdict, MESHFIX_VERDICT_DOUBTFUL);
}

/* meshfix_verdict_worst: clean says least, not orientable most; the list's
   words are meshfix_verdict_string's. */
static void test_verdict_worst(void)
{
    static const meshfix_verdict ascending[] = {MESHFIX_VERDICT_CLEAN, MESHFIX_VERDICT_REPAIRED,
                                                MESHFIX_VERDICT_INSIDE_OUT, MESHFIX_VERDICT_INCONSISTENT,
                                                MESHFIX_VERDICT_DOUBTFUL, MESHFIX_VERDICT_NOT_ORIENTABLE};
    int i, k;
    CHECK_EQ((int)(sizeof(ascending) / sizeof(ascending[0])), (int)MESHFIX_VERDICT_COUNT);
    for (i = 0; i < (int)MESHFIX_VERDICT_COUNT; ++i)
        for (k = 0; k < (int)MESHFIX_VERDICT_COUNT; ++k)
            CHECK_EQ(meshfix_verdict_worst(ascending[i], ascending[k]), ascending[i > k ? i : k]);
    CHECK_EQ(meshfix_verdict_worst(MESHFIX_VERDICT_REPAIRED, MESHFIX_VERDICT_COUNT), MESHFIX_VERDICT_REPAIRED);
    CHECK_EQ(meshfix_verdict_worst((meshfix_verdict)99, MESHFIX_VERDICT_CLEAN), MESHFIX_VERDICT_CLEAN);
    CHECK(strcmp(meshfix_verdict_string(MESHFIX_VERDICT_NOT_ORIENTABLE), "not orientable") == 0);
    CHECK(strcmp(meshfix_verdict_string(MESHFIX_VERDICT_COUNT), "unknown verdict") == 0);
}

/* ---- runner ---- */

static const test_case tests[] = {
    {"quick start compiles and works", test_quick_start},
    {"tetrahedron", test_tetrahedron},
    {"cube with 1 and 5 flipped", test_cube_one_and_five_flipped},
    {"open sheet", test_open_sheet},
    {"moebius strip", test_mobius_strip},
    {"moebius seam independent of input winding", test_mobius_seam_independent_of_winding},
    {"two shells", test_two_shells},
    {"non-manifold fan", test_non_manifold_fan},
    {"bow-tie vertex", test_bow_tie_vertex},
    {"90% flipped sphere", test_ninety_percent_flipped_sphere},
    {"degenerate and duplicate triangles", test_degenerate_triangles},
    {"NaN positions", test_nan_positions},
    {"empty mesh", test_empty_mesh},
    {"strides 12, 16, 32", test_strides},
    {"errors change nothing", test_errors_change_nothing},
    {"allocators and scratch", test_allocators},
    {"property: random flips on closed meshes", test_property_random_flips},
    {"property: random soups", test_property_random_soups},
    {"real models: scrambled and repaired", test_real_models},
    {"hostile and truncated files", test_hostile_files},
    {"policy info: what each policy needs and does", test_policy_info},
    {"options checked before any index is read", test_options_before_indices},
    {"doubtful below: the report's bar", test_doubtful_below},
    {"verdict worst: the order of verdicts", test_verdict_worst},
};

int main(int argc, char **argv)
{
    return run_tests(tests, sizeof(tests) / sizeof(tests[0]), argc > 1 ? argv[1] : NULL);
}
