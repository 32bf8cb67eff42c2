/* Tests of MESHFIX_POLICY_SDF on the six shapes of a contouring pipeline,
   meshed from their SDFs by examples/sdfmesh.h (marching tetrahedra).
   Prints "N passed, N failed". */
#undef NDEBUG
#define MESHFIX_IMPLEMENTATION
#include "../meshfix.h"
#define MESHIO_IMPLEMENTATION
#include "../examples/meshio.h"
#define MESHGEN_IMPLEMENTATION
#include "../examples/meshgen.h"
#define SDFMESH_IMPLEMENTATION
#include "../examples/sdfmesh.h"

#include "check.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct shape {
    const char *name;
    sdfmesh_fn sdf;
    int plain_rule_fails; /* the per-triangle rule leaves triangles reversed: 1 yes, 0 no */
} shape;

/* At cells of 0.1 the plain rule fails on the cylinder only: at its rim
   the mesher leaves flat triangles just below the cap where the distance
   to the side dominates, so the gradient at their centroid lies in their
   plane and they get no vote (a slight tilt would give a vote of either
   sign). The box's edges do the same at finer cells (0.05). */
static const shape shapes[6] = {{"sphere", sdf_sphere, 0},
                                {"box", sdf_box, 0},
                                {"cylinder", sdf_cylinder, 1},
                                {"union of two spheres", sdf_union, 0},
                                {"smooth union of two spheres", sdf_smooth_union, 0},
                                {"thin box (half extents 1, 1, 0.01)", sdf_thin_box, 0}};

/* Cells of 0.1: ten times the thin box's thickness. z = 0 is a grid plane,
   so the corners there are inside the thin box and the slab is found; x
   and y are offset so that no face of a shape lies on a grid plane. */
static int mesh_shape(mio_mesh *m, sdfmesh_fn f, float cell)
{
    int k = (int)(1.3f / cell) + 1;
    float low[3];
    unsigned n[3];
    low[0] = -(float)k * cell + 0.0123f;
    low[1] = -(float)k * cell + 0.0171f;
    low[2] = -(float)k * cell;
    n[0] = n[1] = n[2] = (unsigned)(2 * k);
    return sdfmesh_tetra(m, f, NULL, low, cell, n);
}

static meshfix_options sdf_options(sdfmesh_fn f, meshfix_sdf_mode mode)
{
    meshfix_options o;
    memset(&o, 0, sizeof(o));
    o.policy = MESHFIX_POLICY_SDF;
    o.sdf.distance = f;
    o.sdf.mode = mode;
    return o;
}

/* The plain rule run on a mesh flips nothing exactly when every triangle
   with a normal faces along the gradient at its centroid. */
static size_t triangles_against_gradient(const mio_mesh *m, sdfmesh_fn f)
{
    meshfix_options o = sdf_options(f, MESHFIX_SDF_PER_TRIANGLE);
    meshfix_report r;
    if (meshfix_orient(NULL, m->indices, m->index_count, m->positions, m->vertex_count, 12, &o, &r, NULL) != MESHFIX_OK)
        return (size_t)-1;
    return r.triangles_flipped;
}

/* The mesher's output: closed, manifold, genus 0, consistent, outward. */
static void check_reference(const shape *s, const mio_mesh *m)
{
    meshfix_report r;
    CHECK_EQ(meshfix_inspect(m->indices, m->index_count, m->positions, m->vertex_count, 12, NULL, &r, NULL), MESHFIX_OK);
    CHECK(r.mesh.triangles > 500);
    CHECK_EQ(r.mesh.edges_boundary, 0);
    CHECK_EQ(r.mesh.edges_non_manifold, 0);
    CHECK_EQ(r.mesh.edges_manifold, r.mesh.edges);
    CHECK_EQ(r.mesh.edges_inconsistent, 0);
    CHECK_EQ(r.mesh.vertices_non_manifold, 0);
    CHECK_EQ(r.mesh.triangles_zero_area, 0);
    CHECK_EQ(r.mesh.components, 1);
    CHECK_EQ(r.mesh.euler_characteristic, 2);
    CHECK(r.mesh.signed_volume > 0);
    CHECK_EQ(triangles_against_gradient(m, s->sdf), 0);
}

/* Scramble 10%, 50%, 90%; repair per patch: exactly the mesher's output,
   every edge shared by two triangles in opposite directions, V - E + F = 2,
   and every triangle along the gradient. */
static void test_shape(const shape *s)
{
    static const double fractions[3] = {0.1, 0.5, 0.9};
    mio_mesh m;
    unsigned int *reference, *out;
    int f;
    CHECK(mesh_shape(&m, s->sdf, 0.1f));
    check_reference(s, &m);
    reference = (unsigned int *)malloc(m.index_count * sizeof(unsigned int));
    out = (unsigned int *)malloc(m.index_count * sizeof(unsigned int));
    memcpy(reference, m.indices, m.index_count * sizeof(unsigned int));
    for (f = 0; f < 3; ++f) {
        meshfix_options o = sdf_options(s->sdf, MESHFIX_SDF_PER_PATCH);
        meshfix_report r, after;
        mio_mesh fixed = m;
        size_t scrambled;
        memcpy(m.indices, reference, m.index_count * sizeof(unsigned int));
        scrambled = gen_flip_random(&m, fractions[f], 31 + (unsigned long long)f, NULL);
        CHECK_EQ(meshfix_orient(out, m.indices, m.index_count, m.positions, m.vertex_count, 12, &o, &r, NULL), MESHFIX_OK);
        CHECK(memcmp(out, reference, m.index_count * sizeof(unsigned int)) == 0);
        CHECK_EQ(r.triangles_flipped, scrambled);
        CHECK_EQ(r.mesh.edges_inconsistent, 0);
        CHECK_EQ(r.evidence.triangles_sdf_disagree, 0);
        CHECK_EQ(r.evidence.sdf_evaluations, 6 * (m.index_count / 3));
        fixed.indices = out;
        CHECK_EQ(meshfix_inspect(out, m.index_count, m.positions, m.vertex_count, 12, NULL, &after, NULL), MESHFIX_OK);
        CHECK_EQ(after.mesh.edges_manifold, after.mesh.edges);
        CHECK_EQ(after.mesh.edges_inconsistent, 0);
        CHECK_EQ(after.mesh.euler_characteristic, 2);
        CHECK_EQ(triangles_against_gradient(&fixed, s->sdf), 0);

        /* The plain per-triangle rule never votes against the patch here:
           where it has a vote, the vote is right. */
        o.sdf.mode = MESHFIX_SDF_PER_TRIANGLE;
        CHECK_EQ(meshfix_orient(out, m.indices, m.index_count, m.positions, m.vertex_count, 12, &o, &r, NULL), MESHFIX_OK);
        CHECK_EQ(r.evidence.triangles_sdf_disagree, 0);
    }
    /* Every triangle reversed: per patch restores all of it. The plain rule
       restores the thin box and the blends too: marching tetrahedra put each
       vertex on a tetrahedron edge where f changes sign, so each triangle
       separates its tetrahedron's inside corners from the outside ones and
       faces within 90 degrees of the gradient; central differences with a
       quarter-edge step keep their sign inside the 0.02 slab (|z + h| -
       |z - h| = 2z whenever |z| < h). It fails where the gradient at a
       centroid lies in the triangle's plane: at sharp edges. */
    {
        meshfix_options o = sdf_options(s->sdf, MESHFIX_SDF_PER_PATCH);
        meshfix_report r;
        size_t t;
        for (t = 0; t < m.index_count / 3; ++t) {
            m.indices[3 * t + 1] = reference[3 * t + 2];
            m.indices[3 * t + 2] = reference[3 * t + 1];
        }
        CHECK_EQ(meshfix_orient(out, m.indices, m.index_count, m.positions, m.vertex_count, 12, &o, &r, NULL), MESHFIX_OK);
        CHECK(memcmp(out, reference, m.index_count * sizeof(unsigned int)) == 0);
        o.sdf.mode = MESHFIX_SDF_PER_TRIANGLE;
        CHECK_EQ(meshfix_orient(out, m.indices, m.index_count, m.positions, m.vertex_count, 12, &o, &r, NULL), MESHFIX_OK);
        printf("    %s, all reversed: the plain rule leaves %lu triangles reversed, %lu edges inconsistent; "
               "per patch 0\n", s->name, (unsigned long)(r.mesh.triangles - r.triangles_flipped),
               (unsigned long)r.mesh.edges_inconsistent);
        CHECK_EQ(r.evidence.triangles_sdf_disagree, 0);
        if (s->plain_rule_fails)
            CHECK(r.mesh.edges_inconsistent > 0 && r.triangles_flipped < r.mesh.triangles);
        else
            CHECK(r.mesh.edges_inconsistent == 0 && r.triangles_flipped == r.mesh.triangles);
    }
    memcpy(m.indices, reference, m.index_count * sizeof(unsigned int));
    free(reference);
    free(out);
    mio_free(&m);
}

static void test_sphere(void) { test_shape(&shapes[0]); }
static void test_box(void) { test_shape(&shapes[1]); }
static void test_cylinder(void) { test_shape(&shapes[2]); }
static void test_union(void) { test_shape(&shapes[3]); }
static void test_smooth_union(void) { test_shape(&shapes[4]); }
static void test_thin_box(void) { test_shape(&shapes[5]); }

/* Where the plain rule fails: a box whose faces lie on grid planes (an
   axis-aligned CAD part on its own grid) gives sample values of exactly 0,
   coincident vertices and triangles of zero area. They have no normal, so
   the plain rule cannot judge them and leaves them as scrambled; per patch
   they follow their neighbours. */
static float grid_box(const float p[3], void *user)
{
    float q[3], outside;
    (void)user;
    q[0] = fabsf(p[0]) - 0.8f, q[1] = fabsf(p[1]) - 0.6f, q[2] = fabsf(p[2]) - 0.5f;
    outside = sqrtf((q[0] > 0 ? q[0] * q[0] : 0) + (q[1] > 0 ? q[1] * q[1] : 0) + (q[2] > 0 ? q[2] * q[2] : 0));
    return outside + fminf(fmaxf(q[0], fmaxf(q[1], q[2])), 0.0f);
}

static void test_zero_area(void)
{
    static const float low[3] = {-1.2f, -1.2f, -1.2f};
    static const unsigned n[3] = {24, 24, 24};
    mio_mesh m;
    meshfix_options patch = sdf_options(grid_box, MESHFIX_SDF_PER_PATCH);
    meshfix_options plain = sdf_options(grid_box, MESHFIX_SDF_PER_TRIANGLE);
    meshfix_report r;
    unsigned int *reference, *out;
    CHECK(sdfmesh_tetra(&m, grid_box, NULL, low, 0.1f, n));
    /* the mesher puts several vertices at one point where the surface
       passes through a grid corner: joined by position, those triangles
       would repeat a vertex (excluded, never flipped); this test is about
       triangles that keep three vertices and lose their area */
    patch.topology = plain.topology = MESHFIX_TOPOLOGY_INDICES;
    reference = (unsigned int *)malloc(m.index_count * sizeof(unsigned int));
    out = (unsigned int *)malloc(m.index_count * sizeof(unsigned int));
    /* the mesher winds by the tetrahedron, not by the triangle's own
       normal, so even the triangles with no area come out consistent */
    CHECK_EQ(meshfix_inspect(m.indices, m.index_count, m.positions, m.vertex_count, 12, &patch, &r, NULL), MESHFIX_OK);
    CHECK(r.mesh.triangles_zero_area > 100);
    CHECK_EQ(r.mesh.edges_inconsistent, 0);
    CHECK_EQ(r.mesh.patches_inside_out, 0);
    CHECK_EQ(r.mesh.euler_characteristic, 2);
    memcpy(reference, m.indices, m.index_count * sizeof(unsigned int));
    gen_flip_random(&m, 0.5, 5, NULL);
    CHECK_EQ(meshfix_orient(out, m.indices, m.index_count, m.positions, m.vertex_count, 12, &patch, &r, NULL), MESHFIX_OK);
    CHECK(memcmp(out, reference, m.index_count * sizeof(unsigned int)) == 0);
    CHECK_EQ(r.mesh.edges_inconsistent, 0);
    CHECK_EQ(meshfix_orient(out, m.indices, m.index_count, m.positions, m.vertex_count, 12, &plain, &r, NULL), MESHFIX_OK);
    printf("    grid-aligned box: %lu zero-area triangles; plain rule leaves %lu edges inconsistent, per patch 0\n",
           (unsigned long)r.mesh.triangles_zero_area, (unsigned long)r.mesh.edges_inconsistent);
    CHECK(r.mesh.edges_inconsistent > 50);
    CHECK(memcmp(out, reference, m.index_count * sizeof(unsigned int)) != 0);
    free(reference);
    free(out);
    mio_free(&m);
}

/* A caller's gradient replaces the 6 differences with 1 call. */
static void sphere_gradient(const float p[3], float g[3], void *user)
{
    (void)user;
    g[0] = p[0], g[1] = p[1], g[2] = p[2];
}

static void test_gradient_callback_and_step(void)
{
    mio_mesh m;
    meshfix_options o = sdf_options(sdf_sphere, MESHFIX_SDF_PER_PATCH);
    meshfix_report r;
    unsigned int *reference, *out;
    CHECK(mesh_shape(&m, sdf_sphere, 0.1f));
    reference = (unsigned int *)malloc(m.index_count * sizeof(unsigned int));
    out = (unsigned int *)malloc(m.index_count * sizeof(unsigned int));
    memcpy(reference, m.indices, m.index_count * sizeof(unsigned int));
    gen_flip_random(&m, 0.7, 9, NULL);
    o.sdf.gradient = sphere_gradient;
    CHECK_EQ(meshfix_orient(out, m.indices, m.index_count, m.positions, m.vertex_count, 12, &o, &r, NULL), MESHFIX_OK);
    CHECK(memcmp(out, reference, m.index_count * sizeof(unsigned int)) == 0);
    CHECK_EQ(r.evidence.sdf_evaluations, m.index_count / 3);
    o.sdf.gradient = NULL;
    o.sdf.step = 0.3f; /* three cells: still the right side */
    CHECK_EQ(meshfix_orient(out, m.indices, m.index_count, m.positions, m.vertex_count, 12, &o, &r, NULL), MESHFIX_OK);
    CHECK(memcmp(out, reference, m.index_count * sizeof(unsigned int)) == 0);
    free(reference);
    free(out);
    mio_free(&m);
}

/* An SDF that answers NaN gives no votes: the patch falls back to its
   majority side, still consistent; nothing crashes. */
static float nan_sdf(const float p[3], void *user)
{
    (void)p, (void)user;
    return (float)NAN;
}

static void test_bad_sdf_and_arguments(void)
{
    mio_mesh m;
    meshfix_options o = sdf_options(nan_sdf, MESHFIX_SDF_PER_PATCH);
    meshfix_report r;
    unsigned int before[12];
    CHECK(gen_torus(&m, 12, 8, 2, 0.5f));
    gen_flip_random(&m, 0.3, 4, NULL);
    CHECK_EQ(meshfix_orient(NULL, m.indices, m.index_count, m.positions, m.vertex_count, 12, &o, &r, NULL), MESHFIX_OK);
    CHECK_EQ(r.mesh.edges_inconsistent, 0);
    CHECK_EQ(r.evidence.triangles_sdf_disagree, 0);
    memcpy(before, m.indices, sizeof(before));
    o.sdf.distance = NULL;
    CHECK_EQ(meshfix_orient(m.indices, m.indices, m.index_count, m.positions, m.vertex_count, 12, &o, &r, NULL),
             MESHFIX_ERROR_INVALID_ARGUMENT);
    o.sdf.distance = sdf_sphere;
    CHECK_EQ(meshfix_orient(m.indices, m.indices, m.index_count, NULL, m.vertex_count, 0, &o, &r, NULL),
             MESHFIX_ERROR_POSITIONS_REQUIRED);
    o.sdf.mode = (meshfix_sdf_mode)7;
    CHECK_EQ(meshfix_orient(m.indices, m.indices, m.index_count, m.positions, m.vertex_count, 12, &o, &r, NULL),
             MESHFIX_ERROR_INVALID_ARGUMENT);
    CHECK(memcmp(before, m.indices, sizeof(before)) == 0);
    mio_free(&m);
}

static const test_case tests[] = {
    {"sphere: 10/50/90% flipped, per patch restores it", test_sphere},
    {"box", test_box},
    {"cylinder: the plain rule fails at its sharp rim, per patch does not", test_cylinder},
    {"union of two spheres", test_union},
    {"smooth union of two spheres", test_smooth_union},
    {"thin box, cells ten times thicker than it: neither rule fails", test_thin_box},
    {"zero-area triangles: the plain rule fails, per patch does not", test_zero_area},
    {"gradient callback and step", test_gradient_callback_and_step},
    {"NaN SDF and bad arguments", test_bad_sdf_and_arguments},
};

int main(int argc, char **argv)
{
    return run_tests(tests, sizeof(tests) / sizeof(tests[0]), argc > 1 ? argv[1] : NULL);
}
