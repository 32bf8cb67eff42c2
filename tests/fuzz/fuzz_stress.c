/* libFuzzer stress target for meshfix.h: large meshes, real-valued
   coordinates, every option field, caller scratch, parallel_for, SDF
   callbacks and weld, with an oracle for every call.

   Why another target: fuzz_meshfix.c keeps to 64 vertices on an integer
   grid, so it never builds a deep BVH, a crowded coherence grid or a
   large sample plan. This one decodes the input as

     [settings block]  fixed offsets, read first (see read_settings):
                       calls to make, policy, every meshfix_options field
                       (raw: out-of-range enums, NaN, Inf, negative and
                       huge values), outputs and their capacities,
                       allocator, scratch, parallel_for hook, SDF
                       callback, stride, vertex-count skew, destination
                       layout, weld tolerance, check requirements,
                       (added with the NORMALS policy) evidence.sigma,
                       min_confidence and caller normals per triangle or
                       per vertex with their strides, and (last, added
                       with the 0.2 API) index_size (16-bit indices when
                       the vertices fit), position_size (doubles, moved
                       far from the origin, scaled beyond float range,
                       with bits below float precision), the topology
                       (POSITIONS, INDICES, WELD and its tolerance), the
                       double stride and meshfix_summary's buffer size;
     [mesh program]    a list of operations (see build_mesh) that append
                       vertices and triangles, up to MAX_VERTICES and
                       MAX_TRIANGLES: single vertices in eight coordinate
                       encodings, single triangles (indices may repeat or
                       be out of range), and generators that expand a few
                       bytes into thousands of elements: planes shrinking
                       toward the origin (deep trees), complete
                       hypergraphs (every edge non-manifold), nested
                       closed shells, height-field grids, soups, stacks of
                       coincident triangles, fans on one edge, duplicates,
                       transforms and random flips.

   Oracle, for every call: the result is one of the problems the input
   really has (OK when it has none); an error writes nothing the caller
   passed and does no work (no allocation, SDF or parallel_for call); a
   success returns each triangle as given or as (a, c, b), counts its
   flips right, writes no output beyond its size or capacity, and is
   bit-identical with and without parallel_for (run in reverse or
   shuffled) and with other garbage in fresh memory (so a read of memory
   never written shows too), and with 16-bit indices as with the same
   indices in 32 bits. SEED and MAJORITY are idempotent. Reports agree
   with meshfix_inspect of the input and of the output, their edge and
   degenerate counts with the edges computed here on the vertices the
   topology makes (bit-identical positions by sorting, a weld by
   meshfix_weld over the finite vertices), report.verdict with the counts,
   patches_flipped / patches_doubtful / triangles_doubtful with the
   per-patch outputs; meshfix_summary returns the whole length for any
   buffer (0 and 1 included) and terminates within it. Scratch of
   meshfix_scratch_size() bytes means no allocation. meshfix_check agrees
   with inspect, and its failure names the first failing requirement, its
   count, the lowest failing triangle and an edge of it that fails, in a
   line terminated within its array. Weld clusters (floats or doubles)
   are checked against their definition. Nothing leaks (the allocator
   counts its blocks).

   Build: clang -g -O1 -fsanitize=fuzzer,address,undefined tests/fuzz/fuzz_stress.c -lm
   Seeds: tests/fuzz/make_seeds.c writes tests/fuzz/corpus/stress/. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Findings (tests/fuzz/crashes/README.md) stop a strict run. Findings
   1 to 6 of the first session are fixed in meshfix.h, so the oracles below
   hold them strictly. A finding that is still open gets a
   STRESS_TOLERATE_* macro that skips the check or the inputs it trips,
   so that a long run goes on looking for new ones;
   -DSTRESS_TOLERATE_KNOWN turns on every such macro. Reads of memory the
   library never wrote: build with -fsanitize=fuzzer,memory (run.sh:
   FUZZ_TARGETS=stress-msan). */
#ifdef STRESS_TOLERATE_KNOWN
#endif

/* The library's internal invariants (MESHFIX_ASSERT, a documented
   configuration macro): reported with their text. */
static void stress_assert(int ok, const char *expression, const char *file, int line)
{
    if (ok)
        return;
    fprintf(stderr, "fuzz_stress: meshfix assertion failed: %s (%s:%d)\n", expression, file, line);
    abort();
}
#define MESHFIX_ASSERT(x) stress_assert((x) ? 1 : 0, #x, __FILE__, __LINE__)

#define MESHFIX_IMPLEMENTATION
#include "../../meshfix.h"

#include <float.h>
#include <math.h>
#include <stdint.h>

/* Under MemorySanitizer fresh memory stays unwritten, so MSan itself sees
   every read of it; otherwise it is filled with garbage (see do_run). */
#if defined(__has_feature)
#if __has_feature(memory_sanitizer)
#define STRESS_MSAN 1
#endif
#endif
#ifndef STRESS_MSAN
#define STRESS_MSAN 0
#endif

#define MAX_VERTICES 4096
#define MAX_TRIANGLES 4096
/* ray budgets actually run: bounded so one input costs well under a second */
#define RUN_RAYS_CAP 20000u
/* beyond these the library must refuse (meshfix.h: MESHFIX__MAX_RAYS,
   MESHFIX__MAX_MIN_SAMPLES), so such values are only used in refusal calls */
#define REFUSED_RAYS_ABOVE ((size_t)1 << 24)
#define REFUSED_MIN_SAMPLES_ABOVE 65536u
/* the default budget (visibility.rays = 0) is 65536+ rays: only for small
   meshes (235 non-manifold triangles took 6 s with the sanitizers) */
#define DEFAULT_RAYS_MAX_TRIANGLES 64u


/* ===== failure ===== */

static void fail(const char *what, const char *file, int line)
{
    fprintf(stderr, "fuzz_stress: invariant violated: %s (%s:%d)\n", what, file, line);
    abort();
}
#define REQUIRE(cond, what) ((cond) ? (void)0 : fail(what, __FILE__, __LINE__))

/* ===== byte source: the input, or a generator seeded by it ===== */

typedef struct source {
    const uint8_t *data;
    size_t size;
    uint64_t rng;
    int use_rng; /* generators expand a few input bytes into thousands of values */
} source;

static uint64_t splitmix(uint64_t *state)
{
    uint64_t z = (*state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

/* Exhausted input reads as zeros: short inputs mean defaults. */
static uint8_t take_u8(source *s)
{
    uint8_t b;
    if (s->use_rng)
        return (uint8_t)(splitmix(&s->rng) >> 56);
    if (s->size == 0)
        return 0;
    b = s->data[0];
    s->data++, s->size--;
    return b;
}

static uint16_t take_u16(source *s)
{
    uint16_t lo = take_u8(s);
    return (uint16_t)(lo | (uint16_t)(take_u8(s) << 8));
}

static uint32_t take_u32(source *s)
{
    uint32_t lo = take_u16(s);
    return lo | ((uint32_t)take_u16(s) << 16);
}

static uint64_t take_u64(source *s)
{
    uint64_t lo = take_u32(s);
    return lo | ((uint64_t)take_u32(s) << 32);
}

static float float_from_bits(uint32_t bits)
{
    float f;
    memcpy(&f, &bits, sizeof(f));
    return f;
}

static uint32_t bits_of(float f)
{
    uint32_t bits;
    memcpy(&bits, &f, sizeof(bits));
    return bits;
}

static int is_finite_bits(float f)
{
    return (bits_of(f) & 0x7F800000u) != 0x7F800000u;
}

/* A generator whose seed comes from the input. */
static source generator(source *input)
{
    source g;
    memset(&g, 0, sizeof(g));
    g.use_rng = 1;
    g.rng = take_u64(input);
    return g;
}

static uint32_t below(source *s, uint32_t n)
{
    return n == 0 ? 0 : take_u32(s) % n;
}

/* ===== the mesh being built ===== */

typedef struct mesh {
    float xyz[3 * MAX_VERTICES];
    unsigned int tri[3 * MAX_TRIANGLES];
    size_t vertices, triangles;
} mesh;

static int add_vertex(mesh *m, float x, float y, float z, unsigned int *id)
{
    if (m->vertices >= MAX_VERTICES)
        return 0;
    m->xyz[3 * m->vertices] = x;
    m->xyz[3 * m->vertices + 1] = y;
    m->xyz[3 * m->vertices + 2] = z;
    *id = (unsigned int)m->vertices++;
    return 1;
}

/* flip: store as (a, c, b) */
static int add_triangle(mesh *m, unsigned int a, unsigned int b, unsigned int c, int flip)
{
    if (m->triangles >= MAX_TRIANGLES)
        return 0;
    m->tri[3 * m->triangles] = a;
    m->tri[3 * m->triangles + 1] = flip ? c : b;
    m->tri[3 * m->triangles + 2] = flip ? b : c;
    m->triangles++;
    return 1;
}

/* ===== coordinates: eight encodings ===== */

enum {
    ENC_RAW_BITS,   /* any float: NaN, Inf, denormal, huge */
    ENC_SMALL_INT,  /* -128 .. 127: coincident and grid-like meshes */
    ENC_POW2,       /* +-2^-k, k < 150: nested planes down to denormals */
    ENC_ELEVEN,     /* c * 11^-k, k < 48: values no power of two lines up with */
    ENC_NEAR_MAX,   /* +-(FLT_MAX - j ulps): overflow in any float sum */
    ENC_FIXED,      /* int16 / 256 */
    ENC_REPEAT,     /* an earlier vertex's coordinate, a few ulps off */
    ENC_POW2_HUGE,  /* +-2^k, k < 128 */
    ENC_COUNT
};

static float decode_coord(source *s, const mesh *m, int axis, int encoding)
{
    switch (encoding) {
    case ENC_RAW_BITS:
        return float_from_bits(take_u32(s));
    case ENC_SMALL_INT:
        return (float)(int8_t)take_u8(s);
    case ENC_POW2: {
        uint16_t v = take_u16(s);
        return ldexpf((v & 1) ? -1.0f : 1.0f, -(int)((v >> 1) % 150));
    }
    case ENC_ELEVEN: {
        int c = (int8_t)take_u8(s);
        int k = take_u8(s) % 48;
        return (float)((double)c * pow(11.0, -(double)k));
    }
    case ENC_NEAR_MAX: {
        uint16_t v = take_u16(s);
        return float_from_bits(((v & 1) ? 0x80000000u : 0u) | (0x7F7FFFFFu - (uint32_t)(v >> 1)));
    }
    case ENC_FIXED:
        return (float)(int16_t)take_u16(s) / 256.0f;
    case ENC_REPEAT: {
        uint8_t back = take_u8(s);
        int8_t ulps = (int8_t)take_u8(s);
        uint32_t bits;
        if (m->vertices == 0)
            return 0.0f;
        bits = bits_of(m->xyz[3 * (m->vertices - 1 - back % m->vertices) + (size_t)axis]);
        /* a few ulps off (in the bit pattern), zero ulps most often */
        return float_from_bits(bits + (uint32_t)(int32_t)(ulps / 32));
    }
    default: {
        uint8_t v = take_u8(s);
        return ldexpf((v & 128) ? -1.0f : 1.0f, v & 127);
    }
    }
}

/* Per-coordinate encodings in 9 bits of a 16-bit word. */
static void decode_point(source *s, const mesh *m, uint16_t encodings, float p[3])
{
    int k;
    for (k = 0; k < 3; ++k)
        p[k] = decode_coord(s, m, k, (encodings >> (3 * k)) & 7);
}

/* ===== option values ===== */

/* A float option: mostly valid values (so calls get past validation),
   but also NaN, Inf, negative, huge and raw bits. */
static float decode_option_float(source *s)
{
    uint8_t sel = take_u8(s);
    uint8_t v = take_u8(s);
    static const float specials[7] = {0.0f, -0.0f, 1.0f, FLT_MIN, FLT_MAX, 1e-45f, 0.5f};
    switch (sel % 10) {
    case 0:
    case 1:
        return 0.0f; /* the default */
    case 2:
    case 3:
        return (float)v / 255.0f;
    case 4:
        return (float)v / 2550.0f;
    case 5:
        return specials[v % 7];
    case 6:
        return float_from_bits(take_u32(s));
    case 7:
        return -((float)v + 1.0f) / 16.0f;
    case 8:
        return ldexpf((v & 128) ? -1.0f : 1.0f, v & 127);
    default:
        return (v % 3) == 0 ? NAN : (v % 3) == 1 ? INFINITY : -INFINITY;
    }
}

/* ===== settings: everything but the mesh ===== */

enum { DEST_SEPARATE, DEST_IN_PLACE, DEST_NULL, DEST_OVERLAP, DEST_MODES };
enum { ALLOC_DEFAULT, ALLOC_COUNTING, ALLOC_FAILING, ALLOC_NO_FREE, ALLOC_MODES };
/* caller scratch: none; exactly meshfix_scratch_size() for the call's
   options (no allocation at all); less than the topology needs (refused);
   a few KB more; the topology alone (the geometry may allocate) */
enum { SCRATCH_NONE, SCRATCH_EXACT, SCRATCH_SHORT, SCRATCH_ROOMY, SCRATCH_TOPOLOGY, SCRATCH_MODES };
enum { PARALLEL_NONE, PARALLEL_REVERSE, PARALLEL_SHUFFLE, PARALLEL_MODES };

typedef struct settings {
    /* raw option values, as decoded */
    int policy;
    size_t rays;
    unsigned int min_samples;
    float coherence, c0, eps, kv, sdf_step, up[3];
    float evidence_sigma, min_confidence;
    unsigned int sdf_mode, visibility_flags, seed;
    /* caller normals: per triangle and / or per vertex */
    int triangle_normals, vertex_normals, normals_kind;
    size_t triangle_normals_stride, vertex_normals_stride;
    uint64_t normals_seed;
    /* outputs */
    int want_flipped, want_patch_ids, want_confidence, want_components, want_report;
    size_t confidence_capacity, components_capacity, slack;
    /* machinery */
    int alloc_mode;
    unsigned int fail_at;
    int fail_persistent;
    int scratch_mode;
    size_t scratch_shortfall, scratch_misalign;
    int parallel_mode;
    uint64_t shuffle_seed;
    int sdf_present, sdf_shape, sdf_gradient, sdf_gradient_nan;
    unsigned int sdf_nan_mask;
    /* layout */
    size_t stride;
    int positions_null;
    int vertex_skew;      /* vertex_count passed = built + skew (>= 0) */
    int dest_mode;
    int dest_shift;
    size_t trailing;      /* indices after the last triangle: 0..2 */
    uint8_t fill;         /* pattern of every output buffer before a call */
    /* other calls */
    int call_inspect, call_check, call_weld, call_second;
    float weld_tolerance;
    unsigned int requirements;
    /* formats (0.2): raw values as decoded (may be invalid) */
    unsigned int index_size, position_size, topology;
    float topology_tolerance;
    /* double positions: offset (far from the origin), scale, jitter below float precision */
    int double_offset_kind, double_jitter;
    double double_offset;
    int double_exponent;
    size_t double_stride;
    uint64_t double_seed;
    size_t summary_size;   /* the buffer meshfix_summary gets (0 and 1 included) */
    int outputs_null;      /* no output wanted: pass NULL rather than an empty struct */
} settings;

static size_t decode_rays(source *s)
{
    uint8_t sel = take_u8(s);
    switch (sel % 8) {
    case 0:
        return 0;
    case 1:
        return take_u8(s);
    case 2:
        return take_u16(s);
    case 3:
        return take_u16(s) % RUN_RAYS_CAP;
    case 4:
        return take_u32(s);
    case 5:
        return (size_t)take_u64(s);
    case 6:
        return REFUSED_RAYS_ABOVE + (size_t)take_u8(s) - 128u; /* at the boundary */
    default:
        return (size_t)-1 - take_u8(s);
    }
}

static unsigned int decode_min_samples(source *s)
{
    uint8_t sel = take_u8(s);
    switch (sel % 5) {
    case 0:
        return 0;
    case 1:
        return take_u8(s);
    case 2:
        return take_u16(s);
    case 3:
        return REFUSED_MIN_SAMPLES_ABOVE + take_u8(s) - 128u;
    default:
        return take_u32(s);
    }
}

/* A positions stride for x y z of `size` bytes each: 0 (packed), or at
   least the three coordinates in 4-byte steps. */
static int stride_valid(size_t stride, unsigned int size)
{
    return stride == 0 || (stride >= 3 * (size_t)size && stride % 4 == 0);
}

/* normals: 0 (12 bytes) or whole floats, at least three */
static int normal_stride_valid(size_t stride)
{
    return stride == 0 || (stride >= 12 && stride % 4 == 0);
}

static const size_t strides[16] = {12, 12, 12, 12, 16, 16, 20, 24, 32, 48, 12, 0, 4, 8, 13, 14};
/* doubles: 24 packed; 28 and 36 put doubles on 4-byte boundaries; 12 to 26 are not valid */
static const size_t double_strides[16] = {24, 24, 24, 0, 0, 32, 40, 48, 28, 36, 24, 12, 16, 20, 25, 26};
/* normals: stride 0 is documented as 12 bytes; 4 and 13 are not valid */
static const size_t normal_strides[8] = {0, 12, 12, 16, 24, 0, 4, 13};

/* index_size and position_size: the default (0), the other size, the
   explicit default, or any value */
static unsigned int decode_size(source *s, uint8_t b, unsigned int other, unsigned int standard)
{
    switch (b % 4) {
    case 0:
        return 0;
    case 1:
        return other;
    case 2:
        return standard;
    default:
        return take_u32(s);
    }
}

static void read_settings(source *s, settings *st)
{
    uint8_t b;
    memset(st, 0, sizeof(*st));
    /* calls */
    b = take_u8(s);
    st->call_inspect = (b & 1) != 0;
    st->call_check = (b & 2) != 0;
    st->call_weld = (b & 4) != 0;
    st->want_report = (b & 8) == 0;
    st->positions_null = (b & 0x30) == 0x30; /* one in four */
    st->call_second = (b & 64) == 0;
    /* policy: in range mostly, else any int */
    b = take_u8(s);
    st->policy = b < 240 ? b % MESHFIX_POLICY_COUNT : (int)take_u32(s);
    st->rays = decode_rays(s);
    st->min_samples = decode_min_samples(s);
    st->coherence = decode_option_float(s);
    st->c0 = decode_option_float(s);
    st->eps = decode_option_float(s);
    st->kv = decode_option_float(s);
    st->sdf_step = decode_option_float(s);
    st->up[0] = decode_option_float(s);
    st->up[1] = decode_option_float(s);
    st->up[2] = decode_option_float(s);
    b = take_u8(s);
    st->sdf_mode = b < 240 ? b % 2u : take_u32(s);
    b = take_u8(s);
    st->visibility_flags = b < 200 ? b % 4u : b;
    st->seed = take_u32(s);
    /* outputs: buffers hold capacity + slack elements, the slack must stay untouched */
    b = take_u8(s);
    st->want_flipped = (b & 1) != 0;
    st->want_patch_ids = (b & 2) != 0;
    st->want_confidence = (b & 4) != 0;
    st->want_components = (b & 8) != 0;
    st->slack = (b >> 4) % 4;
    st->confidence_capacity = take_u16(s) % (MAX_TRIANGLES + 2);
    st->components_capacity = take_u16(s) % (MAX_TRIANGLES + 2);
    /* allocator */
    b = take_u8(s);
    st->alloc_mode = b % ALLOC_MODES;
    st->fail_persistent = (b & 4) != 0;
    st->fail_at = 1u + take_u8(s) % 32u;
    /* scratch */
    b = take_u8(s);
    st->scratch_mode = b % SCRATCH_MODES;
    st->scratch_misalign = (b >> 3) % 16;
    st->scratch_shortfall = 1u + take_u16(s);
    /* parallel_for */
    b = take_u8(s);
    st->parallel_mode = b % PARALLEL_MODES;
    st->shuffle_seed = take_u64(s);
    /* SDF callbacks */
    b = take_u8(s);
    st->sdf_present = (b & 0x0F) != 0x0F;
    st->sdf_shape = (b >> 4) % 4;
    st->sdf_gradient = (b & 1) != 0;
    st->sdf_gradient_nan = (b & 2) != 0;
    b = take_u8(s);
    st->sdf_nan_mask = b < 128 ? 0u : (1u << (b % 8)) - 1u; /* 0: never NaN */
    /* layout */
    st->stride = strides[take_u8(s) % 16];
    b = take_u8(s);
    st->vertex_skew = b < 192 ? 0 : (int)(b % 16) - 8;
    b = take_u8(s);
    st->dest_mode = b % DEST_MODES;
    st->dest_shift = (int)(int8_t)take_u8(s);
    b = take_u8(s);
    st->trailing = b < 240 ? 0 : 1u + b % 2u;
    st->fill = take_u8(s);
    /* weld and check */
    st->weld_tolerance = decode_option_float(s);
    st->requirements = take_u8(s) & MESHFIX_REQUIRE_SOLID;
    /* fields added with the NORMALS policy, last so older seeds still decode */
    st->evidence_sigma = decode_option_float(s);
    st->min_confidence = decode_option_float(s);
    b = take_u8(s);
    st->triangle_normals = (b & 1) != 0;
    st->vertex_normals = (b & 2) != 0;
    st->normals_kind = (b >> 2) % 4;
    b = take_u8(s);
    st->triangle_normals_stride = normal_strides[b % 8];
    st->vertex_normals_stride = normal_strides[(b >> 3) % 8];
    st->normals_seed = take_u64(s);
    /* fields added with the 0.2 API: formats, topology, double positions, summary */
    st->index_size = decode_size(s, take_u8(s), 2, 4);
    st->position_size = decode_size(s, take_u8(s), 8, 4);
    b = take_u8(s);
    st->topology = b < 240 ? b % 3u : take_u32(s);
    st->topology_tolerance = decode_option_float(s);
    b = take_u8(s);
    st->double_offset_kind = b % 4;
    st->double_jitter = (b & 4) != 0;
    st->double_exponent = (b & 8) ? (int)(int8_t)take_u8(s) * 8 : 0; /* beyond float range both ways */
    switch (st->double_offset_kind) {
    case 1: { /* +-2^k: survey coordinates, or far beyond */
        uint8_t k = take_u8(s);
        st->double_offset = ldexp((k & 128) ? -1.0 : 1.0, k % 80);
        break;
    }
    case 2: { /* any bits: NaN, Inf, huge, denormal */
        uint64_t bits = take_u64(s);
        memcpy(&st->double_offset, &bits, sizeof(bits));
        break;
    }
    case 3: /* c * 10^k: a decimal coordinate system */
        st->double_offset = (double)(int8_t)take_u8(s) * pow(10.0, (double)(take_u8(s) % 16));
        break;
    default:
        st->double_offset = 0.0;
    }
    st->double_stride = double_strides[take_u8(s) % 16];
    st->double_seed = take_u64(s);
    b = take_u8(s);
    st->summary_size = b < 64 ? b % 8u : b; /* 0 .. 7 often: 0 and 1 included */
    st->outputs_null = (take_u8(s) & 1) != 0;
}

/* ===== the mesh program ===== */

static int random_flip(source *g, uint8_t probability)
{
    return take_u8(g) < probability;
}

/* Planes shrinking toward the origin: triangle k lies in the plane
   axis = s_k, s_k = radix^-(k + axis/3), and is as small as its distance
   to the origin. Centroids in a geometric sequence make SAH cut one
   triangle off per level: the deepest trees there are. */
static void op_shrinking_planes(source *in, mesh *m)
{
    unsigned int count = 1u + take_u8(in) % 64u, k0 = take_u8(in) % 48u, i;
    uint8_t flags = take_u8(in), flips = take_u8(in);
    double radix = (flags & 1) ? 2.0 : 11.0;
    int strip = (flags & 2) != 0, alternate = (flags & 4) != 0, one_axis = (flags & 8) != 0;
    int only = (flags >> 4) % 3, axis;
    unsigned int first = (unsigned int)m->vertices;
    source g = generator(in);
    for (i = 0; i < count; ++i)
        for (axis = 0; axis < 3; ++axis) {
            double e = (double)(k0 + i) + axis / 3.0, s = pow(radix, -e);
            float side = (float)((alternate && (i & 1)) ? -s : s), p[3][3];
            unsigned int ids[3], c;
            int u = (axis + 1) % 3, v = (axis + 2) % 3;
            if (one_axis && axis != only)
                continue;
            for (c = 0; c < 3; ++c)
                p[c][axis] = side;
            p[0][u] = -(float)s, p[0][v] = -(float)s;
            p[1][u] = (float)s, p[1][v] = -(float)s;
            p[2][u] = 0.0f, p[2][v] = (float)s;
            for (c = 0; c < 3; ++c)
                if (!add_vertex(m, p[c][0], p[c][1], p[c][2], &ids[c]))
                    return;
            if (!strip && !add_triangle(m, ids[0], ids[1], ids[2], random_flip(&g, flips)))
                return;
        }
    if (strip) /* one strip through every point: slivers between scales */
        for (i = first; i + 2 < (unsigned int)m->vertices; ++i)
            if (!add_triangle(m, i, i + 1, i + 2, (int)((i - first) & 1) ^ random_flip(&g, flips)))
                return;
}

/* Every triple of n vertices: each edge is shared by n - 2 triangles. */
static void op_hypergraph(source *in, mesh *m)
{
    unsigned int n = 4u + take_u8(in) % 21u, i, j, k, v[24];
    uint8_t flags = take_u8(in);
    uint16_t encodings = take_u16(in);
    source g = generator(in);
    if ((flags & 1) && m->vertices >= n) {
        for (i = 0; i < n; ++i)
            v[i] = (unsigned int)(m->vertices - n + i); /* reuse the latest vertices */
    } else {
        for (i = 0; i < n; ++i) {
            float p[3];
            decode_point(&g, m, encodings, p);
            if (!add_vertex(m, p[0], p[1], p[2], &v[i]))
                return;
        }
    }
    for (i = 0; i < n; ++i)
        for (j = i + 1; j < n; ++j)
            for (k = j + 1; k < n; ++k)
                if (!add_triangle(m, v[i], v[j], v[k], random_flip(&g, flags)))
                    return;
}

static const float tetra_points[4][3] = {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
static const unsigned int tetra_faces[4][3] = {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}};
static const float octa_points[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
static const unsigned int octa_faces[8][3] = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                                             {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
static const float cube_points[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                                        {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
static const unsigned int cube_faces[12][3] = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
                                              {2, 3, 7}, {2, 7, 6}, {1, 2, 6}, {1, 6, 5}, {3, 0, 4}, {3, 4, 7}};

/* Closed shells (outward as listed), nested or side by side, each scaled
   by ratio^i about a common centre: cavities, coincident and touching
   shells, shells too small to see next to the others. */
static void op_shells(source *in, mesh *m)
{
    static const double ratios[6] = {0.5, 1.0 / 11.0, 0.999, 1.0, 2.0, 1e-6};
    unsigned int count = 1u + take_u8(in) % 64u, i, c, f;
    uint8_t kind = take_u8(in), flips = take_u8(in), layout = take_u8(in);
    double ratio = ratios[layout % 6], scale = 1.0;
    float centre[3], step[3];
    source g;
    decode_point(in, m, take_u16(in), centre);
    decode_point(in, m, take_u16(in), step);
    g = generator(in);
    for (i = 0; i < count; ++i, scale *= ratio) {
        const float(*points)[3] = kind % 3 == 0 ? tetra_points : kind % 3 == 1 ? octa_points : cube_points;
        const unsigned int(*faces)[3] = kind % 3 == 0 ? tetra_faces : kind % 3 == 1 ? octa_faces : cube_faces;
        unsigned int corners = kind % 3 == 0 ? 4 : kind % 3 == 1 ? 6 : 8, n = kind % 3 == 0 ? 4 : kind % 3 == 1 ? 8 : 12;
        unsigned int base = (unsigned int)m->vertices, id;
        int inside_out = (kind & 4) && (i & 1); /* every other shell wound inward as a whole */
        for (c = 0; c < corners; ++c) {
            float p[3];
            int k;
            for (k = 0; k < 3; ++k)
                p[k] = (float)((double)centre[k] + (double)step[k] * (layout & 8 ? i : 0) + points[c][k] * scale);
            if (!add_vertex(m, p[0], p[1], p[2], &id))
                return;
        }
        for (f = 0; f < n; ++f)
            if (!add_triangle(m, base + faces[f][0], base + faces[f][1], base + faces[f][2],
                              inside_out ^ random_flip(&g, flips)))
                return;
    }
}

/* A height field: open sheets for VISIBILITY and UP. */
static void op_grid(source *in, mesh *m)
{
    unsigned int w = 2u + take_u8(in) % 63u, h = 2u + take_u8(in) % 63u, x, y, base = (unsigned int)m->vertices, id;
    uint8_t flips = take_u8(in), encoding = take_u8(in);
    float spacing = decode_coord(in, m, 0, ENC_POW2);
    source g = generator(in);
    if (m->vertices + (size_t)w * h > MAX_VERTICES)
        return;
    for (y = 0; y < h; ++y)
        for (x = 0; x < w; ++x) {
            float z = (encoding & 8) ? decode_coord(&g, m, 2, encoding & 7) : 0.0f;
            add_vertex(m, (float)x * spacing, (float)y * spacing, z, &id);
        }
    for (y = 0; y + 1 < h; ++y)
        for (x = 0; x + 1 < w; ++x) {
            unsigned int a = base + y * w + x, b = a + 1, c = a + w, d = c + 1;
            if (!add_triangle(m, a, b, d, random_flip(&g, flips)) || !add_triangle(m, a, d, c, random_flip(&g, flips)))
                return;
        }
}

/* Independent triangles, coordinates from the generator in one encoding
   (or a random one per coordinate). */
static void op_soup(source *in, mesh *m)
{
    unsigned int n = 1u + take_u16(in) % 2048u, t, c;
    uint16_t encodings = take_u16(in);
    int mixed = (encodings & 0x8000) != 0;
    source g = generator(in);
    for (t = 0; t < n; ++t) {
        unsigned int ids[3];
        for (c = 0; c < 3; ++c) {
            float p[3];
            decode_point(&g, m, mixed ? take_u16(&g) : encodings, p);
            if (!add_vertex(m, p[0], p[1], p[2], &ids[c]))
                return;
        }
        if (!add_triangle(m, ids[0], ids[1], ids[2], 0))
            return;
    }
}

/* Copies of one triangle, each with its own vertices: exactly coincident,
   a few ulps apart, or stacked along z. A ray through them visits every box. */
static void op_stack(source *in, mesh *m)
{
    unsigned int n = 2u + take_u8(in), i, c, ids[3];
    uint8_t mode = take_u8(in), flips = take_u8(in);
    float p[3][3];
    source g;
    for (c = 0; c < 3; ++c)
        decode_point(in, m, take_u16(in), p[c]);
    g = generator(in);
    for (i = 0; i < n; ++i) {
        for (c = 0; c < 3; ++c) {
            float q[3];
            int k;
            for (k = 0; k < 3; ++k) {
                q[k] = p[c][k];
                if (mode % 3 == 1)
                    q[k] = float_from_bits(bits_of(q[k]) + (uint32_t)(take_u8(&g) % 5) - 2u);
            }
            if (mode % 3 == 2)
                q[2] = p[c][2] + ldexpf((float)i, -(int)(mode % 64));
            if (!add_vertex(m, q[0], q[1], q[2], &ids[c]))
                return;
        }
        if (!add_triangle(m, ids[0], ids[1], ids[2], random_flip(&g, flips)))
            return;
    }
}

/* n triangles on one edge (a, b), or around one vertex (bow-ties). */
static void op_fan(source *in, mesh *m)
{
    unsigned int n = 1u + take_u8(in), i, a, b, x, y;
    uint8_t mode = take_u8(in), flips = take_u8(in);
    float scale = decode_coord(in, m, 0, ENC_POW2);
    source g = generator(in);
    if (!add_vertex(m, 0, 0, -scale, &a) || !add_vertex(m, 0, 0, scale, &b))
        return;
    for (i = 0; i < n; ++i) {
        float angle = 6.2831853f * (float)i / (float)n;
        if (!add_vertex(m, scale * cosf(angle), scale * sinf(angle), 0, &x))
            return;
        if (mode & 1) { /* bow-tie: two triangles per spoke, sharing only a */
            if (!add_vertex(m, scale * cosf(angle + 0.1f), scale * sinf(angle + 0.1f), scale, &y) ||
                !add_triangle(m, a, x, y, random_flip(&g, flips)))
                return;
        } else if (!add_triangle(m, a, b, x, random_flip(&g, flips))) {
            return;
        }
    }
}

/* Copies of earlier triangles: as they are, reversed, rotated. */
static void op_duplicates(source *in, mesh *m)
{
    unsigned int n = 1u + take_u8(in), i;
    source g = generator(in);
    for (i = 0; i < n && m->triangles > 0; ++i) {
        const unsigned int *t = &m->tri[3 * below(&g, (uint32_t)m->triangles)];
        unsigned int a = t[0], b = t[1], c = t[2], variant = take_u8(&g) % 4;
        int ok = variant == 0   ? add_triangle(m, a, b, c, 0)
                 : variant == 1 ? add_triangle(m, a, b, c, 1)
                 : variant == 2 ? add_triangle(m, b, c, a, 0)
                                : add_triangle(m, c, b, a, 0);
        if (!ok)
            return;
    }
}

/* Changes the latest n vertices: scaled by 2^e, moved, or poisoned. */
static void op_transform(source *in, mesh *m)
{
    size_t n = 1u + take_u8(in), first, v;
    uint8_t kind = take_u8(in);
    int exponent = (int8_t)take_u8(in);
    float offset[3];
    decode_point(in, m, take_u16(in), offset);
    n = (kind & 4) || n > m->vertices ? m->vertices : n;
    first = m->vertices - n;
    for (v = first; v < m->vertices; ++v) {
        float *p = &m->xyz[3 * v];
        int k;
        for (k = 0; k < 3; ++k) {
            if (kind % 4 == 0)
                p[k] = ldexpf(p[k], exponent);
            else if (kind % 4 == 1)
                p[k] = p[k] + offset[k];
            else if (kind % 4 == 2 && (v - first) % (1u + (kind >> 3)) == 0 && k == (int)(v % 3))
                p[k] = offset[k]; /* one coordinate of every few vertices */
        }
        if (kind % 4 == 3) { /* rotate the axes: the same mesh, binned differently */
            float x = p[0];
            p[0] = p[1], p[1] = p[2], p[2] = x;
        }
    }
}

static void op_flip(source *in, mesh *m)
{
    uint8_t probability = take_u8(in);
    source g = generator(in);
    size_t t;
    for (t = 0; t < m->triangles; ++t)
        if (random_flip(&g, probability)) {
            unsigned int x = m->tri[3 * t + 1];
            m->tri[3 * t + 1] = m->tri[3 * t + 2];
            m->tri[3 * t + 2] = x;
        }
}

/* One index: relative to the newest vertex, modulo the count, raw, or a
   repeat of the previous corner (a degenerate triangle). */
static unsigned int decode_index(source *s, const mesh *m, int mode, unsigned int previous)
{
    unsigned int n = (unsigned int)m->vertices;
    switch (mode) {
    case 0: {
        unsigned int back = take_u8(s);
        return back < n ? n - 1 - back : back;
    }
    case 1:
        return n ? take_u16(s) % n : take_u16(s);
    case 2:
        return take_u32(s);
    default:
        return previous;
    }
}

static void op_triangle(source *in, mesh *m)
{
    uint8_t modes = take_u8(in);
    unsigned int a = decode_index(in, m, modes & 3, 0);
    unsigned int b = decode_index(in, m, (modes >> 2) & 3, a);
    unsigned int c = decode_index(in, m, (modes >> 4) & 3, b);
    add_triangle(m, a, b, c, (modes & 64) != 0);
}

static void op_vertex(source *in, mesh *m)
{
    float p[3];
    unsigned int id;
    decode_point(in, m, take_u16(in), p);
    add_vertex(m, p[0], p[1], p[2], &id);
}

/* Random triples of existing vertices: within a window of recent ones
   (connected, non-manifold) or anywhere; now and then one out of range. */
static void op_random_triangles(source *in, mesh *m)
{
    unsigned int n = 1u + take_u16(in) % 2048u, i, window = 3u + take_u8(in);
    uint8_t out_of_range = take_u8(in);
    source g = generator(in);
    unsigned int count = (unsigned int)m->vertices;
    if (count == 0)
        return;
    window = window < count ? window : count;
    for (i = 0; i < n; ++i) {
        unsigned int v[3], c;
        for (c = 0; c < 3; ++c)
            v[c] = count - 1 - below(&g, window);
        if (out_of_range != 0 && take_u8(&g) < out_of_range / 16)
            v[take_u8(&g) % 3] = count + take_u8(&g);
        if (!add_triangle(m, v[0], v[1], v[2], 0))
            return;
    }
}

typedef void (*mesh_op)(source *in, mesh *m);
static const mesh_op mesh_ops[] = {op_vertex,  op_triangle, op_shrinking_planes, op_hypergraph,
                                   op_shells,  op_grid,     op_soup,             op_stack,
                                   op_fan,     op_duplicates, op_transform,      op_flip,
                                   op_random_triangles};
#define MESH_OPS (sizeof(mesh_ops) / sizeof(mesh_ops[0]))

static void build_mesh(source *in, mesh *m)
{
    unsigned int ops = 0;
    m->vertices = m->triangles = 0;
    while (in->size > 0 && ops++ < 256)
        mesh_ops[take_u8(in) % MESH_OPS](in, m);
}

/* ===== callbacks and allocator, each counting its calls ===== */

typedef struct counters {
    size_t alloc_calls, live_blocks, free_calls;
    uint8_t garbage;      /* fresh blocks are filled with this (varied per block), see do_run */
    unsigned int fail_at; /* 0: never */
    int fail_persistent;
    size_t sdf_calls;
    size_t parallel_calls;
} counters;

static void *counting_alloc(size_t size, void *user)
{
    counters *c = (counters *)user;
    void *p;
    c->alloc_calls++;
    if (c->fail_at != 0 && (c->alloc_calls == c->fail_at || (c->fail_persistent && c->alloc_calls > c->fail_at)))
        return NULL;
    c->live_blocks++;
    p = malloc(size);
    if (p != NULL && !STRESS_MSAN) /* garbage: a read of memory never written differs from run to run */
        memset(p, (uint8_t)(c->garbage + 37u * (unsigned int)c->alloc_calls), size);
    return p;
}

static void counting_free(void *p, void *user)
{
    counters *c = (counters *)user;
    REQUIRE(p != NULL, "free_fn called with NULL");
    REQUIRE(c->live_blocks > 0, "free_fn called more often than alloc_fn succeeded");
    c->live_blocks--;
    c->free_calls++;
    free(p);
}

typedef struct sdf_user {
    const settings *st;
    counters *count;
} sdf_user;

/* Cheap and a pure function of the point (results must not depend on
   call order); some points give NaN or Inf. */
static int poisoned(const float p[3], unsigned int mask)
{
    uint32_t h = bits_of(p[0]) * 0x9E3779B1u ^ bits_of(p[1]) * 0x85EBCA77u ^ bits_of(p[2]) * 0xC2B2AE3Du;
    return mask != 0 && ((h ^ (h >> 15)) & mask) == 0;
}

static float stress_sdf(const float p[3], void *user)
{
    sdf_user *u = (sdf_user *)user;
    u->count->sdf_calls++;
    if (poisoned(p, u->st->sdf_nan_mask))
        return (bits_of(p[0]) & 1) ? NAN : INFINITY;
    switch (u->st->sdf_shape) {
    case 0:
        return sqrtf(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]) - 1.0f;
    case 1:
        return p[2];
    case 2: {
        float x = fabsf(p[0]), y = fabsf(p[1]), z = fabsf(p[2]);
        return (x > y ? (x > z ? x : z) : (y > z ? y : z)) - 0.5f;
    }
    default:
        return 0.0f; /* no gradient anywhere */
    }
}

static void stress_sdf_gradient(const float p[3], float g[3], void *user)
{
    sdf_user *u = (sdf_user *)user;
    u->count->sdf_calls++;
    g[0] = p[0], g[1] = p[1], g[2] = p[2];
    if (u->st->sdf_gradient_nan && poisoned(p, u->st->sdf_nan_mask | 1u))
        g[1] = NAN;
}

typedef struct parallel_user {
    const settings *st;
    counters *count;
} parallel_user;

/* Runs every chunk once, in reverse or in an order drawn from the input. */
static void stress_parallel_for(void (*task)(void *context, size_t index), void *context, size_t count, void *user)
{
    parallel_user *u = (parallel_user *)user;
    size_t i, *order;
    uint64_t state = u->st->shuffle_seed;
    u->count->parallel_calls++;
    if (u->st->parallel_mode == PARALLEL_REVERSE) {
        for (i = count; i-- > 0;)
            task(context, i);
        return;
    }
    order = (size_t *)malloc((count ? count : 1) * sizeof(size_t));
    REQUIRE(order != NULL, "harness out of memory");
    for (i = 0; i < count; ++i)
        order[i] = i;
    for (i = count; i > 1; --i) { /* Fisher-Yates */
        size_t j = (size_t)(splitmix(&state) % i), x = order[i - 1];
        order[i - 1] = order[j], order[j] = x;
    }
    for (i = 0; i < count; ++i)
        task(context, order[i]);
    free(order);
}

static void *fill_alloc(size_t bytes, uint8_t fill);

/* ===== the case: mesh as passed, and what is wrong with it ===== */

typedef struct fuzz_case {
    const settings *st;
    const mesh *m;
    unsigned int *indices; /* pristine copy, index_count long, as 32-bit values */
    void *call_indices;    /* the same in the call's format (index_size bytes each) */
    size_t index_count, triangles;
    void *positions;       /* NULL, or vertex_count vertices of stride bytes, floats or doubles */
    size_t positions_bytes;
    size_t vertex_count, stride;
    unsigned int max_index;
    /* the formats every call of the case uses (valid values): the raw
       settings go only to the refusal call */
    unsigned int index_size, position_size; /* 2 or 4; 4 or 8 */
    meshfix_topology topology;              /* INDICES when there are no positions */
    float topology_tolerance;
    unsigned int *rep;     /* vertex_count: the lowest vertex each is one with (topology) */
    unsigned char *degenerate_at; /* per triangle: repeats a vertex after the topology */
    size_t degenerate, joined;
    float *triangle_normals, *vertex_normals; /* NULL or the caller normals */
} fuzz_case;

static unsigned int index_at(const void *indices, unsigned int size, size_t i)
{
    return size == 2 ? ((const uint16_t *)indices)[i] : ((const unsigned int *)indices)[i];
}

/* indices in the call's format */
static void *encode_indices(const unsigned int *indices, size_t count, unsigned int size)
{
    void *out = malloc(count ? count * size : 1);
    size_t i;
    REQUIRE(out != NULL, "harness out of memory");
    for (i = 0; i < count; ++i) {
        if (size == 2)
            ((uint16_t *)out)[i] = (uint16_t)indices[i];
        else
            ((unsigned int *)out)[i] = indices[i];
    }
    return out;
}

static size_t effective_stride(const fuzz_case *fc)
{
    return fc->stride ? fc->stride : 3 * (size_t)fc->position_size;
}

/* Vertex v as the caller gave it, in double (floats widen exactly);
   returns 0 when a coordinate is NaN or infinite. */
static int read_vertex(const fuzz_case *fc, size_t v, double p[3])
{
    const char *q = (const char *)fc->positions + v * effective_stride(fc);
    int k, finite = 1;
    for (k = 0; k < 3; ++k) {
        if (fc->position_size == 8) {
            memcpy(&p[k], q + 8 * k, 8);
        } else {
            float x;
            memcpy(&x, q + 4 * k, 4);
            p[k] = (double)x;
        }
        finite = finite && p[k] - p[k] == 0.0;
    }
    return finite;
}

/* The topology by definition: bit-identical positions (-0 = +0; a NaN or
   infinite vertex joins nothing) by sorting, a weld within the tolerance
   by meshfix_weld over the finite vertices alone (checked against its
   definition by check_weld), or indices. rep[v]: the lowest vertex v is
   one with. */
static const fuzz_case *sort_case;
static int compare_positions(const void *pa, const void *pb)
{
    unsigned int a = *(const unsigned int *)pa, b = *(const unsigned int *)pb;
    double x[3], y[3];
    int k;
    read_vertex(sort_case, a, x);
    read_vertex(sort_case, b, y);
    for (k = 0; k < 3; ++k) {
        uint64_t bx, by;
        x[k] = x[k] == 0.0 ? 0.0 : x[k], y[k] = y[k] == 0.0 ? 0.0 : y[k];
        memcpy(&bx, &x[k], 8), memcpy(&by, &y[k], 8);
        if (bx != by)
            return bx < by ? -1 : 1;
    }
    return a < b ? -1 : a > b;
}

static void compute_topology(fuzz_case *fc)
{
    size_t n = fc->vertex_count, v, i, finite_count = 0;
    unsigned int *order, *seen;
    fc->rep = (unsigned int *)malloc((n ? n : 1) * sizeof(unsigned int));
    REQUIRE(fc->rep != NULL, "harness out of memory");
    for (v = 0; v < n; ++v)
        fc->rep[v] = (unsigned int)v;
    if (fc->positions != NULL && fc->topology != MESHFIX_TOPOLOGY_INDICES && n != 0) {
        order = (unsigned int *)malloc(n * sizeof(unsigned int));
        REQUIRE(order != NULL, "harness out of memory");
        for (v = 0; v < n; ++v) {
            double p[3];
            if (read_vertex(fc, v, p))
                order[finite_count++] = (unsigned int)v;
        }
        if (fc->topology == MESHFIX_TOPOLOGY_POSITIONS) {
            sort_case = fc;
            qsort(order, finite_count, sizeof(unsigned int), compare_positions);
            for (i = 0; i < finite_count;) {
                size_t j = i + 1;
                double a[3], b[3];
                read_vertex(fc, order[i], a);
                for (; j < finite_count; ++j) {
                    int k, same = 1;
                    read_vertex(fc, order[j], b);
                    for (k = 0; k < 3; ++k)
                        same = same && a[k] == b[k]; /* finite: equal as doubles = bits equal but for -0 */
                    if (!same)
                        break;
                    fc->rep[order[j]] = order[i]; /* sorted by (position, index): the first is the lowest */
                }
                i = j;
            }
        } else {
            double *packed = (double *)malloc((finite_count ? finite_count : 1) * 3 * sizeof(double));
            unsigned int *remap = (unsigned int *)malloc((finite_count ? finite_count : 1) * sizeof(unsigned int));
            meshfix_options o;
            size_t unique;
            REQUIRE(packed != NULL && remap != NULL, "harness out of memory");
            for (i = 0; i < finite_count; ++i)
                read_vertex(fc, order[i], &packed[3 * i]);
            memset(&o, 0, sizeof(o));
            o.position_size = 8;
            REQUIRE(meshfix_weld(remap, packed, finite_count, 0, fc->topology_tolerance, &o, &unique) == MESHFIX_OK,
                    "meshfix_weld refused finite doubles (the reference topology)");
            for (i = 0; i < finite_count; ++i)
                fc->rep[order[i]] = order[remap[i]];
            free(packed);
            free(remap);
        }
        free(order);
    }
    /* degenerate triangles and joined indices, as the report counts them */
    fc->degenerate_at = (unsigned char *)malloc(fc->triangles ? fc->triangles : 1);
    seen = (unsigned int *)calloc(n ? n : 1, sizeof(unsigned int));
    REQUIRE(fc->degenerate_at != NULL && seen != NULL, "harness out of memory");
    fc->degenerate = fc->joined = 0;
    for (i = 0; i < fc->triangles; ++i) {
        const unsigned int *t = &fc->indices[3 * i];
        unsigned int a = t[0] < n ? fc->rep[t[0]] : t[0], b = t[1] < n ? fc->rep[t[1]] : t[1];
        unsigned int c = t[2] < n ? fc->rep[t[2]] : t[2];
        fc->degenerate_at[i] = a == b || b == c || a == c;
        fc->degenerate += fc->degenerate_at[i];
    }
    for (i = 0; i < 3 * fc->triangles; ++i) {
        unsigned int x = fc->indices[i];
        if (x < n && !seen[x]) {
            seen[x] = 1;
            fc->joined += fc->rep[x] != x;
        }
    }
    free(seen);
}

/* One caller normal: the face normal of the triangle as built (kind 0),
   that reversed at random (1), a random direction in any encoding,
   NaN and zero included (2), or zero (3). */
static void make_normal(const mesh *m, size_t t, int kind, source *g, float n[3])
{
    memset(n, 0, 3 * sizeof(float));
    if (kind <= 1 && t < m->triangles) {
        const float *a, *b, *c;
        double u[3], v[3], sign = kind == 1 && (take_u8(g) & 1) ? -1.0 : 1.0;
        int k;
        /* a triangle with an index out of range has no face normal */
        if (m->tri[3 * t] >= m->vertices || m->tri[3 * t + 1] >= m->vertices || m->tri[3 * t + 2] >= m->vertices)
            return;
        a = &m->xyz[3 * (size_t)m->tri[3 * t]];
        b = &m->xyz[3 * (size_t)m->tri[3 * t + 1]];
        c = &m->xyz[3 * (size_t)m->tri[3 * t + 2]];
        for (k = 0; k < 3; ++k)
            u[k] = (double)b[k] - (double)a[k], v[k] = (double)c[k] - (double)a[k];
        n[0] = (float)(sign * (u[1] * v[2] - u[2] * v[1]));
        n[1] = (float)(sign * (u[2] * v[0] - u[0] * v[2]));
        n[2] = (float)(sign * (u[0] * v[1] - u[1] * v[0]));
    } else if (kind == 2) {
        decode_point(g, m, take_u16(g), n);
    }
}

/* A normals buffer of `count` entries of `stride` bytes (0 = 12), exactly
   as long as the last entry's 12 bytes, padding NaN. */
static float *make_normals(const fuzz_case *fc, size_t count, size_t stride, int per_vertex)
{
    size_t step = stride ? stride : 12, bytes = count ? (count - 1) * step + 12 : 0, i, t;
    char *buffer = (char *)fill_alloc(bytes, 0xFF);
    size_t *around = NULL;
    source g;
    memset(&g, 0, sizeof(g));
    g.use_rng = 1, g.rng = fc->st->normals_seed;
    if (per_vertex) {
        /* a vertex gets the normal of its last triangle, or noise */
        around = (size_t *)fill_alloc(count * sizeof(size_t), 0xFF);
        for (t = 0; t < fc->m->triangles; ++t)
            for (i = 0; i < 3; ++i)
                if (fc->m->tri[3 * t + i] < count)
                    around[fc->m->tri[3 * t + i]] = t;
    }
    for (i = 0; i < count; ++i) {
        float n[3];
        make_normal(fc->m, per_vertex ? around[i] : i, fc->st->normals_kind, &g, n);
        memcpy(buffer + i * step, n, 12);
    }
    free(around);
    return (float *)(void *)buffer;
}

/* The formats of the case: the decoded values where valid, else the
   defaults; 16-bit indices only when every vertex fits. */
static void case_formats(fuzz_case *fc, const settings *st)
{
    fc->index_size = st->index_size == 2 && fc->vertex_count <= 65536 ? 2u : 4u;
    fc->position_size = st->position_size == 8 ? 8u : 4u;
    fc->topology = st->topology <= MESHFIX_TOPOLOGY_WELD ? (meshfix_topology)st->topology : MESHFIX_TOPOLOGY_POSITIONS;
    fc->topology_tolerance = is_finite_bits(st->topology_tolerance) ? fabsf(st->topology_tolerance) : 0.0f;
    if (st->positions_null)
        fc->topology = MESHFIX_TOPOLOGY_INDICES; /* what the library uses without positions */
}

/* A built float coordinate as a double: scaled by 2^e, moved by the
   offset, and (jitter) given bits below float precision. */
static double to_double(const settings *st, float x, source *g)
{
    double d = ldexp((double)x, st->double_exponent) + st->double_offset;
    if (st->double_jitter && d - d == 0.0 && d != 0.0) {
        uint64_t bits;
        memcpy(&bits, &d, 8);
        bits ^= take_u32(g) & 0x1FFFFFFFu; /* the 29 bits a float does not have */
        memcpy(&d, &bits, 8);
    }
    return d;
}

static void setup_case(fuzz_case *fc, const settings *st, const mesh *m)
{
    size_t i, v, built = m->vertices;
    memset(fc, 0, sizeof(*fc));
    fc->st = st;
    fc->m = m;
    fc->index_count = 3 * m->triangles + st->trailing;
    fc->triangles = fc->index_count / 3;
    /* vertex_count may be smaller than what was built (indices out of
       range: the positions buffer then ends early, so a read past the
       checked count is an ASan error) or larger (unused NaN vertices) */
    if (st->vertex_skew >= 0)
        fc->vertex_count = built + (size_t)st->vertex_skew;
    else
        fc->vertex_count = (size_t)-st->vertex_skew <= built ? built - (size_t)-st->vertex_skew : 0;
    case_formats(fc, st);
    fc->indices = (unsigned int *)malloc((fc->index_count ? fc->index_count : 1) * sizeof(unsigned int));
    REQUIRE(fc->indices != NULL, "harness out of memory");
    memcpy(fc->indices, m->tri, 3 * m->triangles * sizeof(unsigned int));
    for (i = 3 * m->triangles; i < fc->index_count; ++i)
        fc->indices[i] = 0;
    if (fc->index_size == 2) /* what 16 bits hold of the program's indices (raw ones included) */
        for (i = 0; i < fc->index_count; ++i)
            fc->indices[i] &= 0xFFFFu;
    fc->call_indices = encode_indices(fc->indices, fc->index_count, fc->index_size);
    for (i = 0; i < fc->index_count; ++i)
        fc->max_index = fc->indices[i] > fc->max_index ? fc->indices[i] : fc->max_index;
    fc->stride = fc->position_size == 8 ? st->double_stride : st->stride;
    if (st->triangle_normals)
        fc->triangle_normals = make_normals(fc, fc->triangles, st->triangle_normals_stride, 0);
    if (st->vertex_normals)
        fc->vertex_normals = make_normals(fc, fc->vertex_count, st->vertex_normals_stride, 1);
    if (!st->positions_null) {
        size_t stride = effective_stride(fc), size = 3 * (size_t)fc->position_size;
        source g;
        memset(&g, 0, sizeof(g));
        g.use_rng = 1, g.rng = st->double_seed;
        stride = stride < size ? size : stride; /* an invalid stride is refused; the buffer still holds the vertices */
        fc->positions_bytes = fc->vertex_count ? (fc->vertex_count - 1) * stride + size : 0;
        fc->positions = malloc(fc->positions_bytes ? fc->positions_bytes : 1);
        REQUIRE(fc->positions != NULL, "harness out of memory");
        memset(fc->positions, 0xFF, fc->positions_bytes); /* padding and extra vertices: NaN */
        for (v = 0; v < fc->vertex_count && v < built; ++v) {
            char *q = (char *)fc->positions + v * stride;
            if (fc->position_size == 8) {
                double d[3];
                int k;
                for (k = 0; k < 3; ++k)
                    d[k] = to_double(st, m->xyz[3 * v + (size_t)k], &g);
                memcpy(q, d, 24);
            } else {
                memcpy(q, &m->xyz[3 * v], 12);
            }
        }
    }
    if (fc->positions != NULL && !stride_valid(fc->stride, fc->position_size))
        fc->topology = MESHFIX_TOPOLOGY_INDICES; /* every call is refused: no topology to compute */
    compute_topology(fc);
}

static void free_case(fuzz_case *fc)
{
    free(fc->indices);
    free(fc->call_indices);
    free(fc->positions);
    free(fc->triangle_normals);
    free(fc->vertex_normals);
    free(fc->rep);
    free(fc->degenerate_at);
}

static int uses_positions_policy(int policy)
{
    return policy == MESHFIX_POLICY_OUTWARD || policy == MESHFIX_POLICY_SDF || policy == MESHFIX_POLICY_VISIBILITY ||
           policy == MESHFIX_POLICY_UP;
}

/* The options as passed to the library for one call. */
typedef struct call_options {
    meshfix_options o;
    int policy;                 /* as passed (may be out of range) */
    int clearly_invalid;        /* NaN, Inf, negative, rays or floor past the limits, bad enum */
    int format_invalid;         /* index_size, position_size, topology or its tolerance: refused by every call */
    int maybe_invalid;          /* finite but past a documented fraction: either answer is fine */
    int scratch_full;           /* scratch of at least meshfix_scratch_size(): no allocation */
} call_options;

static int float_clearly_invalid(float x)
{
    return !is_finite_bits(x) || x < 0.0f;
}

/* The formats of the case (valid), or (raw) as decoded. */
static void set_formats(const fuzz_case *fc, int raw, meshfix_options *o)
{
    const settings *st = fc->st;
    o->index_size = raw ? st->index_size : fc->index_size;
    o->position_size = raw ? st->position_size : fc->position_size;
    o->topology = raw ? (meshfix_topology)st->topology : fc->topology;
    o->weld_tolerance = raw ? st->topology_tolerance : fc->topology_tolerance;
    if (!raw) {
        /* the valid spellings of the same formats: 0 for the defaults when the settings say so */
        if (st->index_size == 0 && fc->index_size == 4)
            o->index_size = 0;
        if (st->position_size == 0 && fc->position_size == 4)
            o->position_size = 0;
    }
}

/* Options for the main call: the decoded values, or (sanitize) the same
   with every value that must be refused, or that would cost too much,
   replaced by a valid one, so the call gets to the work. */
static void make_options(const fuzz_case *fc, int sanitize, counters *count, sdf_user *su, parallel_user *pu,
                         void *scratch, size_t scratch_size, call_options *co)
{
    const settings *st = fc->st;
    meshfix_options *o = &co->o;
    float *floats[10];
    int i;
    memset(co, 0, sizeof(*co));
    co->policy = st->policy;
    o->policy = (meshfix_policy)st->policy;
    set_formats(fc, !sanitize, o);
    o->visibility.rays = st->rays;
    o->visibility.min_samples = st->min_samples;
    o->visibility.coherence_distance = st->coherence;
    o->visibility.c0 = st->c0;
    o->visibility.eps = st->eps;
    o->visibility.kv = st->kv;
    o->sdf.step = st->sdf_step;
    o->up[0] = st->up[0], o->up[1] = st->up[1], o->up[2] = st->up[2];
    o->sdf.mode = (meshfix_sdf_mode)st->sdf_mode;
    o->visibility.flags = st->visibility_flags;
    o->seed = st->seed;
    o->evidence.sigma = st->evidence_sigma;
    o->evidence.min_confidence = st->min_confidence;
    if (st->sdf_present)
        o->sdf.distance = stress_sdf;
    if (st->sdf_gradient)
        o->sdf.gradient = stress_sdf_gradient;
    o->sdf.user = su;
    if (st->parallel_mode != PARALLEL_NONE) {
        o->parallel_for = stress_parallel_for;
        o->parallel_user = pu;
    }
    if (st->alloc_mode != ALLOC_DEFAULT) {
        o->memory.alloc_func = counting_alloc;
        o->memory.free_func = st->alloc_mode == ALLOC_NO_FREE ? NULL : counting_free;
        o->memory.user_data = count;
    }
    o->memory.scratch = scratch;
    o->memory.scratch_size = scratch_size;
    o->evidence.triangle_normals = fc->triangle_normals;
    o->evidence.triangle_normals_stride = st->triangle_normals_stride;
    o->evidence.vertex_normals = fc->vertex_normals;
    o->evidence.vertex_normals_stride = st->vertex_normals_stride;
    floats[0] = &o->visibility.coherence_distance, floats[1] = &o->visibility.c0, floats[2] = &o->visibility.eps;
    floats[3] = &o->visibility.kv, floats[4] = &o->sdf.step;
    floats[5] = &o->evidence.sigma, floats[6] = &o->evidence.min_confidence;
    floats[7] = &o->up[0], floats[8] = &o->up[1], floats[9] = &o->up[2];
    if (sanitize) {
        co->policy = ((st->policy % MESHFIX_POLICY_COUNT) + MESHFIX_POLICY_COUNT) % MESHFIX_POLICY_COUNT;
        o->policy = (meshfix_policy)co->policy;
        if (o->visibility.rays > RUN_RAYS_CAP)
            o->visibility.rays %= RUN_RAYS_CAP + 1;
        if (o->visibility.min_samples > REFUSED_MIN_SAMPLES_ABOVE)
            o->visibility.min_samples %= REFUSED_MIN_SAMPLES_ABOVE + 1;
        for (i = 0; i < 10; ++i) {
            float *x = floats[i];
            if (!is_finite_bits(*x))
                *x = 0.0f;
            if (i < 7) {
                /* coherence, c0, eps, kv, step, sigma, min_confidence */
                static const float most[7] = {1.0f, 100.0f, 1.0f, 100.0f, 1e30f, 100.0f, 1.0f};
                *x = *x < 0 ? -*x : *x;
                *x = *x > most[i] ? most[i] : *x;
            }
        }
        o->sdf.mode = (meshfix_sdf_mode)(st->sdf_mode % 2u);
        if (co->policy == MESHFIX_POLICY_SDF && o->sdf.distance == NULL)
            o->sdf.distance = stress_sdf;
        if (o->memory.alloc_func != NULL && o->memory.free_func == NULL)
            o->memory.free_func = counting_free;
        /* the buffers are laid out with the decoded strides: without them */
        if (!normal_stride_valid(o->evidence.triangle_normals_stride))
            o->evidence.triangle_normals = NULL, o->evidence.triangle_normals_stride = 0;
        if (!normal_stride_valid(o->evidence.vertex_normals_stride))
            o->evidence.vertex_normals = NULL, o->evidence.vertex_normals_stride = 0;
    }
    /* what every call must refuse: formats it cannot read */
    co->format_invalid = (o->index_size != 0 && o->index_size != 2 && o->index_size != 4) ||
                         (o->position_size != 0 && o->position_size != 4 && o->position_size != 8) ||
                         (unsigned int)o->topology > (unsigned int)MESHFIX_TOPOLOGY_WELD ||
                         float_clearly_invalid(o->weld_tolerance);
    /* what orient must refuse, and what it may */
    co->clearly_invalid = co->policy < 0 || co->policy >= MESHFIX_POLICY_COUNT || co->format_invalid ||
                          o->visibility.rays > REFUSED_RAYS_ABOVE ||
                          o->visibility.min_samples > REFUSED_MIN_SAMPLES_ABOVE ||
                          (o->memory.alloc_func != NULL && o->memory.free_func == NULL) ||
                          (co->policy == MESHFIX_POLICY_SDF &&
                           (o->sdf.distance == NULL || (unsigned int)o->sdf.mode > 1u)) ||
                          /* findings 2 and 4: normals strides, sigma and min_confidence are validated */
                          !normal_stride_valid(o->evidence.triangle_normals_stride) ||
                          !normal_stride_valid(o->evidence.vertex_normals_stride) ||
                          o->evidence.min_confidence > 1.0f;
    for (i = 0; i < 10; ++i)
        co->clearly_invalid |= i < 7 ? float_clearly_invalid(*floats[i]) : !is_finite_bits(*floats[i]);
    /* past the documented ranges: refusing is allowed, and accepting must still give sane results */
    co->maybe_invalid = o->visibility.coherence_distance > 1.0f || o->visibility.eps > 1.0f ||
                        o->visibility.c0 > 100.0f || o->visibility.kv > 100.0f || o->sdf.step > 1e30f ||
                        o->evidence.sigma > 100.0f;
}

/* The cost of a call that gets to the work must stay bounded: the
   default budget (65536 rays and more) only on small meshes. */
static void make_affordable(const fuzz_case *fc, call_options *co)
{
    if (co->o.visibility.rays > RUN_RAYS_CAP)
        co->o.visibility.rays %= RUN_RAYS_CAP + 1;
    if (co->o.visibility.rays == 0 && fc->triangles > DEFAULT_RAYS_MAX_TRIANGLES)
        co->o.visibility.rays = RUN_RAYS_CAP;
}

/* ===== expected results ===== */

/* The topology's share of the scratch: meshfix_scratch_size() for a policy
   that needs no geometry (documented as the topology alone). Less than
   this for the vertices the indices reach must be refused. */
static size_t topology_scratch(const fuzz_case *fc, size_t index_count, size_t vertex_count)
{
    meshfix_options o;
    memset(&o, 0, sizeof(o));
    o.policy = MESHFIX_POLICY_SEED;
    set_formats(fc, 0, &o);
    if (fc->positions == NULL) {
        /* meshfix_scratch_size counts for positions, whose formats this
           call does not have: no join, no float copy of doubles */
        o.topology = MESHFIX_TOPOLOGY_INDICES;
        o.position_size = 0;
    }
    return meshfix_scratch_size(index_count, vertex_count, &o);
}

#define BIT(r) (1u << (unsigned int)(r))

typedef struct expectation {
    unsigned int required; /* problems the input has: one of them must be returned */
    unsigned int allowed;  /* may be returned as well (allocation failure, ambiguous values) */
} expectation;

/* For orient (is_orient) and inspect_ex: what is wrong with this call. */
static expectation expect_run(const fuzz_case *fc, const call_options *co, const counters *count, int is_orient)
{
    expectation e = {0, 0};
    const meshfix_options *o = &co->o;
    int has_positions = fc->positions != NULL;
    if (fc->index_count % 3 != 0)
        e.required |= BIT(MESHFIX_ERROR_NOT_TRIANGLES);
    if (has_positions && !stride_valid(fc->stride, fc->position_size))
        e.required |= BIT(MESHFIX_ERROR_INVALID_ARGUMENT);
    if (fc->index_count != 0 && (size_t)fc->max_index >= fc->vertex_count)
        e.required |= BIT(MESHFIX_ERROR_INDEX_OUT_OF_RANGE);
    if (o->memory.alloc_func != NULL && o->memory.free_func == NULL)
        e.required |= BIT(MESHFIX_ERROR_INVALID_ARGUMENT);
    if (co->format_invalid)
        e.required |= BIT(MESHFIX_ERROR_INVALID_ARGUMENT);
    if (is_orient) {
        if (co->clearly_invalid)
            e.required |= BIT(MESHFIX_ERROR_INVALID_ARGUMENT);
        if (!has_positions && uses_positions_policy(co->policy))
            e.required |= BIT(MESHFIX_ERROR_POSITIONS_REQUIRED);
        if (!has_positions && co->policy == MESHFIX_POLICY_NORMALS)
            e.allowed |= BIT(MESHFIX_ERROR_POSITIONS_REQUIRED);
        if (co->policy == MESHFIX_POLICY_NORMALS && o->evidence.triangle_normals == NULL &&
            o->evidence.vertex_normals == NULL)
            e.required |= BIT(MESHFIX_ERROR_NORMALS_REQUIRED);
    } else if (co->clearly_invalid) {
        e.allowed |= BIT(MESHFIX_ERROR_INVALID_ARGUMENT); /* options inspect does not use */
    }
    if (co->maybe_invalid)
        e.allowed |= BIT(MESHFIX_ERROR_INVALID_ARGUMENT);
    if (o->memory.scratch != NULL && fc->index_count != 0 && fc->index_count % 3 == 0 &&
        (size_t)fc->max_index < fc->vertex_count &&
        o->memory.scratch_size < topology_scratch(fc, fc->index_count, (size_t)fc->max_index + 1))
        e.required |= BIT(MESHFIX_ERROR_SCRATCH_TOO_SMALL);
    /* between the topology's share and meshfix_scratch_size(), the
       geometry of the mesh at hand may or may not fit */
    if (o->memory.scratch != NULL && !co->scratch_full)
        e.allowed |= BIT(MESHFIX_ERROR_SCRATCH_TOO_SMALL);
    if (count->fail_at != 0 && !co->scratch_full)
        e.allowed |= BIT(MESHFIX_ERROR_OUT_OF_MEMORY);
    return e;
}

static void check_result(meshfix_result r, expectation e, const char *call)
{
    char what[160];
    if (e.required == 0 && r == MESHFIX_OK)
        return;
    if (r != MESHFIX_OK && ((e.required | e.allowed) & BIT(r)))
        return;
    snprintf(what, sizeof(what), "%s returned %d (%s); input problems 0x%x, also allowed 0x%x", call, (int)r,
             meshfix_result_string(r), e.required, e.allowed);
    fail(what, __FILE__, __LINE__);
}

/* ===== outputs of one call, with snapshots ===== */

typedef struct outputs {
    unsigned char *block;  /* indices and destination as the call sees them */
    size_t block_len;      /* in indices of index_size bytes */
    unsigned int index_size;
    void *indices, *destination; /* inside block, or separate (dest_extra) */
    unsigned char *dest_extra;
    unsigned char *flipped;
    unsigned int *patch_ids;
    float *confidence;
    meshfix_component *components;
    meshfix_outputs arrays; /* what the call gets (outputs_null: NULL when nothing is wanted) */
    meshfix_report report;
    size_t flipped_len, patch_ids_len, confidence_len, components_len;
} outputs;

typedef struct snapshot {
    void *parts[6];
    size_t sizes[6];
} snapshot;

static void *fill_alloc(size_t bytes, uint8_t fill)
{
    void *p = malloc(bytes ? bytes : 1);
    REQUIRE(p != NULL, "harness out of memory");
    memset(p, fill, bytes);
    return p;
}

/* Fresh buffers: indices copied in, outputs filled with the pattern.
   Destination layouts: its own array; the indices themselves; none; or
   one array holding both, shifted by dest_shift indices. */
static void prepare_outputs(const fuzz_case *fc, int dest_mode, outputs *out)
{
    const settings *st = fc->st;
    size_t n = fc->index_count, t = fc->triangles, shift = (size_t)(st->dest_shift < 0 ? -st->dest_shift : st->dest_shift);
    size_t z = fc->index_size;
    memset(out, 0, sizeof(*out));
    memset(&out->report, st->fill, sizeof(out->report));
    out->index_size = fc->index_size;
    if (dest_mode == DEST_OVERLAP) {
        out->block_len = n + shift;
        out->block = (unsigned char *)fill_alloc(out->block_len * z, st->fill);
        out->indices = out->block + (st->dest_shift < 0 ? shift : 0) * z;
        out->destination = out->block + (st->dest_shift < 0 ? 0 : shift) * z;
    } else {
        out->block_len = n;
        out->block = (unsigned char *)fill_alloc(n * z, st->fill);
        out->indices = out->block;
        if (dest_mode == DEST_IN_PLACE)
            out->destination = out->block;
        else if (dest_mode == DEST_SEPARATE)
            out->destination = out->dest_extra = (unsigned char *)fill_alloc(n * z, st->fill);
    }
    memcpy(out->indices, fc->call_indices, n * z);
    if (st->want_flipped) {
        out->flipped_len = t + st->slack;
        out->flipped = (unsigned char *)fill_alloc(out->flipped_len, st->fill);
    }
    if (st->want_patch_ids) {
        out->patch_ids_len = t + st->slack;
        out->patch_ids = (unsigned int *)fill_alloc(out->patch_ids_len * sizeof(unsigned int), st->fill);
    }
    if (st->want_confidence) {
        out->confidence_len = st->confidence_capacity + st->slack;
        out->confidence = (float *)fill_alloc(out->confidence_len * sizeof(float), st->fill);
    }
    if (st->want_components) {
        out->components_len = st->components_capacity + st->slack;
        out->components = (meshfix_component *)fill_alloc(out->components_len * sizeof(meshfix_component), st->fill);
    }
}

/* The meshfix_outputs the call gets; NULL (when the settings say so)
   if no array is wanted. */
static meshfix_outputs *attach_outputs(const settings *st, outputs *out)
{
    meshfix_outputs *o = &out->arrays;
    o->flipped = out->flipped;
    o->patch_ids = out->patch_ids;
    o->patch_confidence = out->confidence;
    o->patch_confidence_capacity = out->confidence ? st->confidence_capacity : 0;
    o->components = out->components;
    o->components_capacity = out->components ? st->components_capacity : 0;
    if (st->outputs_null && !out->flipped && !out->patch_ids && !out->confidence && !out->components)
        return NULL;
    return o;
}

static void free_outputs(outputs *out)
{
    free(out->block);
    free(out->dest_extra);
    free(out->flipped);
    free(out->patch_ids);
    free(out->confidence);
    free(out->components);
}

static void *duplicate(const void *p, size_t bytes)
{
    void *copy = malloc(bytes ? bytes : 1);
    REQUIRE(copy != NULL, "harness out of memory");
    if (bytes)
        memcpy(copy, p, bytes);
    return copy;
}

static void take_snapshot(const outputs *out, snapshot *s)
{
    const void *parts[6];
    size_t i;
    parts[0] = out->block, s->sizes[0] = out->block_len * out->index_size;
    parts[1] = out->dest_extra, s->sizes[1] = out->dest_extra ? out->block_len * out->index_size : 0;
    parts[2] = out->flipped, s->sizes[2] = out->flipped_len;
    parts[3] = out->patch_ids, s->sizes[3] = out->patch_ids_len * sizeof(unsigned int);
    parts[4] = out->confidence, s->sizes[4] = out->confidence_len * sizeof(float);
    parts[5] = out->components, s->sizes[5] = out->components_len * sizeof(meshfix_component);
    for (i = 0; i < 6; ++i)
        s->parts[i] = parts[i] ? duplicate(parts[i], s->sizes[i]) : NULL;
}

static void check_untouched(const outputs *out, const snapshot *s, const meshfix_report *report_before,
                            const char *call)
{
    static const char *const names[6] = {"indices/destination", "destination", "flipped", "patch_ids",
                                         "patch_confidence", "components"};
    const void *parts[6];
    size_t i;
    char what[128];
    parts[0] = out->block, parts[1] = out->dest_extra, parts[2] = out->flipped;
    parts[3] = out->patch_ids, parts[4] = out->confidence, parts[5] = out->components;
    for (i = 0; i < 6; ++i)
        if (parts[i] != NULL && memcmp(parts[i], s->parts[i], s->sizes[i]) != 0) {
            snprintf(what, sizeof(what), "%s failed but wrote %s", call, names[i]);
            fail(what, __FILE__, __LINE__);
        }
    snprintf(what, sizeof(what), "%s failed but wrote the report", call);
    REQUIRE(memcmp(&out->report, report_before, sizeof(out->report)) == 0, what);
}

static void free_snapshot(snapshot *s)
{
    size_t i;
    for (i = 0; i < 6; ++i)
        free(s->parts[i]);
}

/* ===== one orient or inspect_ex call, fully checked on its own ===== */

typedef struct run {
    meshfix_result result;
    outputs out;
    counters count;
    int is_orient, had_report;
    call_options co;
} run;

static void check_no_work(const run *r, const char *call)
{
    char what[128];
    snprintf(what, sizeof(what), "%s refused the input after doing work (allocation, sdf or parallel_for)", call);
    REQUIRE(r->count.alloc_calls == 0 && r->count.sdf_calls == 0 && r->count.parallel_calls == 0, what);
}

/* Runs orient (is_orient) or inspect_ex with the given options; checks
   the result against the input's problems, that an error wrote nothing
   and did no work, that nothing leaked, and that the const inputs are
   unchanged. */
static void do_run(const fuzz_case *fc, int is_orient, int dest_mode, int sanitize, int use_parallel, int use_failing,
                   int want_report, run *r)
{
    const settings *st = fc->st;
    sdf_user su;
    parallel_user pu;
    snapshot snap;
    meshfix_report report_before;
    void *scratch_raw = NULL;
    char *scratch = NULL;
    size_t scratch_size = 0;
    float *positions_before = NULL;
    meshfix_outputs *arrays, arrays_before;
    const char *call = is_orient ? "meshfix_orient" : "meshfix_inspect";
    memset(r, 0, sizeof(*r));
    r->is_orient = is_orient;
    r->had_report = want_report || !is_orient;
    /* The runs compared bit for bit (with and without parallel_for) get
       different garbage in fresh memory: a read of memory the library
       never wrote shows up as a difference even under ASan, which fills
       fresh blocks with one constant. (MSan finds them directly.) */
    r->count.garbage = (uint8_t)(st->fill ^ (use_parallel ? 0x00u : 0x5Au));
    if (use_failing && st->alloc_mode == ALLOC_FAILING) {
        r->count.fail_at = st->fail_at;
        r->count.fail_persistent = st->fail_persistent;
    }
    su.st = st, su.count = &r->count;
    pu.st = st, pu.count = &r->count;
    make_options(fc, sanitize, &r->count, &su, &pu, NULL, 0, &r->co);
    if (sanitize)
        make_affordable(fc, &r->co);
    if (!use_parallel) {
        r->co.o.parallel_for = NULL;
        r->co.o.parallel_user = NULL;
    }
    if (st->scratch_mode != SCRATCH_NONE) {
        /* sized for these options (the policy and the formats decide what is needed) */
        size_t full = meshfix_scratch_size(fc->index_count, fc->vertex_count, &r->co.o);
        size_t topology = topology_scratch(fc, fc->index_count, fc->vertex_count);
        size_t reached = (size_t)fc->max_index < fc->vertex_count
                             ? topology_scratch(fc, fc->index_count, (size_t)fc->max_index + 1)
                             : topology;
        if (st->scratch_mode == SCRATCH_SHORT)
            scratch_size = reached > st->scratch_shortfall ? reached - st->scratch_shortfall : 0;
        else if (st->scratch_mode == SCRATCH_TOPOLOGY)
            scratch_size = topology;
        else
            scratch_size = full + (st->scratch_mode == SCRATCH_ROOMY ? 4096 : 0);
        scratch_raw = malloc(scratch_size + st->scratch_misalign + 1);
        REQUIRE(scratch_raw != NULL, "harness out of memory");
        scratch = (char *)scratch_raw + st->scratch_misalign;
        if (!STRESS_MSAN)
            memset(scratch_raw, r->count.garbage, scratch_size + st->scratch_misalign + 1);
        r->co.o.memory.scratch = scratch;
        r->co.o.memory.scratch_size = scratch_size;
        /* inspect needs no geometry: the topology is all it takes */
        r->co.scratch_full = fc->index_count != 0 && scratch_size >= (is_orient ? full : topology);
    }
    prepare_outputs(fc, dest_mode, &r->out);
    arrays = attach_outputs(st, &r->out);
    arrays_before = r->out.arrays;
    take_snapshot(&r->out, &snap);
    report_before = r->out.report;
    if (fc->positions)
        positions_before = (float *)duplicate(fc->positions, fc->positions_bytes);
    if (is_orient)
        r->result = meshfix_orient(r->out.destination, r->out.indices, fc->index_count, fc->positions,
                                   fc->vertex_count, fc->stride, &r->co.o, want_report ? &r->out.report : NULL, arrays);
    else
        r->result = meshfix_inspect(r->out.indices, fc->index_count, fc->positions, fc->vertex_count, fc->stride,
                                    &r->co.o, &r->out.report, arrays);
    check_result(r->result, expect_run(fc, &r->co, &r->count, is_orient), call);
    REQUIRE(r->count.live_blocks == 0, "allocator blocks leaked");
    REQUIRE(positions_before == NULL || memcmp(positions_before, fc->positions, fc->positions_bytes) == 0,
            "positions written");
    REQUIRE(memcmp(&arrays_before, &r->out.arrays, sizeof(arrays_before)) == 0, "the meshfix_outputs struct written");
    if (r->out.destination != r->out.indices && !(dest_mode == DEST_OVERLAP && r->result == MESHFIX_OK))
        REQUIRE(memcmp(r->out.indices, fc->call_indices, fc->index_count * fc->index_size) == 0,
                "indices written though destination is elsewhere");
    if (r->result != MESHFIX_OK) {
        check_untouched(&r->out, &snap, &report_before, call);
        if (r->result != MESHFIX_ERROR_OUT_OF_MEMORY)
            check_no_work(r, call);
    } else if (!is_orient) {
        /* inspect ignores flipped and writes no confidence */
        REQUIRE(r->out.flipped == NULL || memcmp(r->out.flipped, snap.parts[2], snap.sizes[2]) == 0,
                "meshfix_inspect wrote flipped");
        REQUIRE(r->out.confidence == NULL || memcmp(r->out.confidence, snap.parts[4], snap.sizes[4]) == 0,
                "meshfix_inspect wrote patch_confidence");
    }
    /* documented: at least meshfix_scratch_size() bytes of scratch, no allocation */
    if (r->co.scratch_full)
        REQUIRE(r->count.alloc_calls == 0, "allocated although the scratch holds meshfix_scratch_size() bytes");
    free(positions_before);
    free_snapshot(&snap);
    free(scratch_raw);
}

static void free_run(run *r)
{
    free_outputs(&r->out);
}

/* ===== checks of a successful call ===== */

/* Each triangle as given or as (a, c, b); flipped flags and the count
   agree; degenerate triangles stay. Returns the output triangles in
   `result` (from the destination, or rebuilt from the flags). */
static int check_orient_output(const fuzz_case *fc, const run *r, unsigned int *result)
{
    const outputs *out = &r->out;
    size_t t, flips = 0;
    int known = out->destination != NULL || out->flipped != NULL;
    for (t = 0; t < fc->triangles; ++t) {
        const unsigned int *in = &fc->indices[3 * t];
        int flipped = -1;
        if (out->destination != NULL) {
            unsigned int o[3];
            int k;
            for (k = 0; k < 3; ++k)
                o[k] = index_at(out->destination, fc->index_size, 3 * t + (size_t)k);
            REQUIRE(o[0] == in[0] && ((o[1] == in[1] && o[2] == in[2]) || (o[1] == in[2] && o[2] == in[1])),
                    "output triangle is neither the input nor its (a, c, b) reversal");
            flipped = !(o[1] == in[1] && o[2] == in[2]);
        }
        if (out->flipped != NULL) {
            REQUIRE(out->flipped[t] <= 1, "flipped flag not 0 or 1");
            REQUIRE(flipped < 0 || in[1] == in[2] || flipped == out->flipped[t], "flipped flag disagrees with destination");
            flipped = out->flipped[t];
        }
        if (flipped > 0)
            REQUIRE(!fc->degenerate_at[t], "degenerate triangle flipped (a vertex repeats after the topology)");
        flips += flipped > 0;
        if (result != NULL) {
            result[3 * t] = in[0];
            result[3 * t + 1] = flipped > 0 ? in[2] : in[1];
            result[3 * t + 2] = flipped > 0 ? in[1] : in[2];
        }
    }
    if (known && r->had_report)
        REQUIRE(r->out.report.triangles_flipped == flips, "report.triangles_flipped is not the number of flips");
    return known;
}

/* Outputs after their size or capacity stay as they were; patch ids and
   confidences and components make sense; the doubtful and flipped
   patches of the report are the ones the outputs show. */
static void check_side_outputs(const fuzz_case *fc, const run *r)
{
    const settings *st = fc->st;
    const outputs *out = &r->out;
    const meshfix_report *rep = &r->out.report;
    size_t t, i, patches = r->had_report ? rep->mesh.patches : (size_t)-1;
    unsigned char fill[sizeof(meshfix_component)];
    memset(fill, st->fill, sizeof(fill));
    for (t = fc->triangles; t < out->flipped_len; ++t)
        REQUIRE(out->flipped[t] == st->fill, "flipped written past index_count / 3");
    for (t = fc->triangles; t < out->patch_ids_len; ++t)
        REQUIRE(memcmp(&out->patch_ids[t], fill, 4) == 0, "patch_ids written past index_count / 3");
    if (out->patch_ids != NULL)
        for (t = 0; t < fc->triangles; ++t) {
            int degenerate = fc->degenerate_at[t];
            REQUIRE(degenerate == (out->patch_ids[t] == 0xFFFFFFFFu),
                    "patch id 0xFFFFFFFF is not exactly the degenerate triangles (after the topology)");
            REQUIRE(degenerate || out->patch_ids[t] < patches, "patch id not below report.mesh.patches");
        }
    for (i = 0; i < out->confidence_len; ++i) {
        int written = i < st->confidence_capacity && i < patches && r->is_orient;
        if (!written && (i >= st->confidence_capacity || r->had_report))
            REQUIRE(memcmp(&out->confidence[i], fill, 4) == 0, "patch_confidence written past capacity or patches");
        else if (written && r->had_report)
            REQUIRE(out->confidence[i] >= 0.0f && out->confidence[i] <= 1.0f, "patch_confidence outside [0, 1] or NaN");
    }
    if (r->is_orient && r->had_report && out->patch_ids != NULL && patches <= MAX_TRIANGLES) {
        /* report.patches_flipped: the patches holding a flipped triangle;
           patches_doubtful and triangles_doubtful: the patches whose
           confidence is below max(0.5, min_confidence) */
        static unsigned char flipped_patch[MAX_TRIANGLES], doubtful[MAX_TRIANGLES];
        size_t count = 0, doubtful_triangles = 0;
        int confidences = out->confidence != NULL && st->confidence_capacity >= patches;
        double threshold = r->co.o.evidence.min_confidence > 0.5f ? (double)r->co.o.evidence.min_confidence : 0.5;
        memset(flipped_patch, 0, patches);
        for (i = 0; i < patches; ++i)
            doubtful[i] = confidences && (double)out->confidence[i] < threshold;
        for (t = 0; t < fc->triangles; ++t) {
            unsigned int p = out->patch_ids[t];
            if (p == 0xFFFFFFFFu)
                continue;
            if (out->flipped != NULL && out->flipped[t])
                flipped_patch[p] = 1;
            doubtful_triangles += doubtful[p];
        }
        if (out->flipped != NULL) {
            for (i = 0; i < patches; ++i)
                count += flipped_patch[i];
            REQUIRE(rep->patches_flipped == count, "report.patches_flipped is not the patches with a flipped triangle");
        }
        if (confidences) {
            for (i = 0, count = 0; i < patches; ++i)
                count += doubtful[i];
            REQUIRE(rep->patches_doubtful == count,
                    "report.patches_doubtful is not the patches with confidence below max(0.5, min_confidence)");
            REQUIRE(rep->triangles_doubtful == doubtful_triangles, "report.triangles_doubtful is not their triangles");
        }
    }
    if (out->components != NULL && r->had_report) {
        size_t n = rep->mesh.components < st->components_capacity ? rep->mesh.components : st->components_capacity;
        size_t sum_triangles = 0, sum_edges = 0, sum_patches = 0, previous = 0;
        long sum_euler = 0;
        for (i = n; i < out->components_len; ++i)
            REQUIRE(memcmp(&out->components[i], fill, sizeof(fill)) == 0, "component written past capacity or count");
        for (i = 0; i < n; ++i) {
            const meshfix_component *c = &out->components[i];
            REQUIRE(c->triangles >= 1 && c->patches >= 1 && c->first_triangle < fc->triangles, "empty component");
            REQUIRE(i == 0 || c->first_triangle > previous, "components not numbered by their lowest triangle");
            REQUIRE((c->closed == 0 || c->closed == 1) && (c->orientable == 0 || c->orientable == 1), "flag not 0/1");
            REQUIRE(c->euler_characteristic == (long)c->vertices - (long)c->edges + (long)c->triangles,
                    "component Euler characteristic is not V - E + F");
            REQUIRE(c->edges_boundary + c->edges_non_manifold <= c->edges, "component edge counts");
            previous = c->first_triangle;
            sum_triangles += c->triangles, sum_edges += c->edges, sum_patches += c->patches;
            sum_euler += c->euler_characteristic;
        }
        if (n == rep->mesh.components) {
            REQUIRE(sum_triangles == rep->mesh.triangles - rep->mesh.triangles_degenerate,
                    "component triangles do not add up");
            REQUIRE(sum_edges == rep->mesh.edges, "component edges do not add up");
            REQUIRE(sum_patches == rep->mesh.patches, "component patches do not add up");
            REQUIRE(sum_euler == rep->mesh.euler_characteristic, "component Euler characteristics do not add up");
        }
    }
}

/* ===== the edges, by definition ===== */

/* Each non-degenerate triangle's half-edges on the vertices the topology
   makes, sorted by edge: an edge is a boundary (1 triangle), manifold (2)
   or non-manifold (3+); it is inconsistent when a direction is used
   twice (an edge of 3+ triangles always is). */
typedef struct half_edge {
    unsigned int lo, hi, triangle, forward;
} half_edge;

typedef struct edge_facts {
    half_edge *h;
    size_t count; /* half-edges */
    size_t edges, boundary, manifold, non_manifold, inconsistent;
    size_t first_inconsistent, first_boundary, first_ring; /* lowest triangle on such an edge, or (size_t)-1 */
} edge_facts;

static int compare_half_edges(const void *pa, const void *pb)
{
    const half_edge *a = (const half_edge *)pa, *b = (const half_edge *)pb;
    if (a->lo != b->lo)
        return a->lo < b->lo ? -1 : 1;
    if (a->hi != b->hi)
        return a->hi < b->hi ? -1 : 1;
    return a->triangle < b->triangle ? -1 : a->triangle > b->triangle;
}

/* 0 boundary, 1 manifold and consistent, 2 manifold and inconsistent, 3 non-manifold; -1 not an edge */
static int edge_kind(const edge_facts *e, unsigned int a, unsigned int b, size_t *first, size_t *size)
{
    half_edge key;
    size_t lo = 0, hi = e->count;
    key.lo = a < b ? a : b, key.hi = a < b ? b : a, key.triangle = 0, key.forward = 0;
    while (lo < hi) { /* the first half-edge of the edge */
        size_t mid = lo + (hi - lo) / 2;
        const half_edge *m = &e->h[mid];
        if (m->lo < key.lo || (m->lo == key.lo && m->hi < key.hi))
            lo = mid + 1;
        else
            hi = mid;
    }
    *first = lo;
    for (*size = 0; lo + *size < e->count && e->h[lo + *size].lo == key.lo && e->h[lo + *size].hi == key.hi;)
        ++*size;
    if (*size == 0)
        return -1;
    if (*size == 1)
        return 0;
    if (*size == 2)
        return e->h[lo].forward == e->h[lo + 1].forward ? 2 : 1;
    return 3;
}

static void edge_facts_of(const fuzz_case *fc, const unsigned int *indices, edge_facts *e)
{
    size_t t, i, j;
    memset(e, 0, sizeof(*e));
    e->first_inconsistent = e->first_boundary = e->first_ring = (size_t)-1;
    e->h = (half_edge *)malloc((3 * fc->triangles + 1) * sizeof(half_edge));
    REQUIRE(e->h != NULL, "harness out of memory");
    for (t = 0; t < fc->triangles; ++t) {
        int k;
        if (fc->degenerate_at[t])
            continue;
        for (k = 0; k < 3; ++k) {
            unsigned int a = fc->rep[indices[3 * t + (size_t)k]], b = fc->rep[indices[3 * t + (size_t)(k + 1) % 3]];
            half_edge *h = &e->h[e->count++];
            h->lo = a < b ? a : b, h->hi = a < b ? b : a;
            h->triangle = (unsigned int)t, h->forward = a < b;
        }
    }
    qsort(e->h, e->count, sizeof(half_edge), compare_half_edges);
    for (i = 0; i < e->count; i = j) {
        size_t size, first, lowest = e->h[i].triangle; /* sorted by triangle within the edge */
        int kind;
        for (j = i; j < e->count && e->h[j].lo == e->h[i].lo && e->h[j].hi == e->h[i].hi;)
            ++j;
        kind = edge_kind(e, e->h[i].lo, e->h[i].hi, &first, &size);
        e->edges++;
        e->boundary += kind == 0;
        e->manifold += kind == 1 || kind == 2;
        e->non_manifold += kind == 3;
        if (kind >= 2) {
            e->inconsistent++;
            e->first_inconsistent = lowest < e->first_inconsistent ? lowest : e->first_inconsistent;
        }
        if (kind == 0)
            e->first_boundary = lowest < e->first_boundary ? lowest : e->first_boundary;
        if (kind == 3)
            e->first_ring = lowest < e->first_ring ? lowest : e->first_ring;
    }
}

/* The mesh facts that count edges and triangles, against the definition. */
static void check_edge_facts(const fuzz_case *fc, const meshfix_mesh_facts *k, const edge_facts *e, int inconsistent)
{
    REQUIRE(k->triangles_degenerate == fc->degenerate, "report.mesh.triangles_degenerate (after the topology)");
    REQUIRE(k->edges == e->edges, "report.mesh.edges is not the number of distinct edges");
    REQUIRE(k->edges_boundary == e->boundary, "report.mesh.edges_boundary");
    REQUIRE(k->edges_manifold == e->manifold, "report.mesh.edges_manifold");
    REQUIRE(k->edges_non_manifold == e->non_manifold, "report.mesh.edges_non_manifold");
    if (inconsistent)
        REQUIRE(k->edges_inconsistent == e->inconsistent, "report.mesh.edges_inconsistent");
}

static void check_report_sane(const fuzz_case *fc, const meshfix_report *rep)
{
    const meshfix_mesh_facts *k = &rep->mesh;
    REQUIRE(k->triangles == fc->triangles, "report.mesh.triangles");
    REQUIRE(k->triangles_degenerate == fc->degenerate, "report.mesh.triangles_degenerate");
    REQUIRE(k->vertices_joined == fc->joined, "report.mesh.vertices_joined is not the used indices joined to a lower one");
    REQUIRE(k->edges == k->edges_boundary + k->edges_manifold + k->edges_non_manifold, "edge counts");
    REQUIRE(k->edges_inconsistent <= k->edges && rep->edges_inconsistent_before <= k->edges, "inconsistent > edges");
    REQUIRE(k->vertices_used <= fc->vertex_count && k->vertices_non_finite <= k->vertices_used, "vertex counts");
    REQUIRE(k->patches <= k->triangles - k->triangles_degenerate && k->components <= k->patches, "patch counts");
    REQUIRE(k->patches_closed <= k->patches && k->components_closed <= k->components &&
                k->components_non_orientable <= k->components && k->patches_inside_out <= k->patches_closed,
            "closed counts");
    REQUIRE(k->triangles_zero_area <= k->triangles - k->triangles_degenerate, "zero-area count");
    REQUIRE(rep->patches_doubtful <= k->patches && rep->triangles_doubtful <= k->triangles, "doubtful counts");
    REQUIRE(rep->patches_flipped <= k->patches && rep->patches_flipped <= rep->triangles_flipped &&
                (rep->patches_flipped == 0) == (rep->triangles_flipped == 0),
            "report.patches_flipped against triangles_flipped and patches");
    REQUIRE(rep->area_doubtful >= 0.0 && (fc->positions != NULL || rep->area_doubtful == 0.0) &&
                (rep->patches_doubtful != 0 || rep->area_doubtful == 0.0),
            "report.area_doubtful");
    REQUIRE(k->area >= 0.0 && (fc->positions != NULL || (k->area == 0.0 && k->signed_volume == 0.0)),
            "report.mesh.area");
}

/* report.verdict, from the counts as the header defines it. */
static void check_verdict(const meshfix_report *rep, int is_orient)
{
    const meshfix_mesh_facts *k = &rep->mesh;
    meshfix_verdict expected;
    if (k->components_non_orientable != 0)
        expected = MESHFIX_VERDICT_NOT_ORIENTABLE;
    else if (!is_orient)
        expected = k->edges_inconsistent != 0   ? MESHFIX_VERDICT_INCONSISTENT
                   : k->patches_inside_out != 0 ? MESHFIX_VERDICT_INSIDE_OUT
                                                : MESHFIX_VERDICT_CLEAN;
    else
        expected = rep->patches_doubtful != 0    ? MESHFIX_VERDICT_DOUBTFUL
                   : rep->triangles_flipped != 0 ? MESHFIX_VERDICT_REPAIRED
                                                 : MESHFIX_VERDICT_CLEAN;
    REQUIRE(rep->verdict == expected, is_orient ? "orient: report.verdict disagrees with the counts"
                                                : "inspect: report.verdict disagrees with the counts");
    REQUIRE(strcmp(meshfix_verdict_string(rep->verdict), "unknown verdict") != 0, "a verdict without a string");
}

/* meshfix_summary: the whole length whatever the buffer, terminated
   within the buffer, nothing written past it, a prefix of the whole
   line when cut. */
static void check_summary(const settings *st, const meshfix_report *rep)
{
    char full[1024], cut[1024 + 16];
    size_t length = meshfix_summary(rep, NULL, 0), size = st->summary_size, i, again;
    REQUIRE(length > 0 && length < 512, "meshfix_summary: empty or absurdly long");
    memset(full, 0x5A, sizeof(full));
    REQUIRE(meshfix_summary(rep, full, sizeof(full)) == length, "meshfix_summary: length differs with the buffer");
    REQUIRE(full[length] == '\0' && strlen(full) == length, "meshfix_summary: whole line not terminated at its length");
    for (i = 0; i < length; ++i)
        REQUIRE(full[i] >= 0x20 && full[i] < 0x7F, "meshfix_summary: not one line of printable text");
    for (i = length + 1; i < sizeof(full); ++i)
        REQUIRE(full[i] == 0x5A, "meshfix_summary wrote past the line");
    memset(cut, 0xA5, sizeof(cut));
    again = meshfix_summary(rep, size ? cut : (st->fill & 1 ? NULL : cut), size);
    REQUIRE(again == length, "meshfix_summary: returned length is not the whole length when cut");
    for (i = size; i < sizeof(cut); ++i)
        REQUIRE((unsigned char)cut[i] == 0xA5, "meshfix_summary wrote past the buffer size");
    if (size != 0) {
        size_t kept = length < size - 1 ? length : size - 1;
        REQUIRE(cut[kept] == '\0', "meshfix_summary: cut line not terminated within the buffer");
        REQUIRE(memcmp(cut, full, kept) == 0, "meshfix_summary: cut line is not a prefix of the whole");
    }
}

/* orient: every patch is decided by exactly one kind of evidence, or kept */
static void check_report_decisions(const meshfix_report *rep)
{
    const meshfix_evidence_counts *e = &rep->evidence;
    REQUIRE(e->patches_by_volume + e->patches_by_parity + e->patches_by_visibility + e->patches_by_normals +
                    e->patches_kept ==
                rep->mesh.patches,
            "report.evidence.patches_by_* and patches_kept do not add up to report.mesh.patches");
}

/* The counts that depend on topology alone are the same for a mesh and
   any rewinding of it. */
static void check_same_topology(const meshfix_report *ra, const meshfix_report *rb, const char *what)
{
    const meshfix_mesh_facts *a = &ra->mesh, *b = &rb->mesh;
    int same = a->triangles == b->triangles && a->triangles_degenerate == b->triangles_degenerate &&
               a->triangles_zero_area == b->triangles_zero_area && a->triangles_duplicate == b->triangles_duplicate &&
               a->vertices_used == b->vertices_used && a->vertices_joined == b->vertices_joined &&
               a->vertices_non_finite == b->vertices_non_finite &&
               a->vertices_non_manifold == b->vertices_non_manifold && a->edges == b->edges &&
               a->edges_boundary == b->edges_boundary && a->edges_manifold == b->edges_manifold &&
               a->edges_non_manifold == b->edges_non_manifold && a->patches == b->patches &&
               a->patches_closed == b->patches_closed && a->components == b->components &&
               a->components_closed == b->components_closed &&
               a->components_non_orientable == b->components_non_orientable &&
               a->euler_characteristic == b->euler_characteristic;
    REQUIRE(same, what);
}

/* Two runs of the same call: bit-identical results and outputs. The
   destinations are compared as index values (the runs may differ in
   index_size). */
static void check_identical(const fuzz_case *fc, const run *a, const run *b, const char *what)
{
    size_t i;
    REQUIRE(a->result == b->result, what);
    if (a->result != MESHFIX_OK)
        return;
    REQUIRE(memcmp(&a->out.report, &b->out.report, sizeof(a->out.report)) == 0, what);
    if (a->out.destination != NULL)
        for (i = 0; i < fc->index_count; ++i)
            REQUIRE(index_at(a->out.destination, a->out.index_size, i) ==
                        index_at(b->out.destination, b->out.index_size, i),
                    what);
    REQUIRE(a->out.flipped == NULL || memcmp(a->out.flipped, b->out.flipped, a->out.flipped_len) == 0, what);
    REQUIRE(a->out.patch_ids == NULL ||
                memcmp(a->out.patch_ids, b->out.patch_ids, a->out.patch_ids_len * sizeof(unsigned int)) == 0,
            what);
    REQUIRE(a->out.confidence == NULL ||
                memcmp(a->out.confidence, b->out.confidence, a->out.confidence_len * sizeof(float)) == 0,
            what);
    REQUIRE(a->out.components == NULL ||
                memcmp(a->out.components, b->out.components, a->out.components_len * sizeof(meshfix_component)) == 0,
            what);
}

/* ===== the other entry points ===== */

/* The case's formats alone (valid): what inspect and check get. */
static meshfix_options format_options(const fuzz_case *fc)
{
    meshfix_options o;
    memset(&o, 0, sizeof(o));
    set_formats(fc, 0, &o);
    return o;
}

static meshfix_report inspect_plain(const fuzz_case *fc, const unsigned int *indices, meshfix_result *result)
{
    meshfix_report rep;
    meshfix_options o = format_options(fc);
    void *call_indices = encode_indices(indices, fc->index_count, fc->index_size);
    memset(&rep, 0, sizeof(rep));
    *result = meshfix_inspect(call_indices, fc->index_count, fc->positions, fc->vertex_count, fc->stride, &o, &rep,
                              NULL);
    free(call_indices);
    return rep;
}

static int text_terminated(const char *text, size_t size)
{
    return memchr(text, '\0', size) != NULL;
}

static int starts_with(const char *text, const char *prefix)
{
    return strncmp(text, prefix, strlen(prefix)) == 0;
}

/* ends (vertex ids after the topology) are two distinct corners of triangle t */
static int edge_of_triangle(const fuzz_case *fc, size_t t, const unsigned int ends[2])
{
    int i, j;
    for (i = 0; i < 3; ++i)
        for (j = 0; j < 3; ++j)
            if (i != j && fc->rep[fc->indices[3 * t + (size_t)i]] == ends[0] &&
                fc->rep[fc->indices[3 * t + (size_t)j]] == ends[1])
                return 1;
    return 0;
}

/* meshfix_check is documented as inspect plus the requirement bits, and
   its failure as the first requirement that fails (in the order of the
   bits), the lowest triangle and an edge that fail it, the count, and a
   line of text within its array. */
static void check_check(const fuzz_case *fc)
{
    static const unsigned int order[5] = {MESHFIX_REQUIRE_CONSISTENT, MESHFIX_REQUIRE_CLOSED, MESHFIX_REQUIRE_MANIFOLD,
                                          MESHFIX_REQUIRE_OUTWARD, MESHFIX_REQUIRE_NO_DEGENERATE};
    static const char *const texts[5] = {"not consistent", "not closed", "not manifold", "not outward", "degenerate"};
    unsigned int req = fc->st->requirements, effective = req ? req : MESHFIX_REQUIRE_CONSISTENT, failing = 0;
    meshfix_result result;
    meshfix_report rep = inspect_plain(fc, fc->indices, &result);
    meshfix_options o = format_options(fc);
    meshfix_check_failure why;
    const meshfix_mesh_facts *k = &rep.mesh;
    size_t count = 0;
    int expected = result == MESHFIX_OK, got, i;
    int needs_positions = (effective & (MESHFIX_REQUIRE_OUTWARD | MESHFIX_REQUIRE_NO_DEGENERATE)) && fc->positions == NULL;
    if (needs_positions)
        expected = 0, result = result == MESHFIX_OK ? MESHFIX_ERROR_POSITIONS_REQUIRED : result;
    if (expected) {
        for (i = 0; i < 5 && failing == 0; ++i) {
            size_t n = 0;
            if (!(effective & order[i]))
                continue;
            switch (i) {
            case 0: n = k->edges_inconsistent; break;
            case 1: n = k->edges_boundary; break;
            case 2: n = k->edges_non_manifold + k->vertices_non_manifold; break;
            case 3: n = k->patches_inside_out; break;
            default: n = k->triangles_degenerate + k->triangles_zero_area + k->triangles_duplicate;
            }
            if (n != 0)
                failing = order[i], count = n;
        }
        expected = failing == 0;
    }
    memset(&why, 0xA5, sizeof(why));
    got = meshfix_check(fc->call_indices, fc->index_count, fc->positions, fc->vertex_count, fc->stride, req, &o, &why);
    REQUIRE(got == expected, "meshfix_check disagrees with meshfix_inspect and the requirement bits");
    /* the same answer without a failure struct */
    REQUIRE(meshfix_check(fc->call_indices, fc->index_count, fc->positions, fc->vertex_count, fc->stride, req, &o,
                          NULL) == got,
            "meshfix_check answers differently without a failure struct");
    REQUIRE(text_terminated(why.text, sizeof(why.text)), "meshfix_check_failure.text not terminated within its array");
    if (result != MESHFIX_OK) {
        /* invalid input, or positions missing: either may be named first */
        REQUIRE(why.result == result || (needs_positions && why.result == MESHFIX_ERROR_POSITIONS_REQUIRED),
                "meshfix_check_failure.result is not what inspect returned");
        size_t first_out = (size_t)-1, j;
        for (j = 0; j < fc->index_count && first_out == (size_t)-1; ++j)
            if (fc->indices[j] >= fc->vertex_count)
                first_out = j / 3;
        /* an index out of range may be located: its triangle */
        REQUIRE(why.requirement == 0 && why.edge[0] == 0xFFFFFFFFu && why.edge[1] == 0xFFFFFFFFu &&
                    (why.triangle == (size_t)-1 ||
                     (why.result == MESHFIX_ERROR_INDEX_OUT_OF_RANGE && why.triangle == first_out)),
                "meshfix_check_failure of invalid input names a requirement, an edge or the wrong triangle");
        REQUIRE(starts_with(why.text, "not valid input"), "meshfix_check_failure.text of invalid input");
        return;
    }
    REQUIRE(why.result == MESHFIX_OK, "meshfix_check_failure.result not OK for valid input");
    if (failing == 0) {
        REQUIRE(why.requirement == 0 && why.count == 0 && why.triangle == (size_t)-1,
                "meshfix_check_failure names a failure where every requirement holds");
        return;
    }
    REQUIRE(why.requirement == failing, "meshfix_check_failure.requirement is not the first failing bit");
    REQUIRE(why.count == count, "meshfix_check_failure.count is not the report's count");
    for (i = 0; i < 5; ++i)
        if (order[i] == failing)
            REQUIRE(starts_with(why.text, texts[i]), "meshfix_check_failure.text does not name the requirement");
    REQUIRE(why.triangle < fc->triangles, "meshfix_check_failure.triangle: no triangle named for a failure");
    REQUIRE((why.edge[0] == 0xFFFFFFFFu) == (why.edge[1] == 0xFFFFFFFFu), "meshfix_check_failure.edge: one end only");
    if (why.edge[0] != 0xFFFFFFFFu) {
        REQUIRE(why.edge[0] < why.edge[1] && why.edge[1] < fc->vertex_count,
                "meshfix_check_failure.edge: not two ordered vertices");
        REQUIRE(edge_of_triangle(fc, why.triangle, why.edge),
                "meshfix_check_failure.edge is not an edge of meshfix_check_failure.triangle");
    }
    if (failing == MESHFIX_REQUIRE_CONSISTENT || failing == MESHFIX_REQUIRE_CLOSED ||
        (failing == MESHFIX_REQUIRE_MANIFOLD && k->edges_non_manifold != 0)) {
        edge_facts e;
        size_t first, size, lowest;
        int kind;
        edge_facts_of(fc, fc->indices, &e);
        REQUIRE(why.edge[0] != 0xFFFFFFFFu, "meshfix_check_failure: no edge named for an edge requirement");
        kind = edge_kind(&e, why.edge[0], why.edge[1], &first, &size);
        lowest = failing == MESHFIX_REQUIRE_CONSISTENT ? e.first_inconsistent
                 : failing == MESHFIX_REQUIRE_CLOSED   ? e.first_boundary
                                                       : e.first_ring;
        REQUIRE(failing == MESHFIX_REQUIRE_CONSISTENT ? kind >= 2 : failing == MESHFIX_REQUIRE_CLOSED ? kind == 0 : kind == 3,
                "meshfix_check_failure.edge does not fail the requirement");
        REQUIRE(why.triangle == lowest, "meshfix_check_failure.triangle is not the lowest that fails the requirement");
        free(e.h);
    } else if (failing == MESHFIX_REQUIRE_NO_DEGENERATE) {
        size_t t;
        for (t = 0; t < fc->triangles && !fc->degenerate_at[t]; ++t) {
        }
        REQUIRE(why.triangle <= t, "meshfix_check_failure.triangle: a lower triangle repeats a vertex");
    }
}

/* as meshfix_weld measures: in double, -0 as +0 */
static double squared_distance(const double *p, const double *q)
{
    double d = 0.0;
    int k;
    for (k = 0; k < 3; ++k) {
        double x = (p[k] == 0.0 ? 0.0 : p[k]) - (q[k] == 0.0 ? 0.0 : q[k]);
        d += x * x;
    }
    return d;
}

/* Whether vertices a and b weld: at tolerance 0 equal positions (-0 =
   +0), else a squared distance within the squared tolerance, summed as
   meshfix_weld sums it. (The squared distance of doubles around 1e-300
   underflows to 0: "<= 0" is not equality.) */
static int vertices_weld(const fuzz_case *fc, size_t a, size_t b, double tolerance)
{
    double p[3], q[3];
    read_vertex(fc, a, p);
    read_vertex(fc, b, q);
    if (tolerance == 0.0)
        return p[0] == q[0] && p[1] == q[1] && p[2] == q[2];
    return squared_distance(p, q) <= tolerance * tolerance;
}

/* Weld: every vertex maps to the lowest representative within the
   tolerance, representatives map to themselves and lie farther apart.
   Floats or doubles as the case has them. */
static void check_weld(const fuzz_case *fc)
{
    const settings *st = fc->st;
    counters count;
    meshfix_options o;
    unsigned int *remap;
    size_t unique = 12345, n = fc->vertex_count, v, reps = 0, checked;
    double tolerance = (double)st->weld_tolerance;
    meshfix_result result;
    expectation e = {0, 0};
    source g;
    if (fc->positions == NULL)
        return;
    memset(&count, 0, sizeof(count));
    memset(&o, 0, sizeof(o));
    /* the raw position_size: anything but 0, 4 and 8 is refused */
    o.position_size = st->position_size;
    if (st->alloc_mode != ALLOC_DEFAULT) {
        o.memory.alloc_func = counting_alloc;
        o.memory.free_func = st->alloc_mode == ALLOC_NO_FREE ? NULL : counting_free;
        o.memory.user_data = &count;
        if (st->alloc_mode == ALLOC_FAILING)
            count.fail_at = st->fail_at, count.fail_persistent = st->fail_persistent;
    }
    remap = (unsigned int *)fill_alloc(n * sizeof(unsigned int), st->fill);
    if (n != 0) {
        int readable = stride_valid(fc->stride, fc->position_size) &&
                       (st->position_size == 0 || st->position_size == 4 || st->position_size == 8);
        if (float_clearly_invalid(st->weld_tolerance) || !readable)
            e.required |= BIT(MESHFIX_ERROR_INVALID_ARGUMENT);
        if (o.memory.alloc_func != NULL && o.memory.free_func == NULL)
            e.required |= BIT(MESHFIX_ERROR_INVALID_ARGUMENT);
        if (readable)
            for (v = 0; v < n; ++v) {
                double p[3];
                if (!read_vertex(fc, v, p))
                    e.required |= BIT(MESHFIX_ERROR_NON_FINITE);
            }
        if (count.fail_at != 0)
            e.allowed |= BIT(MESHFIX_ERROR_OUT_OF_MEMORY);
    }
    result = meshfix_weld(remap, fc->positions, n, fc->stride, st->weld_tolerance, &o, &unique);
    check_result(result, e, "meshfix_weld");
    REQUIRE(count.live_blocks == 0, "meshfix_weld leaked");
    if (result != MESHFIX_OK) {
        for (v = 0; v < n; ++v)
            REQUIRE(memcmp(&remap[v], &(uint32_t){0x01010101u * st->fill}, 4) == 0, "meshfix_weld failed but wrote remap");
        REQUIRE(unique == 12345, "meshfix_weld failed but wrote unique_count");
        REQUIRE(result == MESHFIX_ERROR_OUT_OF_MEMORY || count.alloc_calls == 0,
                "meshfix_weld refused the input after allocating");
        free(remap);
        return;
    }
    for (v = 0; v < n; ++v) {
        REQUIRE(remap[v] <= v && remap[remap[v]] == remap[v], "weld: remap is not to an earlier representative");
        REQUIRE(vertices_weld(fc, v, remap[v], tolerance), "weld: farther than the tolerance");
        reps += remap[v] == v;
    }
    REQUIRE(unique == reps, "weld: unique_count");
    /* no earlier representative within the tolerance was passed over:
       all vertices for small meshes, a sample of 512 for large ones */
    g.use_rng = 1, g.rng = st->shuffle_seed, g.data = NULL, g.size = 0;
    for (checked = 0; checked < (n <= 512 ? n : 512); ++checked) {
        size_t x = n <= 512 ? checked : below(&g, (uint32_t)n), r;
        for (r = 0; r < remap[x]; ++r)
            if (remap[r] == r)
                REQUIRE(!vertices_weld(fc, x, r, tolerance),
                        "weld: a lower representative within the tolerance was passed over");
    }
    free(remap);
}

/* ===== the orient flow ===== */

/* A refusal call with the raw (clearly invalid) option values; every
   other field as in the main call. Nothing may be allocated or called. */
static void check_refusal(const fuzz_case *fc)
{
    run r;
    settings raw = *fc->st;
    fuzz_case copy = *fc;
    /* cheap values for what is not being refused, so a wrong acceptance
       costs little; the refused ones stay as decoded */
    if (raw.rays <= REFUSED_RAYS_ABOVE)
        raw.rays %= RUN_RAYS_CAP + 1;
    raw.alloc_mode = raw.alloc_mode == ALLOC_NO_FREE ? ALLOC_NO_FREE : ALLOC_COUNTING;
    copy.st = &raw;
    do_run(&copy, 1, fc->st->dest_mode, 0, 1, 0, 1, &r);
    if (r.co.clearly_invalid)
        REQUIRE(r.result != MESHFIX_OK, "clearly invalid options accepted");
    free_run(&r);
}

static void orient_flow(const fuzz_case *fc)
{
    const settings *st = fc->st;
    run main_run, reference;
    unsigned int *returned = NULL;
    int known;

    /* options that must be refused: refused without work */
    {
        call_options raw;
        counters dummy;
        memset(&dummy, 0, sizeof(dummy));
        make_options(fc, 0, &dummy, NULL, NULL, NULL, 0, &raw);
        if (raw.clearly_invalid)
            check_refusal(fc);
    }

    /* the main call: sanitized options, failing allocator if chosen */
    do_run(fc, 1, st->dest_mode, 1, 1, 1, st->want_report, &main_run);

    /* the same call without parallel_for (and, if it failed on purpose, also
       with the same failing allocation), fresh memory filled with other
       garbage: bit-identical */
    if (st->parallel_mode != PARALLEL_NONE || st->alloc_mode != ALLOC_DEFAULT || st->scratch_mode != SCRATCH_NONE) {
        do_run(fc, 1, st->dest_mode, 1, 0, 1, st->want_report, &reference);
        check_identical(fc, &main_run, &reference,
                        st->parallel_mode != PARALLEL_NONE
                            ? "result differs with parallel_for running chunks out of order"
                            : "result differs with other garbage in fresh memory");
        free_run(&reference);
    }

    /* 16-bit indices: the same call with the same indices in 32 bits gives
       the same answer, bit for bit */
    if (fc->index_size == 2) {
        fuzz_case wide = *fc;
        wide.index_size = 4;
        wide.call_indices = encode_indices(fc->indices, fc->index_count, 4);
        do_run(&wide, 1, st->dest_mode, 1, 1, 1, st->want_report, &reference);
        if (main_run.result == MESHFIX_OK && st->scratch_mode != SCRATCH_SHORT && st->scratch_mode != SCRATCH_TOPOLOGY &&
            st->alloc_mode != ALLOC_FAILING)
            REQUIRE(reference.result == MESHFIX_OK, "refused with 32-bit indices what 16-bit ones passed");
        if (main_run.result == MESHFIX_OK && reference.result == MESHFIX_OK)
            check_identical(fc, &main_run, &reference, "result differs between 16-bit and 32-bit indices");
        free_run(&reference);
        free(wide.call_indices);
    }
    if (main_run.result != MESHFIX_OK) {
        free_run(&main_run);
        return;
    }

    returned = (unsigned int *)malloc((fc->index_count ? fc->index_count : 1) * sizeof(unsigned int));
    REQUIRE(returned != NULL, "harness out of memory");
    known = check_orient_output(fc, &main_run, returned);
    check_side_outputs(fc, &main_run);
    if (main_run.had_report) {
        meshfix_result in_result, out_result;
        meshfix_report before = inspect_plain(fc, fc->indices, &in_result), after;
        const meshfix_report *rep = &main_run.out.report;
        edge_facts e;
        check_report_sane(fc, rep);
        check_report_decisions(rep);
        check_verdict(rep, 1);
        check_summary(st, rep);
        REQUIRE(in_result == MESHFIX_OK, "meshfix_inspect refused what meshfix_orient accepted");
        check_same_topology(&before, rep, "orient report topology differs from inspect of the input");
        REQUIRE(before.mesh.edges_inconsistent == rep->edges_inconsistent_before,
                "report.edges_inconsistent_before differs from inspect of the input");
        edge_facts_of(fc, fc->indices, &e);
        check_edge_facts(fc, &before.mesh, &e, 1);
        free(e.h);
        if (known) {
            after = inspect_plain(fc, returned, &out_result);
            REQUIRE(out_result == MESHFIX_OK, "meshfix_inspect refused the output");
            check_same_topology(&before, &after, "inspect of the output differs in topology from the input");
            REQUIRE(after.mesh.edges_inconsistent == rep->mesh.edges_inconsistent,
                    "report.mesh.edges_inconsistent is not what the returned mesh has");
            edge_facts_of(fc, returned, &e);
            check_edge_facts(fc, &rep->mesh, &e, 1);
            free(e.h);
        }
        if (main_run.co.policy == MESHFIX_POLICY_SDF)
            REQUIRE(rep->evidence.sdf_evaluations == main_run.count.sdf_calls, "report.evidence.sdf_evaluations");
    }

    /* orient the output again under the same options: SEED and MAJORITY
       must leave it as it is; the others just run */
    if (known && st->call_second) {
        fuzz_case again = *fc;
        settings second = *st;
        run r2;
        second.alloc_mode = second.alloc_mode == ALLOC_FAILING ? ALLOC_COUNTING : second.alloc_mode;
        size_t i;
        again.st = &second;
        again.indices = returned;
        again.call_indices = encode_indices(returned, fc->index_count, fc->index_size);
        do_run(&again, 1, DEST_SEPARATE, 1, 1, 0, 1, &r2);
        REQUIRE(r2.result == MESHFIX_OK, "second orient of the output failed");
        if (main_run.co.policy == MESHFIX_POLICY_SEED || main_run.co.policy == MESHFIX_POLICY_MAJORITY) {
            REQUIRE(r2.out.report.triangles_flipped == 0, "orient is not idempotent (SEED / MAJORITY)");
            for (i = 0; i < fc->index_count; ++i)
                REQUIRE(index_at(r2.out.destination, fc->index_size, i) == returned[i],
                        "orient is not idempotent (SEED / MAJORITY): destination changed");
        } else {
            check_orient_output(&again, &r2, NULL);
        }
        check_verdict(&r2.out.report, 1);
        free_run(&r2);
        free(again.call_indices);
    }
    free(returned);
    free_run(&main_run);
}

static void inspect_flow(const fuzz_case *fc)
{
    run r;
    meshfix_options o = format_options(fc);
    do_run(fc, 0, DEST_NULL, 1, 1, 1, 1, &r);
    if (r.result == MESHFIX_OK) {
        edge_facts e;
        check_report_sane(fc, &r.out.report);
        check_side_outputs(fc, &r);
        check_verdict(&r.out.report, 0);
        check_summary(fc->st, &r.out.report);
        edge_facts_of(fc, fc->indices, &e);
        check_edge_facts(fc, &r.out.report.mesh, &e, 1);
        free(e.h);
    }
    free_run(&r);
    /* the report is required */
    REQUIRE(meshfix_inspect(fc->call_indices, fc->index_count, fc->positions, fc->vertex_count, fc->stride, &o, NULL,
                            NULL) == MESHFIX_ERROR_INVALID_ARGUMENT,
            "meshfix_inspect without a report accepted");
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static mesh m; /* 100 KB: not on the stack */
    settings st;
    fuzz_case fc;
    source in;
    in.data = data, in.size = size, in.rng = 0, in.use_rng = 0;
    read_settings(&in, &st);
    build_mesh(&in, &m);
    setup_case(&fc, &st, &m);
    orient_flow(&fc);
    if (st.call_inspect)
        inspect_flow(&fc);
    if (st.call_check)
        check_check(&fc);
    if (st.call_weld)
        check_weld(&fc);
    free_case(&fc);
    return 0;
}
