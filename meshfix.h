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
       meshfix_weld          merge vertices closer than a tolerance (soups, CAD)
       meshfix_scratch_size  bytes of scratch memory a call needs at most
       meshfix_result_string text of a result code

   ALGORITHM (orient and inspect share stages 1-5)
       1. validate: counts, pointers, stride, every index < vertex_count.
       2. edges: a counting sort puts every half-edge in the bucket of its
          lower vertex; each bucket is sorted by its higher vertex, so the
          half-edges of one edge lie together: a pair become mates, three
          or more are linked into a ring, a single one is a boundary.
       3. patches: the flood fill across manifold edges, done as a
          union-find with parity in triangle order: each triangle gets its
          flip relative to the patch seed, its lowest triangle (a
          neighbour traversing the shared edge in the same direction must
          be flipped). A contradiction means the patch is non-orientable
          (Moebius): it is still oriented as far as its spanning tree
          reaches and the remaining edges are reported.
       4. components: union-find over the rings of non-manifold edges; a
          patch is closed when it owns an even count of each ring.
       5. policy: each patch is then turned as a whole:
            SEED      keep the seed triangle as it is (the plain flood fill);
            MAJORITY  the side that flips less triangle area (or fewer
                      triangles without positions), so a patch with 90% of
                      its triangles wrong does not come out inside-out;
            OUTWARD   closed shells get positive signed volume, except
                      cavities: a shell that crosses no other surface and
                      lies inside an odd number of them (rays from 32 of
                      its points cross the rest an odd number of times, 3
                      of 4 deciding, so an outer shell with gaps still
                      counts) faces inward. Open patches use MAJORITY;
            VISIBILITY Borodin, Zachmann, Klein: per patch, the share of
                      random rays that escape the model from each side
                      (a BVH with a watertight ray/triangle test), the
                      coherence of close boundary edges of other patches,
                      and a greedy merge into super-patches with the
                      paper's rules; each super-patch to its more visible
                      side. For soups, CAD exports with gaps, open sheets;
            UP        each patch toward the side its area-weighted normal
                      leans to along options.up (terrains, height fields);
            SDF       for meshes extracted from a signed distance function:
                      the area-weighted vote of the SDF gradient over the
                      patch's triangles; per triangle (sdf_mode), the plain
                      rule: each triangle faces along the gradient at its
                      centroid. Per patch stays right where single samples
                      fail: triangles with no normal (zero area) and
                      triangles at sharp edges whose centroid gradient lies
                      in their plane (see tests/test_sdf.c);
            AUTO      closed shells OUTWARD, everything else VISIBILITY;
                      MAJORITY without positions.
       6. write: copy indices to destination and swap the last two indices
          of each flipped triangle.
       Time O(index_count + vertex_count) (a vertex of k edges costs
       O(k log k)); hashing only for triangles whose three edges are all
       non-manifold, and only to count duplicates.
       Memory: one block of meshfix_scratch_size(vertex_count, index_count)
       bytes, 35 bytes per triangle + 4 per vertex, freed before return;
       none at all when the caller passes options.scratch.
       Speed (make bench, one run, same meshes): the topology-only repair
       is 3x to 7x faster than OpenMesh building its half-edge structure
       with both on warm memory (about 6x at 1M triangles); a call with a
       full report takes 2.5x to 3x the time of the repair alone.
       References: the edge-map flood fill of the glTF winding auto-fix;
       P. Borodin, G. Zachmann, R. Klein, "Consistent Normal Orientation for
       Polygonal Meshes" (patches, coherence, visibility, greedy merge);
       S. Woop, C. Benthin, I. Wald, "Watertight Ray/Triangle Intersection"
       (JCGT 2013); T. Ize, "Robust BVH Ray Traversal" (JCGT 2013).

   DETERMINISM & THREAD SAFETY
   The output depends only on the inputs and options: counting sorts with
   index tie-breaks, unions in triangle order, no hash iteration, no qsort. Sums
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
   - connect patches across T-junctions or gaps topologically (VISIBILITY
     relates them by the distance of their boundary edges instead);
   - fill holes, remove degenerate or duplicate triangles, or change the
     triangle order or count;
   - let caller scratch cover the ray-casting policies: VISIBILITY, and
     OUTWARD / AUTO with more than one patch, allocate their BVH and ray
     data through the allocator (about 150 bytes per triangle more);
   - promise exact answers on pathological geometry: a ray that visits
     more than 1024 BVH nodes counts as blocked, and a coherence query
     looks at 128 nearby edges at most, so that cost stays linear;
   - index_count is limited to 2^31 - 1.

   VERSION HISTORY
       0.1.0  first release: inspect, flood fill with seed / majority /
              outward / auto / SDF / visibility / up policies, nested
              shells, weld, check, scratch-size query.
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
    X(MESHFIX_ERROR_OUT_OF_MEMORY, "out of memory") \
    X(MESHFIX_ERROR_NON_FINITE, "a position is NaN or infinite (meshfix_weld)")

#define MESHFIX__RESULT_ENUM(name, text) name,
typedef enum meshfix_result {
    MESHFIX_RESULT_LIST(MESHFIX__RESULT_ENUM)
    MESHFIX_RESULT_COUNT
} meshfix_result;
#undef MESHFIX__RESULT_ENUM

/* Which way each consistently wound patch ends up facing. */
typedef enum meshfix_policy {
    MESHFIX_POLICY_AUTO = 0, /* closed shells OUTWARD, the rest VISIBILITY; MAJORITY without positions */
    MESHFIX_POLICY_SEED,     /* the patch's lowest triangle keeps its winding */
    MESHFIX_POLICY_MAJORITY, /* the side that flips less area (or fewer triangles) */
    MESHFIX_POLICY_OUTWARD,  /* closed shells out (cavities in), open patches by MAJORITY */
    MESHFIX_POLICY_SDF,      /* along the gradient of options.sdf (needs positions and sdf) */
    MESHFIX_POLICY_VISIBILITY, /* Borodin et al.: boundary coherence + ray-sampled visibility */
    MESHFIX_POLICY_UP,       /* each patch faces the side its normal leans to along options.up */
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
    /* MESHFIX_POLICY_VISIBILITY (and AUTO for what is not a closed shell).
       Rays: per patch proportional to area, at least visibility_min_samples
       (default 16), visibility_rays in all (default 128 per patch, within
       65536 .. 1048576); the floor gives way when the patches alone would
       exceed the budget. A ray that visits more than 1024 tree nodes (a
       stack of coincident triangles) counts as blocked. Coherence: boundary edges of other patches closer
       than coherence_distance (a fraction of the longest bounding-box side,
       default 0.02). Merge thresholds of the paper: C0 (visibility_c0,
       default 0.5: |c| / l, 1 for coincident opposite edges), eps_v
       (visibility_eps, 0.02), k_v (visibility_kv, 1.5). */
    size_t visibility_rays;
    unsigned int visibility_min_samples;
    float coherence_distance;
    float visibility_c0, visibility_eps, visibility_kv;
    unsigned int visibility_flags;  /* MESHFIX_VISIBILITY_* */
    unsigned int seed;              /* of the ray directions and points; 0 = a fixed default */
    /* optional: run task(context, i) for i in [0, count), in any order, on
       any threads; results are the same as without it, bit for bit */
    void (*parallel_for)(void (*task)(void *context, size_t index), void *context, size_t count, void *user);
    void *parallel_user;
    float up[3];                    /* MESHFIX_POLICY_UP axis; 0, 0, 0 = +z */
    float *patch_confidence;        /* optional out, by patch id: 0 (a coin flip) .. 1 (clear) */
    size_t patch_confidence_capacity;
} meshfix_options;

#define MESHFIX_VISIBILITY_COHERENCE_ONLY 1u /* merge by coherence alone; sides by majority */
#define MESHFIX_VISIBILITY_ONLY 2u           /* no merging: each patch to its more visible side */

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
    size_t rays_cast;             /* VISIBILITY: visibility samples */
    size_t patch_pairs;           /* VISIBILITY: pairs of patches with a coherence */
    size_t patches_merged;        /* VISIBILITY: merges into super-patches */
    size_t pairs_conflicting;     /* VISIBILITY: pairs left wound against their coherence */
    size_t shells_inward;         /* OUTWARD, AUTO: closed shells found to be cavities */
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

/* Weld vertices closer than `tolerance` (0: equal positions, -0 == +0).
   remap[v] becomes the lowest-index vertex that v welds to (v itself for
   the first of each cluster), so a polygon soup with positions per corner
   becomes indexed as indices[i] = remap[i], and an indexed mesh as
   indices[i] = remap[indices[i]]. Deterministic; vertices join the
   earliest representative within the tolerance, so clusters do not chain.
   Returns MESHFIX_ERROR_NON_FINITE for a NaN or infinite position; on any
   error remap is not written.

   remap must hold vertex_count elements; unique_count can be NULL;
   options: only the allocator is used, NULL is fine. */
MESHFIX_API meshfix_result meshfix_weld(unsigned int *remap, const float *vertex_positions, size_t vertex_count,
                                        size_t vertex_positions_stride, float tolerance,
                                        const meshfix_options *options, size_t *unique_count);

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
#if !defined(MESHFIX_SQRT) || !defined(MESHFIX_FLOOR) || !defined(MESHFIX_SIN) || !defined(MESHFIX_COS) || \
    !defined(MESHFIX_FABS)
#include <math.h>
#endif
#ifndef MESHFIX_SIN
#define MESHFIX_SIN(x) sin(x)
#endif
#ifndef MESHFIX_COS
#define MESHFIX_COS(x) cos(x)
#endif
#ifndef MESHFIX_SQRT
#define MESHFIX_SQRT(x) sqrt(x)
#endif
#ifndef MESHFIX_FLOOR
#define MESHFIX_FLOOR(x) floor(x)
#endif
#ifndef MESHFIX_FABS
#define MESHFIX_FABS(x) fabs(x)
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
#define MESHFIX__TRI_OPEN       512u /* has a boundary edge */
#define MESHFIX__TRI_NOT_MANIFOLD 1024u /* has an edge shared by three or more */
#define MESHFIX__TRI_SEAM      2048u /* closes a cycle of contradicting edges */
#define MESHFIX__TRI_NON_FINITE 4096u /* a corner is NaN or infinite: no geometry */
/* patch bits */
#define MESHFIX__PATCH_OPEN           1u /* a boundary edge or an odd share of a ring */
#define MESHFIX__PATCH_NOT_MANIFOLD   2u /* has a boundary or non-manifold edge */
#define MESHFIX__PATCH_NON_ORIENTABLE 4u
#define MESHFIX__PATCH_PARITY         8u /* scratch bit while walking a ring */
#define MESHFIX__PATCH_FLIP          16u /* the turn a geometric policy decided */
#define MESHFIX__PATCH_DECIDED       32u

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
   duplicate table, then the union-find parents, which become patch ids,
   and each patch's list of triangles. `mate` holds each half-edge's higher
   vertex until its bucket links it, and groups patches by component at
   the end. On machines where a fresh page costs microseconds, these bytes
   are most of the time. */
MESHFIX__PRIVATE int meshfix__make_plan(meshfix__plan *plan, size_t vertex_range, size_t triangle_count)
{
    size_t total = 0, half_edges;
    /* vertex_range + 1 must not wrap where size_t has 32 bits */
    if (triangle_count > MESHFIX__MAX_INDEX_COUNT / 3 || vertex_range >= ((size_t)-1) ||
        vertex_range > MESHFIX__MAX_VERTEX_COUNT)
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
    unsigned int *work;           /* 3 per triangle: edge buckets, duplicate table, patches */
    unsigned int *queue;          /* triangles in patch order (inside `work`) */
    unsigned int *tri_patch;      /* union-find parent, then patch id (inside `work`) */
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
    float *confidence;              /* per patch, from the geometric policies; may be NULL */
} meshfix__mesh;

/* The last vertex's x y z (12 bytes at (vertex_count - 1) * stride) lie
   within an address range that size_t can describe. */
MESHFIX__PRIVATE int meshfix__vertices_addressable(size_t vertex_count, size_t stride)
{
    size_t last;
    if (vertex_count == 0)
        return 1;
    if (vertex_count - 1 > ((size_t)-1) / stride)
        return 0;
    last = (vertex_count - 1) * stride;
    return last <= ((size_t)-1) - 3 * sizeof(float);
}

/* Every check that needs no index is made before any index is read: a
   count the scratch plan cannot hold is refused without touching the
   buffer it claims to describe. */
MESHFIX__PRIVATE meshfix_result meshfix__validate(const unsigned int *indices, size_t index_count,
                                                  const float *positions, size_t vertex_count,
                                                  size_t stride, size_t *vertex_range, meshfix__plan *plan)
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
    if (positions != NULL && !meshfix__vertices_addressable(vertex_count, stride))
        return MESHFIX_ERROR_TOO_LARGE;
    if (index_count == 0) {
        *vertex_range = 0;
        return MESHFIX_OK;
    }
    if (!meshfix__make_plan(plan, 0, index_count / 3))
        return MESHFIX_ERROR_TOO_LARGE;
    for (i = 0; i < index_count; ++i)
        highest = indices[i] > highest ? indices[i] : highest;
    if ((size_t)highest >= vertex_count)
        return MESHFIX_ERROR_INDEX_OUT_OF_RANGE;
    *vertex_range = (size_t)highest + 1;
    return meshfix__make_plan(plan, *vertex_range, index_count / 3) ? MESHFIX_OK : MESHFIX_ERROR_TOO_LARGE;
}

MESHFIX__PRIVATE const float *meshfix__position(const meshfix__mesh *m, unsigned int vertex)
{
    return (const float *)(const void *)(m->positions + (size_t)vertex * m->stride);
}

/* On the bit pattern, not by arithmetic: -ffast-math and -Ofast let the
   compiler assume that no value is NaN or infinite and delete `x != x`
   style tests, which engines build with. */
MESHFIX__PRIVATE int meshfix__is_finite(float x)
{
    unsigned int bits;
    MESHFIX_MEMCPY(&bits, &x, sizeof(bits));
    return (bits & 0x7F800000u) != 0x7F800000u;
}

MESHFIX__PRIVATE int meshfix__is_finite_point(const float *p)
{
    return meshfix__is_finite(p[0]) && meshfix__is_finite(p[1]) && meshfix__is_finite(p[2]);
}

/* Marks triangles that repeat a vertex (no topology) and, with positions,
   triangles with a NaN or infinite corner (no geometry: every geometric
   stage skips them, so no NaN reaches a comparison, a bin or a loop
   bound). Returns the degenerate count. */
MESHFIX__PRIVATE size_t meshfix__mark_degenerate(meshfix__mesh *m)
{
    size_t t, count = 0;
    for (t = 0; t < m->triangle_count; ++t) {
        const unsigned int *v = m->indices + 3 * t;
        int degenerate = v[0] == v[1] || v[1] == v[2] || v[0] == v[2];
        unsigned int bits = degenerate ? MESHFIX__TRI_DEGENERATE : 0u;
        if (m->positions != NULL && !(meshfix__is_finite_point(meshfix__position(m, v[0])) &&
                                      meshfix__is_finite_point(meshfix__position(m, v[1])) &&
                                      meshfix__is_finite_point(meshfix__position(m, v[2]))))
            bits |= MESHFIX__TRI_NON_FINITE;
        m->tri_bits[t] = (unsigned short)bits;
        count += (size_t)degenerate;
    }
    return count;
}

/* A triangle that can take part in geometry: distinct, finite corners. */
MESHFIX__PRIVATE int meshfix__has_geometry(const meshfix__mesh *m, unsigned int t)
{
    return !(m->tri_bits[t] & (MESHFIX__TRI_DEGENERATE | MESHFIX__TRI_NON_FINITE));
}

/* ===== >>sort ===== */

/* Sorts ids by a strict total order the caller gives (ties broken by id,
   so the result does not depend on the algorithm): insertion sort for a
   few, heapsort in place above that. Crafted input that piles thousands
   of ids into one hash bucket or one vertex costs O(k log k), never
   O(k^2). */
typedef int (*meshfix__before_fn)(const void *context, unsigned int a, unsigned int b);

MESHFIX__PRIVATE void meshfix__sift_down(unsigned int *ids, size_t root, size_t n, meshfix__before_fn before,
                                         const void *context)
{
    for (;;) {
        size_t child = 2 * root + 1;
        unsigned int x;
        if (child >= n)
            return;
        if (child + 1 < n && before(context, ids[child], ids[child + 1]))
            child++;
        if (!before(context, ids[root], ids[child]))
            return;
        x = ids[root];
        ids[root] = ids[child];
        ids[child] = x;
        root = child;
    }
}

MESHFIX__PRIVATE void meshfix__sort_ids(unsigned int *ids, size_t n, meshfix__before_fn before, const void *context)
{
    size_t i, j;
    if (n <= 16) {
        for (i = 1; i < n; ++i) {
            unsigned int x = ids[i];
            for (j = i; j > 0 && before(context, x, ids[j - 1]); --j)
                ids[j] = ids[j - 1];
            ids[j] = x;
        }
        return;
    }
    for (i = n / 2; i-- > 0;)
        meshfix__sift_down(ids, i, n, before, context);
    for (i = n - 1; i > 0; --i) {
        unsigned int x = ids[0];
        ids[0] = ids[i];
        ids[i] = x;
        meshfix__sift_down(ids, 0, i, before, context);
    }
}

/* ===== >>weld ===== */

/* Welding snaps each vertex to the lowest-index earlier representative
   within the tolerance. Vertices are grouped by cell (as wide as the
   tolerance, or the exact position at tolerance 0): hashed into buckets
   by a counting sort, each bucket sorted by (cell, vertex), so finding a
   cell is a hash and a binary search. Hash collisions, accidental or
   crafted, cost a logarithm, not a scan. Only representatives are
   searched, and they lie more than the tolerance apart, so a cell holds
   a handful of them (27 cells around a vertex hold every vertex that
   close). Clusters never chain, and the result depends only on positions
   and their order. */

typedef struct meshfix__welder {
    const char *positions;
    size_t stride;
    double cell;             /* 0: exact equality */
    size_t mask;             /* buckets - 1 */
    unsigned int *bucket_end; /* per bucket: end of its run in `order` */
    unsigned int *order;     /* vertices bucket by bucket, each sorted by (cell, vertex) */
    unsigned int *home;      /* per vertex: where its cell's run starts in `order` */
    unsigned int *rep_head;  /* per run start: the cell's latest representative */
    unsigned int *rep_next;  /* per representative: the previous one in its cell */
} meshfix__welder;

MESHFIX__PRIVATE void meshfix__weld_load(const meshfix__welder *w, size_t v, float p[3])
{
    const float *q = (const float *)(const void *)(w->positions + v * w->stride);
    int k;
    for (k = 0; k < 3; ++k)
        p[k] = q[k] == 0.0f ? 0.0f : q[k]; /* -0 welds to +0 */
}

MESHFIX__PRIVATE void meshfix__weld_cell(const meshfix__welder *w, const float p[3], double cell[3])
{
    int k;
    for (k = 0; k < 3; ++k)
        cell[k] = w->cell > 0 ? MESHFIX_FLOOR((double)p[k] / w->cell) : (double)p[k];
}

MESHFIX__PRIVATE void meshfix__vertex_cell(const meshfix__welder *w, unsigned int v, double cell[3])
{
    float p[3];
    meshfix__weld_load(w, v, p);
    meshfix__weld_cell(w, p, cell);
}

MESHFIX__PRIVATE size_t meshfix__weld_hash(const double cell[3], size_t mask)
{
    unsigned int h = 2166136261u, bits[2];
    int k, j;
    for (k = 0; k < 3; ++k) {
        double x = cell[k] == 0.0 ? 0.0 : cell[k];
        MESHFIX_MEMCPY(bits, &x, sizeof(bits));
        for (j = 0; j < 2; ++j) {
            h = (h ^ bits[j]) * 16777619u;
            h ^= h >> 13;
        }
    }
    return (size_t)h & mask;
}

/* -1, 0, 1 as cell a is below, at or above cell b (x, then y, then z) */
MESHFIX__PRIVATE int meshfix__compare_cells(const double a[3], const double b[3])
{
    int k;
    for (k = 0; k < 3; ++k)
        if (a[k] != b[k])
            return a[k] < b[k] ? -1 : 1;
    return 0;
}

MESHFIX__PRIVATE int meshfix__weld_before(const void *context, unsigned int a, unsigned int b)
{
    const meshfix__welder *w = (const meshfix__welder *)context;
    double ca[3], cb[3];
    int order;
    meshfix__vertex_cell(w, a, ca);
    meshfix__vertex_cell(w, b, cb);
    order = meshfix__compare_cells(ca, cb);
    return order < 0 || (order == 0 && a < b);
}

/* Groups the vertices: counting sort by bucket (vertex order within a
   bucket), each bucket sorted by cell, and every vertex's run found. */
MESHFIX__PRIVATE void meshfix__weld_group(meshfix__welder *w, size_t vertex_count)
{
    size_t v, b, begin = 0, buckets = w->mask + 1;
    unsigned int sum = 0, i;
    double previous[3];
    MESHFIX_MEMSET(w->bucket_end, 0, buckets * sizeof(unsigned int));
    for (v = 0; v < vertex_count; ++v) {
        double c[3];
        meshfix__vertex_cell(w, (unsigned int)v, c);
        w->home[v] = (unsigned int)meshfix__weld_hash(c, w->mask);
        w->bucket_end[w->home[v]]++;
    }
    for (b = 0; b < buckets; ++b) {
        unsigned int n = w->bucket_end[b];
        w->bucket_end[b] = sum;
        sum += n;
    }
    for (v = 0; v < vertex_count; ++v)
        w->order[w->bucket_end[w->home[v]]++] = (unsigned int)v;
    for (b = 0; b < buckets; begin = w->bucket_end[b++])
        meshfix__sort_ids(w->order + begin, w->bucket_end[b] - begin, meshfix__weld_before, w);
    /* runs of one cell: each vertex learns where its run starts */
    previous[0] = previous[1] = previous[2] = 0.0;
    for (i = 0; i < (unsigned int)vertex_count; ++i) {
        double c[3];
        meshfix__vertex_cell(w, w->order[i], c);
        if (i == 0 || meshfix__compare_cells(c, previous) != 0)
            w->rep_head[i] = i; /* a run starts here; rep_head is set up below */
        else
            w->rep_head[i] = w->rep_head[i - 1];
        w->home[w->order[i]] = w->rep_head[i];
        previous[0] = c[0], previous[1] = c[1], previous[2] = c[2];
    }
    for (i = 0; i < (unsigned int)vertex_count; ++i)
        w->rep_head[i] = MESHFIX__NONE;
}

/* Where the run of `cell` starts in `order`, or NONE: its bucket, then a
   binary search in it. */
MESHFIX__PRIVATE unsigned int meshfix__weld_find_cell(const meshfix__welder *w, const double cell[3])
{
    size_t b = meshfix__weld_hash(cell, w->mask);
    unsigned int lo = b == 0 ? 0 : w->bucket_end[b - 1], hi = w->bucket_end[b];
    double c[3];
    while (lo < hi) {
        unsigned int mid = lo + (hi - lo) / 2;
        meshfix__vertex_cell(w, w->order[mid], c);
        if (meshfix__compare_cells(c, cell) < 0)
            lo = mid + 1;
        else
            hi = mid;
    }
    if (lo == w->bucket_end[b])
        return MESHFIX__NONE;
    meshfix__vertex_cell(w, w->order[lo], c);
    return meshfix__compare_cells(c, cell) == 0 ? lo : MESHFIX__NONE;
}

/* The lowest representative in the run at `run` within the tolerance of p. */
MESHFIX__PRIVATE unsigned int meshfix__weld_nearest(const meshfix__welder *w, unsigned int run, const float p[3],
                                                   double tolerance_squared, unsigned int best)
{
    unsigned int r;
    for (r = w->rep_head[run]; r != MESHFIX__NONE; r = w->rep_next[r]) {
        float q[3];
        double dx, dy, dz;
        meshfix__weld_load(w, r, q);
        dx = (double)p[0] - (double)q[0], dy = (double)p[1] - (double)q[1], dz = (double)p[2] - (double)q[2];
        if (dx * dx + dy * dy + dz * dz <= tolerance_squared && r < best)
            best = r;
    }
    return best;
}

MESHFIX__PRIVATE size_t meshfix__weld_run(meshfix__welder *w, size_t vertex_count, double tolerance,
                                         unsigned int *remap)
{
    size_t v, unique = 0;
    double tolerance_squared = tolerance * tolerance;
    meshfix__weld_group(w, vertex_count);
    for (v = 0; v < vertex_count; ++v) {
        float p[3];
        double c[3], n[3];
        unsigned int best = MESHFIX__NONE, run;
        int dx, dy, dz;
        if (w->cell == 0) {
            /* exact: the first of its run is the lowest vertex at that position */
            remap[v] = w->order[w->home[v]];
            unique += (size_t)(remap[v] == v);
            continue;
        }
        meshfix__weld_load(w, v, p);
        meshfix__weld_cell(w, p, c);
        for (dx = -1; dx <= 1; ++dx)
            for (dy = -1; dy <= 1; ++dy)
                for (dz = -1; dz <= 1; ++dz) {
                    n[0] = c[0] + dx, n[1] = c[1] + dy, n[2] = c[2] + dz;
                    run = meshfix__weld_find_cell(w, n);
                    if (run != MESHFIX__NONE)
                        best = meshfix__weld_nearest(w, run, p, tolerance_squared, best);
                }
        if (best != MESHFIX__NONE) {
            remap[v] = best;
            continue;
        }
        remap[v] = (unsigned int)v;
        unique++;
        w->rep_next[v] = w->rep_head[w->home[v]];
        w->rep_head[w->home[v]] = (unsigned int)v;
    }
    return unique;
}

/* ===== >>edges ===== */

typedef struct meshfix__edge_counts {
    size_t edges, boundary, manifold, non_manifold;
} meshfix__edge_counts;

/* While edges are grouped, mate[h] holds the higher vertex of h's edge:
   each half-edge is read from there until its own bucket links it. */
MESHFIX__PRIVATE int meshfix__half_edge_before(const void *context, unsigned int a, unsigned int b)
{
    const meshfix__mesh *m = (const meshfix__mesh *)context;
    unsigned int ka = m->mate[a], kb = m->mate[b];
    return ka < kb || (ka == kb && a < b);
}

/* Links the half-edges of one undirected edge (a run of a sorted bucket):
   one is a boundary, a pair become mates, three or more a ring in
   increasing order. */
MESHFIX__PRIVATE void meshfix__link_edge(meshfix__mesh *m, const unsigned int *run, size_t n,
                                         meshfix__edge_counts *counts)
{
    size_t k;
    counts->edges++;
    if (n == 1) {
        counts->boundary++;
        m->mate[run[0]] = MESHFIX__NONE;
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
   in a mesh: insertion sort of (key, id) pairs on the stack, stable, and
   the bucket arrives in half-edge order, so the key alone gives the total
   order. A vertex shared by thousands of triangles takes heapsort in
   place, O(k log k) with no memory. Both give the same links. A run's
   keys are all read before it is linked over them. */
#define MESHFIX__SMALL_BUCKET 32
MESHFIX__PRIVATE void meshfix__link_bucket(meshfix__mesh *m, unsigned int *ids, size_t n,
                                           meshfix__edge_counts *counts)
{
    size_t i, j;
    if (n <= MESHFIX__SMALL_BUCKET) {
        meshfix__edge_entry e[MESHFIX__SMALL_BUCKET];
        for (i = 0; i < n; ++i) {
            meshfix__edge_entry x;
            x.high = m->mate[ids[i]];
            x.half_edge = ids[i];
            for (j = i; j > 0 && x.high < e[j - 1].high; --j)
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
    meshfix__sort_ids(ids, n, meshfix__half_edge_before, m);
    for (i = 0; i < n; i = j) {
        unsigned int high = m->mate[ids[i]];
        for (j = i + 1; j < n && m->mate[ids[j]] == high; ++j) {
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
        if (m->tri_bits[t] & MESHFIX__TRI_DEGENERATE) {
            m->mate[3 * t] = m->mate[3 * t + 1] = m->mate[3 * t + 2] = MESHFIX__NONE;
            continue;
        }
        end[tri[0] < tri[1] ? tri[0] : tri[1]]++;
        end[tri[1] < tri[2] ? tri[1] : tri[2]]++;
        end[tri[2] < tri[0] ? tri[2] : tri[0]]++;
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
            unsigned int a = tri[k], b = tri[k == 2 ? 0 : k + 1], h = (unsigned int)(3 * t) + k;
            ids[end[a < b ? a : b]++] = h;
            m->mate[h] = a < b ? b : a;
        }
    }
    /* end[v] is now where bucket v ends */
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

MESHFIX__PRIVATE unsigned int meshfix__apex(const meshfix__mesh *m, unsigned int h)
{
    return m->indices[h % 3 == 0 ? h + 2 : h - 1];
}

MESHFIX__PRIVATE void meshfix__mark_duplicate(meshfix__mesh *m, size_t t)
{
    m->tri_bits[t] = (unsigned short)(m->tri_bits[t] | MESHFIX__TRI_DUPLICATE);
}

/* Triangles with the same vertex set share all three edges, among them
   the edge of their two lowest vertices. If that edge is manifold the two
   are its pair, with the same apex. If it is non-manifold, its ring is
   sorted by apex: equal apexes in a row are copies. Each triangle is
   looked at on one edge only, so the whole count is O(n log n) at worst
   and needs no hash that crafted input could aim at. */
MESHFIX__PRIVATE int meshfix__apex_before(const void *context, unsigned int a, unsigned int b)
{
    const meshfix__mesh *m = (const meshfix__mesh *)context;
    unsigned int x = meshfix__apex(m, a), y = meshfix__apex(m, b);
    return x < y || (x == y && a < b);
}

/* The members of the ring ending at `last` that run the edge of their
   triangle's two lowest vertices, into `out`; returns how many. */
MESHFIX__PRIVATE size_t meshfix__lowest_edge_members(const meshfix__mesh *m, unsigned int last, unsigned int *out)
{
    unsigned int h = last, next = last % 3 == 2 ? last - 2 : last + 1;
    unsigned int high = m->indices[h] < m->indices[next] ? m->indices[next] : m->indices[h];
    size_t n = 0;
    do {
        h = m->mate[h] & ~MESHFIX__RING;
        if (meshfix__apex(m, h) > high)
            out[n++] = h;
    } while (h != last);
    return n;
}

MESHFIX__PRIVATE size_t meshfix__count_duplicates(meshfix__mesh *m)
{
    unsigned int *members = m->work, h, half_edges = (unsigned int)(3 * m->triangle_count);
    size_t t, i, n, count = 0;
    for (h = 0; h < half_edges; ++h) {
        unsigned int g = m->mate[h];
        if (meshfix__is_mate(g) && h < g && meshfix__apex(m, h) == meshfix__apex(m, g))
            meshfix__mark_duplicate(m, g / 3);
        if (!meshfix__is_ring_last(m, h))
            continue;
        n = meshfix__lowest_edge_members(m, h, members);
        meshfix__sort_ids(members, n, meshfix__apex_before, m);
        for (i = 1; i < n; ++i)
            if (meshfix__apex(m, members[i]) == meshfix__apex(m, members[i - 1]))
                meshfix__mark_duplicate(m, members[i] / 3);
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

/* Patches are the classes of a union-find over triangles joined by
   manifold edges. Each triangle keeps its parent and, in TRI_RELATIVE, its
   winding relative to that parent. A class's root is its lowest triangle,
   so every parent is lower than its child: one pass in index order then
   turns parents into patch ids and relative bits into "relative to the
   seed", the lowest triangle. Unions follow triangle order, which flipping
   a triangle does not change, so the seam left in a non-orientable patch
   is the same on every run and for every input winding. */
MESHFIX__PRIVATE unsigned int meshfix__patch_root(meshfix__mesh *m, unsigned int t, unsigned int *relative)
{
    unsigned int *parent = m->tri_patch, r = 0;
    while (parent[t] != t) {
        unsigned int up = parent[t];
        /* path halving: hop t to its grandparent, composing the bits */
        if (parent[up] != up) {
            m->tri_bits[t] ^= (unsigned short)(m->tri_bits[up] & MESHFIX__TRI_RELATIVE);
            parent[t] = parent[up];
        }
        r ^= m->tri_bits[t] & MESHFIX__TRI_RELATIVE;
        t = parent[t];
    }
    *relative = r;
    return t;
}

/* Records that t and u wind the same way relative to their seed unless
   `opposite`; a contradiction marks t as lying on the seam. */
MESHFIX__PRIVATE void meshfix__join_triangles(meshfix__mesh *m, unsigned int t, unsigned int u, unsigned int opposite)
{
    unsigned int rt, ru, bt, bu, high;
    rt = meshfix__patch_root(m, t, &bt);
    ru = meshfix__patch_root(m, u, &bu);
    if (rt == ru) {
        if ((bt ^ bu) != opposite)
            m->tri_bits[t] |= MESHFIX__TRI_SEAM;
        return;
    }
    high = rt < ru ? ru : rt;
    m->tri_patch[high] = rt < ru ? rt : ru;
    m->tri_bits[high] = (unsigned short)(m->tri_bits[high] | (bt ^ bu ^ opposite));
}

/* Joins t to its lower manifold neighbours, in order of neighbour; marks
   t when it has other kinds of edges. */
MESHFIX__PRIVATE void meshfix__join_lower_neighbours(meshfix__mesh *m, unsigned int t)
{
    unsigned int h, n = 0, i, j, u[3], opposite[3];
    for (h = 3 * t; h < 3 * t + 3; ++h) {
        unsigned int g = m->mate[h];
        if (!meshfix__is_mate(g)) {
            m->tri_bits[t] |= g == MESHFIX__NONE ? MESHFIX__TRI_OPEN : MESHFIX__TRI_NOT_MANIFOLD;
            continue;
        }
        if (g / 3 > t)
            continue;
        for (j = n++; j > 0 && u[j - 1] > g / 3; --j) {
            u[j] = u[j - 1];
            opposite[j] = opposite[j - 1];
        }
        u[j] = g / 3;
        /* two triangles that run an edge the same way disagree */
        opposite[j] = (unsigned int)meshfix__same_direction(m, h, g);
    }
    for (i = 0; i < n; ++i)
        meshfix__join_triangles(m, t, u[i], opposite[i]);
}

/* Numbers the patches by their seeds, gives each triangle its patch and
   its winding relative to the seed, and lists each patch's triangles in
   increasing order in `queue`. */
MESHFIX__PRIVATE void meshfix__number_patches(meshfix__mesh *m)
{
    unsigned int t, p, patch = 0, sum = 0, triangles = (unsigned int)m->triangle_count;
    for (t = 0; t < triangles; ++t) {
        unsigned int parent = m->tri_patch[t], bits = m->tri_bits[t];
        if (parent == MESHFIX__NONE)
            continue;
        if (parent == t) {
            m->patch_start[patch] = 0;
            m->patch_bits[patch] = 0;
            m->tri_patch[t] = patch++;
        } else {
            /* the parent is lower: already numbered and relative to the seed */
            m->tri_patch[t] = m->tri_patch[parent];
            bits ^= m->tri_bits[parent] & MESHFIX__TRI_RELATIVE;
            m->tri_bits[t] = (unsigned short)bits;
        }
        p = m->tri_patch[t];
        m->patch_start[p]++;
        if (bits & (MESHFIX__TRI_OPEN | MESHFIX__TRI_NOT_MANIFOLD))
            m->patch_bits[p] |= MESHFIX__PATCH_NOT_MANIFOLD;
        if (bits & MESHFIX__TRI_OPEN)
            m->patch_bits[p] |= MESHFIX__PATCH_OPEN;
        if (bits & MESHFIX__TRI_SEAM)
            m->patch_bits[p] |= MESHFIX__PATCH_NON_ORIENTABLE;
    }
    for (p = 0; p < patch; ++p) {
        unsigned int n = m->patch_start[p];
        m->patch_start[p] = sum;
        sum += n;
    }
    for (t = 0; t < triangles; ++t)
        if (m->tri_patch[t] != MESHFIX__NONE)
            m->queue[m->patch_start[m->tri_patch[t]]++] = t;
    /* patch_start[p] is now where patch p ends */
    for (p = patch; p > 0; --p)
        m->patch_start[p] = m->patch_start[p - 1];
    m->patch_start[0] = 0;
    m->patch_count = patch;
}

/* The flood fill: every triangle becomes a class of its own and joins its
   lower neighbours (already set up), in triangle order; then the classes
   are numbered. Degenerate triangles have no edges and no patch. */
MESHFIX__PRIVATE void meshfix__find_patches(meshfix__mesh *m)
{
    unsigned int t, triangles = (unsigned int)m->triangle_count;
    for (t = 0; t < triangles; ++t) {
        if (m->tri_bits[t] & MESHFIX__TRI_DEGENERATE) {
            m->tri_patch[t] = MESHFIX__NONE;
            continue;
        }
        m->tri_patch[t] = t;
        meshfix__join_lower_neighbours(m, t);
    }
    meshfix__number_patches(m);
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
    double normal[3];       /* area-weighted normal, relative frame */
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

MESHFIX__PRIVATE double meshfix__maxd(double a, double b)
{
    return a > b ? a : b;
}

MESHFIX__PRIVATE double meshfix__mind(double a, double b)
{
    return a < b ? a : b;
}

MESHFIX__PRIVATE double meshfix__max3(double a, double b, double c)
{
    return a > b ? (a > c ? a : c) : (b > c ? b : c);
}

/* The SDF gradient at p: the caller's, or central differences. Returns 0
   when it is not finite or zero (no vote). */
MESHFIX__PRIVATE int meshfix__sdf_gradient(const meshfix_options *o, const float p[3], float step, double g[3],
                                          size_t *evaluations)
{
    int axis, finite = 1;
    if (o->sdf_gradient != NULL) {
        float out[3];
        o->sdf_gradient(p, out, o->sdf_user);
        (*evaluations)++;
        finite = meshfix__is_finite_point(out);
        g[0] = (double)out[0], g[1] = (double)out[1], g[2] = (double)out[2];
    } else {
        for (axis = 0; axis < 3; ++axis) {
            float q[3], ahead, behind;
            q[0] = p[0], q[1] = p[1], q[2] = p[2];
            q[axis] = p[axis] + step;
            ahead = o->sdf(q, o->sdf_user);
            q[axis] = p[axis] - step;
            behind = o->sdf(q, o->sdf_user);
            finite = finite && meshfix__is_finite(ahead) && meshfix__is_finite(behind);
            g[axis] = (double)ahead - (double)behind;
        }
        *evaluations += 6;
    }
    return finite && (g[0] != 0 || g[1] != 0 || g[2] != 0);
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
        double magnitude = meshfix__max3(MESHFIX_FABS((double)centroid[0]), MESHFIX_FABS((double)centroid[1]),
                                         MESHFIX_FABS((double)centroid[2]));
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

/* Corners of t relative to origin, and its normal (b - a) x (c - a), twice
   its area long. */
MESHFIX__PRIVATE void meshfix__load_triangle(const meshfix__mesh *m, unsigned int t, const double origin[3],
                                            double a[3], double b[3], double c[3], double n[3])
{
    meshfix__load_corner(m, m->indices[3 * t], origin, a);
    meshfix__load_corner(m, m->indices[3 * t + 1], origin, b);
    meshfix__load_corner(m, m->indices[3 * t + 2], origin, c);
    n[0] = (b[1] - a[1]) * (c[2] - a[2]) - (b[2] - a[2]) * (c[1] - a[1]);
    n[1] = (b[2] - a[2]) * (c[0] - a[0]) - (b[0] - a[0]) * (c[2] - a[2]);
    n[2] = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}

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
    for (i = m->patch_start[patch]; i < end && !meshfix__has_geometry(m, m->queue[i]); ++i) {
    }
    if (i < end)
        meshfix__load_corner(m, m->indices[3 * m->queue[i]], origin, origin);
    for (i = m->patch_start[patch]; i < end; ++i) {
        unsigned int t = m->queue[i];
        double a[3], b[3], c[3], n[3], area = 0.0, volume;
        if (meshfix__has_geometry(m, t)) {
            meshfix__load_triangle(m, t, origin, a, b, c, n);
            area = 0.5 * MESHFIX_SQRT(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        }
        /* a NaN or infinite corner weighs nothing */
        if (!(area > 0.0)) {
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
            s->normal[0] -= 0.5 * n[0], s->normal[1] -= 0.5 * n[1], s->normal[2] -= 0.5 * n[2];
        } else {
            s->weight_kept += area;
            s->volume_relative += volume;
            s->normal[0] += 0.5 * n[0], s->normal[1] += 0.5 * n[1], s->normal[2] += 0.5 * n[2];
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
    if (m->patch_bits[patch] & MESHFIX__PATCH_DECIDED)
        return (m->patch_bits[patch] & MESHFIX__PATCH_FLIP) != 0;
    if (policy == MESHFIX_POLICY_SEED)
        return 0;
    if (policy == MESHFIX_POLICY_SDF && s->sdf_vote != 0.0)
        return s->sdf_vote < 0.0;
    if ((policy == MESHFIX_POLICY_OUTWARD || policy == MESHFIX_POLICY_AUTO) && meshfix__is_closed_orientable(m, patch) &&
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

/* ===== >>rays ===== */

/* A bounding volume hierarchy over the triangles that have an area, built
   by binned SAH, and a watertight ray/triangle test (Woop, Benthin, Wald,
   "Watertight Ray/Triangle Intersection", JCGT 2013): rays neither leak
   through nor hit twice at shared edges and vertices, so crossing counts
   of closed surfaces are exact parities. */

typedef struct meshfix__bvh_node {
    float bounds[6];    /* low x y z, high x y z */
    unsigned int first; /* leaf: first slot in `order`; inner: left child (right = left + 1) */
    unsigned int count; /* leaf: triangles; inner: 0 */
} meshfix__bvh_node;

typedef struct meshfix__bvh {
    meshfix__bvh_node *nodes;
    unsigned int node_count;
    unsigned int *order;  /* triangle ids, leaf by leaf */
    float *corners;       /* 9 floats per slot of `order` */
    unsigned int count;   /* triangles in the tree */
    float low[3], high[3];
    double diagonal;
    double center[3], scale; /* the frame: corners are (position - center) * scale */
} meshfix__bvh;

typedef struct meshfix__ray {
    float origin[3], direction[3], inverse[3];
    float shear[3];
    int kx, ky, kz;
    int near_side[3];   /* per axis, the index in a node's bounds of the near side */
    float t_min, t_max;
} meshfix__ray;

MESHFIX__PRIVATE void *meshfix__allocate(const meshfix_allocator *a, size_t count, size_t size)
{
    /* one byte more, so that a zero-size request is not a NULL "failure" */
    if (size != 0 && count > (((size_t)-1) - 1) / size)
        return NULL;
    return a->alloc_fn != NULL ? a->alloc_fn(count * size + 1, a->user_data) : MESHFIX_MALLOC(count * size + 1, a->user_data);
}

/* The caller's allocator, or the MESHFIX_MALLOC / MESHFIX_FREE defaults
   (both NULL). */
MESHFIX__PRIVATE void meshfix__pick_allocator(const meshfix_options *options, meshfix_allocator *allocator)
{
    MESHFIX_MEMSET(allocator, 0, sizeof(*allocator));
    if (options != NULL && options->allocator.alloc_fn != NULL)
        *allocator = options->allocator;
}

MESHFIX__PRIVATE void meshfix__release(const meshfix_allocator *a, void *p)
{
    if (p == NULL)
        return;
    if (a->free_fn != NULL)
        a->free_fn(p, a->user_data);
    else
        MESHFIX_FREE(p, a->user_data);
}

MESHFIX__PRIVATE void meshfix__grow_box(float low[3], float high[3], const float p[3])
{
    int k;
    for (k = 0; k < 3; ++k) {
        low[k] = p[k] < low[k] ? p[k] : low[k];
        high[k] = p[k] > high[k] ? p[k] : high[k];
    }
}

MESHFIX__PRIVATE float meshfix__box_area(const float low[3], const float high[3])
{
    float x = high[0] - low[0], y = high[1] - low[1], z = high[2] - low[2];
    return x < 0 ? 0.0f : 2.0f * (x * y + y * z + z * x);
}

/* In double: three floats near 3e38 would overflow to infinity in float.
   The mean of three floats fits in a float again. */
MESHFIX__PRIVATE float meshfix__centroid(const float *corners, int axis)
{
    return (float)(((double)corners[axis] + (double)corners[3 + axis] + (double)corners[6 + axis]) / 3.0);
}

#define MESHFIX__BINS 12
#define MESHFIX__LEAF 4
/* The depth of the tree is bounded, so the traversal's fixed stack always
   holds it: SAH splits down to MESHFIX__BVH_SAH_LEVELS levels (SAH can cut
   one triangle off a range at each level: planes at x = 2^-k for k up to
   100 make a tree 100 deep), then halving, which adds at most 31 levels
   for 2^31 triangles. A traversal keeps at most one pending node per
   level, plus the two it just pushed. */
#define MESHFIX__BVH_SAH_LEVELS 28
#define MESHFIX__BVH_STACK 64

/* The bin of a centroid, clamped before the conversion: a value that is
   not a number (found by fuzzing, from coordinates near FLT_MAX) lands in
   bin 0 instead of being undefined behaviour. */
MESHFIX__PRIVATE unsigned int meshfix__bin(double centroid, double low, double scale)
{
    double x = (centroid - low) * scale;
    if (!(x >= 0.0))
        return 0;
    return x >= (double)(MESHFIX__BINS - 1) ? MESHFIX__BINS - 1 : (unsigned int)x;
}

/* While the tree is built, the 9 floats of a slot hold its triangle's box
   (low x y z, high x y z) and centroid, each computed once; the corners
   replace them at the end. What the build knows of a range of slots: the
   box around its triangles and the box around their centroids. A split
   gets both for its two halves from its bins, so no level re-reads its
   slots to fit boxes. */
#define MESHFIX__SLOT_CENTROID 6
typedef struct meshfix__range {
    unsigned int count;
    float box[6];       /* low x y z, high x y z */
    float centroids[6];
} meshfix__range;

MESHFIX__PRIVATE void meshfix__empty_range(meshfix__range *r)
{
    int k;
    r->count = 0;
    for (k = 0; k < 3; ++k) {
        r->box[k] = 1e30f, r->box[3 + k] = -1e30f;
        r->centroids[k] = 1e30f, r->centroids[3 + k] = -1e30f;
    }
}

MESHFIX__PRIVATE void meshfix__range_add_slot(meshfix__range *r, const float *slot)
{
    r->count++;
    meshfix__grow_box(r->box, r->box + 3, slot);
    meshfix__grow_box(r->box, r->box + 3, slot + 3);
    meshfix__grow_box(r->centroids, r->centroids + 3, slot + MESHFIX__SLOT_CENTROID);
}

MESHFIX__PRIVATE void meshfix__range_add_range(meshfix__range *r, const meshfix__range *other)
{
    if (other->count == 0)
        return; /* its box is inside out: its corners are not points */
    r->count += other->count;
    meshfix__grow_box(r->box, r->box + 3, other->box);
    meshfix__grow_box(r->box, r->box + 3, other->box + 3);
    meshfix__grow_box(r->centroids, r->centroids + 3, other->centroids);
    meshfix__grow_box(r->centroids, r->centroids + 3, other->centroids + 3);
}

/* Float geometry (the tree, rays, sample points, coherence) works in a
   frame that maps the box of the model into [-1, 1]: re-centred, so a
   model far from the origin keeps its small features, and scaled by a
   power of two, which rounds nothing, so no difference or product of
   corners can overflow a float. */
MESHFIX__PRIVATE void meshfix__fit_frame(meshfix__bvh *b, const meshfix__mesh *m,
                                        int (*keep)(const meshfix__mesh *m, unsigned int t))
{
    double low[3] = {0, 0, 0}, high[3] = {0, 0, 0}, half = 0;
    unsigned int t, c, seen = 0;
    int k;
    for (t = 0; t < m->triangle_count; ++t) {
        if (!keep(m, t))
            continue;
        for (c = 0; c < 3; ++c) {
            const float *p = meshfix__position(m, m->indices[3 * t + c]);
            for (k = 0; k < 3; ++k) {
                double x = (double)p[k];
                low[k] = seen == 0 || x < low[k] ? x : low[k];
                high[k] = seen == 0 || x > high[k] ? x : high[k];
            }
            seen = 1;
        }
    }
    for (k = 0; k < 3; ++k) {
        b->center[k] = 0.5 * (low[k] + high[k]);
        half = 0.5 * (high[k] - low[k]) > half ? 0.5 * (high[k] - low[k]) : half;
    }
    b->scale = 1.0;
    while (half * b->scale > 1.0)
        b->scale *= 0.5;
    while (half > 0 && half * b->scale <= 0.5)
        b->scale *= 2.0;
}

MESHFIX__PRIVATE void meshfix__frame_point(const meshfix__bvh *b, const float *p, double out[3])
{
    int k;
    for (k = 0; k < 3; ++k)
        out[k] = ((double)p[k] - b->center[k]) * b->scale;
}

MESHFIX__PRIVATE void meshfix__frame_vertex_of(const meshfix__bvh *b, const float *p, float out[3])
{
    double x[3];
    meshfix__frame_point(b, p, x);
    out[0] = (float)x[0], out[1] = (float)x[1], out[2] = (float)x[2];
}

MESHFIX__PRIVATE void meshfix__frame_vertex(const meshfix__bvh *b, const meshfix__mesh *m, unsigned int v, float out[3])
{
    meshfix__frame_vertex_of(b, meshfix__position(m, v), out);
}

/* Corners by vertex id, not by winding: a hit (and its rounding) must
   not change when the triangle is flipped. */
MESHFIX__PRIVATE void meshfix__load_corners(const meshfix__bvh *b, const meshfix__mesh *m, unsigned int t,
                                           float corners[9])
{
    unsigned int sorted[3], c;
    meshfix__sorted_triangle(m, t, sorted);
    for (c = 0; c < 3; ++c)
        meshfix__frame_vertex(b, m, sorted[c], corners + 3 * c);
}

MESHFIX__PRIVATE void meshfix__fit_range(const meshfix__bvh *b, unsigned int first, unsigned int count,
                                         meshfix__range *r)
{
    unsigned int i;
    meshfix__empty_range(r);
    for (i = first; i < first + count; ++i)
        meshfix__range_add_slot(r, b->corners + 9 * (size_t)i);
}

/* Moves the slots whose centroid falls in a bin below `split` to the front;
   returns how many. */
MESHFIX__PRIVATE unsigned int meshfix__partition(meshfix__bvh *b, unsigned int first, unsigned int count, int axis,
                                                 double low, double scale, unsigned int split)
{
    unsigned int lo = first, hi = first + count;
    while (lo < hi) {
        float *c = b->corners + 9 * (size_t)lo;
        if (meshfix__bin((double)c[MESHFIX__SLOT_CENTROID + axis], low, scale) < split) {
            lo++;
        } else {
            float tmp[9];
            unsigned int id = b->order[lo];
            hi--;
            MESHFIX_MEMCPY(tmp, c, sizeof(tmp));
            MESHFIX_MEMCPY(c, b->corners + 9 * (size_t)hi, sizeof(tmp));
            MESHFIX_MEMCPY(b->corners + 9 * (size_t)hi, tmp, sizeof(tmp));
            b->order[lo] = b->order[hi];
            b->order[hi] = id;
        }
    }
    return lo - first;
}

/* Splits slots [first, first + r->count) at the best of 12 centroid bins
   along the widest axis of their centroids, by the surface area
   heuristic, and describes the halves; returns the size of the left one,
   0 for a leaf. */
MESHFIX__PRIVATE unsigned int meshfix__split(meshfix__bvh *b, unsigned int first, const meshfix__range *r,
                                             int use_sah, meshfix__range *left, meshfix__range *right)
{
    meshfix__range bins[MESHFIX__BINS], below[MESHFIX__BINS];
    unsigned int i, best = 0, j, count = r->count, half;
    float best_cost = 1e38f;
    double scale;
    int axis = 0, k;
    if (count <= MESHFIX__LEAF)
        return 0;
    for (k = 1; k < 3; ++k)
        axis = r->centroids[3 + k] - r->centroids[k] > r->centroids[3 + axis] - r->centroids[axis] ? k : axis;
    if (use_sah && r->centroids[3 + axis] > r->centroids[axis]) {
        scale = (double)MESHFIX__BINS / ((double)r->centroids[3 + axis] - (double)r->centroids[axis]);
        for (j = 0; j < MESHFIX__BINS; ++j)
            meshfix__empty_range(&bins[j]);
        for (i = first; i < first + count; ++i) {
            const float *c = b->corners + 9 * (size_t)i;
            meshfix__range_add_slot(&bins[meshfix__bin((double)c[MESHFIX__SLOT_CENTROID + axis],
                                                       (double)r->centroids[axis], scale)],
                                    c);
        }
        /* below[j]: bins 0 .. j - 1; the sweep back gathers the rest */
        meshfix__empty_range(&below[0]);
        for (j = 1; j < MESHFIX__BINS; ++j) {
            below[j] = below[j - 1];
            meshfix__range_add_range(&below[j], &bins[j - 1]);
        }
        meshfix__empty_range(right);
        for (j = MESHFIX__BINS - 1; j > 0; --j) {
            float cost;
            meshfix__range_add_range(right, &bins[j]);
            if (below[j].count == 0 || right->count == 0)
                continue;
            cost = meshfix__box_area(below[j].box, below[j].box + 3) * (float)below[j].count +
                   meshfix__box_area(right->box, right->box + 3) * (float)right->count;
            /* <= keeps the lowest of equal splits, as a forward search with < would */
            if (cost <= best_cost) {
                best_cost = cost;
                best = j;
            }
        }
        if (best != 0) {
            *left = below[best];
            meshfix__empty_range(right);
            for (j = best; j < MESHFIX__BINS; ++j)
                meshfix__range_add_range(right, &bins[j]);
            return meshfix__partition(b, first, count, axis, (double)r->centroids[axis], scale, best);
        }
    }
    /* all centroids in one point, in one bin, or the tree already deep:
       halve by slot */
    half = count / 2;
    meshfix__fit_range(b, first, half, left);
    meshfix__fit_range(b, first + half, count - half, right);
    return half;
}

MESHFIX__PRIVATE void meshfix__set_node(meshfix__bvh_node *n, unsigned int first, const meshfix__range *r)
{
    MESHFIX_MEMCPY(n->bounds, r->box, sizeof(n->bounds));
    n->first = first;
    n->count = r->count;
}

/* Builds the tree over the triangles with a finite, non-zero area (the
   `keep` test); the arrays come from the allocator. Returns 0 when out of
   memory. Deterministic: no randomness, splits depend only on positions
   and triangle order. */
MESHFIX__PRIVATE int meshfix__build_bvh(meshfix__bvh *b, const meshfix__mesh *m, const meshfix_allocator *a,
                                       int (*keep)(const meshfix__mesh *m, unsigned int t))
{
    unsigned int t, n = 0, stack[MESHFIX__BVH_STACK], level[MESHFIX__BVH_STACK], depth = 0;
    meshfix__range ranges[MESHFIX__BVH_STACK], whole;
    int k;
    MESHFIX_MEMSET(b, 0, sizeof(*b));
    meshfix__fit_frame(b, m, keep);
    /* corners of slot i: corners[9 * i ...] */
    for (t = 0; t < m->triangle_count; ++t)
        n += (unsigned int)keep(m, t);
    b->order = (unsigned int *)meshfix__allocate(a, n, sizeof(unsigned int));
    b->corners = (float *)meshfix__allocate(a, 9 * (size_t)n, sizeof(float));
    b->nodes = (meshfix__bvh_node *)meshfix__allocate(a, 2 * (size_t)n + 1, sizeof(meshfix__bvh_node));
    if (b->order == NULL || b->corners == NULL || b->nodes == NULL)
        return 0;
    for (t = 0; t < m->triangle_count; ++t) {
        float corners[9], *slot = b->corners + 9 * (size_t)b->count;
        if (!keep(m, t))
            continue;
        meshfix__load_corners(b, m, t, corners);
        MESHFIX_MEMCPY(slot, corners, 3 * sizeof(float));
        MESHFIX_MEMCPY(slot + 3, corners, 3 * sizeof(float));
        meshfix__grow_box(slot, slot + 3, corners + 3);
        meshfix__grow_box(slot, slot + 3, corners + 6);
        for (k = 0; k < 3; ++k)
            slot[MESHFIX__SLOT_CENTROID + k] = meshfix__centroid(corners, k);
        b->order[b->count++] = t;
    }
    meshfix__fit_range(b, 0, n, &whole);
    b->node_count = 1;
    meshfix__set_node(&b->nodes[0], 0, &whole);
    for (k = 0; k < 3; ++k)
        b->low[k] = whole.box[k], b->high[k] = whole.box[3 + k];
    for (k = 0; k < 3; ++k) {
        double side = (double)b->high[k] - (double)b->low[k];
        b->diagonal += n == 0 ? 0.0 : side * side;
    }
    b->diagonal = MESHFIX_SQRT(b->diagonal);
    stack[depth] = 0;
    level[depth] = 0;
    ranges[depth++] = whole;
    while (depth > 0) {
        meshfix__range r = ranges[--depth], left, right;
        meshfix__bvh_node *node = &b->nodes[stack[depth]];
        unsigned int first = node->first, split, below = level[depth] + 1;
        split = meshfix__split(b, first, &r, level[depth] < MESHFIX__BVH_SAH_LEVELS, &left, &right);
        if (split == 0 || split == r.count)
            continue;
        node->first = b->node_count;
        node->count = 0;
        meshfix__set_node(&b->nodes[b->node_count], first, &left);
        meshfix__set_node(&b->nodes[b->node_count + 1], first + split, &right);
        stack[depth] = b->node_count;
        level[depth] = below;
        ranges[depth++] = left;
        stack[depth] = b->node_count + 1;
        level[depth] = below;
        ranges[depth++] = right;
        b->node_count += 2;
    }
    for (t = 0; t < n; ++t)
        meshfix__load_corners(b, m, b->order[t], b->corners + 9 * (size_t)t);
    return 1;
}

MESHFIX__PRIVATE void meshfix__free_bvh(meshfix__bvh *b, const meshfix_allocator *a)
{
    meshfix__release(a, b->order);
    meshfix__release(a, b->corners);
    meshfix__release(a, b->nodes);
    MESHFIX_MEMSET(b, 0, sizeof(*b));
}

/* A direction component of 0 would make its inverse infinite and a slab
   test 0 * inf; it is nudged to +-1e-30 instead, so every value in a
   traversal stays finite (the frame keeps positions within [-1, 1]), which
   is also what -ffinite-math-only assumes. */
MESHFIX__PRIVATE void meshfix__setup_ray(meshfix__ray *r, const float origin[3], const float given[3],
                                        float t_min, float t_max)
{
    float direction[3], ax, ay, az;
    int k;
    for (k = 0; k < 3; ++k) {
        direction[k] = given[k];
        if (direction[k] > -1e-30f && direction[k] < 1e-30f)
            direction[k] = given[k] < 0 ? -1e-30f : 1e-30f;
        r->origin[k] = origin[k];
        r->direction[k] = direction[k];
        r->inverse[k] = 1.0f / direction[k];
        r->near_side[k] = r->inverse[k] < 0 ? k + 3 : k;
    }
    ax = direction[0] < 0 ? -direction[0] : direction[0];
    ay = direction[1] < 0 ? -direction[1] : direction[1];
    az = direction[2] < 0 ? -direction[2] : direction[2];
    r->kz = ax > ay ? (ax > az ? 0 : 2) : (ay > az ? 1 : 2);
    r->kx = (r->kz + 1) % 3;
    r->ky = (r->kx + 1) % 3;
    if (direction[r->kz] < 0) {
        int x = r->kx;
        r->kx = r->ky;
        r->ky = x;
    }
    r->shear[0] = direction[r->kx] / direction[r->kz];
    r->shear[1] = direction[r->ky] / direction[r->kz];
    r->shear[2] = 1.0f / direction[r->kz];
    r->t_min = t_min;
    r->t_max = t_max;
}

/* Watertight ray/triangle test; both sides hit. Returns 1 and the
   distance in *t when the ray meets the triangle within (t_min, t_max);
   *zeros tells how many edge functions were exactly 0: 1 on an edge, 2 on
   a vertex, where the neighbours report the same point. */
MESHFIX__PRIVATE int meshfix__hit_triangle(const meshfix__ray *r, const float *c, float *t, int *zeros)
{
    float a[3], b[3], d[3], ax, ay, bx, by, cx, cy, u, v, w, det, az, bz, cz, dist;
    int k;
    for (k = 0; k < 3; ++k) {
        a[k] = c[k] - r->origin[k];
        b[k] = c[3 + k] - r->origin[k];
        d[k] = c[6 + k] - r->origin[k];
    }
    ax = a[r->kx] - r->shear[0] * a[r->kz];
    ay = a[r->ky] - r->shear[1] * a[r->kz];
    bx = b[r->kx] - r->shear[0] * b[r->kz];
    by = b[r->ky] - r->shear[1] * b[r->kz];
    cx = d[r->kx] - r->shear[0] * d[r->kz];
    cy = d[r->ky] - r->shear[1] * d[r->kz];
    u = cx * by - cy * bx;
    v = ax * cy - ay * cx;
    w = bx * ay - by * ax;
    if (u == 0.0f || v == 0.0f || w == 0.0f) {
        /* on an edge in float: decide in double, as the paper does */
        u = (float)((double)cx * (double)by - (double)cy * (double)bx);
        v = (float)((double)ax * (double)cy - (double)ay * (double)cx);
        w = (float)((double)bx * (double)ay - (double)by * (double)ax);
    }
    if ((u < 0 || v < 0 || w < 0) && (u > 0 || v > 0 || w > 0))
        return 0;
    det = u + v + w;
    if (det == 0.0f)
        return 0;
    az = r->shear[2] * a[r->kz];
    bz = r->shear[2] * b[r->kz];
    cz = r->shear[2] * d[r->kz];
    dist = (u * az + v * bz + w * cz) / det;
    if (!(dist > r->t_min && dist < r->t_max))
        return 0;
    *t = dist;
    *zeros = (u == 0.0f) + (v == 0.0f) + (w == 0.0f);
    return 1;
}

/* Slab test; returns the entry distance, or a negative value for a miss.
   A ray aimed at a vertex on the box's face has an empty interval by
   rounding alone: the far side is widened by a few ulps (Ize, "Robust BVH
   Ray Traversal", JCGT 2013). */
MESHFIX__PRIVATE float meshfix__hit_box(const meshfix__ray *r, const meshfix__bvh_node *n, float t_max)
{
    const float *bounds = n->bounds;
    float tx0 = (bounds[r->near_side[0]] - r->origin[0]) * r->inverse[0];
    float tx1 = (bounds[3 - r->near_side[0]] - r->origin[0]) * r->inverse[0] * 1.0000004f;
    float ty0 = (bounds[r->near_side[1]] - r->origin[1]) * r->inverse[1];
    float ty1 = (bounds[5 - r->near_side[1]] - r->origin[1]) * r->inverse[1] * 1.0000004f;
    float tz0 = (bounds[r->near_side[2]] - r->origin[2]) * r->inverse[2];
    float tz1 = (bounds[7 - r->near_side[2]] - r->origin[2]) * r->inverse[2] * 1.0000004f;
    float t0 = r->t_min, t1 = t_max;
    t0 = tx0 > t0 ? tx0 : t0;
    t0 = ty0 > t0 ? ty0 : t0;
    t0 = tz0 > t0 ? tz0 : t0;
    t1 = tx1 < t1 ? tx1 : t1;
    t1 = ty1 < t1 ? ty1 : t1;
    t1 = tz1 < t1 ? tz1 : t1;
    return t0 <= t1 ? t0 : -1.0f;
}

/* What a traversal looks for: the first hit, the closest, or the number of
   hits on triangles outside one group (a crossing count for parity). */
#define MESHFIX__ANY_HIT 0
#define MESHFIX__CLOSEST_HIT 1
#define MESHFIX__COUNT_HITS 2

typedef struct meshfix__query {
    int mode;
    unsigned int skip;           /* a triangle to ignore (the ray's own), or NONE */
    const unsigned int *group;   /* COUNT_HITS: group of each triangle */
    unsigned int skip_group;     /* COUNT_HITS: hits on this group do not count */
    unsigned int hits;           /* COUNT_HITS: crossings, each counted once */
    unsigned int triangle;       /* ANY / CLOSEST: the triangle hit */
    float t;
} meshfix__query;

/* Crossing counts must count a ray through a shared edge or vertex once:
   every triangle around it reports the hit. An edge hit weighs a half (two
   triangles share a manifold edge, and both see the same exact zero); a
   vertex hit counts once per distinct distance. */
#define MESHFIX__VERTEX_HITS 8
typedef struct meshfix__crossings {
    unsigned int halves;
    float vertex_t[MESHFIX__VERTEX_HITS];
    unsigned int vertex_count;
} meshfix__crossings;

MESHFIX__PRIVATE void meshfix__count_crossing(meshfix__crossings *c, float t, int zeros)
{
    unsigned int i;
    if (zeros == 0) {
        c->halves += 2;
    } else if (zeros == 1) {
        c->halves += 1;
    } else {
        /* the triangles around a vertex round its distance differently */
        for (i = 0; i < c->vertex_count && !(c->vertex_t[i] - t <= 1e-6f * t && t - c->vertex_t[i] <= 1e-6f * t); ++i) {
        }
        if (i == c->vertex_count) {
            c->halves += 2;
            if (c->vertex_count < MESHFIX__VERTEX_HITS)
                c->vertex_t[c->vertex_count++] = t;
        }
    }
}

/* A ray that has visited this many nodes is taken as blocked (or stops
   counting). Ordinary rays visit a few dozen; a stack of coincident
   triangles or a fan of thousands of thin ones puts every box across a
   ray's path, and without a bound the rays of a model would cost the
   square of its size. */
#define MESHFIX__RAY_WORK 1024

MESHFIX__PRIVATE int meshfix__trace(const meshfix__bvh *b, const meshfix__ray *r, meshfix__query *q)
{
    unsigned int stack[MESHFIX__BVH_STACK], depth = 0, work = 0;
    float best = r->t_max;
    meshfix__crossings crossings;
    crossings.halves = crossings.vertex_count = 0;
    q->hits = 0;
    q->triangle = MESHFIX__NONE;
    if (b->count == 0)
        return 0;
    if (meshfix__hit_box(r, &b->nodes[0], best) < 0)
        return 0;
    stack[depth++] = 0;
    while (depth > 0) {
        const meshfix__bvh_node *n = &b->nodes[stack[--depth]];
        unsigned int i;
        if (++work > MESHFIX__RAY_WORK) {
            if (q->mode == MESHFIX__ANY_HIT)
                q->hits = 1;
            break;
        }
        if (n->count == 0) {
            /* both children tested here; the nearer one is visited first */
            float near_t = meshfix__hit_box(r, &b->nodes[n->first], best);
            float far_t = meshfix__hit_box(r, &b->nodes[n->first + 1], best);
            unsigned int near_node = n->first, far_node = n->first + 1;
            if (far_t >= 0 && (near_t < 0 || far_t < near_t)) {
                float x = near_t;
                near_t = far_t, far_t = x;
                near_node = n->first + 1, far_node = n->first;
            }
            MESHFIX_ASSERT(depth + 2 <= MESHFIX__BVH_STACK);
            if (far_t >= 0)
                stack[depth++] = far_node;
            if (near_t >= 0)
                stack[depth++] = near_node;
            continue;
        }
        for (i = n->first; i < n->first + n->count; ++i) {
            unsigned int id = b->order[i];
            float t;
            int zeros;
            if (id == q->skip || !meshfix__hit_triangle(r, b->corners + 9 * (size_t)i, &t, &zeros) || t >= best)
                continue;
            if (q->mode == MESHFIX__COUNT_HITS) {
                if (q->group[id] != q->skip_group)
                    meshfix__count_crossing(&crossings, t, zeros);
                continue;
            }
            q->triangle = id;
            q->t = t;
            q->hits = 1;
            if (q->mode == MESHFIX__ANY_HIT)
                return 1;
            best = t;
        }
    }
    if (q->mode == MESHFIX__COUNT_HITS)
        q->hits = (crossings.halves + 1) / 2;
    return q->hits != 0;
}

/* ===== >>visibility ===== */

/* Borodin, Zachmann, Klein: each patch side gets the share of random rays,
   shot from random points of the patch, that escape the model. Every
   sample has its own random stream (seed, patch, sample), and results are
   summed in sample order, so the numbers are bit-identical run to run and
   with or without the caller's parallel_for. */

MESHFIX__PRIVATE unsigned int meshfix__mix(unsigned int h)
{
    h ^= h >> 16;
    h *= 0x7FEB352Du;
    h ^= h >> 15;
    h *= 0x846CA68Bu;
    h ^= h >> 16;
    return h;
}

MESHFIX__PRIVATE float meshfix__random(unsigned int *state)
{
    *state = meshfix__mix(*state + 0x9E3779B9u);
    return (float)(*state >> 8) * (1.0f / 16777216.0f);
}

typedef struct meshfix__geometry {
    meshfix__mesh *m;
    const meshfix_options *o;
    meshfix_allocator allocator;
    meshfix__bvh bvh;
    double *patch_area;       /* per patch */
    double *cumulative_area;  /* per queue slot: area of the patch's triangles up to it */
    unsigned int *sample_start; /* per patch + 1: its first sample */
    unsigned char *sample_result; /* per sample: 1 front escaped, 2 back escaped */
    unsigned int sample_count;
    unsigned int seed;
    float t_min;
} meshfix__geometry;

/* Normal of t in its patch's consistent frame (its relative bit applied);
   *area is 0 when it is not finite. */
MESHFIX__PRIVATE void meshfix__relative_normal(const meshfix__mesh *m, unsigned int t, double n[3], double *area)
{
    double a[3], b[3], c[3], origin[3] = {0, 0, 0}, s;
    if (!meshfix__has_geometry(m, t)) {
        n[0] = n[1] = n[2] = *area = 0.0;
        return;
    }
    meshfix__load_triangle(m, t, origin, a, b, c, n);
    *area = 0.5 * MESHFIX_SQRT(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    s = (m->tri_bits[t] & MESHFIX__TRI_RELATIVE) ? -1.0 : 1.0;
    n[0] *= s, n[1] *= s, n[2] *= s;
}

MESHFIX__PRIVATE int meshfix__has_area(const meshfix__mesh *m, unsigned int t)
{
    double n[3], area;
    meshfix__relative_normal(m, t, n, &area);
    return area > 0.0;
}

/* A random point of patch p, drawn by area, and the triangle it lies on. */
MESHFIX__PRIVATE unsigned int meshfix__sample_point(const meshfix__geometry *g, unsigned int p, unsigned int *state,
                                                   float point[3])
{
    const meshfix__mesh *m = g->m;
    unsigned int lo = m->patch_start[p], hi = m->patch_start[p + 1] - 1, t;
    double target = (double)meshfix__random(state) * g->patch_area[p];
    float u = meshfix__random(state), v = meshfix__random(state), su, corners[9];
    int k;
    while (lo < hi) {
        unsigned int mid = lo + (hi - lo) / 2;
        if (g->cumulative_area[mid] <= target)
            lo = mid + 1;
        else
            hi = mid;
    }
    t = m->queue[lo];
    /* corners by vertex id: the point must not move when t is flipped */
    meshfix__load_corners(&g->bvh, m, t, corners);
    su = (float)MESHFIX_SQRT((double)u);
    for (k = 0; k < 3; ++k)
        point[k] = (1.0f - su) * corners[k] + su * (1.0f - v) * corners[3 + k] + su * v * corners[6 + k];
    return t;
}

MESHFIX__PRIVATE void meshfix__random_direction(unsigned int *state, float d[3])
{
    float z = 1.0f - 2.0f * meshfix__random(state), phi = 6.2831853f * meshfix__random(state);
    float r = (float)MESHFIX_SQRT((double)(1.0f - z * z > 0 ? 1.0f - z * z : 0.0f));
    d[0] = r * (float)MESHFIX_COS((double)phi);
    d[1] = r * (float)MESHFIX_SIN((double)phi);
    d[2] = z;
}

/* One visibility sample: 1 when it escapes from the front side, 2 from
   the back, 0 when the model blocks it. */
MESHFIX__PRIVATE unsigned char meshfix__visibility_sample(const meshfix__geometry *g, unsigned int p, unsigned int i)
{
    unsigned int state = meshfix__mix(g->seed ^ meshfix__mix(p * 0x9E3779B1u ^ meshfix__mix(i + 0x632BE5ABu)));
    float point[3], d[3];
    double n[3], area;
    meshfix__ray ray;
    meshfix__query q;
    unsigned int t = meshfix__sample_point(g, p, &state, point);
    meshfix__random_direction(&state, d);
    meshfix__relative_normal(g->m, t, n, &area);
    meshfix__setup_ray(&ray, point, d, g->t_min, 1e30f);
    q.mode = MESHFIX__ANY_HIT;
    q.skip = t;
    if (meshfix__trace(&g->bvh, &ray, &q))
        return 0;
    return n[0] * (double)d[0] + n[1] * (double)d[1] + n[2] * (double)d[2] >= 0 ? 1 : 2;
}

#define MESHFIX__CHUNK 256
MESHFIX__PRIVATE void meshfix__visibility_chunk(void *context, size_t chunk)
{
    const meshfix__geometry *g = (const meshfix__geometry *)context;
    unsigned int first = (unsigned int)(chunk * MESHFIX__CHUNK), end = first + MESHFIX__CHUNK, p = 0, lo, hi, s;
    end = end > g->sample_count ? g->sample_count : end;
    /* the patch of the first sample: binary search in sample_start */
    lo = 0, hi = (unsigned int)g->m->patch_count;
    while (lo + 1 < hi) {
        unsigned int mid = (lo + hi) / 2;
        if (g->sample_start[mid] <= first)
            lo = mid;
        else
            hi = mid;
    }
    p = lo;
    for (s = first; s < end; ++s) {
        while (s >= g->sample_start[p + 1])
            p++;
        g->sample_result[s] = meshfix__visibility_sample(g, p, s - g->sample_start[p]);
    }
}

/* Samples per patch: proportional to area within the budget, at least a
   floor each; when the floors alone would exceed the budget, strictly by
   area (small patches may get none: they tie and fall back to majority). */
MESHFIX__PRIVATE void meshfix__plan_samples(meshfix__geometry *g, double total_area)
{
    const meshfix_options *o = g->o;
    size_t patches = g->m->patch_count, budget, floor_count, p, sum = 0, spread;
    budget = o->visibility_rays != 0 ? o->visibility_rays : patches * 128;
    if (o->visibility_rays == 0)
        budget = budget < 65536 ? 65536 : budget > 1048576 ? 1048576 : budget;
    floor_count = o->visibility_min_samples != 0 ? o->visibility_min_samples : 16;
    if (floor_count > budget / (patches ? patches : 1))
        floor_count = budget / (patches ? patches : 1);
    spread = budget - floor_count * patches;
    for (p = 0; p < patches; ++p) {
        double share = total_area > 0 ? g->patch_area[p] / total_area : 0.0;
        size_t n = g->patch_area[p] > 0 ? floor_count + (size_t)((double)spread * share) : 0;
        g->sample_start[p] = (unsigned int)sum;
        sum += n;
    }
    g->sample_start[patches] = (unsigned int)sum;
    g->sample_count = (unsigned int)sum;
}

MESHFIX__PRIVATE int meshfix__measure_visibility(meshfix__geometry *g, double *front, double *back)
{
    size_t chunks, c, p;
    g->sample_result = (unsigned char *)meshfix__allocate(&g->allocator, g->sample_count, 1);
    if (g->sample_result == NULL)
        return 0;
    chunks = ((size_t)g->sample_count + MESHFIX__CHUNK - 1) / MESHFIX__CHUNK;
    if (g->o->parallel_for != NULL)
        g->o->parallel_for(meshfix__visibility_chunk, g, chunks, g->o->parallel_user);
    else
        for (c = 0; c < chunks; ++c)
            meshfix__visibility_chunk(g, c);
    for (p = 0; p < g->m->patch_count; ++p) {
        unsigned int s, n = g->sample_start[p + 1] - g->sample_start[p], f = 0, b = 0;
        for (s = g->sample_start[p]; s < g->sample_start[p + 1]; ++s) {
            f += g->sample_result[s] == 1;
            b += g->sample_result[s] == 2;
        }
        front[p] = n ? (double)f / n : 0.0;
        back[p] = n ? (double)b / n : 0.0;
    }
    return 1;
}

/* ===== >>coherence ===== */

/* Closest boundary edges of different patches within a search distance,
   found through a hash grid; the local coherence of two edges is
   -sgn(s) sqrt(|s|) / (1 + d), s the dot product of the edges (each run
   the way its patch's consistent frame runs it), d their distance, all
   lengths divided by the longest side of the bounding box. Patches that
   meet at a non-manifold edge are coherent at distance 0. Local values are
   summed per pair of patches. */

typedef struct meshfix__pair {
    unsigned int a, b;     /* patches, a < b */
    unsigned int low, high; /* the vertices of the edge that gave it: a canonical order for sums */
    double c, length;      /* coherence and the length of the edges that gave it */
} meshfix__pair;

typedef struct meshfix__segment {
    double p[3], q[3];     /* the positions of its lower and higher vertex */
    double sign;           /* +1 when the patch's frame runs it from p to q */
    unsigned int patch;
    unsigned int low, high; /* its vertices: ties break on these, not on winding or order */
} meshfix__segment;

MESHFIX__PRIVATE void meshfix__edge_segment(const meshfix__geometry *g, unsigned int h, double scale,
                                           meshfix__segment *s)
{
    const meshfix__mesh *m = g->m;
    unsigned int t = h / 3, next = h % 3 == 2 ? h - 2 : h + 1;
    int reverse = (m->tri_bits[t] & MESHFIX__TRI_RELATIVE) != 0, k;
    /* geometry by vertex id, winding as a sign: distances and their
       rounding must not depend on which way the input ran the edge */
    s->low = m->indices[h] < m->indices[next] ? m->indices[h] : m->indices[next];
    s->high = m->indices[h] < m->indices[next] ? m->indices[next] : m->indices[h];
    s->sign = ((m->indices[h] < m->indices[next]) != reverse) ? 1.0 : -1.0;
    meshfix__frame_point(&g->bvh, meshfix__position(m, s->low), s->p);
    meshfix__frame_point(&g->bvh, meshfix__position(m, s->high), s->q);
    for (k = 0; k < 3; ++k) {
        s->p[k] *= scale;
        s->q[k] *= scale;
    }
    s->patch = m->tri_patch[t];
}

MESHFIX__PRIVATE int meshfix__segment_before(const meshfix__segment *x, const meshfix__segment *y)
{
    return x->low < y->low || (x->low == y->low && (x->high < y->high || (x->high == y->high && x->patch < y->patch)));
}

MESHFIX__PRIVATE double meshfix__dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

MESHFIX__PRIVATE double meshfix__point_segment_distance(const double x[3], const meshfix__segment *f)
{
    double d[3], r[3], len, t, y[3];
    int k;
    for (k = 0; k < 3; ++k) {
        d[k] = f->q[k] - f->p[k];
        r[k] = x[k] - f->p[k];
    }
    len = meshfix__dot3(d, d);
    t = len > 0 ? meshfix__dot3(r, d) / len : 0.0;
    t = t < 0 ? 0 : t > 1 ? 1 : t;
    for (k = 0; k < 3; ++k)
        y[k] = r[k] - t * d[k];
    return MESHFIX_SQRT(meshfix__dot3(y, y));
}

/* How far edge f is from running along edge e: the mean distance of e's
   two ends and middle from f. The paper takes the shortest distance, but
   across a gap the neighbours of an edge's true counterpart touch its ends
   just as closely; this measure picks the edge that runs alongside. */
MESHFIX__PRIVATE double meshfix__segment_distance(const meshfix__segment *e, const meshfix__segment *f)
{
    double mid[3];
    int k;
    for (k = 0; k < 3; ++k)
        mid[k] = 0.5 * (e->p[k] + e->q[k]);
    return (meshfix__point_segment_distance(e->p, f) + meshfix__point_segment_distance(e->q, f) +
            meshfix__point_segment_distance(mid, f)) / 3.0;
}

MESHFIX__PRIVATE double meshfix__local_coherence(const meshfix__segment *e, const meshfix__segment *f, double d)
{
    double u[3], v[3], s;
    int k;
    for (k = 0; k < 3; ++k) {
        u[k] = e->q[k] - e->p[k];
        v[k] = f->q[k] - f->p[k];
    }
    s = meshfix__dot3(u, v) * e->sign * f->sign;
    return (s > 0 ? -1.0 : s < 0 ? 1.0 : 0.0) * MESHFIX_SQRT(s < 0 ? -s : s) / (1.0 + d);
}

MESHFIX__PRIVATE void meshfix__add_pair(meshfix__pair *pairs, size_t *count, const meshfix__segment *from,
                                        unsigned int other_patch, double c, double length)
{
    meshfix__pair *p = &pairs[(*count)++];
    p->a = from->patch < other_patch ? from->patch : other_patch;
    p->b = from->patch < other_patch ? other_patch : from->patch;
    p->low = from->low;
    p->high = from->high;
    p->c = c;
    p->length = length;
}

#define MESHFIX__NEAREST_CANDIDATES 128

typedef struct meshfix__grid {
    double cell;
    size_t mask;
    unsigned int *start;   /* per bucket + 1 */
    unsigned int *items;   /* segment ids, bucket by bucket */
} meshfix__grid;

MESHFIX__PRIVATE size_t meshfix__grid_bucket(const meshfix__grid *grid, double x, double y, double z)
{
    double c[3];
    c[0] = x, c[1] = y, c[2] = z;
    return meshfix__weld_hash(c, grid->mask);
}

MESHFIX__PRIVATE void meshfix__segment_cells(const meshfix__grid *grid, const meshfix__segment *s, double margin,
                                            double lo[3], double hi[3])
{
    int k;
    for (k = 0; k < 3; ++k) {
        double a = s->p[k] < s->q[k] ? s->p[k] : s->q[k], b = s->p[k] < s->q[k] ? s->q[k] : s->p[k];
        lo[k] = MESHFIX_FLOOR((a - margin) / grid->cell);
        hi[k] = MESHFIX_FLOOR((b + margin) / grid->cell);
    }
}

/* Cell ranges are walked with a double counter: past 2^52, ++x would not
   move (found by fuzzing: an edge of a zero-area triangle far outside the
   model). Such an edge, or one spanning many cells, neither enters the
   grid nor searches it. */
MESHFIX__PRIVATE int meshfix__cells_usable(const double lo[3], const double hi[3])
{
    int k;
    for (k = 0; k < 3; ++k)
        if (!(lo[k] > -1e12 && hi[k] < 1e12 && hi[k] - lo[k] <= 16.0))
            return 0;
    return 1;
}

/* Fills the grid: a counting sort of (bucket, segment) for every cell a
   segment's box touches. Pass 0 counts, pass 1 places. */
MESHFIX__PRIVATE void meshfix__grid_pass(meshfix__grid *grid, const meshfix__segment *segments, unsigned int count,
                                        int place)
{
    unsigned int i;
    for (i = 0; i < count; ++i) {
        double lo[3], hi[3], x, y, z;
        meshfix__segment_cells(grid, &segments[i], 0.0, lo, hi);
        if (!meshfix__cells_usable(lo, hi))
            continue;
        for (x = lo[0]; x <= hi[0]; ++x)
            for (y = lo[1]; y <= hi[1]; ++y)
                for (z = lo[2]; z <= hi[2]; ++z) {
                    size_t bucket = meshfix__grid_bucket(grid, x, y, z);
                    if (place)
                        grid->items[grid->start[bucket]++] = i;
                    else
                        grid->start[bucket + 1]++;
                }
    }
}

/* Stable bottom-up merge sort of pairs (no qsort: the order must not
   depend on the C library). */
MESHFIX__PRIVATE void meshfix__sort_pairs(meshfix__pair *pairs, meshfix__pair *tmp, size_t n,
                                         int (*before)(const meshfix__pair *, const meshfix__pair *))
{
    size_t width, i;
    meshfix__pair *src = pairs, *dst = tmp;
    for (width = 1; width < n; width *= 2) {
        for (i = 0; i < n; i += 2 * width) {
            size_t lo = i, mid = i + width < n ? i + width : n, hi = i + 2 * width < n ? i + 2 * width : n;
            size_t a = lo, b = mid, k = lo;
            while (a < mid && b < hi)
                dst[k++] = before(&src[b], &src[a]) ? src[b++] : src[a++];
            while (a < mid)
                dst[k++] = src[a++];
            while (b < hi)
                dst[k++] = src[b++];
        }
        src = src == pairs ? tmp : pairs;
        dst = dst == pairs ? tmp : pairs;
    }
    if (src != pairs)
        MESHFIX_MEMCPY(pairs, src, n * sizeof(meshfix__pair));
}

MESHFIX__PRIVATE int meshfix__pair_key_before(const meshfix__pair *x, const meshfix__pair *y)
{
    if (x->a != y->a)
        return x->a < y->a;
    if (x->b != y->b)
        return x->b < y->b;
    return x->low < y->low || (x->low == y->low && x->high < y->high);
}

MESHFIX__PRIVATE int meshfix__pair_patches_before(const meshfix__pair *x, const meshfix__pair *y)
{
    return x->a < y->a || (x->a == y->a && x->b < y->b);
}

MESHFIX__PRIVATE int meshfix__pair_strength_before(const meshfix__pair *x, const meshfix__pair *y)
{
    double cx = x->c < 0 ? -x->c : x->c, cy = y->c < 0 ? -y->c : y->c;
    return cx > cy || (cx == cy && meshfix__pair_patches_before(x, y));
}

/* Coherence of every pair of patches that have close boundaries or share a
   non-manifold edge; returns the pairs, summed per pair of patches, in
   *count (0 pairs is fine), or NULL when out of memory. */
MESHFIX__PRIVATE meshfix__pair *meshfix__measure_coherence(meshfix__geometry *g, size_t *count)
{
    meshfix__mesh *m = g->m;
    const meshfix_options *o = g->o;
    unsigned int h, half_edges = (unsigned int)(3 * m->triangle_count), n = 0, i;
    double longest = 0, scale, reach, average = 0, longest_edge = 0;
    meshfix__segment *segments;
    meshfix__pair *pairs, *tmp;
    meshfix__grid grid;
    size_t buckets = 16, pair_count = 0, out = 0, k;
    int axis;
    for (axis = 0; axis < 3; ++axis)
        longest = meshfix__maxd(longest, (double)g->bvh.high[axis] - (double)g->bvh.low[axis]);
    scale = longest > 0 ? 1.0 / longest : 1.0;
    reach = o->coherence_distance > 0 ? (double)o->coherence_distance : 0.02;
    for (h = 0; h < half_edges; ++h)
        n += (m->mate[h] == MESHFIX__NONE || meshfix__is_ring(m->mate[h])) && meshfix__has_geometry(m, h / 3);
    segments = (meshfix__segment *)meshfix__allocate(&g->allocator, n, sizeof(meshfix__segment));
    pairs = (meshfix__pair *)meshfix__allocate(&g->allocator, n, sizeof(meshfix__pair));
    tmp = (meshfix__pair *)meshfix__allocate(&g->allocator, n, sizeof(meshfix__pair));
    MESHFIX_MEMSET(&grid, 0, sizeof(grid));
    if (segments == NULL || pairs == NULL || tmp == NULL)
        goto fail;
    /* boundary edges first (they search), then ring members */
    n = 0;
    for (h = 0; h < half_edges; ++h)
        if (m->mate[h] == MESHFIX__NONE && meshfix__has_geometry(m, h / 3)) {
            double len;
            meshfix__edge_segment(g, h, scale, &segments[n]);
            len = MESHFIX_SQRT((segments[n].q[0] - segments[n].p[0]) * (segments[n].q[0] - segments[n].p[0]) +
                               (segments[n].q[1] - segments[n].p[1]) * (segments[n].q[1] - segments[n].p[1]) +
                               (segments[n].q[2] - segments[n].p[2]) * (segments[n].q[2] - segments[n].p[2]));
            average += len;
            longest_edge = len > longest_edge ? len : longest_edge;
            n++;
        }
    if (n != 0) {
        average /= n;
        grid.cell = reach > average ? reach : average;
        /* a cell at least a quarter of the longest edge: no edge's box
           covers more than 5 x 5 x 5 cells */
        grid.cell = grid.cell > longest_edge / 4 ? grid.cell : longest_edge / 4;
        while (buckets < 2 * (size_t)n)
            buckets *= 2;
        grid.mask = buckets - 1;
        grid.start = (unsigned int *)meshfix__allocate(&g->allocator, buckets + 1, sizeof(unsigned int));
        if (grid.start == NULL)
            goto fail;
        MESHFIX_MEMSET(grid.start, 0, (buckets + 1) * sizeof(unsigned int));
        meshfix__grid_pass(&grid, segments, n, 0);
        for (k = 0; k < buckets; ++k)
            grid.start[k + 1] += grid.start[k];
        grid.items = (unsigned int *)meshfix__allocate(&g->allocator, grid.start[buckets], sizeof(unsigned int));
        if (grid.items == NULL)
            goto fail;
        meshfix__grid_pass(&grid, segments, n, 1); /* start[b] now ends bucket b */
    }
    for (i = 0; i < n; ++i) {
        double lo[3], hi[3], inner_lo[3], inner_hi[3], x, y, z, best = reach, length;
        unsigned int best_id = MESHFIX__NONE, looked = 0;
        int ring;
        meshfix__segment_cells(&grid, &segments[i], reach, lo, hi);
        meshfix__segment_cells(&grid, &segments[i], 0.0, inner_lo, inner_hi);
        if (!meshfix__cells_usable(lo, hi))
            continue;
        /* the cells the edge touches first, then the margin around them, and
           at most MESHFIX__NEAREST_CANDIDATES edges in all: where thousands
           of boundary edges crowd one place (a huge fan, a soup of large
           triangles) the search stays linear, and what it drops is far */
        for (ring = 0; ring < 2; ++ring)
            for (x = lo[0]; x <= hi[0]; ++x)
                for (y = lo[1]; y <= hi[1]; ++y)
                    for (z = lo[2]; z <= hi[2]; ++z) {
                        size_t bucket, j;
                        int inner = x >= inner_lo[0] && x <= inner_hi[0] && y >= inner_lo[1] && y <= inner_hi[1] &&
                                    z >= inner_lo[2] && z <= inner_hi[2];
                        if (inner != (ring == 0))
                            continue;
                        bucket = meshfix__grid_bucket(&grid, x, y, z);
                        for (j = bucket == 0 ? 0 : grid.start[bucket - 1];
                             j < grid.start[bucket] && looked < MESHFIX__NEAREST_CANDIDATES; ++j, ++looked) {
                            unsigned int f = grid.items[j];
                            double d;
                            if (segments[f].patch == segments[i].patch)
                                continue;
                            d = meshfix__segment_distance(&segments[i], &segments[f]);
                            if (d < best || (d == best && (best_id == MESHFIX__NONE ||
                                                           meshfix__segment_before(&segments[f], &segments[best_id])))) {
                                best = d;
                                best_id = f;
                            }
                        }
                    }
        if (best_id == MESHFIX__NONE)
            continue;
        length = MESHFIX_SQRT((segments[i].q[0] - segments[i].p[0]) * (segments[i].q[0] - segments[i].p[0]) +
                              (segments[i].q[1] - segments[i].p[1]) * (segments[i].q[1] - segments[i].p[1]) +
                              (segments[i].q[2] - segments[i].p[2]) * (segments[i].q[2] - segments[i].p[2]));
        meshfix__add_pair(pairs, &pair_count, &segments[i], segments[best_id].patch,
                          meshfix__local_coherence(&segments[i], &segments[best_id], best), length);
    }
    /* patches around a non-manifold edge: each ring member with the next
       member of another patch, at distance 0 */
    for (h = 0; h < half_edges; ++h) {
        unsigned int first, cur;
        if (!meshfix__is_ring_last(m, h))
            continue;
        first = m->mate[h] & ~MESHFIX__RING;
        for (cur = first;; cur = m->mate[cur] & ~MESHFIX__RING) {
            unsigned int next = m->mate[cur] & ~MESHFIX__RING;
            meshfix__segment a, b;
            if (meshfix__has_geometry(m, cur / 3) && meshfix__has_geometry(m, next / 3)) {
                meshfix__edge_segment(g, cur, scale, &a);
                meshfix__edge_segment(g, next, scale, &b);
                if (a.patch != b.patch) {
                    double length = MESHFIX_SQRT((a.q[0] - a.p[0]) * (a.q[0] - a.p[0]) +
                                                 (a.q[1] - a.p[1]) * (a.q[1] - a.p[1]) +
                                                 (a.q[2] - a.p[2]) * (a.q[2] - a.p[2]));
                    meshfix__add_pair(pairs, &pair_count, &a, b.patch, meshfix__local_coherence(&a, &b, 0.0), length);
                }
            }
            if (cur == h)
                break;
        }
    }
    /* sum per pair of patches */
    meshfix__sort_pairs(pairs, tmp, pair_count, meshfix__pair_key_before);
    for (k = 0; k < pair_count; ++k) {
        if (out > 0 && pairs[out - 1].a == pairs[k].a && pairs[out - 1].b == pairs[k].b) {
            pairs[out - 1].c += pairs[k].c;
            pairs[out - 1].length += pairs[k].length;
        } else {
            pairs[out++] = pairs[k];
        }
    }
    meshfix__sort_pairs(pairs, tmp, out, meshfix__pair_strength_before);
    meshfix__release(&g->allocator, segments);
    meshfix__release(&g->allocator, tmp);
    meshfix__release(&g->allocator, grid.start);
    meshfix__release(&g->allocator, grid.items);
    *count = out;
    return pairs;
fail:
    meshfix__release(&g->allocator, segments);
    meshfix__release(&g->allocator, pairs);
    meshfix__release(&g->allocator, tmp);
    meshfix__release(&g->allocator, grid.start);
    meshfix__release(&g->allocator, grid.items);
    return NULL;
}

/* ===== >>merge ===== */

/* Greedy merge into super-patches (Borodin et al. 3.5). Pairs are taken by
   |c|, strongest first; a union-find with orientation parity holds the
   super-patches. Each super-patch keeps its visibility (vf >= vb in its
   current frame) and area. Conforming pairs merge, each side to its more
   visible face; conflicting pairs merge along the coherence when it is
   strong (|c| / l > C0), or when one side's visibility hardly matters
   (both below eps_v, or their ratio below k_v); otherwise they stay apart.
   Unlike the paper, a merged super-patch keeps its members' pairs rather
   than summing them into new ones: the queue is sorted once, O(P log P). */

typedef struct meshfix__merge {
    unsigned int *parent;
    unsigned char *parity;  /* frame of a node relative to its parent */
    unsigned char *turn;    /* roots: frame relative to their own patch's consistent frame */
    double *front, *back, *area;
} meshfix__merge;

MESHFIX__PRIVATE unsigned int meshfix__merge_find(meshfix__merge *g, unsigned int p, unsigned int *parity)
{
    unsigned int root = p, acc = 0, next;
    while (g->parent[root] != root) {
        acc ^= g->parity[root];
        root = g->parent[root];
    }
    /* compress: point every node on the path straight at the root */
    next = p;
    while (g->parent[next] != next) {
        unsigned int up = g->parent[next], own = g->parity[next];
        g->parent[next] = root;
        g->parity[next] = (unsigned char)acc;
        acc ^= own;
        next = up;
    }
    *parity = p != root ? g->parity[p] : 0u;
    return root;
}

/* The final turn of patch p relative to its consistent frame. */
MESHFIX__PRIVATE unsigned int meshfix__merge_turn(meshfix__merge *g, unsigned int p)
{
    unsigned int parity, root = meshfix__merge_find(g, p, &parity);
    return parity ^ g->turn[root];
}

MESHFIX__PRIVATE int meshfix__hardly_visible(double vmax, double vmin, double eps, double kv)
{
    return (vmin > eps && vmax / vmin < kv) || (vmin < eps && vmax < eps);
}

/* Joins the super-patches of A and B, turned by flip_a and flip_b, with
   the visibility front/back of the result. */
MESHFIX__PRIVATE void meshfix__join(meshfix__merge *g, unsigned int a, unsigned int b, unsigned int flip_a,
                                   unsigned int flip_b, double front, double back)
{
    unsigned int root = a < b ? a : b, child = a < b ? b : a;
    g->turn[a] ^= (unsigned char)flip_a;
    g->turn[b] ^= (unsigned char)flip_b;
    g->parent[child] = root;
    g->parity[child] = (unsigned char)(g->turn[child] ^ g->turn[root]);
    g->area[root] = g->area[a] + g->area[b];
    g->front[root] = front;
    g->back[root] = back;
}

typedef struct meshfix__merge_params {
    double c0, eps, kv;
    int use_visibility, use_coherence;
} meshfix__merge_params;

/* Decides one pair; returns 1 when it merged. */
MESHFIX__PRIVATE int meshfix__merge_pair(meshfix__merge *g, const meshfix__pair *pair, const meshfix__merge_params *k)
{
    unsigned int pa, pb, a = meshfix__merge_find(g, pair->a, &pa), b = meshfix__merge_find(g, pair->b, &pb);
    double c, area, va_max, va_min, vb_max, vb_min, v1, v2;
    unsigned int fa, fb, flip_to_cohere;
    if (a == b || pair->c == 0.0)
        return 0; /* already one; or edges at right angles, which say nothing */
    /* the coherence between the two super-patches as they are now turned */
    c = pair->c * ((pa ^ g->turn[a]) ? -1.0 : 1.0) * ((pb ^ g->turn[b]) ? -1.0 : 1.0);
    flip_to_cohere = c < 0; /* turn one of them over to make c positive */
    if (!k->use_visibility) {
        meshfix__join(g, a, b, 0, flip_to_cohere, 0, 0);
        return 1;
    }
    area = g->area[a] + g->area[b];
    if (!(area > 0))
        return 0;
    fa = g->front[a] < g->back[a]; /* 1: its more visible side is its back */
    fb = g->front[b] < g->back[b];
    /* a side with no preference follows the coherence (and a choice that
       depended on which way the input happened to wind would make the
       result depend on it too) */
    if (g->front[a] == g->back[a])
        fa = g->front[b] == g->back[b] ? 0u : fb ^ flip_to_cohere;
    if (g->front[b] == g->back[b])
        fb = fa ^ flip_to_cohere;
    va_max = meshfix__maxd(g->front[a], g->back[a]), va_min = meshfix__mind(g->front[a], g->back[a]);
    vb_max = meshfix__maxd(g->front[b], g->back[b]), vb_min = meshfix__mind(g->front[b], g->back[b]);
    if ((fa ^ fb ^ flip_to_cohere) == 0) {
        /* conforming: both to their more visible side, and coherent */
        meshfix__join(g, a, b, fa, fb, (va_max * g->area[a] + vb_max * g->area[b]) / area,
                      (va_min * g->area[a] + vb_min * g->area[b]) / area);
        return 1;
    }
    v1 = (va_max * g->area[a] + vb_min * g->area[b]) / area; /* A to its best side, B follows */
    v2 = (va_min * g->area[a] + vb_max * g->area[b]) / area; /* B to its best side, A follows */
    if ((pair->length > 0 && (c < 0 ? -c : c) / pair->length > k->c0) ||
        (meshfix__hardly_visible(va_max, va_min, k->eps, k->kv) && v1 < v2) ||
        (meshfix__hardly_visible(vb_max, vb_min, k->eps, k->kv) && v2 < v1)) {
        if (v1 >= v2)
            meshfix__join(g, a, b, fa, fa ^ flip_to_cohere, v1, v2);
        else
            meshfix__join(g, a, b, fb ^ flip_to_cohere, fb, v2, v1);
        return 1;
    }
    return 0;
}

/* ===== >>nesting ===== */

/* A closed shell is a cavity when it lies inside an odd number of other
   surfaces and crosses none. Inside: rays from many points of the shell
   cross the rest of the model an odd number of times; a majority (3 of 4)
   decides, so an outer shell with gaps still encloses. Crossing: an edge
   of the shell passes through a triangle of another patch. */
#define MESHFIX__NESTING_SAMPLES 32

MESHFIX__PRIVATE int meshfix__shell_crosses(const meshfix__geometry *g, unsigned int p)
{
    const meshfix__mesh *m = g->m;
    unsigned int i;
    meshfix__query q;
    q.mode = MESHFIX__COUNT_HITS;
    q.skip = MESHFIX__NONE;
    q.group = m->tri_patch;
    q.skip_group = p;
    for (i = m->patch_start[p]; i < m->patch_start[p + 1]; ++i) {
        unsigned int t = m->queue[i], k;
        if (!meshfix__has_geometry(m, t))
            continue;
        for (k = 0; k < 3; ++k) {
            float a[3], b[3], d[3];
            meshfix__ray ray;
            meshfix__frame_vertex(&g->bvh, m, m->indices[3 * t + k], a);
            meshfix__frame_vertex(&g->bvh, m, m->indices[3 * t + (k + 1) % 3], b);
            d[0] = b[0] - a[0], d[1] = b[1] - a[1], d[2] = b[2] - a[2];
            meshfix__setup_ray(&ray, a, d, 1e-4f, 1.0f - 1e-4f);
            if (meshfix__trace(&g->bvh, &ray, &q))
                return 1;
        }
    }
    return 0;
}

/* Returns 1 when the shell is a cavity; *confidence in [0, 1]. */
MESHFIX__PRIVATE int meshfix__shell_is_cavity(const meshfix__geometry *g, unsigned int p, float *confidence)
{
    unsigned int i, odd = 0;
    meshfix__query q;
    if (meshfix__shell_crosses(g, p)) {
        *confidence = 1.0f;
        return 0;
    }
    q.mode = MESHFIX__COUNT_HITS;
    q.skip = MESHFIX__NONE;
    q.group = g->m->tri_patch;
    q.skip_group = p;
    for (i = 0; i < MESHFIX__NESTING_SAMPLES; ++i) {
        unsigned int state = meshfix__mix(g->seed ^ 0xC0FFEEu ^ meshfix__mix(p * 0x9E3779B1u ^ meshfix__mix(i)));
        float point[3], d[3];
        meshfix__ray ray;
        meshfix__sample_point(g, p, &state, point);
        meshfix__random_direction(&state, d);
        meshfix__setup_ray(&ray, point, d, g->t_min, 1e30f);
        meshfix__trace(&g->bvh, &ray, &q);
        odd += q.hits & 1u;
    }
    *confidence = (float)(odd * 2 > MESHFIX__NESTING_SAMPLES ? 2 * odd - MESHFIX__NESTING_SAMPLES
                                                              : MESHFIX__NESTING_SAMPLES - 2 * odd) /
                  (float)MESHFIX__NESTING_SAMPLES;
    return 4 * odd >= 3 * MESHFIX__NESTING_SAMPLES;
}

/* ===== >>geometry ===== */

MESHFIX__PRIVATE void meshfix__free_geometry(meshfix__geometry *g)
{
    meshfix__free_bvh(&g->bvh, &g->allocator);
    meshfix__release(&g->allocator, g->patch_area);
    meshfix__release(&g->allocator, g->cumulative_area);
    meshfix__release(&g->allocator, g->sample_start);
    meshfix__release(&g->allocator, g->sample_result);
}

MESHFIX__PRIVATE void meshfix__decide(meshfix__mesh *m, unsigned int p, unsigned int turn, float confidence)
{
    m->patch_bits[p] = (unsigned char)(m->patch_bits[p] | MESHFIX__PATCH_DECIDED | (turn ? MESHFIX__PATCH_FLIP : 0u));
    if (m->confidence != NULL)
        m->confidence[p] = confidence;
}

/* UP: each patch faces the side its area-weighted normal leans to. */
MESHFIX__PRIVATE void meshfix__decide_up(meshfix__mesh *m, const meshfix_options *o)
{
    double up[3] = {0, 0, 1}, length;
    unsigned int p;
    if (o->up[0] != 0 || o->up[1] != 0 || o->up[2] != 0)
        up[0] = (double)o->up[0], up[1] = (double)o->up[1], up[2] = (double)o->up[2];
    length = MESHFIX_SQRT(up[0] * up[0] + up[1] * up[1] + up[2] * up[2]);
    for (p = 0; p < m->patch_count; ++p) {
        meshfix__patch_sums s;
        double lean;
        meshfix__sum_patch(m, p, &s);
        lean = (s.normal[0] * up[0] + s.normal[1] * up[1] + s.normal[2] * up[2]) / length;
        /* a closed shell leans nowhere: its sum is zero up to rounding,
           which must not decide (the majority does) */
        if ((lean < 0 ? -lean : lean) > 1e-6 * s.area)
            meshfix__decide(m, p, lean < 0, (float)((lean < 0 ? -lean : lean) / s.area));
    }
}

/* Closed shells: outward, or inward when they are cavities. */
MESHFIX__PRIVATE void meshfix__decide_shells(meshfix__geometry *g, meshfix_report *r)
{
    meshfix__mesh *m = g->m;
    unsigned int p;
    for (p = 0; p < m->patch_count; ++p) {
        meshfix__patch_sums s;
        float confidence;
        int cavity;
        if (!meshfix__is_closed_orientable(m, p))
            continue;
        meshfix__sum_patch(m, p, &s);
        if (!meshfix__volume_is_meaningful(s.volume_relative, s.area))
            continue;
        cavity = meshfix__shell_is_cavity(g, p, &confidence);
        r->shells_inward += (size_t)cavity;
        meshfix__decide(m, p, (unsigned int)((s.volume_relative < 0) != cavity), confidence);
    }
}

MESHFIX__PRIVATE int meshfix__decide_visibility(meshfix__geometry *g, meshfix_report *r)
{
    meshfix__mesh *m = g->m;
    const meshfix_options *o = g->o;
    size_t pair_count = 0, i, patches = m->patch_count;
    meshfix__pair *pairs = NULL;
    meshfix__merge merge;
    meshfix__merge_params k;
    double total_area = 0;
    unsigned int p, *open = NULL;
    int ok = 0;
    k.c0 = o->visibility_c0 > 0 ? (double)o->visibility_c0 : 0.5;
    k.eps = o->visibility_eps > 0 ? (double)o->visibility_eps : 0.02;
    k.kv = o->visibility_kv > 0 ? (double)o->visibility_kv : 1.5;
    k.use_visibility = !(o->visibility_flags & MESHFIX_VISIBILITY_COHERENCE_ONLY);
    k.use_coherence = !(o->visibility_flags & MESHFIX_VISIBILITY_ONLY);
    MESHFIX_MEMSET(&merge, 0, sizeof(merge));
    merge.parent = (unsigned int *)meshfix__allocate(&g->allocator, patches, sizeof(unsigned int));
    merge.parity = (unsigned char *)meshfix__allocate(&g->allocator, patches, 1);
    merge.turn = (unsigned char *)meshfix__allocate(&g->allocator, patches, 1);
    merge.front = (double *)meshfix__allocate(&g->allocator, patches, sizeof(double));
    merge.back = (double *)meshfix__allocate(&g->allocator, patches, sizeof(double));
    merge.area = (double *)meshfix__allocate(&g->allocator, patches, sizeof(double));
    open = (unsigned int *)meshfix__allocate(&g->allocator, patches, sizeof(unsigned int));
    if (!merge.parent || !merge.parity || !merge.turn || !merge.front || !merge.back || !merge.area || !open)
        goto done;
    /* the patches still to decide; the decided ones take no samples */
    for (p = 0; p < patches; ++p) {
        open[p] = !(m->patch_bits[p] & MESHFIX__PATCH_DECIDED);
        merge.parent[p] = p;
        merge.parity[p] = merge.turn[p] = 0;
        merge.area[p] = g->patch_area[p];
        total_area += open[p] ? g->patch_area[p] : 0.0;
    }
    if (k.use_visibility) {
        double *saved = g->patch_area, *weights;
        weights = (double *)meshfix__allocate(&g->allocator, patches, sizeof(double));
        if (weights == NULL)
            goto done;
        for (p = 0; p < patches; ++p)
            weights[p] = open[p] ? g->patch_area[p] : 0.0;
        g->patch_area = weights;
        meshfix__plan_samples(g, total_area);
        g->patch_area = saved;
        meshfix__release(&g->allocator, weights);
        if (!meshfix__measure_visibility(g, merge.front, merge.back))
            goto done;
        r->rays_cast += g->sample_count;
    } else {
        for (p = 0; p < patches; ++p)
            merge.front[p] = merge.back[p] = 0;
    }
    if (k.use_coherence) {
        size_t kept = 0;
        pairs = meshfix__measure_coherence(g, &pair_count);
        if (pairs == NULL)
            goto done;
        for (i = 0; i < pair_count; ++i)
            if (open[pairs[i].a] && open[pairs[i].b])
                pairs[kept++] = pairs[i];
        pair_count = kept;
        r->patch_pairs += pair_count;
        for (i = 0; i < pair_count; ++i)
            r->patches_merged += (size_t)meshfix__merge_pair(&merge, &pairs[i], &k);
    }
    /* every super-patch to its more visible side; without a visibility
       margin (or without visibility at all), to its majority side */
    for (p = 0; p < patches; ++p) {
        unsigned int parity;
        if (open[p] && meshfix__merge_find(&merge, p, &parity) == p) {
            if (merge.front[p] < merge.back[p])
                merge.turn[p] ^= 1;
            else if (merge.front[p] == merge.back[p])
                open[p] = 2; /* decided below by the members' majority */
        }
    }
    {
        /* majority of tied super-patches: area given as is, per root frame */
        double *kept_area = merge.front, *reversed_area = merge.back;
        for (p = 0; p < patches; ++p)
            if (open[p] == 2)
                kept_area[p] = reversed_area[p] = 0;
        for (p = 0; p < patches; ++p) {
            unsigned int parity, root;
            meshfix__patch_sums s;
            if (!open[p])
                continue;
            root = meshfix__merge_find(&merge, p, &parity);
            if (open[root] != 2)
                continue;
            meshfix__sum_patch(m, p, &s);
            /* as the super-patch is turned now, what would keep its winding */
            parity ^= merge.turn[root];
            kept_area[root] += parity ? s.weight_reversed : s.weight_kept;
            reversed_area[root] += parity ? s.weight_kept : s.weight_reversed;
        }
        for (p = 0; p < patches; ++p)
            if (open[p] == 2 && kept_area[p] < reversed_area[p])
                merge.turn[p] ^= 1;
    }
    for (p = 0; p < patches; ++p) {
        unsigned int parity, root;
        double margin;
        if (!open[p])
            continue;
        root = meshfix__merge_find(&merge, p, &parity);
        margin = open[root] == 2 || !k.use_visibility ? 0.0
                 : (meshfix__maxd(merge.front[root], merge.back[root]) - meshfix__mind(merge.front[root], merge.back[root])) /
                       (merge.front[root] + merge.back[root]);
        meshfix__decide(m, p, parity ^ merge.turn[root], (float)margin);
    }
    for (i = 0; i < pair_count; ++i) {
        unsigned int ta = meshfix__merge_turn(&merge, pairs[i].a), tb = meshfix__merge_turn(&merge, pairs[i].b);
        r->pairs_conflicting += (size_t)(pairs[i].c * ((ta ^ tb) ? -1.0 : 1.0) < 0);
    }
    ok = 1;
done:
    meshfix__release(&g->allocator, pairs);
    meshfix__release(&g->allocator, merge.parent);
    meshfix__release(&g->allocator, merge.parity);
    meshfix__release(&g->allocator, merge.turn);
    meshfix__release(&g->allocator, merge.front);
    meshfix__release(&g->allocator, merge.back);
    meshfix__release(&g->allocator, merge.area);
    meshfix__release(&g->allocator, open);
    return ok;
}

/* Decides the patches that need ray queries or an axis: the nesting of
   closed shells (OUTWARD, AUTO), visibility and coherence (VISIBILITY; AUTO
   for the rest), the up axis (UP). Returns 0 when out of memory. */
MESHFIX__PRIVATE int meshfix__decide_by_geometry(meshfix__mesh *m, const meshfix_allocator *allocator,
                                                meshfix_report *r)
{
    meshfix__geometry g;
    int policy = m->policy, ok = 1;
    unsigned int p, i;
    if (policy == MESHFIX_POLICY_UP) {
        meshfix__decide_up(m, m->options);
        return 1;
    }
    if (policy != MESHFIX_POLICY_OUTWARD && policy != MESHFIX_POLICY_AUTO && policy != MESHFIX_POLICY_VISIBILITY)
        return 1;
    /* one closed shell alone: nothing to nest in, its volume decides */
    if (policy != MESHFIX_POLICY_VISIBILITY && m->patch_count == 1 && meshfix__is_closed_orientable(m, 0))
        return 1;
    MESHFIX_MEMSET(&g, 0, sizeof(g));
    g.m = m;
    g.o = m->options;
    g.allocator = *allocator;
    g.seed = m->options->seed != 0 ? m->options->seed : 0x5EEDu;
    g.patch_area = (double *)meshfix__allocate(allocator, m->patch_count, sizeof(double));
    g.cumulative_area = (double *)meshfix__allocate(allocator, m->triangle_count, sizeof(double));
    g.sample_start = (unsigned int *)meshfix__allocate(allocator, m->patch_count + 1, sizeof(unsigned int));
    if (!g.patch_area || !g.cumulative_area || !g.sample_start || !meshfix__build_bvh(&g.bvh, m, allocator, meshfix__has_area)) {
        meshfix__free_geometry(&g);
        return 0;
    }
    g.t_min = (float)(1e-5 * g.bvh.diagonal);
    for (p = 0; p < m->patch_count; ++p) {
        double sum = 0;
        for (i = m->patch_start[p]; i < m->patch_start[p + 1]; ++i) {
            double n[3], area;
            meshfix__relative_normal(m, m->queue[i], n, &area);
            sum += area;
            g.cumulative_area[i] = sum;
        }
        g.patch_area[p] = sum;
    }
    if (policy != MESHFIX_POLICY_VISIBILITY)
        meshfix__decide_shells(&g, r);
    if (policy != MESHFIX_POLICY_OUTWARD)
        ok = meshfix__decide_visibility(&g, r);
    meshfix__free_geometry(&g);
    return ok;
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
    return o->components != NULL && component < o->components_capacity ? &o->components[component] : NULL;
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
                        if (m->positions != NULL)
                            r->vertices_non_finite += (size_t)!meshfix__is_finite_point(meshfix__position(m, v[k]));
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

/* How clear a decision made from the patch's own sums was: the margin of
   the vote that decided it, 0 a coin flip, 1 unanimous. */
MESHFIX__PRIVATE float meshfix__confidence(const meshfix__mesh *m, unsigned int p, int policy,
                                          const meshfix__patch_sums *s)
{
    double total = s->weight_kept + s->weight_reversed, margin = s->weight_kept - s->weight_reversed;
    if (policy == MESHFIX_POLICY_SEED)
        return 1.0f;
    if (policy == MESHFIX_POLICY_SDF && s->area > 0)
        return (float)((s->sdf_vote < 0 ? -s->sdf_vote : s->sdf_vote) / s->area);
    if ((policy == MESHFIX_POLICY_OUTWARD || policy == MESHFIX_POLICY_AUTO) && meshfix__is_closed_orientable(m, p) &&
        meshfix__volume_is_meaningful(s->volume_relative, s->area))
        return 1.0f;
    return total > 0 ? (float)((margin < 0 ? -margin : margin) / total) : 0.0f;
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
        if (o->patch_confidence != NULL && p < o->patch_confidence_capacity && policy >= 0)
            o->patch_confidence[p] = m->confidence != NULL && (bits & MESHFIX__PATCH_DECIDED)
                                         ? m->confidence[p]
                                         : meshfix__confidence(m, p, policy, &s);
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
MESHFIX__PRIVATE meshfix_result meshfix__analyze(meshfix__mesh *m, int policy, const meshfix_options *o, int full,
                                                 const meshfix_allocator *allocator, meshfix_report *r)
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

    meshfix__find_patches(m);
    meshfix__join_components(m);
    r->patches = m->patch_count;
    r->components = m->component_count;

    n = o->components != NULL ? o->components_capacity : 0;
    n = m->component_count < n ? m->component_count : n;
    if (policy >= 0) {
        /* the only stage that allocates: ray queries for some policies */
        if (o->patch_confidence != NULL && m->patch_count != 0) {
            m->confidence = (float *)meshfix__allocate(allocator, m->patch_count, sizeof(float));
            if (m->confidence == NULL)
                return MESHFIX_ERROR_OUT_OF_MEMORY;
        }
        if (!meshfix__decide_by_geometry(m, allocator, r)) {
            meshfix__release(allocator, m->confidence);
            return MESHFIX_ERROR_OUT_OF_MEMORY;
        }
    }
    if (n != 0)
        MESHFIX_MEMSET(o->components, 0, n * sizeof(meshfix_component));
    meshfix__orient_patches(m, policy, o, r);
    meshfix__release(allocator, m->confidence);
    m->confidence = NULL;
#ifdef MESHFIX_DEBUG
    /* the plain per-triangle SDF rule does not promise consistency */
    if (policy >= 0 && !(policy == MESHFIX_POLICY_SDF && o->sdf_mode == MESHFIX_SDF_PER_TRIANGLE))
        meshfix__debug_check_orientation(m);
#endif
    if (!full)
        return MESHFIX_OK;
    r->edges_inconsistent = policy >= 0 ? meshfix__count_inconsistent(m, 1) : r->edges_inconsistent_input;
    meshfix__count_component_edges(m, o);
    r->euler_characteristic = (long)meshfix__count_component_vertices(m, o, r) - (long)r->edges +
                              (long)(r->triangles - r->triangles_degenerate);
    for (c = 0; c < n; ++c)
        o->components[c].euler_characteristic = (long)o->components[c].vertices - (long)o->components[c].edges +
                                                (long)o->components[c].triangles;
    return MESHFIX_OK;
}

MESHFIX__PRIVATE void meshfix__write_triangle(const meshfix__mesh *m, size_t t, unsigned int *destination)
{
    unsigned int a = m->indices[3 * t], b = m->indices[3 * t + 1], c = m->indices[3 * t + 2];
    int flip = (m->tri_bits[t] & MESHFIX__TRI_FLIP) != 0;
    destination[3 * t] = a;
    destination[3 * t + 1] = flip ? c : b;
    destination[3 * t + 2] = flip ? b : c;
}

/* Each triangle is read whole before it is written, and each output
   triangle depends on its own input triangle only. Written in the
   direction memmove would copy, a destination that overlaps the indices
   anywhere (equal, or shifted by any amount) never overwrites an index
   before it is read. The addresses are compared as integers: the two
   pointers may belong to different arrays. */
MESHFIX__PRIVATE void meshfix__write_indices(const meshfix__mesh *m, unsigned int *destination)
{
    size_t t;
    if ((size_t)destination <= (size_t)m->indices)
        for (t = 0; t < m->triangle_count; ++t)
            meshfix__write_triangle(m, t, destination);
    else
        for (t = m->triangle_count; t-- > 0;)
            meshfix__write_triangle(m, t, destination);
}

MESHFIX__PRIVATE void meshfix__write_triangle_outputs(const meshfix__mesh *m, const meshfix_options *o, int policy)
{
    size_t t;
    if (o->flipped != NULL && policy >= 0)
        for (t = 0; t < m->triangle_count; ++t)
            o->flipped[t] = (unsigned char)meshfix__flip_of(m, (unsigned int)t);
    if (o->patch_ids != NULL)
        for (t = 0; t < m->triangle_count; ++t)
            o->patch_ids[t] = m->tri_patch[t];
}

/* Option values outside their documented ranges are refused, not
   clamped: a struct nobody zeroed must not become a 4 GB ray budget. */
#define MESHFIX__MAX_RAYS ((size_t)1 << 24)
#define MESHFIX__MAX_MIN_SAMPLES 65536u

MESHFIX__PRIVATE int meshfix__is_fraction(float x, float most)
{
    return meshfix__is_finite(x) && x >= 0.0f && x <= most;
}

MESHFIX__PRIVATE int meshfix__options_valid(const meshfix_options *o, int policy)
{
    if (policy == MESHFIX_POLICY_SDF &&
        (o->sdf == NULL || (unsigned int)o->sdf_mode > (unsigned int)MESHFIX_SDF_PER_TRIANGLE))
        return 0;
    if (o->allocator.alloc_fn != NULL && o->allocator.free_fn == NULL)
        return 0;
    return o->visibility_rays <= MESHFIX__MAX_RAYS && o->visibility_min_samples <= MESHFIX__MAX_MIN_SAMPLES &&
           meshfix__is_fraction(o->coherence_distance, 1.0f) && meshfix__is_fraction(o->visibility_c0, 1e6f) &&
           meshfix__is_fraction(o->visibility_eps, 1.0f) && meshfix__is_fraction(o->visibility_kv, 1e6f) &&
           meshfix__is_fraction(o->sdf_step, 3e38f) && meshfix__is_finite_point(o->up);
}

/* The pipeline shared by orient and inspect (policy < 0). Outputs are
   written only after every check has passed and the work is done. */
MESHFIX__PRIVATE meshfix_result meshfix__run(unsigned int *destination, const unsigned int *indices,
                                             size_t index_count, const float *positions,
                                             size_t vertex_count, size_t stride,
                                             const meshfix_options *caller_options, int policy,
                                             meshfix_report *report)
{
    meshfix_allocator allocator;
    meshfix__plan plan;
    meshfix__mesh m;
    meshfix_report r;
    meshfix_options options;
    unsigned char *raw, *block;
    size_t vertex_range = 0;
    meshfix_result result;

    /* a copy: NULL means all zero, and the report may share memory with
       the caller's options (it is written last, after every read) */
    if (caller_options != NULL)
        options = *caller_options;
    else
        MESHFIX_MEMSET(&options, 0, sizeof(options));

    /* 1. validate, before touching anything */
    result = meshfix__validate(indices, index_count, positions, vertex_count, stride, &vertex_range, &plan);
    if (result != MESHFIX_OK)
        return result;
    if (policy == MESHFIX_POLICY_AUTO && positions == NULL)
        policy = MESHFIX_POLICY_MAJORITY;
    if ((policy == MESHFIX_POLICY_OUTWARD || policy == MESHFIX_POLICY_SDF || policy == MESHFIX_POLICY_VISIBILITY ||
         policy == MESHFIX_POLICY_UP) && positions == NULL)
        return MESHFIX_ERROR_POSITIONS_REQUIRED;
    if (!meshfix__options_valid(&options, policy))
        return MESHFIX_ERROR_INVALID_ARGUMENT;
    MESHFIX_MEMSET(&r, 0, sizeof(r));
    r.triangles = index_count / 3;
    if (index_count == 0) {
        if (report != NULL)
            *report = r;
        return MESHFIX_OK;
    }

    /* one block holds all scratch: the caller's, or a single allocation */
    meshfix__pick_allocator(&options, &allocator);
    if (options.scratch != NULL) {
        if (options.scratch_size < plan.total)
            return MESHFIX_ERROR_SCRATCH_TOO_SMALL;
        raw = (unsigned char *)options.scratch;
    } else {
        raw = (unsigned char *)(allocator.alloc_fn != NULL ? allocator.alloc_fn(plan.total, allocator.user_data)
                                                           : MESHFIX_MALLOC(plan.total, allocator.user_data));
        if (raw == NULL)
            return MESHFIX_ERROR_OUT_OF_MEMORY;
    }
    block = raw + (16u - (size_t)raw % 16u) % 16u;
    meshfix__bind(&m, block, &plan, indices, index_count, positions, stride, vertex_range, &options, policy);

    /* 2-5. edges, patches, components, policy */
    result = meshfix__analyze(&m, policy, &options, report != NULL || options.components != NULL, &allocator, &r);

    /* 6. write: nothing can fail from here on */
    if (result == MESHFIX_OK) {
        if (destination != NULL && policy >= 0)
            meshfix__write_indices(&m, destination);
        meshfix__write_triangle_outputs(&m, &options, policy);
        if (report != NULL)
            *report = r;
    }
    if (raw != (unsigned char *)options.scratch)
        meshfix__release(&allocator, raw);
    return result;
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

MESHFIX_API meshfix_result meshfix_weld(unsigned int *remap, const float *vertex_positions, size_t vertex_count,
                                        size_t vertex_positions_stride, float tolerance,
                                        const meshfix_options *options, size_t *unique_count)
{
    meshfix_allocator allocator;
    meshfix__welder w;
    unsigned int *block, *result;
    size_t v, buckets = 16, unique, words;
    if (vertex_count == 0) {
        if (unique_count != NULL)
            *unique_count = 0;
        return MESHFIX_OK;
    }
    if (remap == NULL || vertex_positions == NULL || vertex_positions_stride < 3 * sizeof(float) ||
        vertex_positions_stride % sizeof(float) != 0 || !meshfix__is_finite(tolerance) || tolerance < 0.0f)
        return MESHFIX_ERROR_INVALID_ARGUMENT;
    if (vertex_count > MESHFIX__MAX_VERTEX_COUNT - 1 || !meshfix__vertices_addressable(vertex_count, vertex_positions_stride))
        return MESHFIX_ERROR_TOO_LARGE;
    for (v = 0; v < vertex_count; ++v)
        if (!meshfix__is_finite_point((const float *)(const void *)((const char *)vertex_positions +
                                                                    v * vertex_positions_stride)))
            return MESHFIX_ERROR_NON_FINITE;
    if (options != NULL && options->allocator.alloc_fn != NULL && options->allocator.free_fn == NULL)
        return MESHFIX_ERROR_INVALID_ARGUMENT;
    meshfix__pick_allocator(options, &allocator);
    while (buckets < vertex_count)
        buckets *= 2;
    /* bucket ends, then order, home, rep_head, rep_next and the result:
       five words per vertex, checked against overflow */
    if (vertex_count > ((size_t)-1) / sizeof(unsigned int) / 5 - buckets)
        return MESHFIX_ERROR_TOO_LARGE;
    words = buckets + 5 * vertex_count;
    block = (unsigned int *)meshfix__allocate(&allocator, words, sizeof(unsigned int));
    if (block == NULL)
        return MESHFIX_ERROR_OUT_OF_MEMORY;
    MESHFIX_MEMSET(&w, 0, sizeof(w));
    w.positions = (const char *)vertex_positions;
    w.stride = vertex_positions_stride;
    /* a hair wider than the tolerance, so rounding in the division never
       puts two vertices within it more than one cell apart */
    w.cell = (double)tolerance * (1.0 + 1e-9);
    w.mask = buckets - 1;
    w.bucket_end = block;
    w.order = block + buckets;
    w.home = w.order + vertex_count;
    w.rep_head = w.home + vertex_count;
    w.rep_next = w.rep_head + vertex_count;
    result = w.rep_next + vertex_count;
    unique = meshfix__weld_run(&w, vertex_count, (double)tolerance, result);
    MESHFIX_MEMCPY(remap, result, vertex_count * sizeof(unsigned int));
    if (unique_count != NULL)
        *unique_count = unique;
    meshfix__release(&allocator, block);
    return MESHFIX_OK;
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
