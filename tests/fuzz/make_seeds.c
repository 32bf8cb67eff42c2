/* Writes the seed corpus of fuzz_stress.c into tests/fuzz/corpus/stress/
   (or the directory given as argv[1]): one small input per feature, so the
   fuzzer starts from meshes it would take long to find by mutation.

       cc -std=c99 -o build/make_seeds tests/fuzz/make_seeds.c && build/make_seeds

   The byte layout is the one fuzz_stress.c reads: the settings block
   (read_settings, field by field in the same order), then mesh operations
   (build_mesh: an op byte, then that op's parameters). Keep the two in
   step when either changes. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ===== a growing byte buffer ===== */

typedef struct buffer {
    uint8_t data[8192];
    size_t size;
} buffer;

static void put_u8(buffer *b, unsigned int v)
{
    if (b->size >= sizeof(b->data)) {
        fprintf(stderr, "make_seeds: seed too large\n");
        exit(1);
    }
    b->data[b->size++] = (uint8_t)v;
}

static void put_u16(buffer *b, unsigned int v)
{
    put_u8(b, v & 0xFF);
    put_u8(b, (v >> 8) & 0xFF);
}

static void put_u32(buffer *b, uint32_t v)
{
    put_u16(b, v & 0xFFFF);
    put_u16(b, v >> 16);
}

static void put_u64(buffer *b, uint64_t v)
{
    put_u32(b, (uint32_t)v);
    put_u32(b, (uint32_t)(v >> 32));
}

/* ===== the settings block (fuzz_stress.c: read_settings) ===== */

/* decode_option_float selectors: value = sel % 10 */
enum { F_ZERO = 0, F_FRACTION = 2, F_SMALL = 4, F_SPECIAL = 5, F_RAW = 6, F_NEGATIVE = 7, F_POW2 = 8, F_NONFINITE = 9 };
/* F_SPECIAL values: 0, -0, 1, FLT_MIN, FLT_MAX, 1e-45, 0.5; F_NONFINITE: NaN, +Inf, -Inf (v % 3) */

typedef struct option_float {
    unsigned int sel, v;
    uint32_t raw; /* F_RAW only */
} option_float;

enum { AUTO, SEED, MAJORITY, OUTWARD, SDF, VISIBILITY, UP, NORMALS };

typedef struct seed_settings {
    unsigned int calls;         /* bit0 inspect, bit1 check, bit2 weld, bit3 no report, bits 4-5 = 3: no positions, bit6 no second orient */
    unsigned int policy;        /* < 240: policy % 7; else raw_policy follows */
    uint32_t raw_policy;
    unsigned int rays_sel;      /* 0 default, 1 u8, 2 u16, 3 u16 % 20000, 4 u32, 5 u64, 6 2^24 + u8 - 128, 7 SIZE_MAX - u8 */
    uint64_t rays;
    unsigned int samples_sel;   /* 0 default, 1 u8, 2 u16, 3 65536 + u8 - 128, 4 u32 */
    uint32_t samples;
    option_float coherence, c0, eps, kv, sdf_step, up[3];
    unsigned int sdf_mode, visibility_flags;
    uint32_t seed;
    unsigned int outputs;       /* bit0 flipped, bit1 patch_ids, bit2 confidence, bit3 components, bits 4-5 slack */
    unsigned int confidence_capacity, components_capacity;
    unsigned int alloc;         /* % 4: default, counting, failing, no free_fn; bit 2: failures persist */
    unsigned int fail_at;
    unsigned int scratch;       /* % 5: none, exact, short, roomy, topology only; (>> 3) % 16: misalignment */
    unsigned int shortfall;
    unsigned int parallel;      /* % 3: none, reverse, shuffle */
    uint64_t shuffle_seed;
    unsigned int sdf;           /* low nibble 15: no sdf; bit0 gradient, bit1 gradient NaN; (>> 4) % 4 shape */
    unsigned int sdf_nan;       /* >= 128: NaN where a hash & (2^(b % 8) - 1) is 0 */
    unsigned int stride;        /* index into {12,12,12,12,16,16,20,24,32,48,12,0,4,8,13,14} */
    unsigned int skew;          /* >= 192: vertex_count skewed by b % 16 - 8 */
    unsigned int dest, dest_shift;
    unsigned int trailing;      /* >= 240: 1 + b % 2 stray indices */
    unsigned int fill;
    option_float weld_tolerance;
    unsigned int requirements;
    option_float evidence_sigma, min_confidence;
    unsigned int normals;        /* bit0 per triangle, bit1 per vertex; (>> 2) % 4: face normals, randomly
                                    reversed face normals, random (NaN too), zero */
    unsigned int normal_strides; /* % 8 triangle, (>> 3) % 8 vertex, into {0,12,12,16,24,0,4,13} */
    uint64_t normals_seed;
    /* the 0.2 formats */
    unsigned int index_size;     /* % 4: 0 (default), 2 (16-bit, when the vertices fit), 4, raw_index_size */
    uint32_t raw_index_size;
    unsigned int position_size;  /* % 4: 0 (default), 8 (double), 4, raw_position_size */
    uint32_t raw_position_size;
    unsigned int topology;       /* < 240: % 3 POSITIONS, INDICES, WELD; else raw_topology */
    uint32_t raw_topology;
    option_float topology_tolerance;
    unsigned int doubles;        /* % 4 offset: none, +-2^k, raw bits, c * 10^k; bit 2 jitter below float
                                    precision; bit 3 scale by 2^(8 * (int8) exponent) */
    unsigned int exponent;       /* bit 3 of doubles */
    unsigned int offset_k, offset_c; /* offset 1: k (bit 7 sign, % 80); 3: c (int8), k % 16 */
    uint64_t offset_bits;        /* offset 2 */
    unsigned int double_stride;  /* index into {24,24,24,0,0,32,40,48,28,36,24,12,16,20,25,26} */
    uint64_t double_seed;
    unsigned int summary;        /* < 64: buffer of summary % 8 bytes; else that many */
    unsigned int outputs_null;   /* bit 0: no output wanted, pass NULL */
} seed_settings;

static void put_option_float(buffer *b, option_float f)
{
    put_u8(b, f.sel);
    put_u8(b, f.v);
    if (f.sel % 10 == F_RAW)
        put_u32(b, f.raw);
}

static void put_settings(buffer *b, const seed_settings *s)
{
    int k;
    put_u8(b, s->calls);
    put_u8(b, s->policy);
    if (s->policy >= 240)
        put_u32(b, s->raw_policy);
    put_u8(b, s->rays_sel);
    switch (s->rays_sel % 8) {
    case 1: case 6: case 7: put_u8(b, (unsigned int)s->rays); break;
    case 2: case 3: put_u16(b, (unsigned int)s->rays); break;
    case 4: put_u32(b, (uint32_t)s->rays); break;
    case 5: put_u64(b, s->rays); break;
    default: break;
    }
    put_u8(b, s->samples_sel);
    switch (s->samples_sel % 5) {
    case 1: case 3: put_u8(b, s->samples); break;
    case 2: put_u16(b, s->samples); break;
    case 4: put_u32(b, s->samples); break;
    default: break;
    }
    put_option_float(b, s->coherence);
    put_option_float(b, s->c0);
    put_option_float(b, s->eps);
    put_option_float(b, s->kv);
    put_option_float(b, s->sdf_step);
    for (k = 0; k < 3; ++k)
        put_option_float(b, s->up[k]);
    put_u8(b, s->sdf_mode);
    if (s->sdf_mode >= 240)
        put_u32(b, 7);
    put_u8(b, s->visibility_flags);
    put_u32(b, s->seed);
    put_u8(b, s->outputs);
    put_u16(b, s->confidence_capacity);
    put_u16(b, s->components_capacity);
    put_u8(b, s->alloc);
    put_u8(b, s->fail_at);
    put_u8(b, s->scratch);
    put_u16(b, s->shortfall);
    put_u8(b, s->parallel);
    put_u64(b, s->shuffle_seed);
    put_u8(b, s->sdf);
    put_u8(b, s->sdf_nan);
    put_u8(b, s->stride);
    put_u8(b, s->skew);
    put_u8(b, s->dest);
    put_u8(b, s->dest_shift);
    put_u8(b, s->trailing);
    put_u8(b, s->fill);
    put_option_float(b, s->weld_tolerance);
    put_u8(b, s->requirements);
    put_option_float(b, s->evidence_sigma);
    put_option_float(b, s->min_confidence);
    put_u8(b, s->normals);
    put_u8(b, s->normal_strides);
    put_u64(b, s->normals_seed);
    put_u8(b, s->index_size);
    if (s->index_size % 4 == 3)
        put_u32(b, s->raw_index_size);
    put_u8(b, s->position_size);
    if (s->position_size % 4 == 3)
        put_u32(b, s->raw_position_size);
    put_u8(b, s->topology);
    if (s->topology >= 240)
        put_u32(b, s->raw_topology);
    put_option_float(b, s->topology_tolerance);
    put_u8(b, s->doubles);
    if (s->doubles & 8)
        put_u8(b, s->exponent);
    switch (s->doubles % 4) {
    case 1: put_u8(b, s->offset_k); break;
    case 2: put_u64(b, s->offset_bits); break;
    case 3: put_u8(b, s->offset_c), put_u8(b, s->offset_k); break;
    default: break;
    }
    put_u8(b, s->double_stride);
    put_u64(b, s->double_seed);
    put_u8(b, s->summary);
    put_u8(b, s->outputs_null);
}

/* Defaults: every output with room, a report, the second orient, sdf
   present (a sphere), valid stride, destination its own array. */
static seed_settings defaults(unsigned int policy)
{
    seed_settings s;
    memset(&s, 0, sizeof(s));
    s.calls = 1 | 2 | 4;
    s.policy = policy;
    s.rays_sel = 3, s.rays = 2000;
    s.outputs = 1 | 2 | 4 | 8 | (1 << 4);
    s.confidence_capacity = 64;
    s.components_capacity = 64;
    s.fill = 0xA5;
    s.sdf = 0x00;
    s.summary = 200; /* room for the whole line */
    return s;
}

/* ===== mesh operations (fuzz_stress.c: mesh_ops, in this order) ===== */

enum { OP_VERTEX, OP_TRIANGLE, OP_SHRINKING, OP_HYPERGRAPH, OP_SHELLS, OP_GRID, OP_SOUP, OP_STACK, OP_FAN,
       OP_DUPLICATES, OP_TRANSFORM, OP_FLIP, OP_RANDOM_TRIANGLES };
/* coordinate encodings, 3 bits per axis in a 16-bit word */
enum { E_RAW, E_SMALL_INT, E_POW2, E_ELEVEN, E_NEAR_MAX, E_FIXED, E_REPEAT, E_POW2_HUGE };
#define ENCODINGS(x, y, z) ((unsigned int)(x) | ((unsigned int)(y) << 3) | ((unsigned int)(z) << 6))

/* E_SMALL_INT coordinates: one byte each */
static void put_small_point(buffer *b, int x, int y, int z)
{
    put_u16(b, ENCODINGS(E_SMALL_INT, E_SMALL_INT, E_SMALL_INT));
    put_u8(b, (unsigned int)(x & 0xFF));
    put_u8(b, (unsigned int)(y & 0xFF));
    put_u8(b, (unsigned int)(z & 0xFF));
}

/* E_POW2 value +-2^-k, as the u16 the decoder reads */
static unsigned int pow2_code(int negative, unsigned int k)
{
    return (k << 1) | (negative ? 1u : 0u);
}

static void op_shrinking(buffer *b, unsigned int count, unsigned int k0, unsigned int flags, unsigned int flips,
                         uint64_t seed)
{
    put_u8(b, OP_SHRINKING);
    put_u8(b, count - 1);
    put_u8(b, k0);
    put_u8(b, flags); /* bit0 radix 2, bit1 strip, bit2 alternate sign, bit3 one axis ((flags >> 4) % 3) */
    put_u8(b, flips);
    put_u64(b, seed);
}

static void op_hypergraph(buffer *b, unsigned int n, unsigned int flags, unsigned int encodings, uint64_t seed)
{
    put_u8(b, OP_HYPERGRAPH);
    put_u8(b, n - 4);
    put_u8(b, flags); /* bit0: the latest n vertices; the byte is also the flip probability */
    put_u16(b, encodings);
    put_u64(b, seed);
}

static void op_shells(buffer *b, unsigned int count, unsigned int kind, unsigned int flips, unsigned int layout,
                      int centre, int step, uint64_t seed)
{
    put_u8(b, OP_SHELLS);
    put_u8(b, count - 1);
    put_u8(b, kind);   /* % 3: tetra, octa, cube; bit 2: every other shell inside out */
    put_u8(b, flips);
    put_u8(b, layout); /* % 6: ratio 1/2, 1/11, 0.999, 1, 2, 1e-6; bit 3: shells stepped apart */
    put_small_point(b, centre, centre, centre);
    put_small_point(b, step, 0, 0);
    put_u64(b, seed);
}

static void op_grid(buffer *b, unsigned int w, unsigned int h, unsigned int flips, unsigned int encoding,
                    unsigned int spacing_k, uint64_t seed)
{
    put_u8(b, OP_GRID);
    put_u8(b, w - 2);
    put_u8(b, h - 2);
    put_u8(b, flips);
    put_u8(b, encoding); /* bit 3: random heights in encoding & 7 */
    put_u16(b, pow2_code(0, spacing_k));
    put_u64(b, seed);
}

static void op_soup(buffer *b, unsigned int n, unsigned int encodings, uint64_t seed)
{
    put_u8(b, OP_SOUP);
    put_u16(b, n - 1);
    put_u16(b, encodings); /* bit 15: a random encoding per point */
    put_u64(b, seed);
}

static void op_stack(buffer *b, unsigned int n, unsigned int mode, unsigned int flips, uint64_t seed)
{
    put_u8(b, OP_STACK);
    put_u8(b, n - 2);
    put_u8(b, mode); /* % 3: coincident, ulps apart, stacked along z by 2^-(mode % 64) */
    put_u8(b, flips);
    put_small_point(b, 0, 0, 0);
    put_small_point(b, 4, 0, 0);
    put_small_point(b, 0, 4, 0);
    put_u64(b, seed);
}

static void op_fan(buffer *b, unsigned int n, unsigned int mode, unsigned int flips, uint64_t seed)
{
    put_u8(b, OP_FAN);
    put_u8(b, n - 1);
    put_u8(b, mode); /* bit0: bow-ties around one vertex instead of triangles on one edge */
    put_u8(b, flips);
    put_u16(b, pow2_code(0, 0));
    put_u64(b, seed);
}

static void op_duplicates(buffer *b, unsigned int n, uint64_t seed)
{
    put_u8(b, OP_DUPLICATES);
    put_u8(b, n - 1);
    put_u64(b, seed);
}

/* kind % 4: scale by 2^exponent, translate, poison one coordinate of every
   (1 + kind >> 3)-th vertex with the offset, rotate axes; bit 2: all vertices */
static void op_transform(buffer *b, unsigned int n, unsigned int kind, int exponent, unsigned int encodings,
                         uint32_t raw_x)
{
    put_u8(b, OP_TRANSFORM);
    put_u8(b, n - 1);
    put_u8(b, kind);
    put_u8(b, (unsigned int)(exponent & 0xFF));
    put_u16(b, encodings);
    /* offset: x from raw bits (E_RAW) or a small int, y z small ints */
    if ((encodings & 7) == E_RAW)
        put_u32(b, raw_x);
    else
        put_u8(b, raw_x & 0xFF);
    put_u8(b, 1);
    put_u8(b, 1);
}

static void op_flip(buffer *b, unsigned int probability, uint64_t seed)
{
    put_u8(b, OP_FLIP);
    put_u8(b, probability);
    put_u64(b, seed);
}

static void op_triangle_raw(buffer *b, uint32_t x, uint32_t y, uint32_t z)
{
    put_u8(b, OP_TRIANGLE);
    put_u8(b, 2 | (2 << 2) | (2 << 4)); /* three raw 32-bit indices */
    put_u32(b, x);
    put_u32(b, y);
    put_u32(b, z);
}

static void op_random_triangles(buffer *b, unsigned int n, unsigned int window, unsigned int out_of_range,
                                uint64_t seed)
{
    put_u8(b, OP_RANDOM_TRIANGLES);
    put_u16(b, n - 1);
    put_u8(b, window - 3);
    put_u8(b, out_of_range);
    put_u64(b, seed);
}

/* ===== the seeds ===== */

static const char *directory = "tests/fuzz/corpus/stress";
static size_t total;

static void write_seed(const char *name, const buffer *b)
{
    char path[512];
    FILE *f;
    snprintf(path, sizeof(path), "%s/%s", directory, name);
    f = fopen(path, "wb");
    if (f == NULL || fwrite(b->data, 1, b->size, f) != b->size || fclose(f) != 0) {
        fprintf(stderr, "make_seeds: cannot write %s\n", path);
        exit(1);
    }
    total += b->size;
    printf("%-28s %5lu bytes\n", name, (unsigned long)b->size);
}

static option_float of(unsigned int sel, unsigned int v)
{
    option_float f;
    f.sel = sel, f.v = v, f.raw = 0;
    return f;
}

int main(int argc, char **argv)
{
    buffer b;
    seed_settings s;
    if (argc > 1)
        directory = argv[1];

    /* planes shrinking toward the origin, 11^-(k + axis/3) for k < 45: the
       deepest BVH; visibility with coherence over edges of every scale */
    memset(&b, 0, sizeof(b)), s = defaults(VISIBILITY), s.parallel = 1;
    put_settings(&b, &s);
    op_shrinking(&b, 45, 0, 0, 96, 1);
    write_seed("shrinking_planes_11", &b);

    /* the same in powers of two, as one strip of slivers, under AUTO, with
       the chunks of rays shuffled */
    memset(&b, 0, sizeof(b)), s = defaults(AUTO), s.parallel = 2, s.shuffle_seed = 77;
    put_settings(&b, &s);
    op_shrinking(&b, 64, 0, 1 | 2 | 4, 40, 2);
    op_shrinking(&b, 40, 20, 8 | (1 << 4), 128, 3);
    write_seed("shrinking_strip_2", &b);

    /* a soup whose corners include NaN, Inf and denormals (raw bits), and a
       transform that poisons every third vertex with NaN */
    memset(&b, 0, sizeof(b)), s = defaults(OUTWARD);
    put_settings(&b, &s);
    op_soup(&b, 300, 0x8000, 4);
    op_shells(&b, 4, 2, 30, 0, 0, 0, 5);
    op_transform(&b, 60, 2 | (2 << 3), 0, ENCODINGS(E_RAW, E_SMALL_INT, E_SMALL_INT), 0x7FC00000u);
    write_seed("nan_soup", &b);

    /* the complete hypergraph on 24 vertices: 2024 triangles, every edge
       shared by 22; plus duplicates of it in every rotation */
    memset(&b, 0, sizeof(b)), s = defaults(SEED), s.components_capacity = 3;
    put_settings(&b, &s);
    op_hypergraph(&b, 24, 0x80, ENCODINGS(E_SMALL_INT, E_SMALL_INT, E_SMALL_INT), 6);
    op_duplicates(&b, 200, 7);
    write_seed("hypergraph_24", &b);

    /* the same under MAJORITY on degenerate positions (all coincident) */
    memset(&b, 0, sizeof(b)), s = defaults(MAJORITY);
    put_settings(&b, &s);
    op_hypergraph(&b, 16, 0x40, ENCODINGS(E_FIXED, E_FIXED, E_FIXED), 8);
    write_seed("hypergraph_flat", &b);

    /* every option value out of range: the calls must refuse without work */
    memset(&b, 0, sizeof(b)), s = defaults(VISIBILITY);
    s.rays_sel = 7, s.rays = 0;
    s.samples_sel = 4, s.samples = 0xFFFFFFFFu;
    s.coherence = of(F_NONFINITE, 0), s.c0 = of(F_NEGATIVE, 3), s.kv = of(F_NONFINITE, 1);
    s.eps = of(F_POW2, 100), s.sdf_step = of(F_NONFINITE, 2), s.up[1] = of(F_NONFINITE, 0);
    s.policy = 250, s.raw_policy = 0x80000001u;
    s.sdf_mode = 250;
    s.weld_tolerance = of(F_NONFINITE, 0);
    put_settings(&b, &s);
    op_shells(&b, 3, 1, 0, 0, 0, 0, 9);
    write_seed("huge_options", &b);

    /* 2^24 + 1 rays exactly, the rest valid */
    memset(&b, 0, sizeof(b)), s = defaults(AUTO);
    s.rays_sel = 6, s.rays = 129;
    put_settings(&b, &s);
    op_shells(&b, 2, 0, 0, 0, 0, 0, 10);
    write_seed("rays_just_too_many", &b);

    /* nested cubes, every other one a cavity, 1/2 apart: OUTWARD nesting,
       in reverse chunk order */
    memset(&b, 0, sizeof(b)), s = defaults(AUTO), s.parallel = 1;
    put_settings(&b, &s);
    op_shells(&b, 32, 2 | 4, 20, 0, 0, 0, 11);
    op_shells(&b, 20, 1, 10, 1 | 8, 100, 3, 12);
    write_seed("nested_shells", &b);

    /* coincident and near-coincident shells */
    memset(&b, 0, sizeof(b)), s = defaults(OUTWARD);
    put_settings(&b, &s);
    op_shells(&b, 40, 0, 50, 2, 0, 0, 13);
    op_shells(&b, 20, 2, 50, 3, 0, 0, 14);
    write_seed("coincident_shells", &b);

    /* a 64 x 60 height field with random heights, turned up along a tilted axis */
    memset(&b, 0, sizeof(b)), s = defaults(UP);
    s.up[0] = of(F_FRACTION, 30), s.up[2] = of(F_FRACTION, 200);
    put_settings(&b, &s);
    op_grid(&b, 64, 60, 60, 8 | E_FIXED, 3, 15);
    write_seed("grid_up", &b);

    /* the same sheet, flat, for VISIBILITY, coherence only, chunks in reverse,
       blocks from the counting allocator (filled with garbage) */
    memset(&b, 0, sizeof(b)), s = defaults(VISIBILITY), s.visibility_flags = 1, s.parallel = 1, s.alloc = 1;
    put_settings(&b, &s);
    op_grid(&b, 30, 30, 128, 0, 0, 16);
    write_seed("grid_coherence_only", &b);

    /* SDF per patch on octahedra, NaN from a few points, a huge step */
    memset(&b, 0, sizeof(b)), s = defaults(SDF);
    s.sdf_nan = 128 + 3, s.sdf_step = of(F_SPECIAL, 4);
    put_settings(&b, &s);
    op_shells(&b, 16, 1, 60, 0, 0, 0, 17);
    op_soup(&b, 50, ENCODINGS(E_ELEVEN, E_ELEVEN, E_ELEVEN), 18);
    write_seed("sdf_nan", &b);

    /* SDF per triangle with the caller's gradient (NaN now and then) */
    memset(&b, 0, sizeof(b)), s = defaults(SDF);
    s.sdf_mode = 1, s.sdf = 1 | 2 | (2 << 4), s.sdf_nan = 128 + 2;
    put_settings(&b, &s);
    op_grid(&b, 20, 20, 90, 8 | E_SMALL_INT, 1, 19);
    op_shells(&b, 8, 2, 90, 0, 0, 0, 20);
    write_seed("sdf_per_triangle", &b);

    /* 257 coincident copies of one triangle, and 200 ulps apart: rays that
       visit every box; shuffled chunks */
    memset(&b, 0, sizeof(b)), s = defaults(VISIBILITY), s.parallel = 2, s.shuffle_seed = 5;
    put_settings(&b, &s);
    op_stack(&b, 257, 0, 128, 21);
    op_stack(&b, 200, 1, 128, 22);
    op_stack(&b, 200, 2 + 3 * 7, 128, 23);
    write_seed("coincident_stack", &b);

    /* 256 triangles on one edge, and bow-ties around one vertex */
    memset(&b, 0, sizeof(b)), s = defaults(MAJORITY);
    put_settings(&b, &s);
    op_fan(&b, 256, 0, 100, 24);
    op_fan(&b, 128, 1, 100, 25);
    write_seed("fans", &b);

    /* coordinates within a few ulps of FLT_MAX */
    memset(&b, 0, sizeof(b)), s = defaults(VISIBILITY);
    put_settings(&b, &s);
    op_soup(&b, 200, ENCODINGS(E_NEAR_MAX, E_NEAR_MAX, E_NEAR_MAX), 26);
    op_shells(&b, 3, 2, 0, 4, 0, 0, 27);
    op_transform(&b, 24, 0, 126, ENCODINGS(E_SMALL_INT, E_SMALL_INT, E_SMALL_INT), 0);
    write_seed("near_flt_max", &b);

    /* denormal planes 2^-149 and huge 2^127 in one model */
    memset(&b, 0, sizeof(b)), s = defaults(AUTO), s.rays_sel = 0;
    put_settings(&b, &s);
    op_soup(&b, 60, ENCODINGS(E_POW2, E_POW2, E_POW2), 28);
    op_soup(&b, 60, ENCODINGS(E_POW2_HUGE, E_POW2, E_POW2_HUGE), 29);
    write_seed("denormal_and_huge", &b);

    /* caller scratch one byte short, misaligned: SCRATCH_TOO_SMALL */
    memset(&b, 0, sizeof(b)), s = defaults(SEED);
    s.scratch = 2 | (5 << 3), s.shortfall = 0, s.alloc = 1;
    put_settings(&b, &s);
    op_shells(&b, 10, 2, 80, 0, 0, 0, 30);
    write_seed("scratch_short", &b);

    /* caller scratch exactly meshfix_scratch_size(): no allocation at all */
    memset(&b, 0, sizeof(b)), s = defaults(MAJORITY);
    s.scratch = 1 | (3 << 3), s.alloc = 1;
    put_settings(&b, &s);
    op_hypergraph(&b, 12, 0x80, ENCODINGS(E_SMALL_INT, E_SMALL_INT, E_SMALL_INT), 31);
    op_grid(&b, 10, 10, 100, 0, 2, 32);
    write_seed("scratch_exact", &b);

    /* the same for AUTO, whose rays need scratch for units and trees too,
       with an allocator that fails at once (it must not be called); and
       scratch for the topology alone (a geometry that does not fit in the
       rest is refused with SCRATCH_TOO_SMALL) */
    memset(&b, 0, sizeof(b)), s = defaults(AUTO);
    s.scratch = 1 | (7 << 3), s.alloc = 2 | 4, s.fail_at = 0, s.parallel = 1;
    put_settings(&b, &s);
    op_shells(&b, 8, 2 | 4, 40, 0, 0, 0, 50);
    op_grid(&b, 9, 9, 60, 8 | E_FIXED, 2, 51);
    write_seed("scratch_exact_auto", &b);
    memset(&b, 0, sizeof(b)), s = defaults(VISIBILITY);
    s.scratch = 4 | (1 << 3), s.alloc = 1;
    put_settings(&b, &s);
    op_grid(&b, 9, 9, 60, 8 | E_FIXED, 2, 52);
    op_soup(&b, 30, ENCODINGS(E_SMALL_INT, E_SMALL_INT, E_SMALL_INT), 53);
    write_seed("scratch_topology_only", &b);

    /* allocation failing from the third on, VISIBILITY */
    memset(&b, 0, sizeof(b)), s = defaults(VISIBILITY), s.alloc = 2 | 4, s.fail_at = 2;
    put_settings(&b, &s);
    op_shells(&b, 6, 0, 60, 1 | 8, 0, 4, 33);
    op_grid(&b, 8, 8, 30, 0, 0, 34);
    write_seed("allocation_fails", &b);

    /* weld of a soup whose corners repeat earlier ones a few ulps off */
    memset(&b, 0, sizeof(b)), s = defaults(MAJORITY);
    s.calls = 1 | 2 | 4, s.weld_tolerance = of(F_SMALL, 10), s.requirements = 31;
    put_settings(&b, &s);
    op_soup(&b, 100, ENCODINGS(E_FIXED, E_FIXED, E_FIXED), 35);
    op_soup(&b, 300, ENCODINGS(E_REPEAT, E_REPEAT, E_REPEAT), 36);
    write_seed("weld_repeats", &b);

    /* destination overlapping the indices, shifted by 5 and by -7 */
    memset(&b, 0, sizeof(b)), s = defaults(OUTWARD), s.dest = 3, s.dest_shift = 5;
    put_settings(&b, &s);
    op_shells(&b, 5, 1, 128, 0, 0, 0, 37);
    write_seed("overlap_plus", &b);
    memset(&b, 0, sizeof(b)), s = defaults(MAJORITY), s.dest = 3, s.dest_shift = 0xF9, s.stride = 8;
    put_settings(&b, &s);
    op_shells(&b, 5, 2, 128, 0, 0, 0, 38);
    write_seed("overlap_minus_stride32", &b);

    /* indices out of range, vertex_count short by 3, stray indices */
    memset(&b, 0, sizeof(b)), s = defaults(AUTO), s.skew = 192 + 5, s.trailing = 241;
    put_settings(&b, &s);
    op_shells(&b, 3, 2, 0, 0, 0, 0, 39);
    op_triangle_raw(&b, 0, 1, 0xFFFFFFFFu);
    write_seed("out_of_range", &b);

    /* no positions: SEED / MAJORITY / AUTO by counts; the rest refused */
    memset(&b, 0, sizeof(b)), s = defaults(AUTO), s.calls = 1 | 2 | 0x30;
    put_settings(&b, &s);
    op_shells(&b, 6, 0, 70, 0, 0, 0, 40);
    op_random_triangles(&b, 500, 40, 0, 41);
    write_seed("no_positions", &b);

    /* random triangles over c * 11^-k soups, default ray budget (small mesh) */
    memset(&b, 0, sizeof(b)), s = defaults(AUTO), s.rays_sel = 0, s.parallel = 1;
    put_settings(&b, &s);
    op_soup(&b, 40, ENCODINGS(E_ELEVEN, E_ELEVEN, E_ELEVEN), 42);
    op_random_triangles(&b, 200, 60, 0, 43);
    op_flip(&b, 128, 44);
    write_seed("eleven_random", &b);

    /* NORMALS: per-triangle face normals, a third of them reversed, over
       shells and a sheet; and AUTO taking them as evidence */
    memset(&b, 0, sizeof(b)), s = defaults(NORMALS), s.normals = 1 | (1 << 2), s.normals_seed = 45;
    put_settings(&b, &s);
    op_shells(&b, 6, 1, 100, 1 | 8, 0, 3, 46);
    op_grid(&b, 12, 12, 100, 8 | E_FIXED, 2, 47);
    write_seed("normals_per_triangle", &b);
    memset(&b, 0, sizeof(b)), s = defaults(AUTO), s.normals = 2 | (2 << 2), s.normal_strides = 3 << 3;
    s.evidence_sigma = of(F_FRACTION, 255), s.min_confidence = of(F_FRACTION, 128);
    put_settings(&b, &s);
    op_soup(&b, 80, ENCODINGS(E_SMALL_INT, E_SMALL_INT, E_SMALL_INT), 48);
    op_random_triangles(&b, 150, 30, 0, 49);
    write_seed("normals_per_vertex_noise", &b);

    /* ---- the 0.2 formats ---- */

    /* 16-bit indices: shells and a sheet under AUTO, destination
       overlapping the indices, chunks in reverse; a raw index 0x10002
       that 16 bits hold as 2 */
    memset(&b, 0, sizeof(b)), s = defaults(AUTO), s.index_size = 1, s.parallel = 1, s.dest = 3, s.dest_shift = 4;
    put_settings(&b, &s);
    op_shells(&b, 6, 2 | 4, 40, 1 | 8, 0, 3, 60);
    op_grid(&b, 12, 10, 60, 8 | E_FIXED, 2, 61);
    op_triangle_raw(&b, 0, 1, 0x10002u);
    write_seed("indices16_shells", &b);
    memset(&b, 0, sizeof(b)), s = defaults(SEED), s.index_size = 1, s.topology = 1, s.requirements = 31;
    put_settings(&b, &s);
    op_hypergraph(&b, 14, 0x80, ENCODINGS(E_SMALL_INT, E_SMALL_INT, E_SMALL_INT), 62);
    op_duplicates(&b, 60, 63);
    write_seed("indices16_hypergraph", &b);

    /* doubles 2^40 away from the origin, bits below float precision,
       28-byte stride (doubles on 4-byte boundaries): nested shells */
    memset(&b, 0, sizeof(b)), s = defaults(AUTO), s.position_size = 1, s.doubles = 1 | 4, s.offset_k = 40;
    s.double_stride = 8, s.double_seed = 64, s.parallel = 2, s.shuffle_seed = 9;
    put_settings(&b, &s);
    op_shells(&b, 12, 2 | 4, 30, 0, 0, 0, 65);
    op_shells(&b, 6, 1, 30, 1 | 8, 20, 3, 66);
    write_seed("doubles_far", &b);

    /* survey coordinates (4.5e6), welded within a tolerance as the
       topology and by meshfix_weld, corners repeating earlier ones */
    memset(&b, 0, sizeof(b)), s = defaults(MAJORITY), s.position_size = 1, s.doubles = 3, s.offset_c = 45;
    s.offset_k = 5, s.topology = 2, s.topology_tolerance = of(F_SMALL, 10), s.weld_tolerance = of(F_SMALL, 10);
    s.requirements = 31, s.alloc = 1;
    put_settings(&b, &s);
    op_soup(&b, 100, ENCODINGS(E_FIXED, E_FIXED, E_FIXED), 67);
    op_soup(&b, 200, ENCODINGS(E_REPEAT, E_REPEAT, E_REPEAT), 68);
    write_seed("doubles_survey_weld", &b);

    /* doubles scaled by 2^160 and 2^-160: beyond float range both ways,
       under VISIBILITY, packed (stride 0) */
    memset(&b, 0, sizeof(b)), s = defaults(VISIBILITY), s.position_size = 1, s.doubles = 8, s.exponent = 20;
    s.double_stride = 3;
    put_settings(&b, &s);
    op_shells(&b, 4, 2, 60, 0, 0, 0, 69);
    op_grid(&b, 10, 10, 60, 8 | E_SMALL_INT, 0, 70);
    write_seed("doubles_beyond_float", &b);
    memset(&b, 0, sizeof(b)), s = defaults(OUTWARD), s.position_size = 1, s.doubles = 8 | 2, s.exponent = 0xEC;
    s.offset_bits = 0x3FF0000000000001ull, s.scratch = 1, s.alloc = 1;
    put_settings(&b, &s);
    op_shells(&b, 5, 0, 60, 4, 0, 0, 71);
    write_seed("doubles_tiny_scratch", &b);

    /* an engine's vertex buffer split at seams: corners repeating earlier
       positions exactly (joined by default), by index on request */
    memset(&b, 0, sizeof(b)), s = defaults(AUTO), s.requirements = 31, s.summary = 1;
    put_settings(&b, &s);
    op_shells(&b, 3, 2, 0, 1 | 8, 0, 4, 72);
    op_soup(&b, 120, ENCODINGS(E_REPEAT, E_REPEAT, E_REPEAT), 73);
    write_seed("topology_positions_seams", &b);
    memset(&b, 0, sizeof(b)), s = defaults(MAJORITY), s.topology = 1, s.requirements = 2 | 4, s.summary = 0;
    put_settings(&b, &s);
    op_grid(&b, 8, 8, 90, 0, 1, 74);
    op_stack(&b, 20, 0, 128, 75);
    write_seed("topology_indices", &b);
    memset(&b, 0, sizeof(b)), s = defaults(OUTWARD), s.topology = 2, s.topology_tolerance = of(F_FRACTION, 3);
    s.requirements = 1 | 16, s.summary = 5;
    put_settings(&b, &s);
    op_soup(&b, 200, ENCODINGS(E_FIXED, E_FIXED, E_FIXED), 76);
    op_stack(&b, 30, 1, 128, 77);
    write_seed("topology_weld", &b);

    /* formats nobody can read: 3-byte indices, 12-byte coordinates, topology 7 */
    memset(&b, 0, sizeof(b)), s = defaults(SEED), s.index_size = 3, s.raw_index_size = 3, s.position_size = 3;
    s.raw_position_size = 12, s.topology = 250, s.raw_topology = 7, s.topology_tolerance = of(F_NONFINITE, 0);
    put_settings(&b, &s);
    op_shells(&b, 2, 0, 0, 0, 0, 0, 78);
    write_seed("formats_invalid", &b);

    /* meshfix_check's reasons: fans on one edge (manifold), bow-ties,
       open sheets, inside-out shells; no outputs at all (NULL) */
    memset(&b, 0, sizeof(b)), s = defaults(MAJORITY), s.requirements = 2 | 4 | 8 | 16, s.outputs = 0, s.outputs_null = 1;
    s.summary = 2;
    put_settings(&b, &s);
    op_fan(&b, 5, 0, 100, 79);
    op_fan(&b, 4, 1, 100, 80);
    op_shells(&b, 3, 2 | 4, 0, 1 | 8, 0, 4, 81);
    write_seed("check_reasons", &b);

    printf("%lu bytes in all\n", (unsigned long)total);
    return 0;
}
