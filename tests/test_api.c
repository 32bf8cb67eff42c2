/* The 0.2 API as a user meets it: an engine's vertex buffer as it is
   (split at UV and normal seams), 16-bit indices and double positions,
   a model far from the origin, zero-initialised options, a check that
   says why, the verdict and its one-line summary, welding. Real models
   from assimp-testmodels and occt-misc (make test installs them:
   tests/install_deps.sh). Prints "N passed, N failed". */
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
#include "models.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *const engine_models[] = {
    "/usr/share/assimp/models/OBJ/spider.obj", "/usr/share/assimp/models/OBJ/WusonOBJ.obj",
    "/usr/share/assimp/models/OBJ/regr01.obj", "/usr/share/assimp/models/OBJ/empty_mat.obj"};

/* Flags of the triangles the default policy flips, and the report. */
static unsigned char *flips_of(const void *indices, size_t index_count, const void *positions, size_t vertex_count,
                               size_t stride, const meshfix_options *o, meshfix_report *r)
{
    unsigned char *flipped = (unsigned char *)calloc(index_count / 3 + 1, 1);
    meshfix_outputs outputs = {0};
    outputs.flipped = flipped;
    CHECK_EQ(meshfix_orient(NULL, indices, index_count, positions, vertex_count, stride, o, r, &outputs),
             MESHFIX_OK);
    return flipped;
}

/* An engine's buffer, split at seams, gives what its positions give. */
static void test_engine_vertex_buffers(void)
{
    size_t f, splits = 0;
    for (f = 0; f < sizeof(engine_models) / sizeof(engine_models[0]); ++f) {
        engine_mesh e;
        meshfix_report engine, welded, indices_only;
        meshfix_options o = {0};
        unsigned char *a, *b, *c;
        size_t t, differ = 0;
        if (!engine_obj_load(engine_models[f], &e))
            continue;
        a = flips_of(e.indices, e.index_count, e.vertices, e.vertex_count, ENGINE_STRIDE, NULL, &engine);
        b = flips_of(e.by_position, e.index_count, e.positions, e.position_count, 0, NULL, &welded);
        o.topology = MESHFIX_TOPOLOGY_INDICES;
        c = flips_of(e.indices, e.index_count, e.vertices, e.vertex_count, ENGINE_STRIDE, &o, &indices_only);
        for (t = 0; t < e.index_count / 3; ++t)
            differ += a[t] != b[t];
        printf("    %s: %lu vertices for %lu positions; %lu patches, %lu flips as loaded (positions: %lu, %lu; "
               "indices only: %lu, %lu)\n",
               strrchr(engine_models[f], '/') + 1, (unsigned long)e.vertex_count, (unsigned long)e.position_count,
               (unsigned long)engine.mesh.patches, (unsigned long)engine.triangles_flipped,
               (unsigned long)welded.mesh.patches, (unsigned long)welded.triangles_flipped,
               (unsigned long)indices_only.mesh.patches, (unsigned long)indices_only.triangles_flipped);
        CHECK_EQ(differ, 0);
        CHECK_EQ(engine.mesh.patches, welded.mesh.patches);
        CHECK_EQ(engine.mesh.edges_inconsistent, welded.mesh.edges_inconsistent);
        if (e.vertex_count > e.position_count) { /* the file splits vertices at seams */
            splits++;
            CHECK(engine.mesh.vertices_joined > 0);
            /* what the option turns off: the seams cut the topology */
            CHECK(indices_only.mesh.patches > welded.mesh.patches);
        }
        free(a), free(b), free(c);
        engine_free(&e);
    }
    CHECK(splits >= 3);
}

/* Real models and generated scenes: 16-bit indices and double positions
   give the 32-bit float result, bit for bit. */
static void check_formats(const char *name, const mio_mesh *g)
{
    size_t n = g->index_count, i;
    unsigned int *out32 = (unsigned int *)malloc(n * sizeof(unsigned int) + 4);
    unsigned short *idx16 = (unsigned short *)malloc(n * sizeof(unsigned short) + 4);
    unsigned short *out16 = (unsigned short *)malloc(n * sizeof(unsigned short) + 4);
    unsigned int *outd = (unsigned int *)malloc(n * sizeof(unsigned int) + 4);
    double *pd = (double *)malloc(3 * g->vertex_count * sizeof(double) + 8);
    meshfix_report r32, r16, rd;
    meshfix_options o16 = {0}, od = {0};
    int small = g->vertex_count <= 65536;
    CHECK_EQ(meshfix_orient(out32, g->indices, n, g->positions, g->vertex_count, 0, NULL, &r32, NULL), MESHFIX_OK);
    for (i = 0; i < 3 * g->vertex_count; ++i)
        pd[i] = (double)g->positions[i];
    od.position_size = 8;
    CHECK_EQ(meshfix_orient(outd, g->indices, n, pd, g->vertex_count, 0, &od, &rd, NULL), MESHFIX_OK);
    CHECK(memcmp(out32, outd, n * sizeof(unsigned int)) == 0);
    CHECK_EQ(rd.triangles_flipped, r32.triangles_flipped);
    CHECK_EQ(rd.mesh.patches, r32.mesh.patches);
    if (small) {
        for (i = 0; i < n; ++i)
            idx16[i] = (unsigned short)g->indices[i];
        o16.index_size = 2;
        CHECK_EQ(meshfix_orient(out16, idx16, n, g->positions, g->vertex_count, 0, &o16, &r16, NULL), MESHFIX_OK);
        for (i = 0; i < n && out16[i] == out32[i]; ++i) {
        }
        CHECK_EQ(i, n);
        CHECK(memcmp(&r16, &r32, sizeof(r16)) == 0);
        /* in place, 16-bit */
        CHECK_EQ(meshfix_orient(idx16, idx16, n, g->positions, g->vertex_count, 0, &o16, NULL, NULL), MESHFIX_OK);
        CHECK(memcmp(idx16, out16, n * sizeof(unsigned short)) == 0);
    }
    printf("    %s: %lu triangles, %lu flipped; 16-bit %s, double the same\n", name, (unsigned long)(n / 3),
           (unsigned long)r32.triangles_flipped, small ? "the same" : "(over 65536 vertices: not tried)");
    free(out32), free(idx16), free(out16), free(outd), free(pd);
}

static void test_index_and_position_formats(void)
{
    static const char *const files[] = {"/usr/share/opencascade/data/stl/motor.stl",
                                        "/usr/share/assimp/models/OBJ/spider.obj",
                                        "/usr/share/assimp/models/PLY/cube.ply"};
    size_t f, s;
    for (f = 0; f < sizeof(files) / sizeof(files[0]); ++f) {
        mio_mesh g;
        if (!load_model(files[f], &g))
            continue;
        gen_flip_random(&g, 0.3, 7, NULL);
        check_formats(strrchr(files[f], '/') + 1, &g);
        mio_free(&g);
    }
    for (s = 0; s < scene_count(); ++s) {
        scene sc;
        scene_trial t;
        if (scene_build(&sc, scene_get(s)->name, SCENE_SMALL) != 1)
            continue;
        CHECK(scene_trial_make(&t, &sc, &SCENE_CORRUPTIONS[4], 11));
        check_formats(scene_get(s)->name, &t.mesh);
        scene_trial_free(&t);
        scene_free(&sc);
    }
}

/* Doubles in survey coordinates (UTM: 5 * 10^5 east, 5 * 10^6 north) keep
   features a float there would round away. */
static void test_far_from_origin(void)
{
    scene sc;
    scene_trial t;
    double *far_away;
    size_t i, n;
    unsigned int *near_out, *far_out;
    meshfix_options od = {0};
    meshfix_report near, far;
    CHECK(scene_build(&sc, "assembly", SCENE_SMALL) == 1);
    CHECK(scene_trial_make(&t, &sc, &SCENE_CORRUPTIONS[4], 3));
    n = t.mesh.index_count;
    far_away = (double *)malloc(3 * t.mesh.vertex_count * sizeof(double));
    for (i = 0; i < 3 * t.mesh.vertex_count; ++i)
        far_away[i] = (double)t.mesh.positions[i] + (i % 3 == 0 ? 5e5 : i % 3 == 1 ? 5e6 : 100.0); /* UTM-like */
    near_out = (unsigned int *)malloc(n * sizeof(unsigned int));
    far_out = (unsigned int *)malloc(n * sizeof(unsigned int));
    CHECK_EQ(meshfix_orient(near_out, t.mesh.indices, n, t.mesh.positions, t.mesh.vertex_count, 0, NULL, &near, NULL),
             MESHFIX_OK);
    od.position_size = 8;
    CHECK_EQ(meshfix_orient(far_out, t.mesh.indices, n, far_away, t.mesh.vertex_count, 0, &od, &far, NULL),
             MESHFIX_OK);
    /* the same coordinates rounded to float: the parts lose their shape */
    {
        float *as_float = (float *)malloc(3 * t.mesh.vertex_count * sizeof(float));
        unsigned int *rounded_out = (unsigned int *)malloc(n * sizeof(unsigned int));
        meshfix_report rounded;
        size_t wrong = 0;
        for (i = 0; i < 3 * t.mesh.vertex_count; ++i)
            as_float[i] = (float)far_away[i];
        CHECK_EQ(meshfix_orient(rounded_out, t.mesh.indices, n, as_float, t.mesh.vertex_count, 0, NULL, &rounded,
                                NULL),
                 MESHFIX_OK);
        for (i = 0; i < n; i += 3)
            wrong += memcmp(rounded_out + i, near_out + i, 3 * sizeof(unsigned int)) != 0;
        printf("    assembly at UTM-like coordinates in doubles: %lu flipped, as at the origin; the same coordinates "
               "in floats: %lu triangles come out otherwise\n",
               (unsigned long)far.triangles_flipped, (unsigned long)wrong);
        CHECK(wrong > 0);
        free(rounded_out);
        free(as_float);
    }
    CHECK(memcmp(near_out, far_out, n * sizeof(unsigned int)) == 0);
    CHECK_EQ(far.mesh.triangles_zero_area, near.mesh.triangles_zero_area);
    CHECK(near.triangles_flipped > 0);
    free(far_away), free(near_out), free(far_out);
    scene_trial_free(&t);
    scene_free(&sc);
}

static const float tetra_p[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
static const unsigned int tetra_i[] = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};

/* meshfix_check names the requirement, the place and the count. */
static void test_check_says_why(void)
{
    meshfix_check_failure why;
    unsigned int idx[12], open[9], bowtie[] = {0, 1, 2, 0, 3, 4};
    static const float bowtie_p[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, -1, 0, 0, 0, -1, 0};
    CHECK(meshfix_check(tetra_i, 12, tetra_p, 4, 0, MESHFIX_REQUIRE_SOLID, NULL, &why));
    CHECK_EQ(why.requirement, 0);
    CHECK(strcmp(why.text, "ok") == 0);
    /* one triangle turned: its edges run like its neighbours' */
    memcpy(idx, tetra_i, sizeof(idx));
    idx[4] = 3, idx[5] = 1;
    CHECK(!meshfix_check(idx, 12, tetra_p, 4, 0, 0, NULL, &why));
    printf("    %s\n", why.text);
    CHECK_EQ(why.result, MESHFIX_OK);
    CHECK_EQ(why.requirement, MESHFIX_REQUIRE_CONSISTENT);
    CHECK_EQ(why.count, 3);
    CHECK(why.triangle == 0 || why.triangle == 1);
    CHECK(strstr(why.text, "not consistent: 3 edges") == why.text);
    /* open: the first boundary edge */
    memcpy(open, tetra_i, sizeof(open));
    CHECK(!meshfix_check(open, 9, tetra_p, 4, 0, MESHFIX_REQUIRE_CLOSED, NULL, &why));
    printf("    %s\n", why.text);
    CHECK_EQ(why.requirement, MESHFIX_REQUIRE_CLOSED);
    CHECK_EQ(why.count, 3);
    CHECK(why.edge[0] < why.edge[1] && why.edge[1] < 4);
    /* bow-tie: two fans at vertex 0 */
    CHECK(!meshfix_check(bowtie, 6, bowtie_p, 5, 0, MESHFIX_REQUIRE_MANIFOLD, NULL, &why));
    printf("    %s\n", why.text);
    CHECK_EQ(why.requirement, MESHFIX_REQUIRE_MANIFOLD);
    CHECK(strstr(why.text, "vertex 0") != NULL);
    /* inside out */
    memcpy(idx, tetra_i, sizeof(idx));
    {
        size_t t;
        for (t = 0; t < 4; ++t) {
            unsigned int x = idx[3 * t + 1];
            idx[3 * t + 1] = idx[3 * t + 2], idx[3 * t + 2] = x;
        }
    }
    CHECK(meshfix_check(idx, 12, tetra_p, 4, 0, MESHFIX_REQUIRE_CONSISTENT, NULL, &why));
    CHECK(!meshfix_check(idx, 12, tetra_p, 4, 0, MESHFIX_REQUIRE_SOLID, NULL, &why));
    printf("    %s\n", why.text);
    CHECK_EQ(why.requirement, MESHFIX_REQUIRE_OUTWARD);
    CHECK_EQ(why.triangle, 0);
    /* a repeated vertex */
    memcpy(idx, tetra_i, sizeof(idx));
    idx[7] = idx[6];
    CHECK(!meshfix_check(idx, 12, tetra_p, 4, 0, MESHFIX_REQUIRE_NO_DEGENERATE, NULL, &why));
    printf("    %s\n", why.text);
    CHECK_EQ(why.requirement, MESHFIX_REQUIRE_NO_DEGENERATE);
    CHECK_EQ(why.triangle, 2);
    /* not valid input: the result says so */
    memcpy(idx, tetra_i, sizeof(idx));
    idx[3] = 9;
    CHECK(!meshfix_check(idx, 12, tetra_p, 4, 0, 0, NULL, &why));
    printf("    %s\n", why.text);
    CHECK_EQ(why.result, MESHFIX_ERROR_INDEX_OUT_OF_RANGE);
    CHECK_EQ(why.triangle, 1);
    CHECK(strstr(why.text, "index 9 in triangle 1, 4 vertices") != NULL);
    CHECK(!meshfix_check(tetra_i, 12, NULL, 4, 0, MESHFIX_REQUIRE_OUTWARD, NULL, &why));
    CHECK_EQ(why.result, MESHFIX_ERROR_POSITIONS_REQUIRED);
    /* no failure struct is fine */
    CHECK(!meshfix_check(idx, 12, tetra_p, 4, 0, 0, NULL, NULL));
}

/* The verdict and the line that says it. */
static void test_verdict_and_summary(void)
{
    meshfix_report r;
    meshfix_options o = {0};
    unsigned int idx[12], out[12];
    char line[160], tiny[8];
    size_t length;
    mio_mesh strip;
    memcpy(idx, tetra_i, sizeof(idx));
    CHECK_EQ(meshfix_orient(out, idx, 12, tetra_p, 4, 0, NULL, &r, NULL), MESHFIX_OK);
    CHECK_EQ(r.verdict, MESHFIX_VERDICT_CLEAN);
    meshfix_summary(&r, line, sizeof(line));
    CHECK(strcmp(line, "clean: nothing to flip (4 triangles, 1 patch)") == 0);
    idx[4] = 3, idx[5] = 1;
    CHECK_EQ(meshfix_orient(out, idx, 12, tetra_p, 4, 0, NULL, &r, NULL), MESHFIX_OK);
    CHECK_EQ(r.verdict, MESHFIX_VERDICT_REPAIRED);
    length = meshfix_summary(&r, line, sizeof(line));
    CHECK(strcmp(line, "fixed 1 triangle in 1 patch") == 0);
    CHECK_EQ(length, strlen(line));
    /* cut short, still terminated, and the length of the whole line */
    CHECK_EQ(meshfix_summary(&r, tiny, sizeof(tiny)), length);
    CHECK(strcmp(tiny, "fixed 1") == 0);
    CHECK_EQ(meshfix_summary(&r, NULL, 0), length);
    CHECK(strcmp(meshfix_verdict_string(r.verdict), "repaired") == 0);
    /* inspect: what is wrong as given */
    CHECK_EQ(meshfix_inspect(idx, 12, tetra_p, 4, 0, NULL, &r, NULL), MESHFIX_OK);
    CHECK_EQ(r.verdict, MESHFIX_VERDICT_INCONSISTENT);
    meshfix_summary(&r, line, sizeof(line));
    printf("    %s\n", line);
    CHECK(strstr(line, "inconsistent: 3 edges run") == line);
    /* an assembly with half of every part reversed at random: some parts
       have too little evidence either way */
    {
        scene sc;
        scene_trial t;
        CHECK(scene_build(&sc, "assembly", SCENE_SMALL) == 1);
        CHECK(scene_trial_make(&t, &sc, &SCENE_CORRUPTIONS[5], 5));
        CHECK_EQ(meshfix_orient(NULL, t.mesh.indices, t.mesh.index_count, t.mesh.positions, t.mesh.vertex_count, 0,
                                &o, &r, NULL),
                 MESHFIX_OK);
        meshfix_summary(&r, line, sizeof(line));
        printf("    %s\n", line);
        CHECK(r.patches_doubtful > 0);
        CHECK_EQ(r.verdict, MESHFIX_VERDICT_DOUBTFUL);
        CHECK(strstr(line, "fixed ") == line && strstr(line, "of the area) doubtful") != NULL);
        scene_trial_free(&t);
        scene_free(&sc);
    }
    /* a Moebius strip */
    CHECK(gen_mobius(&strip, 24));
    CHECK_EQ(meshfix_orient(strip.indices, strip.indices, strip.index_count, strip.positions, strip.vertex_count, 0,
                            NULL, &r, NULL),
             MESHFIX_OK);
    CHECK_EQ(r.verdict, MESHFIX_VERDICT_NOT_ORIENTABLE);
    meshfix_summary(&r, line, sizeof(line));
    printf("    %s\n", line);
    CHECK(strstr(line, "not orientable: 1 component") == line);
    mio_free(&strip);
}

/* `= {0}` is every default, and NULL options are the same. */
static void test_zero_options(void)
{
    meshfix_options zero = {0};
    meshfix_report a, b;
    unsigned int x[12], y[12];
    CHECK_EQ(meshfix_orient(x, tetra_i, 12, tetra_p, 4, 0, &zero, &a, NULL), MESHFIX_OK);
    CHECK_EQ(meshfix_orient(y, tetra_i, 12, tetra_p, 4, 0, NULL, &b, NULL), MESHFIX_OK);
    CHECK(memcmp(x, y, sizeof(x)) == 0 && memcmp(&a, &b, sizeof(a)) == 0);
    /* sizes other than the two of each are refused */
    zero.index_size = 3;
    CHECK_EQ(meshfix_orient(x, tetra_i, 12, tetra_p, 4, 0, &zero, &a, NULL), MESHFIX_ERROR_INVALID_ARGUMENT);
    zero.index_size = 0, zero.position_size = 2;
    CHECK_EQ(meshfix_orient(x, tetra_i, 12, tetra_p, 4, 0, &zero, &a, NULL), MESHFIX_ERROR_INVALID_ARGUMENT);
    zero.position_size = 0, zero.topology = (meshfix_topology)7;
    CHECK_EQ(meshfix_orient(x, tetra_i, 12, tetra_p, 4, 0, &zero, &a, NULL), MESHFIX_ERROR_INVALID_ARGUMENT);
}

/* TOPOLOGY_WELD joins corners a CAD export left a hair apart; exact
   positions do not. */
static void test_weld_topology(void)
{
    mio_mesh g, soup;
    meshfix_options o = {0};
    meshfix_report exact, welded;
    size_t i;
    unsigned int remap_f[64], remap_d[64];
    size_t unique_f, unique_d;
    double pd[3 * 64];
    CHECK(gen_sphere(&g, 6, 8, 0, 0, 0, 1));
    /* a soup: every corner its own vertex, moved by up to 1e-5 */
    CHECK(gen_soup(&soup, &g));
    for (i = 0; i < 3 * soup.vertex_count; ++i)
        soup.positions[i] += (float)((double)((i * 2654435761u) % 1000) * 1e-8);
    CHECK_EQ(meshfix_inspect(soup.indices, soup.index_count, soup.positions, soup.vertex_count, 0, NULL, &exact, NULL),
             MESHFIX_OK);
    o.topology = MESHFIX_TOPOLOGY_WELD;
    o.weld_tolerance = 1e-4f;
    CHECK_EQ(meshfix_inspect(soup.indices, soup.index_count, soup.positions, soup.vertex_count, 0, &o, &welded, NULL),
             MESHFIX_OK);
    CHECK_EQ(exact.mesh.patches, soup.index_count / 3);
    CHECK_EQ(welded.mesh.patches, 1);
    CHECK_EQ(welded.mesh.patches_closed, 1);
    /* meshfix_weld reads doubles too, with the same answer */
    for (i = 0; i < 3 * 64 && i < 3 * soup.vertex_count; ++i)
        pd[i] = (double)soup.positions[i];
    CHECK_EQ(meshfix_weld(remap_f, soup.positions, 64, 0, 1e-4f, NULL, &unique_f), MESHFIX_OK);
    o.position_size = 8;
    CHECK_EQ(meshfix_weld(remap_d, pd, 64, 0, 1e-4f, &o, &unique_d), MESHFIX_OK);
    CHECK(memcmp(remap_f, remap_d, sizeof(remap_f)) == 0);
    CHECK_EQ(unique_f, unique_d);
    CHECK(unique_f < 64);
    mio_free(&g);
    mio_free(&soup);
}

/* A small mesh costs little under every policy: no floor of rays sized
   for large meshes (VISIBILITY's 65536 once cast 32768 pairs at a quad).
   Counted in rays, not time: what a policy casts on a flat quad, facing
   up, which no policy may turn over. */
static void test_small_mesh_few_rays(void)
{
    static const float quad[12] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
    static const unsigned int indices[6] = {0, 1, 2, 0, 2, 3};
    int policy;
    for (policy = 0; policy < MESHFIX_POLICY_COUNT; ++policy) {
        meshfix_options o = {0};
        meshfix_report r;
        unsigned int out[6];
        static const float up[3] = {0, 0, 1};
        if (policy == MESHFIX_POLICY_SDF || policy == MESHFIX_POLICY_NORMALS)
            continue; /* they need a function or normals */
        o.policy = (meshfix_policy)policy;
        memcpy(o.up, up, sizeof(up));
        CHECK_EQ(meshfix_orient(out, indices, 6, quad, 4, 12, &o, &r, NULL), MESHFIX_OK);
        printf("    policy %d: %lu rays, %lu flipped\n", policy, (unsigned long)r.evidence.rays_cast,
               (unsigned long)r.triangles_flipped);
        CHECK(r.evidence.rays_cast <= 64 * 2);
        CHECK_EQ(r.triangles_flipped, 0);
    }
}

static const test_case tests[] = {
    {"an engine's vertex buffer, split at seams, orients as its positions", test_engine_vertex_buffers},
    {"16-bit indices and double positions give the 32-bit float result", test_index_and_position_formats},
    {"doubles 10^6 from the origin (UTM-like) orient as at the origin", test_far_from_origin},
    {"meshfix_check says which requirement fails, where and how often", test_check_says_why},
    {"the verdict and its one-line summary", test_verdict_and_summary},
    {"zero options are the defaults; unknown formats are refused", test_zero_options},
    {"TOPOLOGY_WELD joins corners a hair apart; weld reads doubles", test_weld_topology},
    {"a quad casts at most 64 rays a triangle under every policy", test_small_mesh_few_rays},
};

int main(int argc, char **argv)
{
    return run_tests(tests, sizeof(tests) / sizeof(tests[0]), argc > 1 ? argv[1] : NULL);
}
