/* scenes_check.c - checks that the part generators of examples/meshgen.h
   and the scenes of tests/scenes.h are what they claim: closed where
   closed, with the right volume and Euler characteristic, every triangle
   facing the stated way, cuts and corruptions keeping the truth. Without
   this, a scene with a wrong truth would score the library wrongly.

   Build:  cc -std=c99 -O2 -I. -o build/scenes_check tests/eval/scenes_check.c -lm
   Usage:  scenes_check [FILTER]     prints "N passed, N failed" */
#define MESHFIX_IMPLEMENTATION
#include "meshfix.h"
#define MESHIO_IMPLEMENTATION
#include "examples/meshio.h"
#define MESHGEN_IMPLEMENTATION
#include "examples/meshgen.h"
#define SCENES_IMPLEMENTATION
#include "tests/scenes.h"

#include "tests/check.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- geometry of one triangle ---- */

static void corner(const mio_mesh *m, size_t t, int k, double p[3])
{
    const float *v = m->positions + 3 * (size_t)m->indices[3 * t + (size_t)k];
    p[0] = v[0], p[1] = v[1], p[2] = v[2];
}

/* (b - a) x (c - a) and the centroid of triangle t. */
static void normal_and_centre(const mio_mesh *m, size_t t, double n[3], double c[3])
{
    double a[3], b[3], d[3];
    int k;
    corner(m, t, 0, a);
    corner(m, t, 1, b);
    corner(m, t, 2, d);
    n[0] = (b[1] - a[1]) * (d[2] - a[2]) - (b[2] - a[2]) * (d[1] - a[1]);
    n[1] = (b[2] - a[2]) * (d[0] - a[0]) - (b[0] - a[0]) * (d[2] - a[2]);
    n[2] = (b[0] - a[0]) * (d[1] - a[1]) - (b[1] - a[1]) * (d[0] - a[0]);
    for (k = 0; k < 3; ++k)
        c[k] = (a[k] + b[k] + d[k]) / 3;
}

static double signed_volume(const mio_mesh *m)
{
    size_t t;
    double v = 0;
    for (t = 0; t < m->index_count / 3; ++t) {
        double a[3], b[3], c[3];
        corner(m, t, 0, a);
        corner(m, t, 1, b);
        corner(m, t, 2, c);
        v += a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0]);
    }
    return v / 6;
}

static int near(double a, double b, double relative)
{
    return fabs(a - b) <= relative * fabs(b);
}

/* Closed, manifold, consistent, with this Euler characteristic and a
   volume within `relative` of `volume`. */
static void check_solid(const char *name, const mio_mesh *m, long euler, double volume, double relative)
{
    meshfix_report r;
    double v = signed_volume(m);
    CHECK_EQ(meshfix_inspect(m->indices, m->index_count, m->positions, m->vertex_count, 12, NULL, &r, NULL), MESHFIX_OK);
    CHECK_EQ(r.mesh.edges_boundary, 0);
    CHECK_EQ(r.mesh.edges_non_manifold, 0);
    CHECK_EQ(r.mesh.vertices_non_manifold, 0);
    CHECK_EQ(r.mesh.edges_inconsistent, 0);
    CHECK_EQ(r.mesh.triangles_degenerate + r.mesh.triangles_zero_area, 0);
    CHECK_EQ(r.mesh.euler_characteristic, euler);
    if (!near(v, volume, relative)) {
        printf("    %s: volume %g, expected %g\n", name, v, volume);
        failures++;
    }
}

/* Every triangle's normal agrees with direction(centroid). */
typedef void (*direction_fn)(const double c[3], double d[3]);

static size_t count_against(const mio_mesh *m, direction_fn direction)
{
    size_t t, against = 0;
    for (t = 0; t < m->index_count / 3; ++t) {
        double n[3], c[3], d[3];
        normal_and_centre(m, t, n, c);
        direction(c, d);
        against += n[0] * d[0] + n[1] * d[1] + n[2] * d[2] <= 0;
    }
    return against;
}

static void up(const double c[3], double d[3])
{
    (void)c;
    d[0] = 0, d[1] = 0, d[2] = 1;
}

static void away_from_z_axis(const double c[3], double d[3])
{
    d[0] = c[0], d[1] = c[1], d[2] = 0;
}

/* Out of a U along y, open to +z: sideways on the walls, away from the
   y axis on the bottom. */
static void out_of_channel(const double c[3], double d[3])
{
    d[0] = c[0], d[1] = 0, d[2] = c[2] > 1e-6 ? 0 : c[2];
}

/* ---- the generators ---- */

static void test_box(void)
{
    static const float lo[3] = {-1, 0, 2}, hi[3] = {1, 0.5f, 2.25f};
    mio_mesh m;
    CHECK(gen_box(&m, 1, lo, hi));
    CHECK_EQ(m.index_count / 3, 12);
    CHECK_EQ(m.vertex_count, 8);
    check_solid("box", &m, 2, 2 * 0.5 * 0.25, 1e-6);
    mio_free(&m);
    CHECK(gen_box(&m, 7, lo, hi));
    CHECK_EQ(m.index_count / 3, 12 * 49);
    check_solid("box 7", &m, 2, 2 * 0.5 * 0.25, 1e-6);
    mio_free(&m);
}

static void test_boxes_bracket_housings(void)
{
    static const float size[3] = {1, 0.8f, 0.6f};
    const double w = 0.05, outer = 1 * 0.8 * 0.6, hollow = 0.9 * 0.7 * 0.5;
    mio_mesh m;
    CHECK(gen_bracket(&m, 0.4f, 0.3f, 0.5f, 0.05f, 0.03f));
    check_solid("bracket", &m, 2, 0.4 * 0.05 * 0.5 + 0.05 * 0.25 * 0.5, 1e-5);
    mio_free(&m);
    CHECK(gen_housing(&m, size, (float)w, GEN_HOUSING_SEALED, 0.05f));
    check_solid("sealed housing", &m, 4, outer - hollow, 1e-5);
    mio_free(&m);
    /* a tunnel joining the two spheres of the sealed housing makes one
       sphere, not a torus: Euler characteristic 2 */
    CHECK(gen_housing(&m, size, (float)w, GEN_HOUSING_WINDOW, 0.05f));
    check_solid("housing with a window", &m, 2, outer - hollow - w * 0.32 * 0.24, 1e-4);
    mio_free(&m);
    CHECK(gen_housing(&m, size, (float)w, GEN_HOUSING_OPEN_TOP, 0.05f));
    check_solid("cup", &m, 2, outer - 0.9 * 0.7 * 0.55, 1e-5);
    mio_free(&m);
}

static void test_tubes_and_sheets(void)
{
    const double pi = 3.14159265358979323846;
    mio_mesh m;
    meshfix_report r;
    CHECK(gen_cylinder(&m, 64, 5, 3, 0.5f, 2));
    CHECK_EQ(m.index_count / 3, 2 * 64 * 5 + 2 * 64 * 5);
    check_solid("cylinder", &m, 2, pi * 0.25 * 2, 0.01);
    mio_free(&m);
    CHECK(gen_cylinder(&m, 16, 1, 1, 0.5f, 2)); /* fan caps */
    check_solid("cylinder with fans", &m, 2, pi * 0.25 * 2, 0.03);
    mio_free(&m);
    CHECK(gen_pipe(&m, 40, 6, 0.3f, 1));
    CHECK_EQ(count_against(&m, away_from_z_axis), 0);
    CHECK_EQ(meshfix_inspect(m.indices, m.index_count, m.positions, m.vertex_count, 12, NULL, &r, NULL), MESHFIX_OK);
    CHECK_EQ(r.mesh.edges_boundary, 80);
    CHECK_EQ(r.mesh.edges_inconsistent, 0);
    mio_free(&m);
    CHECK(gen_disc(&m, 64, 1, 1));
    CHECK_EQ(m.index_count / 3, 64);
    CHECK_EQ(count_against(&m, up), 0);
    mio_free(&m);
    CHECK(gen_disc(&m, 30, 7, 1));
    CHECK_EQ(count_against(&m, up), 0);
    CHECK_EQ(meshfix_inspect(m.indices, m.index_count, m.positions, m.vertex_count, 12, NULL, &r, NULL), MESHFIX_OK);
    CHECK_EQ(r.mesh.edges_boundary, 30);
    CHECK_EQ(r.mesh.edges_inconsistent, 0);
    mio_free(&m);
    CHECK(gen_plane(&m, 3, 2, 1.5f, 0.5f));
    CHECK_EQ(count_against(&m, up), 0);
    mio_free(&m);
    CHECK(gen_terrain(&m, 60, 1, 0.05f, 0.25f));
    CHECK_EQ(count_against(&m, up), 0);
    mio_free(&m);
    CHECK(gen_channel(&m, 30, 10, 0.2f, 0.15f, 1));
    CHECK_EQ(count_against(&m, out_of_channel), 0);
    CHECK_EQ(meshfix_inspect(m.indices, m.index_count, m.positions, m.vertex_count, 12, NULL, &r, NULL), MESHFIX_OK);
    CHECK_EQ(r.mesh.edges_inconsistent, 0);
    CHECK_EQ(r.mesh.edges_boundary, 2 * 30 + 2 * 10);
    mio_free(&m);
}

static void test_transform_and_subdivide(void)
{
    static const float mirror[9] = {-1, 0, 0, 0, 1, 0, 0, 0, 1}, shift[3] = {3, 0, 0};
    static const float lo[3] = {0, 0, 0}, hi[3] = {1, 2, 3};
    mio_mesh m;
    CHECK(gen_box(&m, 2, lo, hi));
    gen_transform(&m, mirror, shift);
    check_solid("mirrored box", &m, 2, 6, 1e-6);
    CHECK(gen_subdivide(&m));
    CHECK_EQ(m.index_count / 3, 4 * 12 * 4);
    check_solid("subdivided box", &m, 2, 6, 1e-6);
    mio_free(&m);
    CHECK(gen_torus(&m, 30, 12, 2, 0.5f));
    CHECK(gen_subdivide(&m));
    check_solid("subdivided torus", &m, 0, signed_volume(&m), 0);
    CHECK(signed_volume(&m) > 0);
    mio_free(&m);
}

/* The cut keeps triangles and corners in order, shares no vertex across
   patches, and moves vertices only a little. */
static void test_cut(void)
{
    mio_mesh m, c;
    meshfix_report r;
    unsigned int *patch;
    size_t t, patches, crossing = 0;
    int k;
    CHECK(gen_sphere(&m, 40, 80, 0, 0, 0, 1));
    patch = (unsigned int *)malloc(m.index_count / 3 * sizeof(unsigned int));
    patches = gen_cut(&c, patch, &m, 100, 0.01f, 5);
    CHECK(patches >= 90 && patches <= 100);
    CHECK_EQ(c.index_count, m.index_count);
    for (t = 0; t < m.index_count / 3; ++t)
        for (k = 0; k < 3; ++k) {
            double a[3], b[3];
            corner(&m, t, k, a);
            corner(&c, t, k, b);
            CHECK(fabs(a[0] - b[0]) + fabs(a[1] - b[1]) + fabs(a[2] - b[2]) < 0.03);
        }
    CHECK_EQ(meshfix_inspect(c.indices, c.index_count, c.positions, c.vertex_count, 12, NULL, &r, NULL), MESHFIX_OK);
    CHECK_EQ(r.mesh.edges_inconsistent, 0);
    CHECK(r.mesh.patches >= patches);
    /* a vertex of the cut belongs to triangles of one patch only */
    {
        unsigned int *owner = (unsigned int *)malloc(c.vertex_count * sizeof(unsigned int));
        memset(owner, 0xFF, c.vertex_count * sizeof(unsigned int));
        for (t = 0; t < c.index_count; ++t) {
            unsigned int v = c.indices[t];
            crossing += owner[v] != 0xFFFFFFFFu && owner[v] != patch[t / 3];
            owner[v] = patch[t / 3];
        }
        free(owner);
    }
    CHECK_EQ(crossing, 0);
    free(patch);
    mio_free(&m);
    mio_free(&c);
}

/* Corruptions: the truth says which triangles face as generated. */
static void test_corruptions(void)
{
    mio_mesh m, g;
    unsigned char *truth;
    unsigned int *from, *patch;
    size_t t, n, reversed;
    CHECK(gen_sphere(&g, 20, 30, 0, 0, 0, 1));
    n = g.index_count / 3;
    truth = (unsigned char *)malloc(n);
    from = (unsigned int *)malloc(n * sizeof(unsigned int));
    patch = (unsigned int *)malloc(n * sizeof(unsigned int));
    CHECK(gen_cut(&m, patch, &g, 20, 0.01f, 3) > 0);
    memset(truth, 1, n);
    reversed = gen_reverse_random(&m, truth, 0.3, 9);
    CHECK(reversed > n / 5 && reversed < n * 2 / 5);
    reversed = gen_reverse_patches(&m, truth, patch, 0.5, 4);
    CHECK(reversed > 0 && reversed < n);
    gen_reverse_all(&m, truth);
    CHECK(gen_shuffle(&m, truth, from, 6));
    /* truth[t] must say whether new triangle t is wound as original from[t] */
    for (t = 0; t < n; ++t) {
        const unsigned int *now = m.indices + 3 * t, *was = g.indices + 3 * (size_t)from[t];
        double a[3], b[3], na[3], nb[3];
        normal_and_centre(&m, t, na, a);
        normal_and_centre(&g, from[t], nb, b);
        CHECK(fabs(a[0] - b[0]) + fabs(a[1] - b[1]) + fabs(a[2] - b[2]) < 0.03);
        CHECK_EQ(truth[t], na[0] * nb[0] + na[1] * nb[1] + na[2] * nb[2] > 0);
        (void)now, (void)was;
    }
    free(truth);
    free(from);
    free(patch);
    mio_free(&m);
    mio_free(&g);
}

/* ---- the scenes ---- */

/* Per part: whether it is closed, and its signed volume. */
static void part_facts(const scene *s, size_t part, int *closed, double *volume)
{
    mio_mesh sub = s->mesh;
    meshfix_report r;
    size_t t, n = 0;
    sub.indices = (unsigned int *)malloc(s->mesh.index_count * sizeof(unsigned int) + 1);
    for (t = 0; t < s->mesh.index_count / 3; ++t)
        if (s->part[t] == part)
            memcpy(sub.indices + 3 * n++, s->mesh.indices + 3 * t, 3 * sizeof(unsigned int));
    sub.index_count = 3 * n;
    *closed = meshfix_inspect(sub.indices, sub.index_count, sub.positions, sub.vertex_count, 12, NULL, &r, NULL) == MESHFIX_OK &&
              r.mesh.edges_boundary == 0 && r.mesh.edges_non_manifold == 0 && r.mesh.edges_inconsistent == 0;
    *volume = signed_volume(&sub);
    free(sub.indices);
}

/* Hollows are the parts meant to face into themselves. */
static int is_hollow(const char *name)
{
    return strcmp(name, "hollow") == 0 || strcmp(name, "glass inside") == 0;
}

static void check_scene(const scene_info *info, scene_size size)
{
    scene s;
    size_t t, triangles, p;
    int built = scene_build(&s, info->name, size);
    if (built < 0) {
        printf("    %s: not available (skipped)\n", info->name);
        return;
    }
    CHECK_EQ(built, 1);
    if (built != 1)
        return;
    triangles = s.mesh.index_count / 3;
    printf("    %-16s %-5s %8lu triangles %3lu parts %4lu patches\n", info->name, size == SCENE_SMALL ? "small" : "large",
           (unsigned long)triangles, (unsigned long)s.part_count, (unsigned long)s.patches);
    /* a generated scene at its two sizes; a corpus file (details 0 and 0)
       is as large as it is */
    if (info->small != 0 || info->large != 0)
        CHECK(size == SCENE_SMALL ? triangles < 20000 : triangles >= 100000 && triangles <= 1000000);
    else
        CHECK(triangles > 0);
    for (t = 0; t < triangles; ++t)
        CHECK(s.truth[t] == 1 && s.part[t] < s.part_count && (s.patch == NULL || s.patch[t] < s.patches));
    /* closed parts (before a cut) face out of their material */
    for (p = 0; s.patch == NULL && p < s.part_count; ++p) {
        int closed;
        double volume;
        part_facts(&s, p, &closed, &volume);
        if (closed && (volume > 0) == is_hollow(s.parts[p].name)) {
            printf("    %s: part %lu (%s) has volume %g\n", info->name, (unsigned long)p, s.parts[p].name, volume);
            failures++;
        }
    }
    scene_free(&s);
}

static void test_scenes_small(void)
{
    size_t i;
    for (i = 0; i < scene_count(); ++i)
        check_scene(scene_get(i), SCENE_SMALL);
}

static void test_scenes_large(void)
{
    size_t i;
    for (i = 0; i < scene_count(); ++i)
        check_scene(scene_get(i), SCENE_LARGE);
}

/* Bounds of each part: lo x y z, hi x y z. */
static void part_bounds(const scene *s, double (*bounds)[6])
{
    size_t p, i;
    int k;
    for (p = 0; p < s->part_count; ++p)
        for (k = 0; k < 3; ++k)
            bounds[p][k] = 1e30, bounds[p][k + 3] = -1e30;
    for (i = 0; i < s->mesh.index_count; ++i) {
        const float *v = s->mesh.positions + 3 * (size_t)s->mesh.indices[i];
        double *b = bounds[s->part[i / 3]];
        for (k = 0; k < 3; ++k) {
            b[k] = fmin(b[k], (double)v[k]);
            b[k + 3] = fmax(b[k + 3], (double)v[k]);
        }
    }
}

static int apart(const double a[6], const double b[6])
{
    int k;
    for (k = 0; k < 3; ++k)
        if (a[k + 3] < b[k] || b[k + 3] < a[k])
            return 1;
    return 0;
}

static int within(const double a[6], const double b[6])
{
    int k;
    for (k = 0; k < 3; ++k)
        if (a[k] <= b[k] || a[k + 3] >= b[k + 3])
            return 0;
    return 1;
}

/* No two parts touch: their boxes are apart, and a part near the housing
   lies in its hollow or away from it. */
static void test_parts_apart(void)
{
    static const char *names[] = {"assembly", "assembly_sealed", "parts"};
    static const double housing[6] = {0, 0, 0, 1, 0.8, 0.6}, hollow[6] = {0.04, 0.04, 0.04, 0.96, 0.76, 0.56};
    double bounds[SCENE_MAX_PARTS][6];
    size_t n, p, q;
    for (n = 0; n < sizeof(names) / sizeof(names[0]); ++n) {
        scene s;
        CHECK_EQ(scene_build(&s, names[n], SCENE_SMALL), 1);
        part_bounds(&s, bounds);
        for (p = 0; p < s.part_count; ++p) {
            int is_housing = n < 2 && strcmp(s.parts[p].name, "housing") == 0;
            if (is_housing)
                continue;
            if (n < 2 && !apart(bounds[p], housing) && !within(bounds[p], hollow)) {
                printf("    %s: part %lu (%s) touches the housing\n", names[n], (unsigned long)p, s.parts[p].name);
                failures++;
            }
            for (q = p + 1; q < s.part_count; ++q)
                if (!(n < 2 && strcmp(s.parts[q].name, "housing") == 0) && !apart(bounds[p], bounds[q])) {
                    printf("    %s: parts %lu (%s) and %lu (%s) touch\n", names[n], (unsigned long)p, s.parts[p].name,
                           (unsigned long)q, s.parts[q].name);
                    failures++;
                }
        }
        scene_free(&s);
    }
}

/* How far apart the copies of one vertex end up in the cut cavity (the
   uncut cavity, built again, tells which corners were one vertex),
   against the diagonal of the model. */
static void test_seam_width(void)
{
    scene cut, whole;
    unsigned detail = scene_find("cavity_cut")->small;
    size_t t, k, pairs = 0;
    double sum = 0, widest = 0, lo[3] = {1e30, 1e30, 1e30}, hi[3] = {-1e30, -1e30, -1e30}, diagonal = 0;
    float *seen;
    CHECK_EQ(scene_cavity_cut(&cut, detail), 1);
    CHECK_EQ(scene_cavity(&whole, detail), 1);
    seen = (float *)malloc(3 * whole.mesh.vertex_count * sizeof(float));
    for (k = 0; k < 3 * whole.mesh.vertex_count; ++k)
        seen[k] = NAN;
    for (t = 0; t < cut.mesh.index_count; ++t) {
        const float *p = cut.mesh.positions + 3 * (size_t)cut.mesh.indices[t];
        float *q = seen + 3 * (size_t)whole.mesh.indices[t];
        double d = 0;
        for (k = 0; k < 3; ++k) {
            lo[k] = fmin(lo[k], (double)p[k]);
            hi[k] = fmax(hi[k], (double)p[k]);
            d += ((double)p[k] - (double)q[k]) * ((double)p[k] - (double)q[k]);
        }
        if (isnan(q[0])) {
            memcpy(q, p, 3 * sizeof(float));
        } else if (d > 0) {
            sum += sqrt(d);
            widest = sqrt(d) > widest ? sqrt(d) : widest;
            pairs++;
        }
    }
    for (k = 0; k < 3; ++k)
        diagonal += (hi[k] - lo[k]) * (hi[k] - lo[k]);
    diagonal = sqrt(diagonal);
    printf("    cavity_cut: seams %.3f%% of the diagonal wide on average, %.3f%% at most\n",
           100 * sum / (double)(pairs ? pairs : 1) / diagonal, 100 * widest / diagonal);
    CHECK(pairs > 0);
    CHECK(sum / (double)(pairs ? pairs : 1) > 0.001 * diagonal && widest < 0.02 * diagonal);
    free(seen);
    scene_free(&whole);
    scene_free(&cut);
}

static const test_case tests[] = {
    {"box", test_box},
    {"boxes, bracket, housings", test_boxes_bracket_housings},
    {"tubes and sheets", test_tubes_and_sheets},
    {"transform and subdivide", test_transform_and_subdivide},
    {"cut", test_cut},
    {"corruptions keep the truth", test_corruptions},
    {"scenes (small)", test_scenes_small},
    {"parts apart", test_parts_apart},
    {"seam width", test_seam_width},
    {"scenes (large)", test_scenes_large},
};

int main(int argc, char **argv)
{
    return run_tests(tests, sizeof(tests) / sizeof(tests[0]), argc > 1 ? argv[1] : NULL);
}
