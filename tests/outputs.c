/* Prints one line per (mesh, policy): a digest of everything a call
   returns (indices, flags, patch ids, the report's counts, confidences
   to one decimal).
   `make test` builds it several ways (-O0, -O2, -O3 -ffast-math, clang,
   -m32 where it installs, the scalar path) and compares the lines: the
   output must not depend on the compiler, its flags or the word size. */
#define MESHFIX_IMPLEMENTATION
#include "../meshfix.h"
#define MESHIO_IMPLEMENTATION
#include "../examples/meshio.h"
#define MESHGEN_IMPLEMENTATION
#include "../examples/meshgen.h"
#define SCENES_IMPLEMENTATION
#include "scenes.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static unsigned int digest_bytes(unsigned int h, const void *data, size_t size)
{
    const unsigned char *p = (const unsigned char *)data;
    size_t i;
    for (i = 0; i < size; ++i)
        h = (h ^ p[i]) * 16777619u;
    return h;
}

/* The report as text: the same on every word size (its doubles rounded
   to 6 digits: sums in another order may differ in the last bits,
   decisions may not). */
static unsigned int digest_report(unsigned int h, const meshfix_report *r)
{
    char text[256];
    snprintf(text, sizeof(text), "%lu %lu %lu %lu %lu %lu %lu %lu %lu %lu %lu %lu %.6g %.6g",
             (unsigned long)r->triangles_flipped, (unsigned long)r->mesh.patches, (unsigned long)r->mesh.patches_closed,
             (unsigned long)r->mesh.patches_inside_out, (unsigned long)r->mesh.components, (unsigned long)r->mesh.edges_inconsistent,
             (unsigned long)r->mesh.triangles_duplicate, (unsigned long)r->mesh.vertices_non_manifold,
             (unsigned long)r->evidence.shells_inward, (unsigned long)r->evidence.rays_cast, (unsigned long)r->evidence.patches_merged,
             (unsigned long)r->mesh.triangles_zero_area, r->mesh.area, r->mesh.signed_volume);
    return digest_bytes(h, text, strlen(text));
}

static void run(const char *name, const mio_mesh *g)
{
    static const char *const names[] = {"auto", "seed", "majority", "outward", "visibility", "up", "normals"};
    static const meshfix_policy policies[] = {MESHFIX_POLICY_AUTO,    MESHFIX_POLICY_SEED,
                                              MESHFIX_POLICY_MAJORITY, MESHFIX_POLICY_OUTWARD,
                                              MESHFIX_POLICY_VISIBILITY, MESHFIX_POLICY_UP, MESHFIX_POLICY_NORMALS};
    size_t triangles = g->index_count / 3, p;
    unsigned int *out = (unsigned int *)malloc(g->index_count * sizeof(unsigned int) + 4);
    unsigned int *ids = (unsigned int *)malloc(triangles * sizeof(unsigned int) + 4);
    unsigned char *flipped = (unsigned char *)malloc(triangles + 4);
    float confidence[64];
    for (p = 0; p < sizeof(names) / sizeof(names[0]); ++p) {
        meshfix_options o;
        meshfix_outputs outputs;
        meshfix_report r;
        meshfix_result result;
        unsigned int h = 2166136261u;
        size_t i;
        char text[32];
        memset(&o, 0, sizeof(o));
        o.policy = policies[p];
        o.evidence.vertex_normals = g->positions; /* normals pointing away from the origin: evidence to weigh */
        memset(&outputs, 0, sizeof(outputs));
        outputs.flipped = flipped;
        outputs.patch_ids = ids;
        outputs.patch_confidence = confidence;
        outputs.patch_confidence_capacity = 64;
        memset(confidence, 0, sizeof(confidence));
        result = meshfix_orient(out, g->indices, g->index_count, g->positions, g->vertex_count, 12, &o, &r, &outputs);
        snprintf(text, sizeof(text), "%d", (int)result);
        h = digest_bytes(h, text, strlen(text));
        if (result == MESHFIX_OK) {
            h = digest_bytes(h, out, g->index_count * sizeof(unsigned int));
            h = digest_bytes(h, flipped, triangles);
            h = digest_bytes(h, ids, triangles * sizeof(unsigned int));
            /* confidences to one decimal: a measure, not a decision */
            for (i = 0; i < 64 && i < r.mesh.patches; ++i) {
                snprintf(text, sizeof(text), "%.1f", (double)confidence[i]);
                h = digest_bytes(h, text, strlen(text));
            }
            h = digest_report(h, &r);
        }
        printf("%-28s %-10s %08x flipped %lu\n", name, names[p], h,
               result == MESHFIX_OK ? (unsigned long)r.triangles_flipped : 0ul);
    }
    free(out);
    free(ids);
    free(flipped);
}

/* The input meshes travel in a file from the reference build to the
   others: the generators use sin and cos, which builds round differently,
   and the comparison is about meshfix, given the same input. */
static int save(FILE *f, const char *name, const mio_mesh *g)
{
    unsigned int counts[3];
    counts[0] = (unsigned int)strlen(name), counts[1] = (unsigned int)g->vertex_count;
    counts[2] = (unsigned int)g->index_count;
    return fwrite(counts, sizeof(counts), 1, f) == 1 && fwrite(name, 1, counts[0], f) == counts[0] &&
           fwrite(g->positions, 3 * sizeof(float), g->vertex_count, f) == g->vertex_count &&
           fwrite(g->indices, sizeof(unsigned int), g->index_count, f) == g->index_count;
}

/* Reads the next mesh; 0 at the end of the file. */
static int load_next(FILE *f, char *name, mio_mesh *g)
{
    unsigned int counts[3];
    if (fread(counts, sizeof(counts), 1, f) != 1 || counts[0] >= 64)
        return 0;
    g->vertex_count = counts[1], g->index_count = counts[2];
    g->positions = (float *)malloc(3 * sizeof(float) * g->vertex_count + 4);
    g->indices = (unsigned int *)malloc(sizeof(unsigned int) * g->index_count + 4);
    name[counts[0]] = 0;
    return fread(name, 1, counts[0], f) == counts[0] &&
           fread(g->positions, 3 * sizeof(float), g->vertex_count, f) == g->vertex_count &&
           fread(g->indices, sizeof(unsigned int), g->index_count, f) == g->index_count;
}

static int generate(FILE *f)
{
    mio_mesh g, t;
    unsigned long long seed = 21;
    size_t i;
    int ok = gen_sphere(&g, 12, 16, 0.1f, 0.2f, 0.3f, 1);
    gen_flip_random(&g, 0.3, 1, NULL);
    ok = ok && save(f, "sphere, 30% reversed", &g) && gen_sphere(&t, 8, 10, 0.1f, 0.2f, 0.3f, 0.5f);
    ok = ok && gen_append(&g, &t) && save(f, "sphere with a cavity", &g);
    mio_free(&t);
    mio_free(&g);
    ok = ok && gen_torus(&g, 24, 12, 1, 0.3f);
    gen_flip_random(&g, 0.6, 2, NULL);
    ok = ok && save(f, "torus, 60% reversed", &g);
    mio_free(&g);
    ok = ok && gen_grid(&g, 12, 9);
    for (i = 0; ok && i < g.vertex_count; ++i)
        g.positions[3 * i + 2] = (float)(0.05 * gen_uniform(&seed));
    gen_flip_random(&g, 0.2, 3, NULL);
    ok = ok && save(f, "terrain, 20% reversed", &g);
    mio_free(&g);
    ok = ok && gen_mobius(&g, 30) && save(f, "moebius", &g);
    mio_free(&g);
    /* a soup of 400 triangles in a box, every corner its own vertex */
    g.vertex_count = g.index_count = 1200;
    g.positions = (float *)malloc(3 * g.vertex_count * sizeof(float));
    g.indices = (unsigned int *)malloc(g.index_count * sizeof(unsigned int));
    for (i = 0; i < 3 * g.vertex_count; ++i)
        g.positions[i] = (float)gen_uniform(&seed);
    for (i = 0; i < g.index_count; ++i)
        g.indices[i] = (unsigned int)i;
    ok = ok && save(f, "soup of 400", &g);
    mio_free(&g);
    /* generated scenes, 30% of their triangles reversed */
    {
        static const char *scenes[] = {"cavity_cut", "glass", "assembly", "parts"};
        for (i = 0; ok && i < sizeof(scenes) / sizeof(scenes[0]); ++i) {
            scene s;
            scene_trial trial;
            ok = scene_build(&s, scenes[i], SCENE_SMALL) == 1 && scene_trial_make(&trial, &s, &SCENE_CORRUPTIONS[4], 3);
            ok = ok && save(f, scenes[i], &trial.mesh);
            scene_trial_free(&trial);
            scene_free(&s);
        }
    }
    return ok;
}

/* outputs --write FILE: generates the meshes into FILE; outputs FILE:
   prints the digest lines of the meshes in FILE. */
int main(int argc, char **argv)
{
    FILE *f;
    char name[64];
    mio_mesh g;
    if (argc == 3 && strcmp(argv[1], "--write") == 0) {
        f = fopen(argv[2], "wb");
        if (f == NULL || !generate(f) || fclose(f) != 0)
            return 1;
        return 0;
    }
    if (argc != 2 || (f = fopen(argv[1], "rb")) == NULL)
        return 1;
    while (load_next(f, name, &g)) {
        run(name, &g);
        mio_free(&g);
    }
    fclose(f);
    return 0;
}
