/* meshfix.h - v0.1.0 - triangle winding (face orientation) repair - MIT license, see end of file

   Finds and repairs inconsistent triangle winding in indexed triangle meshes:
   reports what is wrong (inspect), and flips the triangles that face the
   wrong way (orient). C99 or C++, libc and libm only, no globals.

   DO THIS in exactly one C or C++ file:

       #define MESHFIX_IMPLEMENTATION
       #include "meshfix.h"

   and include "meshfix.h" without the define everywhere else.

   QUICK START

       meshfix_report report;
       meshfix_result r = meshfix_orient(indices, indices, index_count,
                                         positions, vertex_count, sizeof(float) * 3,
                                         NULL, &report);
       if (r != MESHFIX_OK)
           printf("meshfix: %s\n", meshfix_result_string(r));
       else
           printf("flipped %u triangles\n", (unsigned)report.triangles_flipped);

       assert(meshfix_check(indices, index_count, positions, vertex_count,
                            sizeof(float) * 3, MESHFIX_REQUIRE_SOLID));

   MESH CONVENTIONS
   A mesh is a triangle list: index_count / 3 triangles of 32-bit indices into
   a vertex array whose first 12 bytes per vertex are float x, y, z.
   Front faces wind counter-clockwise (right-handed), so the face normal of
   (a, b, c) is (b - a) x (c - a). An edge is an unordered vertex pair; it is
   a boundary edge when one triangle uses it, manifold when two do and
   non-manifold when three or more do. Two triangles are consistently wound
   across a manifold edge when they traverse it in opposite directions; an
   edge where some direction is used by two triangles is inconsistent (what
   the glTF validator calls GEOMETRY_INCONSISTENT_WINDING; an edge of three
   or more triangles is always inconsistent). A patch is a maximal set of
   triangles connected through manifold edges; a component is a maximal set
   connected through any shared edge. A patch is closed when each of its
   edges is used by an even number of its own triangles. Triangles that
   repeat a vertex index are degenerate: they are counted, take no part in
   the topology and are never flipped. Flipping (a, b, c) writes (a, c, b):
   the first (provoking) vertex stays first.

   CONFIGURATION (define before including the implementation)
       MESHFIX_API           extern   linkage of the public functions
       MESHFIX_STATIC        -        makes every function static to the file
       MESHFIX_MALLOC(s,u)   malloc   allocation with the allocator's user_data;
       MESHFIX_FREE(p,u)     free     define both or neither
       MESHFIX_ASSERT(x)     assert   internal invariants only, never input
       MESHFIX_DEBUG         on when NDEBUG is not defined: extra invariant checks
       MESHFIX_MEMSET, MESHFIX_MEMCPY, MESHFIX_SQRT   string.h / math.h

   API
       meshfix_orient        repair winding into a destination buffer (or report only)
       meshfix_inspect       report topology and winding problems, never writes
       meshfix_inspect_ex    the same with options (allocator, per-component output)
       meshfix_check         one-line assertion for unit tests
       meshfix_scratch_size  bytes of scratch memory a call needs at most
       meshfix_result_string text of a result code

   ALGORITHM (orient and inspect share stages 1-5)
       1. validate: counts, pointers, stride, every index < vertex_count.
       2. edges: a counting sort puts every half-edge in the bucket of its
          lower vertex; each bucket is sorted by its higher vertex, so the
          half-edges of one edge lie together: a pair become mates, three
          or more are linked into a ring, a single one is a boundary.
       3. patches: breadth-first flood fill across manifold edges from the
          lowest unvisited triangle; each triangle gets its flip relative to
          the patch seed (a neighbour traversing the shared edge in the same
          direction must be flipped). A contradiction means the patch is
          non-orientable (Moebius): the fill still orients it as far as its
          spanning tree reaches and the remaining edges are reported.
       4. components: union-find over the rings of non-manifold edges; a
          patch is closed when it owns an even count of each ring.
       5. policy: each patch is then turned as a whole:
            SEED      keep the seed triangle as it is (the plain flood fill);
            MAJORITY  the side that flips less triangle area (or fewer
                      triangles without positions), so a patch with 90% of
                      its triangles wrong does not come out inside-out;
            OUTWARD   closed patches get positive signed volume; open ones
                      use MAJORITY. Each closed shell faces out on its own:
                      a cavity shell inside another is also turned outward
                      (nesting needs the ray caster, not in this version);
            SDF       for meshes extracted from a signed distance function:
                      the area-weighted vote of the SDF gradient over the
                      patch's triangles; per triangle (sdf_mode), the plain
                      rule: each triangle faces along the gradient at its
                      centroid. Per patch stays right where single samples
                      fail: triangles with no normal (zero area) and
                      triangles at sharp edges whose centroid gradient lies
                      in their plane (see tests/test_sdf.c);
            AUTO      OUTWARD with positions, MAJORITY without.
       6. write: copy indices to destination and swap the last two indices
          of each flipped triangle.
       Time O(index_count + vertex_count) (a vertex of k edges costs
       O(k log k)); hashing only for triangles whose three edges are all
       non-manifold, and only to count duplicates.
       Memory: one block of meshfix_scratch_size(vertex_count, index_count)
       bytes, 35 bytes per triangle + 4 per vertex, freed before return;
       none at all when the caller passes options.scratch.
       Speed (make bench, one run, same mesh, 1M triangles): the
       topology-only repair is ~4x faster than OpenMesh building its
       half-edge structure with both on warm memory; a call with a report
       takes 1.3x to 2x the time of the repair alone.
       References: the edge-map flood fill of the glTF winding auto-fix;
       P. Borodin, G. Zachmann, R. Klein, "Consistent Normal Orientation for
       Polygonal Meshes" (patches as the unit of orientation).

   DETERMINISM & THREAD SAFETY
   The output depends only on the inputs and options: counting sorts with
   index tie-breaks, BFS in index order, no hash iteration, no qsort. Sums
   are accumulated in double in a fixed order. Compilers that contract to
   FMA or use x87 precision can change decisions whose margin is within
   rounding (a patch whose two sides have equal area). There are no mutable
   statics: concurrent calls on different meshes are safe with no setup.

   ERRORS
   Every function returns a meshfix_result; data problems are results, never
   asserts. On any error nothing the caller passed is written (destination,
   report, options outputs), and everything allocated is freed.

   LIMITATIONS / DOES NOT
   - weld vertices: triangles connect only through shared indices;
   - orient across T-junctions, gaps or non-manifold edges (each patch is
     decided on its own there);
   - fill holes, remove degenerate or duplicate triangles, or change the
     triangle order or count;
   - detect nested shells (cavities) yet: OUTWARD faces every closed shell out.
   - index_count is limited to 2^31 - 1.

   VERSION HISTORY
       0.1.0  first release: inspect, flood fill with seed / majority /
              outward / auto / SDF policies, check, scratch-size query.
*/
#ifndef MESHFIX_H
#define MESHFIX_H

#include <stddef.h>

#define MESHFIX_VERSION_MAJOR 0
#define MESHFIX_VERSION_MINOR 1
#define MESHFIX_VERSION_PATCH 0
#define MESHFIX_VERSION (MESHFIX_VERSION_MAJOR * 10000 + MESHFIX_VERSION_MINOR * 100 + MESHFIX_VERSION_PATCH)

#ifndef MESHFIX_API
#ifdef MESHFIX_STATIC
#if defined(__GNUC__) || defined(__clang__)
#define MESHFIX_API static __attribute__((unused))
#else
#define MESHFIX_API static
#endif
#else
#define MESHFIX_API extern
#endif
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* Result codes and their text, from one list. */
#define MESHFIX_RESULT_LIST(X) \
    X(MESHFIX_OK, "ok") \
    X(MESHFIX_ERROR_INVALID_ARGUMENT, "invalid argument: NULL pointer with a non-zero count, bad stride or unknown option value") \
    X(MESHFIX_ERROR_NOT_TRIANGLES, "index count is not a multiple of 3") \
    X(MESHFIX_ERROR_INDEX_OUT_OF_RANGE, "an index is not less than vertex_count") \
    X(MESHFIX_ERROR_TOO_LARGE, "too large: index_count above 2^31-1, vertex_count above 2^32 or a size that overflows") \
    X(MESHFIX_ERROR_POSITIONS_REQUIRED, "the chosen policy needs vertex positions") \
    X(MESHFIX_ERROR_SCRATCH_TOO_SMALL, "options.scratch is smaller than meshfix_scratch_size()") \
    X(MESHFIX_ERROR_OUT_OF_MEMORY, "out of memory")

#define MESHFIX__RESULT_ENUM(name, text) name,
typedef enum meshfix_result {
    MESHFIX_RESULT_LIST(MESHFIX__RESULT_ENUM)
    MESHFIX_RESULT_COUNT
} meshfix_result;
#undef MESHFIX__RESULT_ENUM

/* Which way each consistently wound patch ends up facing. */
typedef enum meshfix_policy {
    MESHFIX_POLICY_AUTO = 0, /* OUTWARD with positions, MAJORITY without */
    MESHFIX_POLICY_SEED,     /* the patch's lowest triangle keeps its winding */
    MESHFIX_POLICY_MAJORITY, /* the side that flips less area (or fewer triangles) */
    MESHFIX_POLICY_OUTWARD,  /* closed patches by signed volume, open ones by MAJORITY */
    MESHFIX_POLICY_SDF,      /* along the gradient of options.sdf (needs positions and sdf) */
    MESHFIX_POLICY_COUNT
} meshfix_policy;

/* How MESHFIX_POLICY_SDF decides. */
typedef enum meshfix_sdf_mode {
    MESHFIX_SDF_PER_PATCH = 0, /* each patch by an area-weighted vote of its triangles */
    MESHFIX_SDF_PER_TRIANGLE   /* each triangle by the gradient at its centroid alone */
} meshfix_sdf_mode;

typedef struct meshfix_allocator {
    void *(*alloc_fn)(size_t size, void *user_data);
    void (*free_fn)(void *ptr, void *user_data);
    void *user_data;
} meshfix_allocator;

/* Per-component facts, filled by meshfix_orient / meshfix_inspect_ex when
   options.components is set. Components are numbered by their lowest triangle. */
typedef struct meshfix_component {
    size_t first_triangle;
    size_t triangles;          /* degenerate triangles belong to no component */
    size_t vertices;           /* distinct vertices used by its triangles */
    size_t edges;
    size_t edges_boundary;
    size_t edges_non_manifold;
    size_t patches;
    long euler_characteristic; /* vertices - edges + triangles; 2 for a sphere */
    int closed;                /* 1 when every edge is shared by exactly two of its triangles */
    int orientable;            /* 0 when a patch of it is non-orientable (Moebius, Klein) */
    double area;               /* 0 without positions */
    double signed_volume;      /* over its closed orientable patches, as returned */
} meshfix_component;

/* All fields zero = defaults; a NULL options pointer = all defaults. */
typedef struct meshfix_options {
    meshfix_policy policy;         /* default MESHFIX_POLICY_AUTO */
    meshfix_allocator allocator;   /* alloc_fn NULL = MESHFIX_MALLOC / MESHFIX_FREE */
    void *scratch;                 /* caller memory of scratch_size bytes: no allocation at all */
    size_t scratch_size;
    unsigned char *flipped;        /* optional out: index_count / 3 flags, 1 = flipped */
    unsigned int *patch_ids;       /* optional out: index_count / 3 patch ids, 0xFFFFFFFF = degenerate */
    meshfix_component *components; /* optional out: the first components_capacity components */
    size_t components_capacity;
    /* MESHFIX_POLICY_SDF: a signed distance function, negative inside. Its
       gradient at a triangle's centroid says which way is out. Without
       sdf_gradient it is taken by central differences, 6 calls per
       triangle, with a step of sdf_step, or when that is 0 a quarter of
       the triangle's longest edge (small enough to stay near the triangle)
       but at least 32 float steps of the centroid's coordinates
       (4e-6 * (1 + max |c|), so a sliver's stencil does not collapse). */
    float (*sdf)(const float position[3], void *user);
    void (*sdf_gradient)(const float position[3], float gradient[3], void *user); /* optional */
    void *sdf_user;
    float sdf_step;
    meshfix_sdf_mode sdf_mode;
} meshfix_options;

/* What a call found. For meshfix_orient it describes the mesh as returned
   (edges_inconsistent is what is left after repair); for inspect, the input. */
typedef struct meshfix_report {
    size_t triangles;
    size_t triangles_degenerate;  /* a vertex index repeats: excluded, never flipped */
    size_t triangles_zero_area;   /* with positions: zero or non-finite area */
    size_t triangles_duplicate;   /* same three vertices as a lower triangle, any order */
    size_t triangles_flipped;     /* orient only */
    size_t vertices_used;
    size_t vertices_non_finite;   /* used vertices with a NaN or infinite coordinate */
    size_t vertices_non_manifold; /* triangles around it form 2+ fans (bow-tie, or on an edge of 3+) */
    size_t edges;
    size_t edges_boundary;        /* 1 triangle */
    size_t edges_manifold;        /* 2 triangles */
    size_t edges_non_manifold;    /* 3 or more triangles */
    size_t edges_inconsistent;    /* a direction used by 2+ triangles */
    size_t edges_inconsistent_input; /* the same count before repair */
    size_t patches;
    size_t patches_closed;
    size_t patches_inside_out;    /* closed patches, wound one way, with clearly negative volume */
    size_t components;
    size_t components_closed;     /* every edge manifold */
    size_t components_non_orientable;
    long euler_characteristic;    /* sum over components of V - E + F */
    double area;                  /* 0 without positions */
    double signed_volume;         /* over closed orientable patches; 0 without positions */
    size_t triangles_sdf_disagree; /* SDF: triangles whose own gradient vote disagrees with their patch's */
    size_t sdf_evaluations;       /* SDF: calls of sdf and sdf_gradient */
} meshfix_report;

/* meshfix_check requirements; 0 means MESHFIX_REQUIRE_CONSISTENT. */
#define MESHFIX_REQUIRE_CONSISTENT   1u  /* no edge with a direction used twice */
#define MESHFIX_REQUIRE_CLOSED       2u  /* no boundary edge */
#define MESHFIX_REQUIRE_MANIFOLD     4u  /* no edge of 3+ triangles, no bow-tie vertex */
#define MESHFIX_REQUIRE_OUTWARD      8u  /* no closed patch inside-out (needs positions) */
#define MESHFIX_REQUIRE_NO_DEGENERATE 16u /* no repeated index, zero area or duplicate triangle */
#define MESHFIX_REQUIRE_SOLID        31u /* all of the above */

/* Repair winding.
   Makes every orientable patch consistently wound and turns each patch to
   the side its policy chooses. Triangle order and count are preserved; a
   flipped triangle (a, b, c) becomes (a, c, b). A mesh already wound the
   chosen way comes back unchanged with report->triangles_flipped == 0.
   Returns MESHFIX_OK or an error; on error nothing is written.

   destination receives index_count indices; may equal indices; may be NULL
   to get only the report and the options outputs.
   indices may be NULL only when index_count is 0.
   vertex_positions may be NULL for SEED, MAJORITY and AUTO (counts instead
   of areas); otherwise vertex_count vertices of vertex_positions_stride
   bytes (a multiple of 4, at least 12), x y z floats first.
   options and report can be NULL. Without a report (and without
   options->components) the descriptive counts are skipped, which saves a
   quarter to a half of the time (make bench). */
MESHFIX_API meshfix_result meshfix_orient(unsigned int *destination,
                                          const unsigned int *indices, size_t index_count,
                                          const float *vertex_positions, size_t vertex_count,
                                          size_t vertex_positions_stride,
                                          const meshfix_options *options,
                                          meshfix_report *report);

/* Inspect without writing anything but the report.
   Returns MESHFIX_OK or an error (then report is untouched).
   Arguments as for meshfix_orient; report must not be NULL. */
MESHFIX_API meshfix_result meshfix_inspect(const unsigned int *indices, size_t index_count,
                                           const float *vertex_positions, size_t vertex_count,
                                           size_t vertex_positions_stride,
                                           meshfix_report *report);

/* meshfix_inspect with options: allocator, scratch, patch_ids and
   components are used; policy and flipped are ignored. */
MESHFIX_API meshfix_result meshfix_inspect_ex(const unsigned int *indices, size_t index_count,
                                              const float *vertex_positions, size_t vertex_count,
                                              size_t vertex_positions_stride,
                                              const meshfix_options *options,
                                              meshfix_report *report);

/* One-line assertion for unit tests.
   Returns 1 when the mesh is valid input and meets every MESHFIX_REQUIRE_*
   bit of requirements (0 = MESHFIX_REQUIRE_CONSISTENT), else 0.
   vertex_positions can be NULL unless OUTWARD or NO_DEGENERATE is asked. */
MESHFIX_API int meshfix_check(const unsigned int *indices, size_t index_count,
                              const float *vertex_positions, size_t vertex_count,
                              size_t vertex_positions_stride, unsigned int requirements);

/* Scratch bytes that any call on a mesh of these counts needs at most.
   Returns 0 when the counts are too large (the call would return
   MESHFIX_ERROR_TOO_LARGE) or index_count is 0 (no scratch needed). */
MESHFIX_API size_t meshfix_scratch_size(size_t vertex_count, size_t index_count);

/* Returns a static, never NULL, English text for a result code. */
MESHFIX_API const char *meshfix_result_string(meshfix_result result);

#ifdef __cplusplus
}
#endif
#endif /* MESHFIX_H */

/* ---- stop reading here if you only want the API ---- */

#if defined(__INTELLISENSE__) || defined(__CDT_PARSER__)
#define MESHFIX_IMPLEMENTATION
#endif

#ifdef MESHFIX_IMPLEMENTATION
#ifndef MESHFIX_IMPLEMENTATION_INCLUDED
#define MESHFIX_IMPLEMENTATION_INCLUDED

/* ===== >>config ===== */

#if defined(MESHFIX_MALLOC) != defined(MESHFIX_FREE)
#error "define both MESHFIX_MALLOC and MESHFIX_FREE, or neither"
#endif
#ifndef MESHFIX_MALLOC
#include <stdlib.h>
#define MESHFIX_MALLOC(size, user) ((void)(user), malloc(size))
#define MESHFIX_FREE(ptr, user) ((void)(user), free(ptr))
#endif
#ifndef MESHFIX_ASSERT
#include <assert.h>
#define MESHFIX_ASSERT(x) assert(x)
#endif
#if !defined(MESHFIX_MEMSET) || !defined(MESHFIX_MEMCPY)
#include <string.h>
#endif
#ifndef MESHFIX_MEMSET
#define MESHFIX_MEMSET(dst, value, size) memset((dst), (value), (size))
#endif
#ifndef MESHFIX_MEMCPY
#define MESHFIX_MEMCPY(dst, src, size) memcpy((dst), (src), (size))
#endif
#ifndef MESHFIX_SQRT
#include <math.h>
#define MESHFIX_SQRT(x) sqrt(x)
#endif
#if !defined(MESHFIX_DEBUG) && !defined(NDEBUG)
#define MESHFIX_DEBUG 1
#endif

#if defined(__GNUC__) || defined(__clang__)
#define MESHFIX__PRIVATE static __attribute__((unused))
#else
#define MESHFIX__PRIVATE static
#endif

/* Half-edge h = 3 * triangle + corner runs from indices[h] to the next
   corner. mate[h] holds the other half-edge of a manifold edge, NONE on a
   boundary, or the next member of a non-manifold edge's ring with RING set. */
#define MESHFIX__NONE 0xFFFFFFFFu
#define MESHFIX__RING 0x80000000u
#define MESHFIX__MAX_INDEX_COUNT ((size_t)0x7FFFFFFF)
#define MESHFIX__MAX_VERTEX_COUNT ((size_t)0xFFFFFFFFu)

/* triangle bits */
#define MESHFIX__TRI_RELATIVE   1u /* flipped relative to its patch seed */
#define MESHFIX__TRI_DEGENERATE 2u
#define MESHFIX__TRI_FLIP       4u /* final decision */
#define MESHFIX__TRI_CORNER_SEEN 8u /* << corner: fan walk visited corner 0, 1, 2 */
#define MESHFIX__TRI_DUPLICATE 64u /* same vertex set as a lower triangle */
#define MESHFIX__TRI_VOTE_OUT  128u /* SDF: as given, faces along the gradient */
#define MESHFIX__TRI_VOTE_IN   256u /* SDF: as given, faces against it */
/* patch bits */
#define MESHFIX__PATCH_OPEN           1u /* a boundary edge or an odd share of a ring */
#define MESHFIX__PATCH_NOT_MANIFOLD   2u /* has a boundary or non-manifold edge */
#define MESHFIX__PATCH_NON_ORIENTABLE 4u
#define MESHFIX__PATCH_PARITY         8u /* scratch bit while walking a ring */
#define MESHFIX__PATCH_FLIP          16u

typedef char meshfix__unsigned_int_is_32_bits[sizeof(unsigned int) == 4 ? 1 : -1];

/* ===== >>memory ===== */

typedef struct meshfix__plan {
    size_t mate, work, tri_bits, vertex_work, patch_start, patch_link, patch_bits;
    size_t total;
} meshfix__plan;

MESHFIX__PRIVATE int meshfix__add_size(size_t *total, size_t count, size_t element_size, size_t *offset)
{
    size_t bytes, aligned = (*total + 15u) & ~(size_t)15u;
    if (aligned < *total || (element_size != 0 && count > ((size_t)-1) / element_size))
        return 0;
    bytes = count * element_size;
    if (aligned + bytes < aligned)
        return 0;
    *offset = aligned;
    *total = aligned + bytes;
    return 1;
}

/* One block holds every array. `work` holds the edge buckets, then the
   duplicate table, then the flood fill's queue and patch ids; `mate` is
   reused at the end to group patches by component. On machines where a
   fresh page costs microseconds, these bytes are most of the time. */
MESHFIX__PRIVATE int meshfix__make_plan(meshfix__plan *plan, size_t vertex_range, size_t triangle_count)
{
    size_t total = 0, half_edges;
    if (triangle_count > MESHFIX__MAX_INDEX_COUNT / 3 || vertex_range > MESHFIX__MAX_VERTEX_COUNT)
        return 0;
    half_edges = triangle_count * 3;
    return meshfix__add_size(&total, half_edges, 4, &plan->mate) &&
           meshfix__add_size(&total, half_edges + 16, 4, &plan->work) &&
           meshfix__add_size(&total, triangle_count, 2, &plan->tri_bits) &&
           meshfix__add_size(&total, vertex_range + 1, 4, &plan->vertex_work) &&
           meshfix__add_size(&total, triangle_count + 1, 4, &plan->patch_start) &&
           meshfix__add_size(&total, triangle_count, 4, &plan->patch_link) &&
           meshfix__add_size(&total, triangle_count, 1, &plan->patch_bits) &&
           meshfix__add_size(&total, 0, 1, &plan->total) && (plan->total = total + 16) > total;
}

/* ===== >>validate ===== */

typedef struct meshfix__edge_entry {
    unsigned int high;      /* the higher vertex of the edge */
    unsigned int half_edge;
} meshfix__edge_entry;

typedef struct meshfix__mesh {
    const unsigned int *indices;
    size_t triangle_count;
    size_t vertex_range;          /* highest index + 1 */
    const char *positions;        /* NULL when not given */
    size_t stride;
    unsigned int *mate;           /* 3 per triangle */
    unsigned int *work;           /* 3 per triangle: edge buckets, duplicate table, flood fill */
    unsigned int *queue;          /* triangles in patch order (inside `work`) */
    unsigned int *tri_patch;      /* (inside `work`) */
    unsigned short *tri_bits;
    unsigned int *vertex_work;    /* sort counts, then vertex marks */
    unsigned int *patch_start;    /* patch p owns queue[patch_start[p] .. patch_start[p + 1]) */
    unsigned int *patch_link;     /* union-find parent, then component id */
    unsigned char *patch_bits;
    unsigned char *component_bits; /* (inside `work`, after tri_patch) */
    size_t patch_count;
    size_t component_count;
    const meshfix_options *options; /* the SDF callbacks; may be NULL */
    int policy;                     /* < 0: inspect */
} meshfix__mesh;

MESHFIX__PRIVATE meshfix_result meshfix__validate(const unsigned int *indices, size_t index_count,
                                                  const float *positions, size_t vertex_count,
                                                  size_t stride, size_t *vertex_range)
{
    size_t i;
    unsigned int highest = 0;
    if (index_count % 3 != 0)
        return MESHFIX_ERROR_NOT_TRIANGLES;
    if (index_count > MESHFIX__MAX_INDEX_COUNT || vertex_count > MESHFIX__MAX_VERTEX_COUNT)
        return MESHFIX_ERROR_TOO_LARGE;
    if (index_count != 0 && indices == NULL)
        return MESHFIX_ERROR_INVALID_ARGUMENT;
    if (positions != NULL && (stride < 3 * sizeof(float) || stride % sizeof(float) != 0))
        return MESHFIX_ERROR_INVALID_ARGUMENT;
    if (positions != NULL && vertex_count > 0 && (vertex_count - 1) > ((size_t)-1) / stride)
        return MESHFIX_ERROR_TOO_LARGE;
    for (i = 0; i < index_count; ++i)
        highest = indices[i] > highest ? indices[i] : highest;
    if (index_count != 0 && (size_t)highest >= vertex_count)
        return MESHFIX_ERROR_INDEX_OUT_OF_RANGE;
    *vertex_range = index_count != 0 ? (size_t)highest + 1 : 0;
    return MESHFIX_OK;
}

MESHFIX__PRIVATE const float *meshfix__position(const meshfix__mesh *m, unsigned int vertex)
{
    return (const float *)(const void *)(m->positions + (size_t)vertex * m->stride);
}

MESHFIX__PRIVATE int meshfix__is_finite(float x)
{
    return (x - x) == 0.0f; /* NaN and infinities give NaN */
}

MESHFIX__PRIVATE size_t meshfix__mark_degenerate(meshfix__mesh *m)
{
    size_t t, count = 0;
    for (t = 0; t < m->triangle_count; ++t) {
        const unsigned int *v = m->indices + 3 * t;
        int degenerate = v[0] == v[1] || v[1] == v[2] || v[0] == v[2];
        m->tri_bits[t] = (unsigned short)(degenerate ? MESHFIX__TRI_DEGENERATE : 0);
        count += (size_t)degenerate;
    }
    return count;
}

/* ===== >>edges ===== */

typedef struct meshfix__edge_counts {
    size_t edges, boundary, manifold, non_manifold;
} meshfix__edge_counts;

MESHFIX__PRIVATE unsigned int meshfix__edge_high(const meshfix__mesh *m, unsigned int h)
{
    unsigned int a = m->indices[h], b = m->indices[h % 3 == 2 ? h - 2 : h + 1];
    return a < b ? b : a;
}

MESHFIX__PRIVATE int meshfix__entry_less(const meshfix__edge_entry *a, const meshfix__edge_entry *b)
{
    return a->high < b->high || (a->high == b->high && a->half_edge < b->half_edge);
}

MESHFIX__PRIVATE int meshfix__half_edge_less(const meshfix__mesh *m, unsigned int a, unsigned int b)
{
    unsigned int ka = meshfix__edge_high(m, a), kb = meshfix__edge_high(m, b);
    return ka < kb || (ka == kb && a < b);
}

MESHFIX__PRIVATE void meshfix__sift_down(const meshfix__mesh *m, unsigned int *e, size_t root, size_t n)
{
    for (;;) {
        size_t child = 2 * root + 1;
        unsigned int x;
        if (child >= n)
            return;
        if (child + 1 < n && meshfix__half_edge_less(m, e[child], e[child + 1]))
            child++;
        if (!meshfix__half_edge_less(m, e[root], e[child]))
            return;
        x = e[root];
        e[root] = e[child];
        e[child] = x;
        root = child;
    }
}

/* Links the half-edges of one undirected edge (a run of a sorted bucket):
   a pair becomes mates, three or more a ring in increasing order. */
MESHFIX__PRIVATE void meshfix__link_edge(meshfix__mesh *m, const unsigned int *run, size_t n,
                                         meshfix__edge_counts *counts)
{
    size_t k;
    counts->edges++;
    if (n == 1) {
        counts->boundary++;
    } else if (n == 2) {
        counts->manifold++;
        m->mate[run[0]] = run[1];
        m->mate[run[1]] = run[0];
    } else {
        counts->non_manifold++;
        for (k = 0; k < n; ++k)
            m->mate[run[k]] = run[k + 1 < n ? k + 1 : 0] | MESHFIX__RING;
    }
}

/* Sorts a bucket of half-edges by (higher vertex, half-edge) and links
   each run of one edge. A bucket holds the edges of one vertex, a handful
   in a mesh: sorted as (key, id) pairs on the stack. A vertex shared by
   thousands of triangles takes heapsort in place, O(k log k) with no
   memory. The order is total, so both give the same links. */
#define MESHFIX__SMALL_BUCKET 32
MESHFIX__PRIVATE void meshfix__link_bucket(meshfix__mesh *m, unsigned int *ids, size_t n,
                                           meshfix__edge_counts *counts)
{
    size_t i, j;
    if (n <= MESHFIX__SMALL_BUCKET) {
        meshfix__edge_entry e[MESHFIX__SMALL_BUCKET];
        for (i = 0; i < n; ++i) {
            meshfix__edge_entry x;
            x.high = meshfix__edge_high(m, ids[i]);
            x.half_edge = ids[i];
            for (j = i; j > 0 && meshfix__entry_less(&x, &e[j - 1]); --j)
                e[j] = e[j - 1];
            e[j] = x;
        }
        for (i = 0; i < n; ++i)
            ids[i] = e[i].half_edge;
        for (i = 0; i < n; i = j) {
            for (j = i + 1; j < n && e[j].high == e[i].high; ++j) {
            }
            meshfix__link_edge(m, ids + i, j - i, counts);
        }
        return;
    }
    for (i = n / 2; i-- > 0;)
        meshfix__sift_down(m, ids, i, n);
    for (i = n - 1; i > 0; --i) {
        unsigned int x = ids[0];
        ids[0] = ids[i];
        ids[i] = x;
        meshfix__sift_down(m, ids, 0, i);
    }
    for (i = 0; i < n; i = j) {
        unsigned int high = meshfix__edge_high(m, ids[i]);
        for (j = i + 1; j < n && meshfix__edge_high(m, ids[j]) == high; ++j) {
        }
        meshfix__link_edge(m, ids + i, j - i, counts);
    }
}

/* Groups the half-edges by undirected edge: a counting sort into one
   bucket per lower vertex (each bucket in increasing half-edge order),
   then each bucket sorted by its higher vertex and cut into runs. */
MESHFIX__PRIVATE void meshfix__build_edges(meshfix__mesh *m, meshfix__edge_counts *counts)
{
    unsigned int *end = m->vertex_work, *ids = m->work, sum = 0, k;
    size_t t, v, begin = 0;
    MESHFIX_MEMSET(end, 0, (m->vertex_range + 1) * sizeof(unsigned int));
    for (t = 0; t < m->triangle_count; ++t) {
        const unsigned int *tri = m->indices + 3 * t;
        if (m->tri_bits[t] & MESHFIX__TRI_DEGENERATE)
            continue;
        for (k = 0; k < 3; ++k) {
            unsigned int a = tri[k], b = tri[k == 2 ? 0 : k + 1];
            end[a < b ? a : b]++;
        }
    }
    for (v = 0; v <= m->vertex_range; ++v) {
        unsigned int n = end[v];
        end[v] = sum;
        sum += n;
    }
    for (t = 0; t < m->triangle_count; ++t) {
        const unsigned int *tri = m->indices + 3 * t;
        if (m->tri_bits[t] & MESHFIX__TRI_DEGENERATE)
            continue;
        for (k = 0; k < 3; ++k) {
            unsigned int a = tri[k], b = tri[k == 2 ? 0 : k + 1];
            ids[end[a < b ? a : b]++] = (unsigned int)(3 * t) + k;
        }
    }
    /* end[v] is now where bucket v ends */
    MESHFIX_MEMSET(m->mate, 0xFF, 3 * m->triangle_count * sizeof(unsigned int));
    MESHFIX_MEMSET(counts, 0, sizeof(*counts));
    for (v = 0; v < m->vertex_range; begin = end[v++])
        meshfix__link_bucket(m, ids + begin, end[v] - begin, counts);
}

MESHFIX__PRIVATE int meshfix__is_mate(unsigned int link)
{
    return !(link & MESHFIX__RING);
}

MESHFIX__PRIVATE int meshfix__is_ring(unsigned int link)
{
    return link != MESHFIX__NONE && (link & MESHFIX__RING);
}

/* Members of a ring are linked in increasing order, so the member whose
   successor is smaller is the last one: each ring is visited once from it. */
MESHFIX__PRIVATE int meshfix__is_ring_last(const meshfix__mesh *m, unsigned int h)
{
    unsigned int link = m->mate[h];
    return meshfix__is_ring(link) && (link & ~MESHFIX__RING) < h;
}

MESHFIX__PRIVATE int meshfix__same_direction(const meshfix__mesh *m, unsigned int h, unsigned int g)
{
    return m->indices[h] == m->indices[g];
}

/* ===== >>duplicates ===== */

MESHFIX__PRIVATE void meshfix__sorted_triangle(const meshfix__mesh *m, size_t t, unsigned int s[3])
{
    unsigned int a = m->indices[3 * t], b = m->indices[3 * t + 1], c = m->indices[3 * t + 2], x;
    if (a > b) { x = a; a = b; b = x; }
    if (b > c) { x = b; b = c; c = x; }
    if (a > b) { x = a; a = b; b = x; }
    s[0] = a; s[1] = b; s[2] = c;
}

MESHFIX__PRIVATE unsigned int meshfix__hash_triple(const unsigned int s[3])
{
    unsigned int h = s[0] * 0x9E3779B1u;
    h = (h ^ (h >> 15) ^ s[1]) * 0x85EBCA77u;
    h = (h ^ (h >> 13) ^ s[2]) * 0xC2B2AE3Du;
    return h ^ (h >> 16);
}

MESHFIX__PRIVATE unsigned int meshfix__apex(const meshfix__mesh *m, unsigned int h)
{
    return m->indices[h % 3 == 0 ? h + 2 : h - 1];
}

MESHFIX__PRIVATE void meshfix__mark_duplicate(meshfix__mesh *m, size_t t)
{
    m->tri_bits[t] = (unsigned short)(m->tri_bits[t] | MESHFIX__TRI_DUPLICATE);
}

/* Triangles with the same vertex set share all three edges. If one of
   those edges is manifold the two are its pair, with the same apex; if
   none is, all three edges are non-manifold, which is rare, and those
   triangles go through a table keyed by their sorted vertices (in the
   free `work` buffer). The table only marks triangles; counts do not
   depend on where anything landed in it. */
MESHFIX__PRIVATE int meshfix__all_edges_non_manifold(const meshfix__mesh *m, size_t t)
{
    return meshfix__is_ring(m->mate[3 * t]) && meshfix__is_ring(m->mate[3 * t + 1]) &&
           meshfix__is_ring(m->mate[3 * t + 2]);
}

MESHFIX__PRIVATE size_t meshfix__count_duplicates(meshfix__mesh *m)
{
    unsigned int *slots = m->work, h, half_edges = (unsigned int)(3 * m->triangle_count);
    size_t size = 4, mask, t, count = 0, candidates = 0;
    for (h = 0; h < half_edges; ++h) {
        unsigned int g = m->mate[h];
        if (meshfix__is_mate(g) && h < g && meshfix__apex(m, h) == meshfix__apex(m, g))
            meshfix__mark_duplicate(m, g / 3);
    }
    for (t = 0; t < m->triangle_count; ++t)
        candidates += (size_t)meshfix__all_edges_non_manifold(m, t);
    /* at most two thirds full, and never more than the 3 per triangle of `work` */
    while (size < candidates + candidates / 2)
        size *= 2;
    mask = size - 1;
    if (candidates != 0)
        MESHFIX_MEMSET(slots, 0xFF, size * sizeof(unsigned int));
    for (t = 0; t < m->triangle_count && candidates != 0; ++t) {
        unsigned int key[3], other[3];
        size_t i;
        if (!meshfix__all_edges_non_manifold(m, t))
            continue;
        meshfix__sorted_triangle(m, t, key);
        for (i = meshfix__hash_triple(key) & mask;; i = (i + 1) & mask) {
            if (slots[i] == MESHFIX__NONE) {
                slots[i] = (unsigned int)t;
                break;
            }
            meshfix__sorted_triangle(m, slots[i], other);
            if (other[0] == key[0] && other[1] == key[1] && other[2] == key[2]) {
                meshfix__mark_duplicate(m, t);
                break;
            }
        }
    }
    for (t = 0; t < m->triangle_count; ++t)
        count += (size_t)((m->tri_bits[t] & MESHFIX__TRI_DUPLICATE) != 0);
    return count;
}

/* ===== >>fans ===== */

/* A vertex is manifold when the triangles around it form one fan: one
   chain linked through manifold edges, closed or open. Walking the chain
   needs no orientation: in each triangle, leave by the other edge at v. */
MESHFIX__PRIVATE unsigned int meshfix__corner_of(const meshfix__mesh *m, unsigned int t, unsigned int v)
{
    return m->indices[3 * t] == v ? 0u : m->indices[3 * t + 1] == v ? 1u : 2u;
}

MESHFIX__PRIVATE void meshfix__mark_corner(meshfix__mesh *m, unsigned int t, unsigned int corner)
{
    m->tri_bits[t] = (unsigned short)(m->tri_bits[t] | (MESHFIX__TRI_CORNER_SEEN << corner));
}

/* Walks from triangle t across half-edge h (which touches v) until the fan
   ends or comes back to t. Returns 1 when it came back: a closed fan. */
MESHFIX__PRIVATE int meshfix__walk_fan(meshfix__mesh *m, unsigned int t, unsigned int h, unsigned int v)
{
    for (;;) {
        unsigned int g = m->mate[h], u, corner;
        if (!meshfix__is_mate(g))
            return 0;
        u = g / 3;
        if (u == t)
            return 1;
        corner = meshfix__corner_of(m, u, v);
        meshfix__mark_corner(m, u, corner);
        /* g is u's outgoing or incoming half-edge at v; leave by the other */
        h = g == 3 * u + corner ? 3 * u + (corner + 2) % 3 : 3 * u + corner;
    }
}

MESHFIX__PRIVATE size_t meshfix__count_non_manifold_vertices(meshfix__mesh *m)
{
    unsigned int *fans = m->vertex_work, t, corner;
    size_t v, count = 0;
    MESHFIX_MEMSET(fans, 0, m->vertex_range * sizeof(unsigned int));
    for (t = 0; t < m->triangle_count; ++t) {
        if (m->tri_bits[t] & MESHFIX__TRI_DEGENERATE)
            continue;
        for (corner = 0; corner < 3; ++corner) {
            unsigned int vertex = m->indices[3 * t + corner];
            if (m->tri_bits[t] & (MESHFIX__TRI_CORNER_SEEN << corner))
                continue;
            meshfix__mark_corner(m, t, corner);
            fans[vertex]++;
            if (!meshfix__walk_fan(m, t, 3 * t + corner, vertex))
                meshfix__walk_fan(m, t, 3 * t + (corner + 2) % 3, vertex);
        }
    }
    for (v = 0; v < m->vertex_range; ++v)
        count += (size_t)(fans[v] > 1);
    return count;
}

/* ===== >>patches ===== */

/* The manifold neighbours of t as half-edges, ordered by neighbour
   triangle: an order that flipping t does not change, so the spanning tree
   (and the seam left in a non-orientable patch) is the same on every run.
   Returns how many; marks the patch when t has other kinds of edges. */
MESHFIX__PRIVATE unsigned int meshfix__neighbours(meshfix__mesh *m, unsigned int t, unsigned int patch,
                                                 unsigned int h_out[3])
{
    unsigned int h, n = 0, i, j, u[3];
    for (h = 3 * t; h < 3 * t + 3; ++h) {
        unsigned int g = m->mate[h];
        if (meshfix__is_mate(g)) {
            u[n] = g / 3;
            h_out[n++] = h;
            continue;
        }
        m->patch_bits[patch] |= MESHFIX__PATCH_NOT_MANIFOLD;
        if (g == MESHFIX__NONE)
            m->patch_bits[patch] |= MESHFIX__PATCH_OPEN;
    }
    for (i = 1; i < n; ++i)
        for (j = i; j > 0 && u[j - 1] > u[j]; --j) {
            unsigned int x = h_out[j], y = u[j];
            h_out[j] = h_out[j - 1];
            u[j] = u[j - 1];
            h_out[j - 1] = x;
            u[j - 1] = y;
        }
    return n;
}

/* Breadth-first flood fill across manifold edges. The seed of each patch is
   its lowest triangle; a neighbour that runs the shared edge the same way
   gets the opposite relative flip. */
MESHFIX__PRIVATE void meshfix__flood_patches(meshfix__mesh *m)
{
    size_t seed, head = 0, tail = 0;
    unsigned int patch = 0;
    for (seed = 0; seed < m->triangle_count; ++seed)
        m->tri_patch[seed] = MESHFIX__NONE;
    for (seed = 0; seed < m->triangle_count; ++seed) {
        if (m->tri_patch[seed] != MESHFIX__NONE || (m->tri_bits[seed] & MESHFIX__TRI_DEGENERATE))
            continue;
        m->patch_start[patch] = (unsigned int)tail;
        m->patch_bits[patch] = 0;
        m->tri_patch[seed] = patch;
        m->queue[tail++] = (unsigned int)seed;
        while (head < tail) {
            unsigned int t = m->queue[head++], half_edges[3], i;
            unsigned int relative = m->tri_bits[t] & MESHFIX__TRI_RELATIVE;
            unsigned int count = meshfix__neighbours(m, t, patch, half_edges);
            for (i = 0; i < count; ++i) {
                unsigned int h = half_edges[i], g = m->mate[h], u = g / 3;
                unsigned int wanted = relative ^ (unsigned int)meshfix__same_direction(m, h, g);
                if (m->tri_patch[u] == MESHFIX__NONE) {
                    m->tri_patch[u] = patch;
                    m->tri_bits[u] = (unsigned short)((m->tri_bits[u] & ~MESHFIX__TRI_RELATIVE) | wanted);
                    m->queue[tail++] = u;
                } else if ((m->tri_bits[u] & MESHFIX__TRI_RELATIVE) != wanted) {
                    m->patch_bits[patch] |= MESHFIX__PATCH_NON_ORIENTABLE;
                }
            }
        }
        patch++;
    }
    m->patch_start[patch] = (unsigned int)tail;
    m->patch_count = patch;
}

/* ===== >>components ===== */

MESHFIX__PRIVATE unsigned int meshfix__find_root(unsigned int *parent, unsigned int p)
{
    while (parent[p] != p) {
        parent[p] = parent[parent[p]];
        p = parent[p];
    }
    return p;
}

MESHFIX__PRIVATE void meshfix__unite(unsigned int *parent, unsigned int a, unsigned int b)
{
    a = meshfix__find_root(parent, a);
    b = meshfix__find_root(parent, b);
    if (a < b)
        parent[b] = a;
    else if (b < a)
        parent[a] = b;
}

/* A patch that owns an odd number of a ring's half-edges has an unmatched
   side there: it is open. Two passes over the ring with a parity bit. */
MESHFIX__PRIVATE void meshfix__walk_ring(meshfix__mesh *m, unsigned int last)
{
    unsigned int first = m->mate[last] & ~MESHFIX__RING, h = first;
    unsigned int first_patch = m->tri_patch[first / 3];
    for (;;) {
        unsigned int p = m->tri_patch[h / 3];
        m->patch_bits[p] ^= MESHFIX__PATCH_PARITY;
        meshfix__unite(m->patch_link, first_patch, p);
        if (h == last)
            break;
        h = m->mate[h] & ~MESHFIX__RING;
    }
    for (h = first;; h = m->mate[h] & ~MESHFIX__RING) {
        unsigned int p = m->tri_patch[h / 3];
        if (m->patch_bits[p] & MESHFIX__PATCH_PARITY)
            m->patch_bits[p] = (unsigned char)((m->patch_bits[p] & ~MESHFIX__PATCH_PARITY) | MESHFIX__PATCH_OPEN);
        if (h == last)
            break;
    }
}

/* Joins patches that share non-manifold edges into components, numbered by
   their lowest patch; afterwards patch_link[p] is p's component id. */
MESHFIX__PRIVATE void meshfix__join_components(meshfix__mesh *m)
{
    unsigned int p, h, count = 0, half_edges = (unsigned int)(3 * m->triangle_count);
    for (p = 0; p < m->patch_count; ++p)
        m->patch_link[p] = p;
    for (h = 0; h < half_edges; ++h)
        if (meshfix__is_ring_last(m, h))
            meshfix__walk_ring(m, h);
    for (p = 0; p < m->patch_count; ++p) {
        unsigned int root = meshfix__find_root(m->patch_link, p);
        m->patch_link[p] = root == p ? count++ : m->patch_link[root];
    }
    m->component_count = count;
}

/* What a patch's triangles add up to, in two frames: as given, and as the
   flood fill made them consistent ("relative": each one flipped by its
   relative bit). Volumes are taken about the patch's first vertex. */
typedef struct meshfix__patch_sums {
    double weight_kept;     /* weight of triangles with relative bit 0 */
    double weight_reversed; /* weight of triangles with relative bit 1 */
    double area;
    double volume_given;
    double volume_relative;
    size_t zero_area;
    size_t reversed;        /* triangles with relative bit 1: the patch is not consistent as given */
    double sdf_vote;        /* SDF: area-weighted vote, relative frame; > 0 keeps the seed side */
    size_t sdf_evaluations;
} meshfix__patch_sums;

MESHFIX__PRIVATE void meshfix__load_corner(const meshfix__mesh *m, unsigned int vertex, const double origin[3],
                                          double out[3])
{
    const float *v = meshfix__position(m, vertex);
    out[0] = (double)v[0] - origin[0];
    out[1] = (double)v[1] - origin[1];
    out[2] = (double)v[2] - origin[2];
}

/* ===== >>sdf ===== */

MESHFIX__PRIVATE double meshfix__max3(double a, double b, double c)
{
    return a > b ? (a > c ? a : c) : (b > c ? b : c);
}

/* The SDF gradient at p: the caller's, or central differences. Returns 0
   when it is not finite or zero (no vote). */
MESHFIX__PRIVATE int meshfix__sdf_gradient(const meshfix_options *o, const float p[3], float step, double g[3],
                                          size_t *evaluations)
{
    int axis;
    if (o->sdf_gradient != NULL) {
        float out[3];
        o->sdf_gradient(p, out, o->sdf_user);
        (*evaluations)++;
        g[0] = out[0], g[1] = out[1], g[2] = out[2];
    } else {
        for (axis = 0; axis < 3; ++axis) {
            float q[3];
            double ahead, behind;
            q[0] = p[0], q[1] = p[1], q[2] = p[2];
            q[axis] = p[axis] + step;
            ahead = (double)o->sdf(q, o->sdf_user);
            q[axis] = p[axis] - step;
            behind = (double)o->sdf(q, o->sdf_user);
            g[axis] = ahead - behind;
        }
        *evaluations += 6;
    }
    return g[0] * 0 + g[1] * 0 + g[2] * 0 == 0 && (g[0] != 0 || g[1] != 0 || g[2] != 0);
}

/* Marks how triangle t faces, as given, against the SDF gradient at its
   centroid; returns +1 along, -1 against, 0 no vote. a, b, c are its
   corners relative to origin, n its (unnormalised) normal. */
MESHFIX__PRIVATE int meshfix__sdf_vote(meshfix__mesh *m, unsigned int t, const double origin[3], const double a[3],
                                      const double b[3], const double c[3], const double n[3],
                                      size_t *evaluations)
{
    const meshfix_options *o = m->options;
    float centroid[3], step = o->sdf_step;
    double g[3], dot;
    int k, vote;
    for (k = 0; k < 3; ++k)
        centroid[k] = (float)(origin[k] + (a[k] + b[k] + c[k]) / 3.0);
    if (!(step > 0.0f)) {
        double ab = (b[0] - a[0]) * (b[0] - a[0]) + (b[1] - a[1]) * (b[1] - a[1]) + (b[2] - a[2]) * (b[2] - a[2]);
        double bc = (c[0] - b[0]) * (c[0] - b[0]) + (c[1] - b[1]) * (c[1] - b[1]) + (c[2] - b[2]) * (c[2] - b[2]);
        double ca = (a[0] - c[0]) * (a[0] - c[0]) + (a[1] - c[1]) * (a[1] - c[1]) + (a[2] - c[2]) * (a[2] - c[2]);
        double magnitude = meshfix__max3(centroid[0] < 0 ? -centroid[0] : centroid[0],
                                         centroid[1] < 0 ? -centroid[1] : centroid[1],
                                         centroid[2] < 0 ? -centroid[2] : centroid[2]);
        double quarter = 0.25 * MESHFIX_SQRT(meshfix__max3(ab, bc, ca));
        /* a sliver's quarter edge can vanish in float next to its position */
        double least = 4e-6 * (1.0 + magnitude);
        step = (float)(quarter > least ? quarter : least);
    }
    if (!meshfix__sdf_gradient(o, centroid, step, g, evaluations))
        return 0;
    dot = n[0] * g[0] + n[1] * g[1] + n[2] * g[2];
    vote = dot > 0 ? 1 : dot < 0 ? -1 : 0;
    m->tri_bits[t] = (unsigned short)(m->tri_bits[t] | (vote > 0 ? MESHFIX__TRI_VOTE_OUT : 0u) |
                                      (vote < 0 ? MESHFIX__TRI_VOTE_IN : 0u));
    return vote;
}

/* ===== >>orient ===== */

MESHFIX__PRIVATE void meshfix__sum_patch(meshfix__mesh *m, unsigned int patch, meshfix__patch_sums *s)
{
    unsigned int i, end = m->patch_start[patch + 1];
    double origin[3] = {0, 0, 0};
    MESHFIX_MEMSET(s, 0, sizeof(*s));
    for (i = m->patch_start[patch]; i < end; ++i)
        s->reversed += (size_t)(m->tri_bits[m->queue[i]] & MESHFIX__TRI_RELATIVE);
    if (m->positions == NULL) {
        s->weight_reversed = (double)s->reversed;
        s->weight_kept = (double)(end - m->patch_start[patch] - s->reversed);
        return;
    }
    /* volumes about a vertex of the patch, not the far-away origin, so
       closed shells keep their precision */
    meshfix__load_corner(m, m->indices[3 * m->queue[m->patch_start[patch]]], origin, origin);
    for (i = m->patch_start[patch]; i < end; ++i) {
        unsigned int t = m->queue[i];
        const unsigned int *tri = m->indices + 3 * (size_t)t;
        double a[3], b[3], c[3], n[3], area, volume;
        meshfix__load_corner(m, tri[0], origin, a);
        meshfix__load_corner(m, tri[1], origin, b);
        meshfix__load_corner(m, tri[2], origin, c);
        n[0] = (b[1] - a[1]) * (c[2] - a[2]) - (b[2] - a[2]) * (c[1] - a[1]);
        n[1] = (b[2] - a[2]) * (c[0] - a[0]) - (b[0] - a[0]) * (c[2] - a[2]);
        n[2] = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
        area = 0.5 * MESHFIX_SQRT(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        /* a NaN or infinite coordinate leaves a NaN or infinite area: weight 0 */
        if (!(area > 0.0 && area - area == 0.0)) {
            s->zero_area++;
            continue;
        }
        volume = (a[0] * (b[1] * c[2] - b[2] * c[1]) + a[1] * (b[2] * c[0] - b[0] * c[2]) +
                  a[2] * (b[0] * c[1] - b[1] * c[0])) / 6.0;
        s->area += area;
        s->volume_given += volume;
        if (m->policy == MESHFIX_POLICY_SDF) {
            int vote = meshfix__sdf_vote(m, t, origin, a, b, c, n, &s->sdf_evaluations);
            s->sdf_vote += (m->tri_bits[t] & MESHFIX__TRI_RELATIVE) ? -vote * area : vote * area;
        }
        if (m->tri_bits[t] & MESHFIX__TRI_RELATIVE) {
            s->weight_reversed += area;
            s->volume_relative -= volume;
        } else {
            s->weight_kept += area;
            s->volume_relative += volume;
        }
    }
}

/* A volume this small next to the patch's area is flat (a two-sided sheet
   closed on itself): its sign says nothing, so it is not used. */
MESHFIX__PRIVATE int meshfix__volume_is_meaningful(double volume, double area)
{
    double magnitude = volume < 0 ? -volume : volume;
    return area > 0.0 && magnitude > 1e-9 * area * MESHFIX_SQRT(area);
}

MESHFIX__PRIVATE int meshfix__is_closed_orientable(const meshfix__mesh *m, unsigned int patch)
{
    return !(m->patch_bits[patch] & (MESHFIX__PATCH_OPEN | MESHFIX__PATCH_NON_ORIENTABLE));
}

/* Returns 1 when the patch should be turned over (relative to its seed). */
MESHFIX__PRIVATE int meshfix__decide_patch(const meshfix__mesh *m, unsigned int patch,
                                          meshfix_policy policy, const meshfix__patch_sums *s)
{
    if (policy == MESHFIX_POLICY_SEED)
        return 0;
    if (policy == MESHFIX_POLICY_SDF && s->sdf_vote != 0.0)
        return s->sdf_vote < 0.0;
    if (policy == MESHFIX_POLICY_OUTWARD && meshfix__is_closed_orientable(m, patch) &&
        meshfix__volume_is_meaningful(s->volume_relative, s->area))
        return s->volume_relative < 0.0;
    /* MAJORITY: turning the patch flips the kept triangles instead of the
       reversed ones; keep the seed side on a tie. Areas that are all zero
       fall back to counting triangles. */
    if (s->weight_kept + s->weight_reversed > 0.0)
        return s->weight_kept < s->weight_reversed;
    {
        unsigned int i, kept = 0, reversed = 0;
        for (i = m->patch_start[patch]; i < m->patch_start[patch + 1]; ++i) {
            unsigned int relative = m->tri_bits[m->queue[i]] & MESHFIX__TRI_RELATIVE;
            kept += !relative;
            reversed += relative;
        }
        return kept < reversed;
    }
}

/* ===== >>report ===== */

MESHFIX__PRIVATE unsigned int meshfix__flip_of(const meshfix__mesh *m, unsigned int t)
{
    return (m->tri_bits[t] & MESHFIX__TRI_FLIP) ? 1u : 0u;
}

/* A manifold edge is inconsistent when, after the flips, both triangles run
   it the same way; an edge of 3+ triangles always repeats a direction. */
MESHFIX__PRIVATE size_t meshfix__count_inconsistent(const meshfix__mesh *m, int with_flips)
{
    unsigned int h, half_edges = (unsigned int)(3 * m->triangle_count);
    size_t count = 0;
    for (h = 0; h < half_edges; ++h) {
        unsigned int g = m->mate[h];
        if (meshfix__is_ring_last(m, h)) {
            count++;
        } else if (meshfix__is_mate(g) && h < g) {
            unsigned int flips = with_flips ? meshfix__flip_of(m, h / 3) ^ meshfix__flip_of(m, g / 3) : 0u;
            count += (size_t)((unsigned int)meshfix__same_direction(m, h, g) ^ flips);
        }
    }
    return count;
}

MESHFIX__PRIVATE meshfix_component *meshfix__component_out(const meshfix_options *o, unsigned int component)
{
    return o != NULL && o->components != NULL && component < o->components_capacity ? &o->components[component] : NULL;
}

/* Counts each edge once, for the component of its triangles. */
MESHFIX__PRIVATE void meshfix__count_component_edges(const meshfix__mesh *m, const meshfix_options *o)
{
    unsigned int h, half_edges = (unsigned int)(3 * m->triangle_count);
    for (h = 0; h < half_edges; ++h) {
        unsigned int g = m->mate[h];
        meshfix_component *c;
        if (m->tri_bits[h / 3] & MESHFIX__TRI_DEGENERATE)
            continue;
        c = meshfix__component_out(o, m->patch_link[m->tri_patch[h / 3]]);
        if (c == NULL)
            continue;
        if (g == MESHFIX__NONE) {
            c->edges++;
            c->edges_boundary++;
        } else if (meshfix__is_ring_last(m, h)) {
            c->edges++;
            c->edges_non_manifold++;
        } else if (meshfix__is_mate(g) && h < g) {
            c->edges++;
        }
    }
}

/* Distinct vertices per component: patches are grouped by component (a
   counting sort into the free `mate` buffer), then a vertex is counted the
   first time each component touches it. Returns the sum over components. */
MESHFIX__PRIVATE size_t meshfix__count_component_vertices(meshfix__mesh *m, const meshfix_options *o,
                                                          meshfix_report *r)
{
    unsigned int *offsets = m->mate, *order = m->mate + m->component_count + 1, *mark = m->vertex_work;
    unsigned int p, c, i, sum = 0;
    size_t pairs = 0;
    MESHFIX_MEMSET(offsets, 0, (m->component_count + 1) * sizeof(unsigned int));
    MESHFIX_MEMSET(mark, 0, m->vertex_range * sizeof(unsigned int));
    for (p = 0; p < m->patch_count; ++p)
        offsets[m->patch_link[p]]++;
    for (c = 0; c <= m->component_count; ++c) {
        unsigned int n = offsets[c];
        offsets[c] = sum;
        sum += n;
    }
    for (p = 0; p < m->patch_count; ++p)
        order[offsets[m->patch_link[p]]++] = p;
    for (c = 0, i = 0; c < m->component_count; ++c) {
        size_t vertices = 0;
        meshfix_component *out = meshfix__component_out(o, c);
        for (; i < m->patch_count && m->patch_link[order[i]] == c; ++i) {
            unsigned int q, patch = order[i];
            for (q = m->patch_start[patch]; q < m->patch_start[patch + 1]; ++q) {
                const unsigned int *v = m->indices + 3 * m->queue[q];
                int k;
                for (k = 0; k < 3; ++k) {
                    if (mark[v[k]] == 0) {
                        r->vertices_used++;
                        if (m->positions != NULL) {
                            const float *x = meshfix__position(m, v[k]);
                            r->vertices_non_finite += (size_t)!(meshfix__is_finite(x[0]) &&
                                                               meshfix__is_finite(x[1]) &&
                                                               meshfix__is_finite(x[2]));
                        }
                    }
                    if (mark[v[k]] != c + 1) {
                        mark[v[k]] = c + 1;
                        vertices++;
                    }
                }
            }
        }
        if (out != NULL)
            out->vertices = vertices;
        pairs += vertices;
    }
    return pairs;
}

MESHFIX__PRIVATE void meshfix__add_patch_to_component(const meshfix__mesh *m, unsigned int patch,
                                                      const meshfix__patch_sums *s, double volume,
                                                      meshfix_component *c)
{
    unsigned int bits = m->patch_bits[patch];
    if (c->patches == 0) {
        c->first_triangle = m->queue[m->patch_start[patch]];
        c->closed = 1;
        c->orientable = 1;
    }
    c->patches++;
    c->triangles += m->patch_start[patch + 1] - m->patch_start[patch];
    c->area += s->area;
    c->signed_volume += volume;
    if (bits & MESHFIX__PATCH_NOT_MANIFOLD)
        c->closed = 0;
    if (bits & MESHFIX__PATCH_NON_ORIENTABLE)
        c->orientable = 0;
}

/* SDF: counts a triangle whose own vote disagrees with the patch's flip;
   returns the flip the mode asks for: per patch, the patch's; per
   triangle, its own vote's. */
MESHFIX__PRIVATE unsigned int meshfix__sdf_flip(const meshfix__mesh *m, unsigned int t, unsigned int patch_flip,
                                               meshfix_report *r)
{
    unsigned int bits = m->tri_bits[t];
    int has_vote = (bits & (MESHFIX__TRI_VOTE_IN | MESHFIX__TRI_VOTE_OUT)) != 0;
    unsigned int own_flip = (bits & MESHFIX__TRI_VOTE_IN) ? 1u : 0u;
    if (has_vote && own_flip != patch_flip)
        r->triangles_sdf_disagree++;
    /* the plain rule: a triangle with no vote (zero area, no gradient) stays as given */
    return m->options->sdf_mode == MESHFIX_SDF_PER_TRIANGLE ? own_flip : patch_flip;
}

/* Turns each patch as the policy decides (policy < 0: inspect, no turns),
   marks the flipped triangles, and sums the report's totals as returned. */
MESHFIX__PRIVATE void meshfix__orient_patches(meshfix__mesh *m, int policy, const meshfix_options *o,
                                              meshfix_report *r)
{
    unsigned int p, c;
    MESHFIX_MEMSET(m->component_bits, 0, m->component_count);
    for (p = 0; p < m->patch_count; ++p) {
        meshfix__patch_sums s;
        unsigned int i, turn = 0, bits = m->patch_bits[p];
        double volume;
        meshfix_component *out = meshfix__component_out(o, m->patch_link[p]);
        meshfix__sum_patch(m, p, &s);
        r->sdf_evaluations += s.sdf_evaluations;
        if (policy >= 0) {
            turn = (unsigned int)meshfix__decide_patch(m, p, (meshfix_policy)policy, &s);
            for (i = m->patch_start[p]; i < m->patch_start[p + 1]; ++i) {
                unsigned int t = m->queue[i];
                unsigned int flip = (m->tri_bits[t] & MESHFIX__TRI_RELATIVE) ^ turn;
                if (policy == MESHFIX_POLICY_SDF)
                    flip = meshfix__sdf_flip(m, t, flip, r);
                m->tri_bits[t] = (unsigned short)(m->tri_bits[t] | (flip ? MESHFIX__TRI_FLIP : 0u));
                r->triangles_flipped += flip;
            }
        }
        volume = policy < 0 ? s.volume_given : turn ? -s.volume_relative : s.volume_relative;
        if (!meshfix__is_closed_orientable(m, p))
            volume = 0.0;
        r->triangles_zero_area += s.zero_area;
        r->area += s.area;
        r->signed_volume += volume;
        r->patches_closed += (size_t)!(bits & MESHFIX__PATCH_OPEN);
        /* inside-out only means something for a patch wound one way throughout */
        if (policy >= 0 || s.reversed == 0)
            r->patches_inside_out += (size_t)(volume < 0.0 && meshfix__volume_is_meaningful(volume, s.area));
        if (out != NULL)
            meshfix__add_patch_to_component(m, p, &s, volume, out);
        m->component_bits[m->patch_link[p]] |= (unsigned char)bits;
    }
    for (c = 0; c < m->component_count; ++c) {
        r->components_closed += (size_t)!(m->component_bits[c] & MESHFIX__PATCH_NOT_MANIFOLD);
        r->components_non_orientable += (size_t)((m->component_bits[c] & MESHFIX__PATCH_NON_ORIENTABLE) != 0);
    }
}

#ifdef MESHFIX_DEBUG
/* After orienting, every manifold edge inside an orientable patch must be
   run in opposite directions by its two triangles. */
MESHFIX__PRIVATE void meshfix__debug_check_orientation(const meshfix__mesh *m)
{
    unsigned int h, half_edges = (unsigned int)(3 * m->triangle_count);
    for (h = 0; h < half_edges; ++h) {
        unsigned int g = m->mate[h];
        if (meshfix__is_mate(g) && !(m->patch_bits[m->tri_patch[h / 3]] & MESHFIX__PATCH_NON_ORIENTABLE))
            MESHFIX_ASSERT(((unsigned int)meshfix__same_direction(m, h, g) ^ meshfix__flip_of(m, h / 3) ^
                            meshfix__flip_of(m, g / 3)) == 0);
    }
}
#endif

/* ===== >>pipeline ===== */

MESHFIX__PRIVATE void meshfix__bind(meshfix__mesh *m, unsigned char *block, const meshfix__plan *plan,
                                    const unsigned int *indices, size_t index_count, const float *positions,
                                    size_t stride, size_t vertex_range, const meshfix_options *options, int policy)
{
    MESHFIX_MEMSET(m, 0, sizeof(*m));
    m->options = options;
    m->policy = policy;
    m->indices = indices;
    m->triangle_count = index_count / 3;
    m->vertex_range = vertex_range;
    m->positions = (const char *)positions;
    m->stride = stride;
    m->mate = (unsigned int *)(void *)(block + plan->mate);
    m->work = (unsigned int *)(void *)(block + plan->work);
    m->queue = m->work;
    m->tri_patch = m->queue + m->triangle_count;
    m->component_bits = (unsigned char *)(m->queue + 2 * m->triangle_count);
    m->tri_bits = (unsigned short *)(void *)(block + plan->tri_bits);
    m->vertex_work = (unsigned int *)(void *)(block + plan->vertex_work);
    m->patch_start = (unsigned int *)(void *)(block + plan->patch_start);
    m->patch_link = (unsigned int *)(void *)(block + plan->patch_link);
    m->patch_bits = block + plan->patch_bits;
}

/* Stages 2 to 5 on a bound mesh; fills r and the component outputs. The
   counts that only describe the mesh (duplicates, non-manifold vertices,
   inconsistent edges, Euler characteristic) are skipped when `full` is 0:
   the caller asked for neither a report nor components. */
MESHFIX__PRIVATE void meshfix__analyze(meshfix__mesh *m, int policy, const meshfix_options *o, int full,
                                       meshfix_report *r)
{
    meshfix__edge_counts edges;
    size_t c, n;

    r->triangles_degenerate = meshfix__mark_degenerate(m);
    meshfix__build_edges(m, &edges);
    r->edges = edges.edges;
    r->edges_boundary = edges.boundary;
    r->edges_manifold = edges.manifold;
    r->edges_non_manifold = edges.non_manifold;
    if (full) {
        r->triangles_duplicate = meshfix__count_duplicates(m);
        r->edges_inconsistent_input = meshfix__count_inconsistent(m, 0);
        r->vertices_non_manifold = meshfix__count_non_manifold_vertices(m);
    }

    meshfix__flood_patches(m);
    meshfix__join_components(m);
    r->patches = m->patch_count;
    r->components = m->component_count;

    n = o != NULL && o->components != NULL ? o->components_capacity : 0;
    n = m->component_count < n ? m->component_count : n;
    if (n != 0)
        MESHFIX_MEMSET(o->components, 0, n * sizeof(meshfix_component));
    meshfix__orient_patches(m, policy, o, r);
#ifdef MESHFIX_DEBUG
    /* the plain per-triangle SDF rule does not promise consistency */
    if (policy >= 0 && !(policy == MESHFIX_POLICY_SDF && o->sdf_mode == MESHFIX_SDF_PER_TRIANGLE))
        meshfix__debug_check_orientation(m);
#endif
    if (!full)
        return;
    r->edges_inconsistent = policy >= 0 ? meshfix__count_inconsistent(m, 1) : r->edges_inconsistent_input;
    meshfix__count_component_edges(m, o);
    r->euler_characteristic = (long)meshfix__count_component_vertices(m, o, r) - (long)r->edges +
                              (long)(r->triangles - r->triangles_degenerate);
    for (c = 0; c < n; ++c)
        o->components[c].euler_characteristic = (long)o->components[c].vertices - (long)o->components[c].edges +
                                                (long)o->components[c].triangles;
}

MESHFIX__PRIVATE void meshfix__write_indices(const meshfix__mesh *m, unsigned int *destination)
{
    size_t t;
    if (destination != m->indices)
        MESHFIX_MEMCPY(destination, m->indices, 3 * m->triangle_count * sizeof(unsigned int));
    for (t = 0; t < m->triangle_count; ++t) {
        if (m->tri_bits[t] & MESHFIX__TRI_FLIP) {
            unsigned int x = destination[3 * t + 1];
            destination[3 * t + 1] = destination[3 * t + 2];
            destination[3 * t + 2] = x;
        }
    }
}

MESHFIX__PRIVATE void meshfix__write_triangle_outputs(const meshfix__mesh *m, const meshfix_options *o, int policy)
{
    size_t t;
    if (o != NULL && o->flipped != NULL && policy >= 0)
        for (t = 0; t < m->triangle_count; ++t)
            o->flipped[t] = (unsigned char)meshfix__flip_of(m, (unsigned int)t);
    if (o != NULL && o->patch_ids != NULL)
        for (t = 0; t < m->triangle_count; ++t)
            o->patch_ids[t] = m->tri_patch[t];
}

/* The pipeline shared by orient and inspect (policy < 0). Outputs are
   written only after every check has passed and the work is done. */
MESHFIX__PRIVATE meshfix_result meshfix__run(unsigned int *destination, const unsigned int *indices,
                                             size_t index_count, const float *positions,
                                             size_t vertex_count, size_t stride,
                                             const meshfix_options *options, int policy,
                                             meshfix_report *report)
{
    meshfix_allocator allocator;
    meshfix__plan plan;
    meshfix__mesh m;
    meshfix_report r;
    unsigned char *raw, *block;
    size_t vertex_range = 0;
    meshfix_result result;

    /* 1. validate, before touching anything */
    result = meshfix__validate(indices, index_count, positions, vertex_count, stride, &vertex_range);
    if (result != MESHFIX_OK)
        return result;
    if (policy == MESHFIX_POLICY_AUTO)
        policy = positions != NULL ? MESHFIX_POLICY_OUTWARD : MESHFIX_POLICY_MAJORITY;
    if ((policy == MESHFIX_POLICY_OUTWARD || policy == MESHFIX_POLICY_SDF) && positions == NULL)
        return MESHFIX_ERROR_POSITIONS_REQUIRED;
    if (policy == MESHFIX_POLICY_SDF &&
        (options->sdf == NULL || (unsigned int)options->sdf_mode > (unsigned int)MESHFIX_SDF_PER_TRIANGLE))
        return MESHFIX_ERROR_INVALID_ARGUMENT;
    MESHFIX_MEMSET(&r, 0, sizeof(r));
    r.triangles = index_count / 3;
    if (index_count == 0) {
        if (report != NULL)
            *report = r;
        return MESHFIX_OK;
    }
    if (!meshfix__make_plan(&plan, vertex_range, index_count / 3))
        return MESHFIX_ERROR_TOO_LARGE;

    /* one block holds all scratch: the caller's, or a single allocation */
    MESHFIX_MEMSET(&allocator, 0, sizeof(allocator));
    if (options != NULL && options->allocator.alloc_fn != NULL) {
        if (options->allocator.free_fn == NULL)
            return MESHFIX_ERROR_INVALID_ARGUMENT;
        allocator = options->allocator;
    }
    if (options != NULL && options->scratch != NULL) {
        if (options->scratch_size < plan.total)
            return MESHFIX_ERROR_SCRATCH_TOO_SMALL;
        raw = (unsigned char *)options->scratch;
    } else {
        raw = (unsigned char *)(allocator.alloc_fn != NULL ? allocator.alloc_fn(plan.total, allocator.user_data)
                                                           : MESHFIX_MALLOC(plan.total, allocator.user_data));
        if (raw == NULL)
            return MESHFIX_ERROR_OUT_OF_MEMORY;
    }
    block = raw + (16u - (size_t)raw % 16u) % 16u;
    meshfix__bind(&m, block, &plan, indices, index_count, positions, stride, vertex_range, options, policy);

    /* 2-5. edges, patches, components, policy */
    meshfix__analyze(&m, policy, options, report != NULL || (options != NULL && options->components != NULL), &r);

    /* 6. write: nothing can fail from here on */
    if (destination != NULL && policy >= 0)
        meshfix__write_indices(&m, destination);
    meshfix__write_triangle_outputs(&m, options, policy);
    if (report != NULL)
        *report = r;
    if (raw != (unsigned char *)(options != NULL ? options->scratch : NULL)) {
        if (allocator.free_fn != NULL)
            allocator.free_fn(raw, allocator.user_data);
        else
            MESHFIX_FREE(raw, allocator.user_data);
    }
    return MESHFIX_OK;
}

/* ===== >>public ===== */

MESHFIX_API meshfix_result meshfix_orient(unsigned int *destination, const unsigned int *indices,
                                          size_t index_count, const float *vertex_positions,
                                          size_t vertex_count, size_t vertex_positions_stride,
                                          const meshfix_options *options, meshfix_report *report)
{
    int policy = options != NULL ? (int)options->policy : (int)MESHFIX_POLICY_AUTO;
    if (policy < 0 || policy >= (int)MESHFIX_POLICY_COUNT)
        return MESHFIX_ERROR_INVALID_ARGUMENT;
    return meshfix__run(destination, indices, index_count, vertex_positions, vertex_count,
                        vertex_positions_stride, options, policy, report);
}

MESHFIX_API meshfix_result meshfix_inspect_ex(const unsigned int *indices, size_t index_count,
                                              const float *vertex_positions, size_t vertex_count,
                                              size_t vertex_positions_stride, const meshfix_options *options,
                                              meshfix_report *report)
{
    if (report == NULL)
        return MESHFIX_ERROR_INVALID_ARGUMENT;
    return meshfix__run(NULL, indices, index_count, vertex_positions, vertex_count, vertex_positions_stride,
                        options, -1, report);
}

MESHFIX_API meshfix_result meshfix_inspect(const unsigned int *indices, size_t index_count,
                                           const float *vertex_positions, size_t vertex_count,
                                           size_t vertex_positions_stride, meshfix_report *report)
{
    return meshfix_inspect_ex(indices, index_count, vertex_positions, vertex_count, vertex_positions_stride,
                              NULL, report);
}

MESHFIX_API int meshfix_check(const unsigned int *indices, size_t index_count, const float *vertex_positions,
                              size_t vertex_count, size_t vertex_positions_stride, unsigned int requirements)
{
    meshfix_report r;
    unsigned int needs_positions = MESHFIX_REQUIRE_OUTWARD | MESHFIX_REQUIRE_NO_DEGENERATE;
    if (requirements == 0)
        requirements = MESHFIX_REQUIRE_CONSISTENT;
    if ((requirements & needs_positions) && vertex_positions == NULL)
        return 0;
    if (meshfix_inspect(indices, index_count, vertex_positions, vertex_count, vertex_positions_stride, &r) !=
        MESHFIX_OK)
        return 0;
    if ((requirements & MESHFIX_REQUIRE_CONSISTENT) && r.edges_inconsistent != 0)
        return 0;
    if ((requirements & MESHFIX_REQUIRE_CLOSED) && r.edges_boundary != 0)
        return 0;
    if ((requirements & MESHFIX_REQUIRE_MANIFOLD) && r.edges_non_manifold + r.vertices_non_manifold != 0)
        return 0;
    if ((requirements & MESHFIX_REQUIRE_OUTWARD) && r.patches_inside_out != 0)
        return 0;
    if ((requirements & MESHFIX_REQUIRE_NO_DEGENERATE) &&
        r.triangles_degenerate + r.triangles_zero_area + r.triangles_duplicate != 0)
        return 0;
    return 1;
}

MESHFIX_API size_t meshfix_scratch_size(size_t vertex_count, size_t index_count)
{
    meshfix__plan plan;
    if (index_count == 0 || index_count > MESHFIX__MAX_INDEX_COUNT ||
        !meshfix__make_plan(&plan, vertex_count, (index_count + 2) / 3))
        return 0;
    return plan.total;
}

MESHFIX_API const char *meshfix_result_string(meshfix_result result)
{
#define MESHFIX__RESULT_TEXT(name, text) text,
    static const char *const texts[] = {MESHFIX_RESULT_LIST(MESHFIX__RESULT_TEXT) "unknown result"};
#undef MESHFIX__RESULT_TEXT
    unsigned int i = (unsigned int)result;
    return texts[i < (unsigned int)MESHFIX_RESULT_COUNT ? i : (unsigned int)MESHFIX_RESULT_COUNT];
}

#endif /* MESHFIX_IMPLEMENTATION_INCLUDED */
#endif /* MESHFIX_IMPLEMENTATION */

/*
------------------------------------------------------------------------------
This software is available under 2 licenses -- choose whichever you prefer.
------------------------------------------------------------------------------
ALTERNATIVE A - MIT License
Copyright (c) 2026 the meshfix.h authors
Permission is hereby granted, free of charge, to any person obtaining a copy of
this software and associated documentation files (the "Software"), to deal in
the Software without restriction, including without limitation the rights to
use, copy, modify, merge, publish, distribute, sublicense, and/or sell copies
of the Software, and to permit persons to whom the Software is furnished to do
so, subject to the following conditions:
The above copyright notice and this permission notice shall be included in all
copies or substantial portions of the Software.
THE SOFTWARE IS PROVIDED "AS IS", WITHOUT WARRANTY OF ANY KIND, EXPRESS OR
IMPLIED, INCLUDING BUT NOT LIMITED TO THE WARRANTIES OF MERCHANTABILITY,
FITNESS FOR A PARTICULAR PURPOSE AND NONINFRINGEMENT. IN NO EVENT SHALL THE
AUTHORS OR COPYRIGHT HOLDERS BE LIABLE FOR ANY CLAIM, DAMAGES OR OTHER
LIABILITY, WHETHER IN AN ACTION OF CONTRACT, TORT OR OTHERWISE, ARISING FROM,
OUT OF OR IN CONNECTION WITH THE SOFTWARE OR THE USE OR OTHER DEALINGS IN THE
SOFTWARE.
------------------------------------------------------------------------------
ALTERNATIVE B - Public Domain (www.unlicense.org)
This is free and unencumbered software released into the public domain.
Anyone is free to copy, modify, publish, use, compile, sell, or distribute this
software, either in source code form or as a compiled binary, for any purpose,
commercial or non-commercial, and by any means.
In jurisdictions that recognize copyright laws, the author or authors of this
software dedicate any and all copyright interest in the software to the public
domain. We make this dedication for the benefit of the public at large and to
the detriment of our heirs and successors. We intend this dedication to be an
overt act of relinquishment in perpetuity of all present and future rights to
this software under copyright law.
THE SOFTWARE IS PROVIDED "AS IS", WITHOUT WARRANTY OF ANY KIND, EXPRESS OR
IMPLIED, INCLUDING BUT NOT LIMITED TO THE WARRANTIES OF MERCHANTABILITY,
FITNESS FOR A PARTICULAR PURPOSE AND NONINFRINGEMENT. IN NO EVENT SHALL THE
AUTHORS BE LIABLE FOR ANY CLAIM, DAMAGES OR OTHER LIABILITY, WHETHER IN AN
ACTION OF CONTRACT, TORT OR OTHERWISE, ARISING FROM, OUT OF OR IN CONNECTION
WITH THE SOFTWARE OR THE USE OR OTHER DEALINGS IN THE SOFTWARE.
------------------------------------------------------------------------------
*/
