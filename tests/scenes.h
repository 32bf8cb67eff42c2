/* scenes.h - generated scenes whose every triangle's intended facing is
   known by construction, for tests, tests/eval/scenes_eval.c and benchmarks

   A scene is a triangle mesh plus, per triangle, its truth (1 = faces the
   intended way as it now stands; all 1 when built), the part it belongs
   to, and, for scenes cut into unwelded patches, its patch. Corrupt a
   scene with gen_shuffle, gen_reverse_all, gen_reverse_patches and
   gen_reverse_random of examples/meshgen.h: they keep the truth.

   Intended facing: solids out of their material (so a cavity faces into
   the cavity), pipes away from their axis, U-channels away from the side
   they enclose, sheets and terrains +z. A part is `flat` when it is a flat
   sheet: nothing in the geometry tells its sides apart, +z is a
   convention.

   Every scene takes a `detail` (its resolution: see SCENES below) and has
   a small one (under 20k triangles, for unit tests) and a large one
   (100k to 1M triangles, for benchmarks).

   Include meshfix.h, examples/meshio.h and examples/meshgen.h first;
   define SCENES_IMPLEMENTATION in one file (where the implementations of
   meshio.h and meshgen.h are, too). */
#ifndef MESHFIX_TESTS_SCENES_H
#define MESHFIX_TESTS_SCENES_H
#include <stddef.h>

#define SCENE_MAX_PARTS 64
#define SCENE_PI 3.14159265358979323846

typedef struct scene_part {
    const char *name; /* a static string: "housing", "pipe", ... */
    int flat;         /* a flat sheet: its side is a convention, not geometry */
} scene_part;

typedef struct scene {
    mio_mesh mesh;
    unsigned char *truth; /* per triangle: 1 = faces the intended way as it stands */
    unsigned int *part;   /* per triangle: index into parts */
    unsigned int *patch;  /* per triangle: its patch; NULL when the scene is not cut */
    size_t patches;
    size_t part_count;
    scene_part parts[SCENE_MAX_PARTS];
} scene;

typedef enum scene_size { SCENE_SMALL, SCENE_LARGE } scene_size;

typedef struct scene_info {
    const char *name;
    int (*build)(scene *s, unsigned detail);
    unsigned small, large; /* detail of the two sizes (0 and 0: a corpus file, one size) */
    const char *about;
} scene_info;

/* Each returns 1 when built, 0 when out of memory, -1 when not available
   (scene_spider: the model file is missing or not closed). */
int scene_quad(scene *s, unsigned detail);            /* unit square, detail^2 quads, +z (flat) */
int scene_terrain(scene *s, unsigned detail);         /* gentle hills, detail^2 quads, +z */
int scene_canyon(scene *s, unsigned detail);          /* hills and a deep V-valley, detail^2 quads, +z */
int scene_disc(scene *s, unsigned detail);            /* flat disc, +z; detail 1: a fan of 64 */
int scene_sphere(scene *s, unsigned detail);          /* closed; detail rings */
int scene_torus(scene *s, unsigned detail);           /* closed, genus 1; detail around the tube */
int scene_cavity(scene *s, unsigned detail);          /* ball of radius 1 with a hollow of radius 0.5 */
int scene_cavity_cut(scene *s, unsigned detail);      /* the same cut into 300 unwelded patches */
int scene_glass(scene *s, unsigned detail);           /* two crossing balls in a glass shell, cut */
int scene_nested(scene *s, unsigned detail);          /* ball, hollow in it, ball in the hollow */
int scene_assembly(scene *s, unsigned detail);        /* housing with a window, parts in and out */
int scene_assembly_sealed(scene *s, unsigned detail); /* sealed housing, parts only inside */
int scene_parts(scene *s, unsigned detail);           /* every part generator, side by side */
int scene_spider(scene *s, unsigned detail);          /* assimp's spider.obj, closed parts, subdivided */
int scene_city(scene *s, unsigned detail);            /* 26 closed buildings (boxes, L and U blocks) on a block */
/* Two real files from the project's corpus (tests/corpus/fetch.sh, under
   $MESHFIX_CORPUS, default build/corpus); -1 when it is missing. */
int scene_projection_box(scene *s, unsigned detail); /* OpenSCAD's projection.stl: a box, its shell wound inward */
int scene_buildings(scene *s, unsigned detail);      /* OpenFOAM's windAroundBuildings buildings.obj, 26 closed */
int scene_cavity_box(scene *s, unsigned detail);      /* a box around a closed shell wound inward (a hollow) */
int scene_cavity_coarse(scene *s, unsigned detail);   /* a box of 108 triangles around a fine hollow (CAD beside a scan) */
int scene_crossing(scene *s, unsigned detail);        /* three closed shells through each other, each outward */
int scene_cad_part(scene *s, unsigned detail);        /* a machined block: through-holes, a pocket, a slot */

/* The scene table: scene_get(i) for i < scene_count(), or by name (NULL
   when unknown). */
size_t scene_count(void);
const scene_info *scene_get(size_t i);
const scene_info *scene_find(const char *name);
/* Builds a named scene at a size; the same results as the functions. */
int scene_build(scene *s, const char *name, scene_size size);
void scene_free(scene *s);
/* Area of triangle t (double precision). */
double scene_triangle_area(const mio_mesh *m, size_t t);

/* A scene cut the way real exports are: into k unwelded patches grown
   from k random seed triangles (gen_cut), the seams exact (the copies
   stay, joined again by position), gapped (every copy 3% of the way to
   its patch's middle) or jittered (each seam copy moved 0.5 to 1 x
   `jitter` of the diagonal in a random direction: gaps and overlaps).
   Truth and parts carry over; `out` is a scene of its own (scene_free). */
typedef enum scene_seams { SCENE_SEAMS_EXACT, SCENE_SEAMS_GAP, SCENE_SEAMS_JITTER } scene_seams;
int scene_cut_as_exported(const scene *in, scene *out, unsigned k, scene_seams seams, double jitter,
                          unsigned long long seed);
/* The trust suite's corruption of a cut scene: a random half of its
   patches reversed whole, then each triangle with probability 0.02;
   `indices` and `truth` (copies of the scene's) are changed. */
void scene_corrupt_cut(const scene *s, unsigned int *indices, unsigned char *truth, unsigned long long seed);

/* The corruptions a scene is repaired from, each keeping the truth. Some
   leave no trace of which side of a flat sheet was meant: there, flat
   parts are left out of the score (`scored`). */
typedef enum scene_corruption_kind {
    SCENE_KEEP,       /* correct as built */
    SCENE_SHUFFLE,    /* correct, triangles shuffled, corners rotated */
    SCENE_INSIDE_OUT, /* every triangle reversed */
    SCENE_PATCHES,    /* whole patches of a cut scene reversed with probability p */
    SCENE_RANDOM      /* triangles reversed with probability p */
} scene_corruption_kind;

typedef struct scene_corruption {
    const char *name;
    scene_corruption_kind kind;
    double p;
    int hides_convention;
} scene_corruption;

#define SCENE_CORRUPTION_COUNT 6
extern const scene_corruption SCENE_CORRUPTIONS[SCENE_CORRUPTION_COUNT];

/* One corrupted copy of a scene; positions are borrowed from it. */
typedef struct scene_trial {
    mio_mesh mesh;
    unsigned char *truth;  /* as the corrupted input stands */
    unsigned int *part;
    unsigned char *scored; /* 0: undecided, left out of the score */
    unsigned int *from;    /* per triangle: its index in the scene */
} scene_trial;

/* Returns 0 when out of memory. */
int scene_trial_make(scene_trial *t, const scene *s, const scene_corruption *c, unsigned long long seed);
void scene_trial_free(scene_trial *t);
#endif

#ifdef SCENES_IMPLEMENTATION
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- building a scene from parts ---- */

static void scene_init(scene *s)
{
    memset(s, 0, sizeof(*s));
}

void scene_free(scene *s)
{
    mio_free(&s->mesh);
    free(s->truth);
    free(s->part);
    free(s->patch);
    scene_init(s);
}

/* Appends a generated part (all its triangles face the intended way) and
   frees it. Returns 0 when out of memory or when the part was not built
   (then `part` may be garbage: a generator that refuses its arguments
   does not touch it). */
static int scene_add(scene *s, mio_mesh *part, int built, const char *name, int flat)
{
    size_t before = s->mesh.index_count / 3, after, t;
    unsigned char *truth;
    unsigned int *ids;
    int ok = s->part_count < SCENE_MAX_PARTS;
    if (!built)
        return 0;
    after = before + part->index_count / 3;
    if (ok && (truth = (unsigned char *)realloc(s->truth, after + 1)) != NULL)
        s->truth = truth;
    else
        ok = 0;
    if (ok && (ids = (unsigned int *)realloc(s->part, after * sizeof(unsigned int) + 1)) != NULL)
        s->part = ids;
    else
        ok = 0;
    if (ok && s->mesh.positions == NULL && s->mesh.indices == NULL) { /* the first part: no copy */
        s->mesh = *part;
        memset(part, 0, sizeof(*part));
    } else if (ok) {
        ok = gen_append(&s->mesh, part);
    }
    if (ok) {
        for (t = before; t < after; ++t) {
            s->truth[t] = 1;
            s->part[t] = (unsigned int)s->part_count;
        }
        s->parts[s->part_count].name = name;
        s->parts[s->part_count].flat = flat;
        s->part_count++;
    }
    mio_free(part);
    return ok;
}

/* Places a built part (gen_transform) before adding it. */
static int scene_add_placed(scene *s, mio_mesh *part, int built, const char *name, int flat, const float rotation[9],
                            const float offset[3])
{
    if (built)
        gen_transform(part, rotation, offset);
    return scene_add(s, part, built, name, flat);
}

/* Cuts the whole scene into about `patches` unwelded patches (gen_cut). */
static int scene_cut(scene *s, size_t patches, float gap, unsigned long long seed)
{
    mio_mesh cut;
    unsigned int *patch = (unsigned int *)malloc(s->mesh.index_count / 3 * sizeof(unsigned int) + 1);
    if (patch == NULL)
        return 0;
    s->patches = gen_cut(&cut, patch, &s->mesh, patches, gap, seed);
    if (s->patches == 0) {
        free(patch);
        return 0;
    }
    mio_free(&s->mesh);
    s->mesh = cut;
    free(s->patch);
    s->patch = patch;
    return 1;
}

/* A finished scene, or a failed one freed. */
static int scene_done(scene *s, int ok)
{
    if (!ok)
        scene_free(s);
    return ok ? 1 : 0;
}

/* Rotations (row-major) to place parts: the z axis of a pipe onto x or y,
   a channel's y axis onto x, a channel upside down, a quarter turn. */
static const float SCENE_IDENTITY[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
static const float SCENE_Z_TO_X[9] = {0, 0, 1, 0, 1, 0, -1, 0, 0};
static const float SCENE_Z_TO_Y[9] = {1, 0, 0, 0, 0, 1, 0, -1, 0};
static const float SCENE_Y_TO_X[9] = {0, 1, 0, -1, 0, 0, 0, 0, 1};
static const float SCENE_UPSIDE_DOWN[9] = {-1, 0, 0, 0, 1, 0, 0, 0, -1};
static const float SCENE_QUARTER_TURN[9] = {0, -1, 0, 1, 0, 0, 0, 0, 1};

/* Segments for a length at the scene's edge length h, at least `least`. */
static unsigned scene_segments(double length, double h, unsigned least)
{
    double n = ceil(length / h);
    return n > least ? (unsigned)n : least;
}

/* ---- sheets and terrains ---- */

int scene_quad(scene *s, unsigned detail)
{
    mio_mesh g;
    scene_init(s);
    return scene_done(s, scene_add(s, &g, gen_plane(&g, detail, detail, 1, 1), "quad", 1));
}

int scene_terrain(scene *s, unsigned detail)
{
    mio_mesh g;
    scene_init(s);
    return scene_done(s, scene_add(s, &g, gen_terrain(&g, detail, 1, 0.05f, 0), "terrain", 0));
}

int scene_canyon(scene *s, unsigned detail)
{
    mio_mesh g;
    scene_init(s);
    return scene_done(s, scene_add(s, &g, gen_terrain(&g, detail, 1, 0.03f, 0.25f), "canyon", 0));
}

int scene_disc(scene *s, unsigned detail)
{
    mio_mesh g;
    unsigned segments = detail <= 1 ? 64 : 4 * detail;
    scene_init(s);
    return scene_done(s, scene_add(s, &g, gen_disc(&g, segments, detail, 1), "disc", 1));
}

/* ---- closed shells ---- */

int scene_sphere(scene *s, unsigned detail)
{
    mio_mesh g;
    scene_init(s);
    return scene_done(s, scene_add(s, &g, gen_sphere(&g, detail, 2 * detail, 0, 0, 0, 1), "sphere", 0));
}

int scene_torus(scene *s, unsigned detail)
{
    mio_mesh g;
    scene_init(s);
    return scene_done(s, scene_add(s, &g, gen_torus(&g, 2 * detail, detail, 1, 0.4f), "torus", 0));
}

/* A sphere wound inward: the wall of a hollow. */
static int scene_hollow(mio_mesh *g, unsigned rings, float radius)
{
    if (!gen_sphere(g, rings, 2 * rings, 0, 0, 0, radius))
        return 0;
    gen_reverse_all(g, NULL);
    return 1;
}

static int scene_build_cavity(scene *s, unsigned detail)
{
    mio_mesh g;
    unsigned inner = detail / 2 > 3 ? detail / 2 : 3;
    scene_init(s);
    return scene_add(s, &g, gen_sphere(&g, detail, 2 * detail, 0, 0, 0, 1), "ball", 0) &&
           scene_add(s, &g, scene_hollow(&g, inner, 0.5f), "hollow", 0);
}

int scene_cavity(scene *s, unsigned detail)
{
    return scene_done(s, scene_build_cavity(s, detail));
}

/* Vertices move 3% of the way to their patch's centroid: seams 0.2% of
   the model's diagonal wide on average, 0.6% at most (scenes_check). */
#define SCENE_CUT_GAP 0.03f

int scene_cavity_cut(scene *s, unsigned detail)
{
    return scene_done(s, scene_build_cavity(s, detail) && scene_cut(s, 300, SCENE_CUT_GAP, 11));
}

int scene_glass(scene *s, unsigned detail)
{
    mio_mesh g;
    unsigned ball = detail / 2 > 3 ? detail / 2 : 3;
    scene_init(s);
    return scene_done(s, scene_add(s, &g, gen_sphere(&g, detail, 2 * detail, 0, 0, 0, 3), "glass outside", 0) &&
                             scene_add(s, &g, scene_hollow(&g, detail, 2.8f), "glass inside", 0) &&
                             scene_add(s, &g, gen_sphere(&g, ball, 2 * ball, -0.5f, 0, 0, 1), "ball", 0) &&
                             scene_add(s, &g, gen_sphere(&g, ball, 2 * ball, 0.6f, 0.1f, 0, 1), "ball", 0) &&
                             scene_cut(s, 300, SCENE_CUT_GAP, 12));
}

int scene_nested(scene *s, unsigned detail)
{
    mio_mesh g;
    unsigned middle = 2 * detail / 3 > 3 ? 2 * detail / 3 : 3, inner = detail / 3 > 3 ? detail / 3 : 3;
    scene_init(s);
    return scene_done(s, scene_add(s, &g, gen_sphere(&g, detail, 2 * detail, 0, 0, 0, 3), "ball", 0) &&
                             scene_add(s, &g, scene_hollow(&g, middle, 2), "hollow", 0) &&
                             scene_add(s, &g, gen_sphere(&g, inner, 2 * inner, 0.2f, 0, 0, 1), "island", 0));
}

/* ---- assemblies ---- */

typedef enum scene_kind { SCENE_PIPE, SCENE_CHANNEL, SCENE_SHEET, SCENE_BRACKET } scene_kind;

/* One part of an assembly: its kind, its size (pipe: radius, length;
   channel: radius, wall, length; sheet: x, y; bracket: width, height,
   length, thickness), rotation and offset. */
typedef struct scene_placement {
    scene_kind kind;
    float size[4];
    const float *rotation;
    float offset[3];
} scene_placement;

/* In the housing [0, 1] x [0, 0.8] x [0, 0.6] with walls 0.04 thick (the
   hollow is [0.04, 0.96] x [0.04, 0.76] x [0.04, 0.56], the window in the
   +x wall y 0.24..0.56, z 0.18..0.42): no two parts touch. */
static const scene_placement SCENE_INSIDE[] = {
    {SCENE_PIPE, {0.05f, 0.5f, 0, 0}, SCENE_Z_TO_X, {0.1f, 0.15f, 0.12f}},         /* x .1-.6 y .1-.2 z .07-.17 */
    {SCENE_PIPE, {0.04f, 0.3f, 0, 0}, SCENE_IDENTITY, {0.85f, 0.62f, 0.1f}},      /* x .81-.89 y .58-.66 z .1-.4 */
    {SCENE_CHANNEL, {0.06f, 0.06f, 0.35f, 0}, SCENE_IDENTITY, {0.3f, 0.3f, 0.2f}}, /* x .24-.36 y .3-.65 z .14-.26 */
    {SCENE_CHANNEL, {0.05f, 0.05f, 0.3f, 0}, SCENE_Y_TO_X, {0.45f, 0.45f, 0.35f}}, /* x .45-.75 y .4-.5 z .3-.4 */
    {SCENE_CHANNEL, {0.05f, 0.04f, 0.25f, 0}, SCENE_UPSIDE_DOWN, {0.15f, 0.45f, 0.45f}}, /* x .1-.2 y .45-.7 z .41-.5 */
    {SCENE_SHEET, {0.3f, 0.2f, 0, 0}, SCENE_IDENTITY, {0.55f, 0.1f, 0.48f}},       /* x .55-.85 y .1-.3 z .48 */
    {SCENE_SHEET, {0.2f, 0.15f, 0, 0}, SCENE_IDENTITY, {0.1f, 0.1f, 0.3f}},        /* x .1-.3 y .1-.25 z .3 */
    {SCENE_BRACKET, {0.15f, 0.12f, 0.18f, 0.02f}, SCENE_IDENTITY, {0.6f, 0.55f, 0.06f}},  /* x .6-.75 y .55-.73 z .06-.18 */
    {SCENE_BRACKET, {0.1f, 0.1f, 0.15f, 0.02f}, SCENE_QUARTER_TURN, {0.8f, 0.25f, 0.06f}}, /* x .65-.8 y .25-.35 z .06-.16 */
};

/* Beside the housing, in the open. */
static const scene_placement SCENE_OUTSIDE[] = {
    {SCENE_PIPE, {0.06f, 0.6f, 0, 0}, SCENE_Z_TO_Y, {1.2f, 0.1f, 0.2f}},
    {SCENE_CHANNEL, {0.08f, 0.08f, 0.5f, 0}, SCENE_IDENTITY, {-0.3f, 0.1f, 0.1f}},
    {SCENE_SHEET, {0.4f, 0.3f, 0, 0}, SCENE_IDENTITY, {0.1f, -0.5f, 0}},
    {SCENE_BRACKET, {0.2f, 0.15f, 0.2f, 0.03f}, SCENE_IDENTITY, {0.8f, -0.45f, 0}},
};

static int scene_add_part(scene *s, const scene_placement *p, double h)
{
    mio_mesh g;
    const float *z = p->size;
    double a = (double)z[0], b = (double)z[1], c = (double)z[2];
    int built = 0, flat = 0;
    const char *name = "";
    switch (p->kind) {
    case SCENE_PIPE: /* radius a, length b */
        built = gen_pipe(&g, scene_segments(2 * SCENE_PI * a, h, 8), scene_segments(b, h, 1), z[0], z[1]);
        name = "pipe";
        break;
    case SCENE_CHANNEL: /* radius a, walls b, length c */
        built = gen_channel(&g, scene_segments(2 * b + SCENE_PI * a, h, 8), scene_segments(c, h, 1), z[0], z[1], z[2]);
        name = "channel";
        break;
    case SCENE_SHEET: /* a by b */
        built = gen_plane(&g, scene_segments(a, h, 1), scene_segments(b, h, 1), z[0], z[1]);
        name = "sheet", flat = 1;
        break;
    case SCENE_BRACKET: /* width, height, length, thickness */
        built = gen_bracket(&g, z[0], z[1], z[2], z[3], (float)h);
        name = "bracket";
        break;
    }
    return scene_add_placed(s, &g, built, name, flat, p->rotation, p->offset);
}

static int scene_build_assembly(scene *s, unsigned detail, gen_housing_kind kind, int outside)
{
    static const float size[3] = {1, 0.8f, 0.6f};
    mio_mesh g;
    double h = 1.0 / (detail > 0 ? detail : 1);
    size_t i;
    int ok;
    scene_init(s);
    ok = scene_add(s, &g, gen_housing(&g, size, 0.04f, kind, (float)h), "housing", 0);
    for (i = 0; ok && i < sizeof(SCENE_INSIDE) / sizeof(SCENE_INSIDE[0]); ++i)
        ok = scene_add_part(s, &SCENE_INSIDE[i], h);
    for (i = 0; ok && outside && i < sizeof(SCENE_OUTSIDE) / sizeof(SCENE_OUTSIDE[0]); ++i)
        ok = scene_add_part(s, &SCENE_OUTSIDE[i], h);
    return scene_done(s, ok);
}

int scene_assembly(scene *s, unsigned detail)
{
    return scene_build_assembly(s, detail, GEN_HOUSING_WINDOW, 1);
}

int scene_assembly_sealed(scene *s, unsigned detail)
{
    return scene_build_assembly(s, detail, GEN_HOUSING_SEALED, 0);
}

/* Every part generator once, 0.8 apart along x, nothing enclosing
   anything: how each kind of part fares on its own. */
int scene_parts(scene *s, unsigned detail)
{
    static const float box_lo[3] = {0, 0, 0}, box_hi[3] = {0.5f, 0.4f, 0.3f}, housing[3] = {0.6f, 0.5f, 0.4f};
    mio_mesh g;
    double h = 1.0 / (detail > 0 ? detail : 1);
    unsigned around = scene_segments(2 * SCENE_PI * 0.2, h, 8), along = scene_segments(0.5, h, 1);
    float at[3] = {0, 0, 0};
    int ok;
    scene_init(s);
    ok = scene_add_placed(s, &g, gen_box(&g, scene_segments(0.4, h, 1), box_lo, box_hi), "box", 0, SCENE_IDENTITY, at);
    at[0] += 0.8f;
    ok = ok && scene_add_placed(s, &g, gen_cylinder(&g, around, along, scene_segments(0.2, h, 1), 0.2f, 0.5f), "cylinder", 0,
                                SCENE_IDENTITY, at);
    at[0] += 0.8f;
    ok = ok && scene_add_placed(s, &g, gen_pipe(&g, around, along, 0.2f, 0.5f), "pipe", 0, SCENE_IDENTITY, at);
    at[0] += 0.8f;
    ok = ok && scene_add_placed(s, &g, gen_channel(&g, scene_segments(0.4 + SCENE_PI * 0.2, h, 8), along, 0.2f, 0.2f, 0.5f),
                                "channel", 0, SCENE_IDENTITY, at);
    at[0] += 0.8f;
    ok = ok && scene_add_placed(s, &g, gen_bracket(&g, 0.4f, 0.3f, 0.5f, 0.05f, (float)h), "bracket", 0, SCENE_IDENTITY, at);
    at[0] += 0.8f;
    ok = ok && scene_add_placed(s, &g, gen_housing(&g, housing, 0.05f, GEN_HOUSING_OPEN_TOP, (float)h), "cup", 0,
                                SCENE_IDENTITY, at);
    at[0] += 0.8f;
    ok = ok && scene_add_placed(s, &g, gen_housing(&g, housing, 0.05f, GEN_HOUSING_WINDOW, (float)h), "housing (window)", 0,
                                SCENE_IDENTITY, at);
    at[0] += 0.8f;
    ok = ok && scene_add_placed(s, &g, gen_housing(&g, housing, 0.05f, GEN_HOUSING_SEALED, (float)h), "housing (sealed)", 0,
                                SCENE_IDENTITY, at);
    at[0] += 0.8f;
    ok = ok && scene_add_placed(s, &g, gen_disc(&g, around, scene_segments(0.2, h, 1), 0.2f), "disc", 1, SCENE_IDENTITY, at);
    return scene_done(s, ok);
}

/* ---- blocks of solids: the trust suite's families ---- */

/* 26 closed buildings on a 6 x 5 block (four lots left empty), as a BIM
   export gives them: boxes, L and U blocks (unions of boxes, welded where
   they meet), rows of houses that share party walls (each house its own
   closed box, wall on wall), towers standing on podiums (the tower's floor
   on the podium's roof), all standing on a ground slab (a closed box of 12
   triangles the buildings' floors rest on). Every solid faces out; the
   touching faces lie on each other without sharing a vertex (the sizes
   keep their grids apart), as separately modelled objects do. */
int scene_city(scene *s, unsigned detail)
{
    double h = 1.0 / (detail > 0 ? detail : 1);
    unsigned lot, built = 0;
    mio_mesh g;
    static const float slab_lo[3] = {-0.3f, -0.3f, -0.2f}, slab_hi[3] = {8.8f, 7.3f, 0};
    int ok;
    scene_init(s);
    ok = scene_add(s, &g, gen_box(&g, 1, slab_lo, slab_hi), "ground", 0);
    for (lot = 0; ok && lot < 30 && built < 26; ++lot) {
        float x = 1.5f * (float)(lot % 6), y = 1.5f * (float)(lot / 6), top = 0.4f + 0.3f * (float)((lot * 7) % 5);
        gen_aabb add[4];
        size_t n = 1, k;
        if (lot == 8 || lot == 15 || lot == 22 || lot == 27)
            continue; /* a square, a park: streets meet there */
        if (lot % 7 == 3) { /* a row of three houses, wall on wall */
            for (k = 0; ok && k < 3 && built < 26; ++k, ++built) {
                add[0] = gen_make_aabb(x + 0.4f * (float)k, y, 0, x + 0.4f * (float)(k + 1), y + 0.77f + 0.03f * (float)k,
                                       0.33f + 0.09f * (float)k);
                ok = scene_add(s, &g, gen_boxes(&g, add, 1, NULL, 0, (float)h), "house", 0);
            }
            continue;
        }
        if (lot % 4 == 1) { /* a tower on a podium */
            add[0] = gen_make_aabb(x, y, 0, x + 1.1f, y + 1.0f, 0.3f);
            add[1] = gen_make_aabb(x + 0.3137f, y + 0.2071f, 0.3f, x + 0.8137f, y + 0.7071f, 0.3f + 2 * top);
            ok = scene_add(s, &g, gen_boxes(&g, &add[0], 1, NULL, 0, (float)h), "podium", 0) &&
                 scene_add(s, &g, gen_boxes(&g, &add[1], 1, NULL, 0, (float)h), "tower", 0);
            built++;
            continue;
        }
        add[0] = gen_make_aabb(x, y, 0, x + 1.0f, y + 0.6f, top);
        if (lot % 3 == 1) /* an L: a wing along y */
            add[n++] = gen_make_aabb(x, y, 0, x + 0.4f, y + 1.0f, 0.7f * top);
        if (lot % 5 == 2) { /* a U: wings on both ends */
            add[n++] = gen_make_aabb(x, y, 0, x + 0.3f, y + 1.1f, top);
            add[n++] = gen_make_aabb(x + 0.7f, y, 0, x + 1.0f, y + 1.1f, top);
        }
        ok = scene_add(s, &g, gen_boxes(&g, add, n, NULL, 0, (float)h), "building", 0);
        built++;
    }
    return scene_done(s, ok);
}

/* A solid box with a hollow in it: the box faces out, the hollow's wall
   (a sphere) faces into the hollow. */
int scene_cavity_box(scene *s, unsigned detail)
{
    static const float lo[3] = {-1.5f, -1.5f, -1.5f}, hi[3] = {1.5f, 1.5f, 1.5f};
    mio_mesh g;
    unsigned rings = detail > 3 ? detail : 3;
    scene_init(s);
    return scene_done(s, scene_add(s, &g, gen_box(&g, detail > 0 ? detail : 1, lo, hi), "box", 0) &&
                             scene_add(s, &g, scene_hollow(&g, rings, 1.0f), "hollow", 0));
}

/* The same, but the box is 108 triangles and the hollow fine (detail
   rings): cut, the box's seams are a hundred times longer than the
   hollow's, as where a CAD box holds a scanned part. */
int scene_cavity_coarse(scene *s, unsigned detail)
{
    static const float lo[3] = {-1.5f, -1.5f, -1.5f}, hi[3] = {1.5f, 1.5f, 1.5f};
    mio_mesh g;
    scene_init(s);
    return scene_done(s, scene_add(s, &g, gen_box(&g, 3, lo, hi), "box", 0) &&
                             scene_add(s, &g, scene_hollow(&g, detail > 3 ? detail : 3, 0.5f), "hollow", 0));
}

/* Three closed shells through each other (a sphere, a box and a torus, as
   overlapping parts of an assembly or a soup of solids are exported):
   each faces out of its own material. */
int scene_crossing(scene *s, unsigned detail)
{
    static const float lo[3] = {-0.2f, -0.7f, -0.7f}, hi[3] = {1.6f, 0.7f, 0.7f};
    static const float at[3] = {0.9f, 0, 0};
    mio_mesh g;
    unsigned rings = detail > 3 ? detail : 3;
    scene_init(s);
    return scene_done(s, scene_add(s, &g, gen_sphere(&g, rings, 2 * rings, 0, 0, 0, 1), "sphere", 0) &&
                             scene_add(s, &g, gen_box(&g, detail > 0 ? detail : 1, lo, hi), "box", 0) &&
                             scene_add_placed(s, &g, gen_torus(&g, 2 * rings, rings, 0.9f, 0.3f), "torus", 0,
                                              SCENE_Z_TO_Y, at));
}

/* A machined block: two through-holes, a blind pocket from the top and a
   slot along the bottom; one closed surface of genus 2. */
int scene_cad_part(scene *s, unsigned detail)
{
    gen_aabb add = gen_make_aabb(0, 0, 0, 2.0f, 1.2f, 0.8f), cut[4];
    mio_mesh g;
    double h = 1.0 / (detail > 0 ? detail : 1);
    cut[0] = gen_make_aabb(0.2f, 0.3f, -0.1f, 0.5f, 0.6f, 0.9f);   /* hole */
    cut[1] = gen_make_aabb(1.5f, 0.6f, -0.1f, 1.8f, 0.9f, 0.9f);   /* hole */
    cut[2] = gen_make_aabb(0.8f, 0.2f, 0.4f, 1.3f, 1.0f, 0.9f);    /* pocket */
    cut[3] = gen_make_aabb(-0.1f, 0.5f, -0.1f, 2.1f, 0.7f, 0.15f); /* slot */
    scene_init(s);
    return scene_done(s, scene_add(s, &g, gen_boxes(&g, &add, 1, cut, 4, (float)h), "block", 0));
}

/* ---- a real model ---- */

static const char *scene_models_dir(void)
{
    const char *dir = getenv("MESHFIX_MODELS");
    return dir != NULL ? dir : "/usr/share/assimp/models";
}

/* Keeps the triangles of `m` whose keep[t] is set, reversed where flip[t]. */
static void scene_keep(mio_mesh *m, const unsigned char *keep, const unsigned char *flip)
{
    size_t t, kept = 0;
    for (t = 0; t < m->index_count / 3; ++t)
        if (keep[t]) {
            unsigned int a = m->indices[3 * t], b = m->indices[3 * t + 1], c = m->indices[3 * t + 2];
            m->indices[3 * kept] = a;
            m->indices[3 * kept + 1] = flip[t] ? c : b;
            m->indices[3 * kept + 2] = flip[t] ? b : c;
            kept++;
        }
    m->index_count = 3 * kept;
}

/* Which patches (from meshfix: consistently wound, manifold) are closed,
   and which have negative volume: each patch inspected on its own. */
static int scene_closed_patches(const mio_mesh *m, const unsigned int *patch_id, size_t patches, unsigned char *closed,
                                unsigned char *inverted)
{
    size_t p, t, n;
    unsigned int *sub = (unsigned int *)malloc(m->index_count * sizeof(unsigned int) + 1);
    if (sub == NULL)
        return 0;
    for (p = 0; p < patches; ++p) {
        meshfix_report r;
        for (t = 0, n = 0; t < m->index_count / 3; ++t)
            if (patch_id[t] == p)
                memcpy(sub + 3 * n++, m->indices + 3 * t, 3 * sizeof(unsigned int));
        closed[p] = meshfix_inspect(sub, 3 * n, m->positions, m->vertex_count, 12, NULL, &r, NULL) == MESHFIX_OK &&
                    r.mesh.edges_boundary == 0 && r.mesh.edges_non_manifold == 0 && r.mesh.edges_inconsistent == 0 && n > 0;
        inverted[p] = r.mesh.signed_volume < 0;
    }
    free(sub);
    return 1;
}

/* The model welded, without its degenerate triangles and open parts, each
   closed part wound consistently and outward (by its own signed volume:
   parts of a model are solids of their own, even where one lies inside
   another). 1 when it is closed and consistent then, -1 when not. */
static int scene_make_closed(mio_mesh *m)
{
    size_t t, triangles = m->index_count / 3, i;
    unsigned int *remap = (unsigned int *)malloc(m->vertex_count * sizeof(unsigned int) + 1);
    unsigned int *patch_id = (unsigned int *)malloc(triangles * sizeof(unsigned int) + 1);
    unsigned char *keep = (unsigned char *)malloc(triangles + 1), *flip = (unsigned char *)malloc(triangles + 1);
    unsigned char *closed = (unsigned char *)malloc(triangles + 1), *inverted = (unsigned char *)malloc(triangles + 1);
    meshfix_options o;
    meshfix_outputs outputs;
    meshfix_report r;
    int result = 0;
    if (remap == NULL || patch_id == NULL || keep == NULL || flip == NULL || closed == NULL || inverted == NULL)
        goto done;
    if (meshfix_weld(remap, m->positions, m->vertex_count, 12, 0, NULL, NULL) != MESHFIX_OK)
        goto done;
    for (i = 0; i < m->index_count; ++i)
        m->indices[i] = remap[m->indices[i]];
    for (t = 0; t < triangles; ++t) {
        const unsigned int *v = m->indices + 3 * t;
        keep[t] = v[0] != v[1] && v[1] != v[2] && v[2] != v[0];
        flip[t] = 0;
    }
    scene_keep(m, keep, flip);
    triangles = m->index_count / 3;
    /* the seed policy only makes each patch consistent: which way a patch
       faces is decided below, by its volume */
    memset(&o, 0, sizeof(o));
    memset(&outputs, 0, sizeof(outputs));
    o.policy = MESHFIX_POLICY_SEED;
    outputs.patch_ids = patch_id;
    if (meshfix_orient(m->indices, m->indices, m->index_count, m->positions, m->vertex_count, 12, &o, &r, &outputs) != MESHFIX_OK ||
        !scene_closed_patches(m, patch_id, r.mesh.patches, closed, inverted))
        goto done;
    for (t = 0; t < triangles; ++t) {
        keep[t] = closed[patch_id[t]];
        flip[t] = inverted[patch_id[t]];
    }
    scene_keep(m, keep, flip);
    result = meshfix_inspect(m->indices, m->index_count, m->positions, m->vertex_count, 12, NULL, &r, NULL) == MESHFIX_OK &&
                     r.mesh.edges_boundary == 0 && r.mesh.edges_inconsistent == 0 && r.mesh.patches_inside_out == 0 && r.mesh.triangles > 0
                 ? 1
                 : -1;
done:
    free(remap);
    free(patch_id);
    free(keep);
    free(flip);
    free(closed);
    free(inverted);
    return result;
}

static const char *scene_corpus_dir(void)
{
    const char *dir = getenv("MESHFIX_CORPUS");
    return dir != NULL ? dir : "build/corpus";
}

/* A corpus file's closed parts, outward; -1 when missing or not closed. */
static int scene_load_closed(mio_mesh *g, const char *package, const char *file)
{
    char path[1024], error[256];
    int made;
    snprintf(path, sizeof(path), "%s/%s/%s", scene_corpus_dir(), package, file);
    if (!mio_load(path, g, error, sizeof(error)))
        return -1;
    made = scene_make_closed(g);
    if (made != 1)
        mio_free(g);
    return made;
}

/* The gapped cavity of trust round 3: OpenSCAD's
   examples/Basics/projection.stl (Debian openscad; 4,160 triangles): a
   box of 192 around a shell of 3,968, the shell wound inward (a hollow in
   the box's solid). detail is not used. */
int scene_projection_box(scene *s, unsigned detail)
{
    mio_mesh g;
    meshfix_outputs out;
    meshfix_report r;
    size_t n, t, p, largest = 0;
    unsigned int *ids;
    double *area;
    int made = scene_load_closed(&g, "openscad", "openscad__examples__Basics__projection.stl");
    (void)detail;
    if (made != 1)
        return made;
    n = g.index_count / 3;
    ids = (unsigned int *)malloc(n * sizeof(unsigned int) + 4);
    area = (double *)calloc(n + 1, sizeof(double));
    memset(&out, 0, sizeof(out));
    out.patch_ids = ids;
    if (ids == NULL || area == NULL ||
        meshfix_inspect(g.indices, g.index_count, g.positions, g.vertex_count, 12, NULL, &r, &out) != MESHFIX_OK) {
        free(ids), free(area), mio_free(&g);
        return 0;
    }
    for (t = 0; t < n; ++t)
        area[ids[t] < n ? ids[t] : n] += scene_triangle_area(&g, t);
    for (p = 1; p < r.mesh.patches; ++p)
        largest = area[p] > area[largest] ? p : largest;
    for (t = 0; t < n; ++t) /* every shell but the box: inward */
        if (ids[t] != largest) {
            unsigned int x = g.indices[3 * t + 1];
            g.indices[3 * t + 1] = g.indices[3 * t + 2], g.indices[3 * t + 2] = x;
        }
    free(ids);
    free(area);
    scene_init(s);
    return scene_done(s, scene_add(s, &g, 1, "projection.stl: a box, its shell inward", 0));
}

/* The gapped buildings of trust round 3: OpenFOAM's windAroundBuildings
   constant/triSurface/buildings.obj (Debian openfoam-examples; 26 closed
   buildings, 400,020 triangles); detail is not used. */
int scene_buildings(scene *s, unsigned detail)
{
    mio_mesh g;
    int made = scene_load_closed(&g, "openfoam-examples",
                                 "doc__openfoam-examples__examples__incompressible__simpleFoam__windAroundBuildings__"
                                 "constant__triSurface__buildings.obj");
    (void)detail;
    if (made != 1)
        return made;
    scene_init(s);
    return scene_done(s, scene_add(s, &g, 1, "buildings", 0));
}

int scene_spider(scene *s, unsigned detail)
{
    char path[512], error[256];
    mio_mesh g;
    unsigned level;
    int made;
    scene_init(s);
    snprintf(path, sizeof(path), "%s/OBJ/spider.obj", scene_models_dir());
    if (!mio_load(path, &g, error, sizeof(error)))
        return -1;
    made = scene_make_closed(&g);
    for (level = 0; made == 1 && level < detail; ++level)
        made = gen_subdivide(&g);
    if (made != 1) {
        mio_free(&g);
        return made;
    }
    return scene_done(s, scene_add(s, &g, 1, "spider", 0));
}

/* ---- the table ---- */

static const scene_info SCENES[] = {
    {"quad", scene_quad, 1, 400, "unit square, flat, +z; detail^2 quads"},
    {"terrain", scene_terrain, 20, 500, "height field with gentle hills, +z; detail^2 quads"},
    {"canyon", scene_canyon, 90, 400, "height field with a deep meandering V-valley, +z"},
    {"disc", scene_disc, 1, 220, "flat disc, +z; detail 1: a fan of 64, else detail rings"},
    {"sphere", scene_sphere, 60, 250, "closed sphere; detail rings"},
    {"torus", scene_torus, 60, 250, "closed torus; detail around its tube"},
    {"cavity", scene_cavity, 60, 220, "ball r 1 with a hollow r 0.5 (wound inward)"},
    {"cavity_cut", scene_cavity_cut, 60, 220, "the cavity cut into 300 unwelded patches"},
    {"glass", scene_glass, 42, 160, "two crossing balls in a glass shell r 3/2.8, cut into 300 patches"},
    {"nested", scene_nested, 50, 200, "ball r 3, hollow r 2 in it, ball r 1 in the hollow"},
    {"assembly", scene_assembly, 20, 90, "housing with a window; pipes, channels, sheets, brackets in and out"},
    {"assembly_sealed", scene_assembly_sealed, 20, 90, "sealed housing (hollow inward), the same parts inside only"},
    {"parts", scene_parts, 25, 130, "box, cylinder, pipe, channel, bracket, cup, housings, disc side by side"},
    {"spider", scene_spider, 0, 4, "assimp-testmodels OBJ/spider.obj: its closed parts, outward, subdivided detail times"},
    {"city", scene_city, 7, 40, "26 buildings on a ground slab: blocks, party-wall rows, towers on podiums, touching"},
    {"cavity_box", scene_cavity_box, 20, 150, "box 3 wide around a hollow r 1 (wound inward)"},
    {"crossing", scene_crossing, 30, 140, "a sphere, a box and a torus through each other, each outward"},
    {"cad_part", scene_cad_part, 20, 110, "machined block: two through-holes, a pocket, a slot (genus 2)"},
    {"cavity_coarse", scene_cavity_coarse, 40, 160, "box of 108 triangles around a fine hollow r 0.5 (wound inward)"},
    {"projection_box", scene_projection_box, 0, 0, "corpus: OpenSCAD's projection.stl, its shell wound inward in its box"},
    {"buildings", scene_buildings, 0, 0, "corpus: OpenFOAM's buildings.obj, 26 closed buildings, 400k triangles"},
};

size_t scene_count(void)
{
    return sizeof(SCENES) / sizeof(SCENES[0]);
}

const scene_info *scene_get(size_t i)
{
    return i < scene_count() ? &SCENES[i] : NULL;
}

const scene_info *scene_find(const char *name)
{
    size_t i;
    for (i = 0; i < scene_count(); ++i)
        if (strcmp(SCENES[i].name, name) == 0)
            return &SCENES[i];
    return NULL;
}

int scene_build(scene *s, const char *name, scene_size size)
{
    const scene_info *info = scene_find(name);
    scene_init(s);
    if (info == NULL)
        return 0;
    return info->build(s, size == SCENE_SMALL ? info->small : info->large);
}

double scene_triangle_area(const mio_mesh *m, size_t t)
{
    const float *a = m->positions + 3 * (size_t)m->indices[3 * t], *b = m->positions + 3 * (size_t)m->indices[3 * t + 1];
    const float *c = m->positions + 3 * (size_t)m->indices[3 * t + 2];
    double u[3], v[3], n[3];
    int k;
    for (k = 0; k < 3; ++k) {
        u[k] = (double)b[k] - (double)a[k];
        v[k] = (double)c[k] - (double)a[k];
    }
    n[0] = u[1] * v[2] - u[2] * v[1];
    n[1] = u[2] * v[0] - u[0] * v[2];
    n[2] = u[0] * v[1] - u[1] * v[0];
    return 0.5 * sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
}
int scene_cut_as_exported(const scene *in, scene *out, unsigned k, scene_seams seams, double jitter,
                          unsigned long long seed)
{
    size_t n = in->mesh.index_count / 3;
    scene_init(out);
    out->patch = (unsigned int *)malloc(n * sizeof(unsigned int) + 1);
    out->truth = (unsigned char *)malloc(n + 1);
    out->part = (unsigned int *)malloc(n * sizeof(unsigned int) + 1);
    if (out->patch == NULL || out->truth == NULL || out->part == NULL) {
        scene_free(out);
        return 0;
    }
    out->patches = seams == SCENE_SEAMS_GAP
                       ? gen_cut(&out->mesh, out->patch, &in->mesh, k, SCENE_CUT_GAP, seed)
                       : gen_cut_jittered(&out->mesh, out->patch, &in->mesh, k, seams == SCENE_SEAMS_JITTER ? jitter : 0.0,
                                          seed);
    memcpy(out->truth, in->truth, n);
    memcpy(out->part, in->part, n * sizeof(unsigned int));
    out->part_count = in->part_count;
    memcpy(out->parts, in->parts, sizeof(in->parts));
    if (out->patches == 0)
        scene_free(out);
    return out->patches != 0;
}

void scene_corrupt_cut(const scene *s, unsigned int *indices, unsigned char *truth, unsigned long long seed)
{
    mio_mesh m = s->mesh;
    m.indices = indices;
    gen_reverse_patches(&m, truth, s->patch, 0.5, seed ^ 0xA5A5ull);
    gen_reverse_random(&m, truth, 0.02, seed ^ 0x5A5Aull);
}

const scene_corruption SCENE_CORRUPTIONS[SCENE_CORRUPTION_COUNT] = {
    {"correct", SCENE_KEEP, 0, 0},      {"shuffled", SCENE_SHUFFLE, 0, 0},     {"inside-out", SCENE_INSIDE_OUT, 0, 1},
    {"patches", SCENE_PATCHES, 0.5, 1}, {"random-0.3", SCENE_RANDOM, 0.3, 0}, {"random-0.5", SCENE_RANDOM, 0.5, 1},
};

void scene_trial_free(scene_trial *t)
{
    free(t->mesh.indices);
    free(t->truth);
    free(t->part);
    free(t->scored);
    free(t->from);
}

int scene_trial_make(scene_trial *t, const scene *s, const scene_corruption *c, unsigned long long seed)
{
    size_t n = s->mesh.index_count / 3, i;
    int ok;
    t->mesh = s->mesh;
    t->mesh.indices = (unsigned int *)malloc(s->mesh.index_count * sizeof(unsigned int) + 1);
    t->truth = (unsigned char *)malloc(n + 1);
    t->part = (unsigned int *)malloc(n * sizeof(unsigned int) + 1);
    t->scored = (unsigned char *)malloc(n + 1);
    t->from = (unsigned int *)malloc(n * sizeof(unsigned int) + 1);
    ok = t->from != NULL && t->mesh.indices != NULL && t->truth != NULL && t->part != NULL && t->scored != NULL;
    if (ok) {
        memcpy(t->mesh.indices, s->mesh.indices, s->mesh.index_count * sizeof(unsigned int));
        memcpy(t->truth, s->truth, n);
        for (i = 0; i < n; ++i)
            t->from[i] = (unsigned int)i;
        switch (c->kind) {
        case SCENE_KEEP:
            break;
        case SCENE_SHUFFLE:
            ok = gen_shuffle(&t->mesh, t->truth, t->from, seed);
            break;
        case SCENE_INSIDE_OUT:
            gen_reverse_all(&t->mesh, t->truth);
            break;
        case SCENE_PATCHES:
            if (s->patch != NULL)
                gen_reverse_patches(&t->mesh, t->truth, s->patch, c->p, seed);
            break;
        case SCENE_RANDOM:
            gen_reverse_random(&t->mesh, t->truth, c->p, seed);
            break;
        }
    }
    for (i = 0; ok && i < n; ++i) {
        t->part[i] = s->part[t->from[i]];
        t->scored[i] = (unsigned char)!(c->hides_convention && s->parts[t->part[i]].flat);
    }
    if (!ok)
        scene_trial_free(t);
    return ok;
}
#endif /* SCENES_IMPLEMENTATION */
