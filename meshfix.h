/* meshfix.h - v0.2.0 - triangle winding (face orientation) repair - MIT license, see end of file

   Finds and repairs inconsistent triangle winding in indexed triangle meshes:
   reports what is wrong (inspect, check), and flips the triangles that face
   the wrong way (orient). C99 or C++, libc and libm only, no globals.

   DO THIS in exactly one C or C++ file:

       #define MESHFIX_IMPLEMENTATION
       #include "meshfix.h"

   and include "meshfix.h" without the define everywhere else.

   QUICK START

       #include <stdio.h>
       #include "meshfix.h"

       int fix_winding(unsigned int *indices, size_t index_count,
                       const float *positions, size_t vertex_count)
       {
           meshfix_report report;
           char line[160];
           meshfix_result r = meshfix_orient(indices, indices, index_count, positions,
                                             vertex_count, 3 * sizeof(float), NULL, &report, NULL);
           if (r != MESHFIX_OK) {
               printf("meshfix: %s\n", meshfix_result_string(r));
               return 0;
           }
           meshfix_summary(&report, line, sizeof(line));
           printf("%s\n", line); // "clean: ...", "fixed 72 triangles in 3 patches", ...
           return 1;
       }

       int is_solid(const unsigned int *indices, size_t index_count,
                    const float *positions, size_t vertex_count)
       {
           meshfix_check_failure why;
           if (meshfix_check(indices, index_count, positions, vertex_count, 0,
                             MESHFIX_REQUIRE_SOLID, NULL, &why))
               return 1;
           printf("%s\n", why.text); // "not closed: 3 boundary edges; edge 1-2 of ..."
           return 0;
       }

   MESH CONVENTIONS
   A mesh is a triangle list: index_count / 3 triangles of 32-bit (or, with
   options.index_size = 2, 16-bit) indices into vertex_count vertices whose
   first 12 bytes are float x, y, z (24 bytes of double with
   options.position_size = 8), `stride` bytes apart (0: packed). Front faces
   wind counter-clockwise (right-handed): the normal of (a, b, c) is
   (b - a) x (c - a). Corners with bit-identical positions are one vertex,
   whatever their index (options.topology: by index only, or welded within
   a tolerance), so a vertex buffer split at UV or normal seams works as it
   is. An edge is a pair of vertices; it is a boundary edge when one
   triangle uses it, manifold when two do and non-manifold when three or
   more do. Two triangles are consistently wound across a manifold edge
   when they run it in opposite directions; an edge where some direction is
   used by two triangles is inconsistent (the GEOMETRY_INCONSISTENT_WINDING
   check of the xeokit SDK's scene-model inspector; an edge of three or more
   triangles always is). A patch is a maximal set of triangles connected
   through manifold edges; a component, through any shared edge. A patch is
   closed when each of its edges is used by an even number of its own
   triangles. Triangles that repeat a vertex are degenerate: counted, no
   part of the topology, never flipped. Flipping (a, b, c) writes (a, c, b):
   the first (provoking) vertex stays first.

   CONFIGURATION (define before including the implementation)
       MESHFIX_API           extern   linkage of the public functions
       MESHFIX_STATIC        -        makes every function static to the file
       MESHFIX_MALLOC(s,u)   malloc   allocation with the allocator's user_data;
       MESHFIX_FREE(p,u)     free     define both or neither
       MESHFIX_ASSERT(x)     assert   internal invariants only, never input
       MESHFIX_DEBUG         on when NDEBUG is not defined: extra invariant checks
       MESHFIX_NO_SIMD       -        the scalar ray tests instead of SSE2 / NEON
                                      (the same results, bit for bit)
       MESHFIX_TRACE((f,..)) nothing  printf-like trace of the decision stage
       MESHFIX_MEMSET, MESHFIX_MEMCPY, MESHFIX_SQRT, MESHFIX_FLOOR, MESHFIX_FABS,
       MESHFIX_SIN, MESHFIX_COS, MESHFIX_EXP, MESHFIX_LOG  string.h / math.h

   API
       meshfix_orient        repair winding into a destination buffer (or report only)
       meshfix_inspect       report topology and winding problems, never writes
       meshfix_check         one-line assertion for unit tests, with the reason
       meshfix_summary       a report in one line of plain words
       meshfix_weld          merge vertices closer than a tolerance (soups, CAD)
       meshfix_scratch_size  bytes of scratch memory a call needs at most
       meshfix_result_string, meshfix_verdict_string, meshfix_policy_string, meshfix_policy_from_string
       meshfix_policy_info   what a policy does and needs; meshfix_doubtful_below,
                             meshfix_verdict_worst: the report's rules, for callers

   ALGORITHM (orient, inspect and check share it; sections of the
   implementation below are in this order)
       1. validate: counts, pointers, formats, every index < vertex_count,
          before anything is read that the counts do not vouch for.
       2. input: 16-bit indices widened; vertices with bit-identical
          positions joined (a hash into buckets, each bucket sorted: no
          crafted input makes it quadratic); double positions re-centred on
          their box and converted to float.
       3. edges: a counting sort puts every half-edge in the bucket of its
          lower vertex; each bucket sorted by its higher vertex, so the
          half-edges of an edge lie together: two become mates, three or
          more a ring, one a boundary.
       4. patches: the flood fill across manifold edges, as a union-find
          with parity in triangle order; a contradiction means the patch
          is non-orientable (Moebius) and its remaining edges are reported.
       5. components: union-find over the rings of non-manifold edges.
       6. decide: each patch is turned as a whole:
            SEED      its lowest triangle keeps its winding (the plain flood
                      fill of the xeokit inspector's auto-fix);
            MAJORITY  the side that flips less area (or fewer triangles);
            AUTO      on evidence, weighed in one place: patches that join
                      across boundary edges running side by side
                      (coherence) form units; a closed or nearly closed
                      unit faces out by its signed volume, in if it is a
                      cavity (rays from it cross the shells around it an
                      odd number of times); an open unit by the shells
                      around it, the parity of its own crossings and the
                      share of rays that escape from each side; the
                      caller's normals when given. Each vote counts only
                      beyond evidence.sigma standard errors; without
                      significant evidence a unit keeps the side its
                      patches' winding favours (each patch by the square
                      root of its area, each triangle in a patch by its
                      area): a correct mesh comes back unchanged.
                      Rays are drawn in batches until the verdict is
                      settled. MAJORITY without positions;
            OUTWARD   AUTO with open units by MAJORITY;
            VISIBILITY Borodin, Zachmann, Klein: coherence, ray-sampled
                      visibility and the paper's greedy super-patch merge;
            NORMALS   the caller's normals (evidence.*_normals);
            UP        the side the area-weighted normal leans to (terrain);
            SDF       the area-weighted vote of the SDF gradient over the
                      patch (or, sdf.mode, each triangle on its own).
          Rays: a two-level tree (per unit, built on demand, then over the
          units), eight-wide nodes by binned SAH (large units from Morton
          clusters), SIMD box and triangle tests, the watertight
          ray/triangle test, so crossing counts of closed surfaces are
          exact parities.
       7. write: indices to destination with the flipped triangles' last
          two swapped, then the outputs and the report.
       Time: O(n log n) worst case, linear on ordinary meshes; the ray
       stage costs a bounded number of rays per unit.
       Memory: one block for stages 1-5 (35 bytes per triangle and 4 per
       vertex; 12 and about 24 more when positions join corners, 12 per
       vertex more for doubles), and one for the geometric decision when a
       mesh is more than one closed shell; none when the caller passes
       options.memory.scratch of meshfix_scratch_size() bytes.
       References: the edge-map flood fill of the xeokit SDK's inspector;
       P. Borodin, G. Zachmann, R. Klein, "Consistent Normal Orientation for
       Polygonal Meshes" (CGI 2004); S. Woop, C. Benthin, I. Wald,
       "Watertight Ray/Triangle Intersection" (JCGT 2013); T. Ize, "Robust
       BVH Ray Traversal" (JCGT 2013).

   DETERMINISM & THREAD SAFETY
   The output depends only on the inputs and options: counting sorts with
   index tie-breaks, unions in triangle order, seeded ray streams, sums in
   double in a fixed order; the same on every run, with or without
   parallel_for, with SIMD or without. Compilers that contract to FMA (or
   use x87 precision) may change a decision whose margin is within
   rounding. No mutable statics: concurrent calls are safe with no setup.

   ERRORS
   Every function returns a status; bad data is a status, never an assert.
   On any error nothing the caller passed is written (destination, report,
   outputs), and everything allocated is freed. NaN and infinite positions
   are data: counted, and their triangles weigh nothing.

   LIMITATIONS / DOES NOT
   - connect patches across T-junctions or gaps topologically (the
     evidence relates them by their boundary edges instead);
   - fill holes, remove degenerate or duplicate triangles, or change the
     triangle order or count;
   - promise exact answers on pathological geometry: a ray that visits
     more than 1024 tree nodes counts as blocked, and a coherence query
     looks at 128 nearby edges at most, so that cost stays linear;
   - index_count is limited to 2^31 - 1.

   VERSION HISTORY (CHANGELOG.md has the migration from 0.1)
       0.2.0  options hold inputs only (grouped), outputs apart, one
              inspect, check with a reason, verdict and summary, topology
              from positions, 16-bit indices, double positions, evidence-
              based default policy, four-wide SIMD ray tree, scratch for
              every policy.
       0.1.0  first release.
*/
#ifndef MESHFIX_H
#define MESHFIX_H

#include <stddef.h>

#define MESHFIX_VERSION_MAJOR 0
#define MESHFIX_VERSION_MINOR 2
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
    X(MESHFIX_ERROR_INVALID_ARGUMENT, "invalid argument: NULL pointer with a non-zero count, bad stride or an option out of range") \
    X(MESHFIX_ERROR_NOT_TRIANGLES, "index count is not a multiple of 3") \
    X(MESHFIX_ERROR_INDEX_OUT_OF_RANGE, "an index is not less than vertex_count") \
    X(MESHFIX_ERROR_TOO_LARGE, "too large: index_count above 2^31-1, vertex_count above 2^32 or a size that overflows") \
    X(MESHFIX_ERROR_POSITIONS_REQUIRED, "the chosen policy needs vertex positions") \
    X(MESHFIX_ERROR_SCRATCH_TOO_SMALL, "options.memory.scratch is smaller than meshfix_scratch_size()") \
    X(MESHFIX_ERROR_OUT_OF_MEMORY, "out of memory") \
    X(MESHFIX_ERROR_NON_FINITE, "a position is NaN or infinite (meshfix_weld)") \
    X(MESHFIX_ERROR_NORMALS_REQUIRED, "MESHFIX_POLICY_NORMALS needs options.evidence.triangle_normals or vertex_normals")

#define MESHFIX__RESULT_ENUM(name, text) name,
typedef enum meshfix_result {
    MESHFIX_RESULT_LIST(MESHFIX__RESULT_ENUM)
    MESHFIX_RESULT_COUNT
} meshfix_result;
#undef MESHFIX__RESULT_ENUM

/* Which way each consistently wound patch ends up facing, from one list:
   the enum, the name (meshfix_policy_string, the tool's --policy), a line
   for help texts and menus, what the policy needs (meshfix_policy_info:
   positions, the caller's normals, the SDF callback, the up axis), how it
   decides and what its confidence is. How it decides: PATCH, each patch
   by its own rule; SHELLS, units of patches weighed against their winding
   as given, with rays drawn on options.visibility's budget only until each
   verdict is settled; MERGE, VISIBILITY's greedy merge, which casts its
   whole budget. SHELLS and MERGE cast rays (meshfix_policy_info's
   casts_rays). Its confidence: PROBABILITY, a fitted probability that the
   verdict is right; MARGIN, the margin of its evidence (the report's
   doubtful bar, meshfix_doubtful_below, is 0.9 for the one, 0.5 for the
   other, or min_confidence where higher). */
#define MESHFIX_POLICY_LIST(X) \
    X(MESHFIX_POLICY_AUTO, "auto", "the evidence decides: closed shells out (cavities in), open parts by the " \
      "shells around them, their own crossings and escaping rays, the caller's normals when given; no evidence, " \
      "no flip (majority without positions)", 0, 0, 0, 0, SHELLS, PROBABILITY) \
    X(MESHFIX_POLICY_SEED, "seed", "each patch's lowest triangle keeps its winding (the plain flood fill)", 0, 0, 0, 0, PATCH, MARGIN) \
    X(MESHFIX_POLICY_MAJORITY, "majority", "each patch turns to the side that flips less area (or fewer triangles)", 0, 0, 0, 0, PATCH, MARGIN) \
    X(MESHFIX_POLICY_OUTWARD, "outward", "auto with the open parts by majority", 1, 0, 0, 0, SHELLS, MARGIN) \
    X(MESHFIX_POLICY_SDF, "sdf", "along the gradient of options.sdf.distance", 1, 0, 1, 0, PATCH, MARGIN) \
    X(MESHFIX_POLICY_VISIBILITY, "visibility", "Borodin et al.: boundary coherence, ray-sampled visibility, greedy merge", 1, 0, 0, 0, MERGE, MARGIN) \
    X(MESHFIX_POLICY_UP, "up", "each patch faces the side its normal leans to along the up axis (options.up): terrain, floors", 1, 0, 0, 1, PATCH, MARGIN) \
    X(MESHFIX_POLICY_NORMALS, "normals", "each patch faces the way the caller's normals say", 1, 1, 0, 0, PATCH, MARGIN)

#define MESHFIX__POLICY_ENUM(name, text, line, positions, normals, distance, up, decides, confidence) name,
typedef enum meshfix_policy {
    MESHFIX_POLICY_LIST(MESHFIX__POLICY_ENUM)
    MESHFIX_POLICY_COUNT
} meshfix_policy;
#undef MESHFIX__POLICY_ENUM

/* A policy as meshfix_policy_info describes it. */
typedef struct meshfix_policy_facts {
    const char *name;        /* "auto", ...: meshfix_policy_string's */
    const char *description; /* one line in plain words */
    int needs_positions;     /* MESHFIX_ERROR_POSITIONS_REQUIRED without them */
    int needs_normals;       /* MESHFIX_ERROR_NORMALS_REQUIRED without evidence.*_normals */
    int needs_distance;      /* calls options.sdf.distance: a function, so not for a file alone */
    int reads_up;            /* reads options.up */
    int casts_rays;          /* builds trees and casts rays (options.visibility's budget); AUTO with positions */
} meshfix_policy_facts;

/* Which corners are one vertex for the edge map. */
typedef enum meshfix_topology {
    MESHFIX_TOPOLOGY_POSITIONS = 0, /* corners with bit-identical positions (-0 = +0), whatever their index:
                                       an engine's vertex buffer split at UV and normal seams works as it is */
    MESHFIX_TOPOLOGY_INDICES,       /* equal indices only */
    MESHFIX_TOPOLOGY_WELD           /* positions within options.weld_tolerance (as meshfix_weld) */
} meshfix_topology;

/* How MESHFIX_POLICY_SDF decides. */
typedef enum meshfix_sdf_mode {
    MESHFIX_SDF_PER_PATCH = 0, /* each patch by an area-weighted vote of its triangles */
    MESHFIX_SDF_PER_TRIANGLE   /* each triangle by the gradient at its centroid alone */
} meshfix_sdf_mode;

/* Options: inputs only, all zero = defaults, a NULL pointer = all zero.
   `meshfix_options o = {0};` in C and C++, `meshfix_options o = {};` in
   C++. Fields are added at the end of a group, with 0 meaning what the
   library did before, so zero-initialised callers keep compiling and
   keep their results. */
typedef struct meshfix_memory_options {
    void *(*alloc_func)(size_t size, void *user_data); /* NULL: MESHFIX_MALLOC / MESHFIX_FREE */
    void (*free_func)(void *ptr, void *user_data);
    void *user_data;
    void *scratch;        /* meshfix_scratch_size() bytes: the call allocates nothing */
    size_t scratch_size;
} meshfix_memory_options;

typedef struct meshfix_evidence_options {
    /* No evidence, no flip: a vote from rays counts only within mean +-
       sigma standard errors (default 3); a patch whose verdict has a
       confidence below min_confidence (default 0) keeps the way most of
       its area faces ("repair only what is certain"). */
    float sigma;
    float min_confidence;
    /* Normals the file or the engine has (STL facet normals, OBJ vn, glTF
       NORMAL): evidence under AUTO, the only one under NORMALS. Per
       triangle (index_count / 3) or per vertex (vertex_count, by index),
       x y z floats first; stride 0 = 12 bytes. */
    const float *triangle_normals;
    size_t triangle_normals_stride;
    const float *vertex_normals;
    size_t vertex_normals_stride;
} meshfix_evidence_options;

typedef struct meshfix_visibility_options {
    /* Rays per patch proportional to area, at least min_samples (default
       16), `rays` in all (default 64 per triangle under 1024 triangles;
       else for VISIBILITY 128 per patch, at least 65536, at most
       1048576, and for AUTO and OUTWARD 1048576, which they draw on only
       until each verdict is settled). Coherence:
       boundary edges of other patches closer than coherence_distance (of
       the longest box side, default 0.02) or a twentieth of the edge's
       own length, whichever is more. The paper's merge thresholds:
       c0 (default 0.5), eps (0.02), kv (1.5). */
    size_t rays;
    unsigned int min_samples;
    float coherence_distance;
    float c0, eps, kv;
    unsigned int flags; /* MESHFIX_VISIBILITY_* */
} meshfix_visibility_options;

#define MESHFIX_VISIBILITY_COHERENCE_ONLY 1u /* merge by coherence alone; sides by majority */
#define MESHFIX_VISIBILITY_ONLY 2u           /* no merging: each patch to its more visible side */

typedef struct meshfix_sdf_options {
    /* A signed distance function, negative inside, called with positions
       as the caller gave them (in float). Without `gradient` it is taken
       by central differences, 6 calls per triangle, with a step of `step`,
       or when 0 a quarter of the triangle's longest edge but at least 32
       float steps of the centroid's coordinates. */
    float (*distance)(const float position[3], void *user);
    void (*gradient)(const float position[3], float gradient[3], void *user); /* optional */
    void *user;
    float step;
    meshfix_sdf_mode mode;
} meshfix_sdf_options;

typedef struct meshfix_options {
    unsigned int index_size;     /* 4 (or 0): 32-bit indices; 2: 16-bit */
    unsigned int position_size;  /* 4 (or 0): float x y z; 8: double (re-centred before float work) */
    meshfix_topology topology;   /* default MESHFIX_TOPOLOGY_POSITIONS */
    float weld_tolerance;        /* MESHFIX_TOPOLOGY_WELD */
    meshfix_policy policy;       /* default MESHFIX_POLICY_AUTO */
    float up[3];                 /* MESHFIX_POLICY_UP axis; 0, 0, 0 = +z */
    unsigned int seed;           /* of the ray directions and points; 0 = a fixed default */
    meshfix_evidence_options evidence;
    meshfix_visibility_options visibility;
    meshfix_sdf_options sdf;
    meshfix_memory_options memory;
    /* optional: run task(context, i) for i in [0, count), in any order, on
       any threads; results are the same as without it, bit for bit */
    void (*parallel_for)(void (*task)(void *context, size_t index), void *context, size_t count, void *user);
    void *parallel_user;
} meshfix_options;

/* Per-component facts (outputs.components). Components are numbered by
   their lowest triangle. */
typedef struct meshfix_component {
    size_t first_triangle;
    size_t triangles;          /* degenerate triangles belong to no component */
    size_t vertices;           /* distinct vertices (after topology) of its triangles */
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

/* Optional per-triangle and per-patch results: the caller's arrays, each
   NULL when not wanted. Written only when the call succeeds. */
typedef struct meshfix_outputs {
    unsigned char *flipped;        /* out: index_count / 3 flags, 1 = flipped (orient) */
    unsigned int *patch_ids;       /* out: index_count / 3 patch ids, 0xFFFFFFFF = degenerate */
    float *patch_confidence;       /* out: by patch id, 0 .. 1: AUTO, the probability that its verdict is right
                                      (fitted, see README "Confidence"); other policies, the evidence's margin */
    size_t patch_confidence_capacity; /* in: elements of patch_confidence */
    meshfix_component *components; /* out: the first components_capacity components */
    size_t components_capacity;    /* in */
    unsigned char *patch_evidence; /* out: by patch id, what decided it: a meshfix_evidence (orient) */
    size_t patch_evidence_capacity; /* in: elements of patch_evidence */
} meshfix_outputs;

/* What decided a patch (outputs.patch_evidence; report.evidence counts them). */
typedef enum meshfix_evidence {
    MESHFIX_EVIDENCE_NONE = 0,   /* nothing significant: kept the side most of its area faces */
    MESHFIX_EVIDENCE_VOLUME,     /* closed or nearly closed: signed volume and nesting */
    MESHFIX_EVIDENCE_PARITY,     /* crossings of its own surface or of the shells around it */
    MESHFIX_EVIDENCE_VISIBILITY, /* rays escaping from one side */
    MESHFIX_EVIDENCE_NORMALS,    /* the caller's normals */
    MESHFIX_EVIDENCE_POLICY      /* the rule of a policy that looks at nothing else (seed, majority, up, SDF) */
} meshfix_evidence;

/* What happened, in one word (meshfix_summary says it in a line), from
   one list: the enum, its word (meshfix_verdict_string) and its rank for
   meshfix_verdict_worst (how much a caller is told to look). */
#define MESHFIX_VERDICT_LIST(X) \
    X(MESHFIX_VERDICT_CLEAN, "clean", 0)                   /* consistent, facing the policy's way: nothing flipped */ \
    X(MESHFIX_VERDICT_REPAIRED, "repaired", 1)             /* triangles flipped, every verdict confident */ \
    X(MESHFIX_VERDICT_DOUBTFUL, "doubtful", 4)             /* some patches' verdicts are doubtful (flipped or not) */ \
    X(MESHFIX_VERDICT_NOT_ORIENTABLE, "not orientable", 5) /* a Moebius or Klein part: some edges stay inconsistent */ \
    X(MESHFIX_VERDICT_INCONSISTENT, "inconsistent", 3)     /* inspect: inconsistent winding found */ \
    X(MESHFIX_VERDICT_INSIDE_OUT, "inside out", 2)         /* inspect: consistent, but closed patches face inward */

#define MESHFIX__VERDICT_ENUM(name, text, rank) name,
typedef enum meshfix_verdict {
    MESHFIX_VERDICT_LIST(MESHFIX__VERDICT_ENUM)
    MESHFIX_VERDICT_COUNT
} meshfix_verdict;
#undef MESHFIX__VERDICT_ENUM

/* What the mesh is (orient: as returned; inspect: as given). Topology is
   counted on vertices as options.topology joins them. */
typedef struct meshfix_mesh_facts {
    size_t triangles;
    size_t triangles_degenerate;  /* a vertex repeats: excluded, never flipped */
    size_t triangles_zero_area;   /* with positions: zero or non-finite area */
    size_t triangles_duplicate;   /* same three vertices as a lower triangle, any order */
    size_t vertices_used;
    size_t vertices_joined;       /* used indices that share a vertex with a lower index (topology) */
    size_t vertices_non_finite;   /* used vertices with a NaN or infinite coordinate */
    size_t vertices_non_manifold; /* triangles around it form 2+ fans (bow-tie, or on an edge of 3+) */
    size_t edges;
    size_t edges_boundary;        /* 1 triangle */
    size_t edges_manifold;        /* 2 triangles */
    size_t edges_non_manifold;    /* 3 or more triangles */
    size_t edges_inconsistent;    /* a direction used by 2+ triangles */
    size_t patches;
    size_t patches_closed;
    size_t patches_inside_out;    /* closed patches, wound one way, with clearly negative volume */
    size_t components;
    size_t components_closed;     /* every edge manifold */
    size_t components_non_orientable;
    long euler_characteristic;    /* sum over components of V - E + F */
    double area;                  /* 0 without positions */
    double signed_volume;         /* over closed orientable patches; 0 without positions */
} meshfix_mesh_facts;

/* What decided the patches (orient). */
typedef struct meshfix_evidence_counts {
    size_t patches_by_volume;     /* closed or nearly closed: signed volume and nesting */
    size_t patches_by_parity;     /* open: crossings of their own surface or of the shells around them */
    size_t patches_by_visibility; /* rays escaping from one side */
    size_t patches_by_normals;    /* the caller's normals */
    size_t patches_kept;          /* no significant evidence (or a policy's own rule) */
    size_t shells_inward;         /* closed (or gapped but closed) shells left facing in: cavities, and shells
                                     whose winding and normals keep them in (a room); geometry alone turns the
                                     rest out */
    size_t rays_cast;
    size_t patch_pairs;           /* geometric policies: pairs of patches with a coherence */
    size_t patches_merged;        /* geometric policies: joins into units (VISIBILITY: super-patches) */
    size_t pairs_conflicting;     /* geometric policies: pairs left wound against their coherence */
    size_t sdf_evaluations;       /* SDF: calls of distance and gradient */
    size_t triangles_sdf_disagree; /* SDF: triangles whose own vote disagrees with their patch's */
    size_t triangles_against_normals; /* flipped although their clear normal (options.evidence) agreed with
                                         their winding as given */
} meshfix_evidence_counts;

/* Out only: a call writes all of it, or (on error) none of it. */
typedef struct meshfix_report {
    meshfix_verdict verdict;
    size_t triangles_flipped;
    size_t patches_flipped;
    size_t patches_doubtful;      /* confidence below 0.9 under AUTO, else 0.5 (or min_confidence when higher) */
    size_t triangles_doubtful;
    double area_doubtful;         /* of those patches; 0 without positions */
    /* The mesh as given, what meshfix_inspect reports of it (for inspect
       the same as edges_inconsistent, verdict, patches_inside_out and
       signed_volume): one orient tells before and after. */
    size_t edges_inconsistent_before;
    meshfix_verdict verdict_before;
    size_t patches_inside_out_before;
    double signed_volume_before;
    meshfix_mesh_facts mesh;
    meshfix_evidence_counts evidence;
} meshfix_report;

/* Repair winding.
   Makes every orientable patch consistently wound and turns each patch to
   the side its policy chooses. Triangle order and count are preserved; a
   flipped triangle (a, b, c) becomes (a, c, b). A mesh already wound the
   chosen way comes back unchanged with report->triangles_flipped == 0.
   Returns MESHFIX_OK or an error; on error nothing is written.

   indices: index_count indices of options->index_size bytes (NULL only
   when index_count is 0). destination: index_count indices of the same
   size; may equal indices; NULL for the report and outputs only.
   positions: vertex_count vertices, x y z of options->position_size bytes
   each first, `stride` bytes apart (0 = packed); may be NULL for SEED,
   MAJORITY and AUTO (counts instead of areas). options, report and
   outputs may be NULL; without a report (and components) the
   descriptive counts are skipped. */
MESHFIX_API meshfix_result meshfix_orient(void *destination, const void *indices, size_t index_count,
                                          const void *positions, size_t vertex_count, size_t stride,
                                          const meshfix_options *options, meshfix_report *report,
                                          meshfix_outputs *outputs);

/* Inspect without changing anything: the report (required) and outputs
   (patch_ids, components) describe the mesh as given. Arguments as for
   meshfix_orient; the policy is not used. */
MESHFIX_API meshfix_result meshfix_inspect(const void *indices, size_t index_count, const void *positions,
                                           size_t vertex_count, size_t stride, const meshfix_options *options,
                                           meshfix_report *report, meshfix_outputs *outputs);

/* meshfix_check requirements; 0 means MESHFIX_REQUIRE_CONSISTENT. */
#define MESHFIX_REQUIRE_CONSISTENT    1u  /* no edge with a direction used twice */
#define MESHFIX_REQUIRE_CLOSED        2u  /* no boundary edge */
#define MESHFIX_REQUIRE_MANIFOLD      4u  /* no edge of 3+ triangles, no bow-tie vertex */
#define MESHFIX_REQUIRE_OUTWARD       8u  /* no closed patch inside-out (needs positions) */
#define MESHFIX_REQUIRE_NO_DEGENERATE 16u /* no repeated vertex, zero area or duplicate triangle */
#define MESHFIX_REQUIRE_SOLID         31u /* all of the above */

/* Why meshfix_check failed: the first requirement (in the order of the
   bits) that does not hold, where, and how often. */
typedef struct meshfix_check_failure {
    meshfix_result result;     /* not MESHFIX_OK: the mesh is not valid input */
    unsigned int requirement;  /* the MESHFIX_REQUIRE_* bit that failed; 0 when all hold */
    size_t count;              /* edges, vertices, patches or triangles that fail it */
    size_t triangle;           /* the lowest triangle that fails it, or (size_t)-1 */
    unsigned int edge[2];      /* an edge that fails it (vertex indices), or 0xFFFFFFFF twice */
    char text[200];            /* one line, e.g. "not consistent: 3 edges; edge 12-40 runs 12->40 in
                                  triangles 7 and 9" */
} meshfix_check_failure;

/* One-line assertion for unit tests: 1 when the mesh is valid input and
   meets every bit of `requirements`, else 0 and, when `failure` is not
   NULL, why. positions may be NULL unless OUTWARD or NO_DEGENERATE is
   asked; options (formats, topology, memory) may be NULL. */
MESHFIX_API int meshfix_check(const void *indices, size_t index_count, const void *positions, size_t vertex_count,
                              size_t stride, unsigned int requirements, const meshfix_options *options,
                              meshfix_check_failure *failure);

/* Scratch bytes that a call with these options on any mesh of these
   counts needs at most (the worst mesh of that size: a soup). A call
   given that much in options.memory.scratch allocates nothing. Returns 0
   when the counts are too large, index_count is 0 (nothing needed) or
   the options would be refused (MESHFIX_ERROR_INVALID_ARGUMENT). */
MESHFIX_API size_t meshfix_scratch_size(size_t index_count, size_t vertex_count, const meshfix_options *options);

/* Weld vertices closer than `tolerance` (0: equal positions, -0 == +0).
   remap[v] becomes the lowest-index vertex that v welds to (v itself for
   the first of each cluster), so a soup with positions per corner becomes
   indexed as indices[i] = remap[i]. Deterministic; vertices join the
   earliest representative within the tolerance, so clusters do not chain.
   Returns MESHFIX_ERROR_NON_FINITE for a NaN or infinite position; on
   error remap is not written. remap holds vertex_count elements;
   unique_count may be NULL; options: position_size and memory are used,
   and options a call would refuse are refused here too. */
MESHFIX_API meshfix_result meshfix_weld(unsigned int *remap, const void *positions, size_t vertex_count,
                                        size_t stride, float tolerance, const meshfix_options *options,
                                        size_t *unique_count);

/* A line in plain words for a report, e.g. "fixed 72 triangles in 3
   patches; 2 patches (1.2% of the area) doubtful", into buffer (always
   terminated when size > 0). Returns the length of the whole line, as
   snprintf does. */
MESHFIX_API size_t meshfix_summary(const meshfix_report *report, char *buffer, size_t size);

/* Static, never NULL, English texts. */
MESHFIX_API const char *meshfix_result_string(meshfix_result result);
MESHFIX_API const char *meshfix_verdict_string(meshfix_verdict verdict);
/* A policy's name in lower case ("auto", "seed", ..., "normals"; "unknown
   policy" out of range), and back (MESHFIX_POLICY_COUNT for a name that is
   none): the names the command-line tool and the bindings take. */
MESHFIX_API const char *meshfix_policy_string(meshfix_policy policy);
MESHFIX_API meshfix_policy meshfix_policy_from_string(const char *name);
/* What a policy is and needs (static; NULL out of range): help texts,
   menus and the bindings' option tables read it. */
MESHFIX_API const meshfix_policy_facts *meshfix_policy_info(meshfix_policy policy);
/* The confidence below which a patch's verdict is doubtful, as the report
   counts it (options NULL: the defaults): under AUTO 0.9 (its confidence
   is a probability), under the others 0.5 (a margin), or
   options->evidence.min_confidence where that is higher. AUTO without
   positions runs as MAJORITY: ask for MAJORITY then. */
MESHFIX_API float meshfix_doubtful_below(const meshfix_options *options, meshfix_policy policy);
/* Of two verdicts, the one that asks more of the caller's attention
   (clean < repaired < inside out < inconsistent < doubtful < not
   orientable): the verdict of several meshes reported together. */
MESHFIX_API meshfix_verdict meshfix_verdict_worst(meshfix_verdict a, meshfix_verdict b);

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
    !defined(MESHFIX_FABS) || !defined(MESHFIX_EXP) || !defined(MESHFIX_LOG)
#include <math.h>
#endif
#ifndef MESHFIX_EXP
#define MESHFIX_EXP(x) exp(x)
#endif
#ifndef MESHFIX_LOG
#define MESHFIX_LOG(x) log(x)
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
/* MESHFIX_TRACE((format, ...)): what the decision stage weighed, unit by
   unit; define it as printf to read it. Double parentheses: C89 has no
   variadic macros. */
#ifndef MESHFIX_TRACE
#define MESHFIX_TRACE(arguments)
#endif

/* SIMD where the compiler targets it; MESHFIX_NO_SIMD forces the scalar
   path (the same results, bit for bit). */
#if !defined(MESHFIX_NO_SIMD) && (defined(__SSE2__) || defined(_M_X64) || (defined(_M_IX86_FP) && _M_IX86_FP >= 2))
#include <emmintrin.h>
#define MESHFIX__SSE 1
#define MESHFIX__NEON 0
#elif !defined(MESHFIX_NO_SIMD) && (defined(__ARM_NEON) || defined(__ARM_NEON__))
#include <arm_neon.h>
#define MESHFIX__SSE 0
#define MESHFIX__NEON 1
#else
#define MESHFIX__SSE 0
#define MESHFIX__NEON 0
#endif

#if defined(__GNUC__) || defined(__clang__)
#define MESHFIX__PRIVATE static __attribute__((unused))
#define MESHFIX__INLINE_ALWAYS __attribute__((always_inline, unused)) __inline__
#elif defined(_MSC_VER)
#define MESHFIX__PRIVATE static
#define MESHFIX__INLINE_ALWAYS __forceinline
#else
#define MESHFIX__PRIVATE static
#define MESHFIX__INLINE_ALWAYS
#endif

/* Eight lanes at once where the CPU has AVX2, asked at run time: GCC and
   Clang compile those functions for AVX2 alone (a target attribute) next
   to the SSE2 ones, and the ray tracer picks per call. Where SSE2 is not
   the compiler's own path (MESHFIX_NO_SIMD, 32-bit x87 builds) and under
   MSVC-like compilers, or with MESHFIX_NO_AVX2, there is no AVX2 path. */
#if MESHFIX__SSE && (defined(__GNUC__) || defined(__clang__)) && !defined(_MSC_VER) && !defined(MESHFIX_NO_AVX2) && \
    (defined(__x86_64__) || defined(__i386__))
#include <immintrin.h>
#define MESHFIX__AVX2 1
#define MESHFIX__AVX2_FUNCTION static __attribute__((target("avx2"), unused))
#else
#define MESHFIX__AVX2 0
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
#define MESHFIX__TRI_NO_AREA   8192u /* finite, distinct corners on one line (in double) */
#define MESHFIX__TRI_CUT      16384u /* an inconsistent edge its normals keep: the patch ends there */
/* patch bits */
#define MESHFIX__PATCH_OPEN           1u /* a boundary edge or an odd share of a ring */
#define MESHFIX__PATCH_NOT_MANIFOLD   2u /* has a boundary or non-manifold edge */
#define MESHFIX__PATCH_NON_ORIENTABLE 4u
#define MESHFIX__PATCH_PARITY         8u /* scratch bit while walking a ring */
#define MESHFIX__PATCH_FLIP          16u /* the turn a geometric policy decided */
#define MESHFIX__PATCH_DECIDED       32u

typedef char meshfix__unsigned_int_is_32_bits[sizeof(unsigned int) == 4 ? 1 : -1];

/* Runs task(context, 0 .. count - 1) on the caller's parallel_for when it
   gave one and there are two tasks or more, else here in order. Each task
   writes only its own part, so the result is the same either way. */
MESHFIX__PRIVATE void meshfix__run_tasks(const meshfix_options *o, void (*task)(void *context, size_t index),
                                        void *context, size_t count)
{
    size_t i;
    if (o != NULL && o->parallel_for != NULL && count > 1)
        o->parallel_for(task, context, count, o->parallel_user);
    else
        for (i = 0; i < count; ++i)
            task(context, i);
}

/* A stage of MESHFIX__PARALLEL_UNIT items or more (triangles, vertices,
   slots) runs over MESHFIX__STAGE_CHUNKS equal chunks of them, tasks of
   meshfix__run_tasks; a smaller one is one chunk. The chunks depend on
   the count alone, never on the threads, and what they add up is added
   in chunk order: the same bits whether they run side by side or not. */
#ifndef MESHFIX__PARALLEL_UNIT
#define MESHFIX__PARALLEL_UNIT 65536
#endif
#define MESHFIX__STAGE_CHUNKS 32

MESHFIX__PRIVATE size_t meshfix__stage_chunks(size_t n)
{
    return n >= MESHFIX__PARALLEL_UNIT ? MESHFIX__STAGE_CHUNKS : 1;
}

/* The first item of chunk i of `chunks` equal chunks of n (chunk `chunks`: n). */
MESHFIX__PRIVATE size_t meshfix__chunk_start(size_t n, size_t i, size_t chunks)
{
    size_t rest = n % chunks;
    return n / chunks * i + (i < rest ? i : rest);
}

/* A stage over chunks of n items: its own context, and what each chunk
   counts (up to two numbers), for the caller to add in chunk order. */
typedef struct meshfix__stage {
    void *context;
    size_t n, chunks;
    size_t count[MESHFIX__STAGE_CHUNKS][2];
} meshfix__stage;

/* Runs task over the chunks of n items (meshfix__stage_chunks) with
   `context` as the stage's; returns the sum of what the chunks counted
   (their first numbers; `second`, when not NULL, gets the second ones'). */
MESHFIX__PRIVATE size_t meshfix__run_stage(const meshfix_options *o, void (*task)(void *stage, size_t chunk),
                                          void *context, size_t n, size_t *second)
{
    meshfix__stage s;
    size_t c, sum = 0, other = 0;
    s.context = context;
    s.n = n;
    s.chunks = meshfix__stage_chunks(n);
    for (c = 0; c < s.chunks; ++c)
        s.count[c][0] = s.count[c][1] = 0;
    meshfix__run_tasks(o, task, &s, s.chunks);
    for (c = 0; c < s.chunks; ++c) {
        sum += s.count[c][0];
        other += s.count[c][1];
    }
    if (second != NULL)
        *second = other;
    return sum;
}

/* Whether the caller runs tasks side by side: a stage that has a
   cheaper way on one thread (the same result, found in another order)
   takes it without. */
MESHFIX__PRIVATE int meshfix__threads(const meshfix_options *o)
{
    return o != NULL && o->parallel_for != NULL;
}

/* Chunk `chunk` of a stage: [*begin, *end). */
MESHFIX__PRIVATE void meshfix__chunk_range(const meshfix__stage *s, size_t chunk, size_t *begin, size_t *end)
{
    *begin = meshfix__chunk_start(s->n, chunk, s->chunks);
    *end = meshfix__chunk_start(s->n, chunk + 1, s->chunks);
}

/* ===== >>policies ===== */

/* A policy's traits, from MESHFIX_POLICY_LIST: what it needs from the
   caller and whether it casts rays (meshfix__policies, the public
   meshfix_policy_info's), how it decides and what its confidence is
   (meshfix__traits). The pipeline asks these two tables; it names a
   policy in two kinds of places only. meshfix__decide_patch, the one
   function that applies each patch-by-patch policy's own rule (SEED,
   MAJORITY, SDF, UP, NORMALS), switches on it. And AUTO has rules of its
   own: without positions it runs as MAJORITY (meshfix__resolve_policy),
   and the shells decision tells it from OUTWARD (meshfix__decide_by_shells,
   meshfix__shell_evidence, meshfix__fit_row, and meshfix__decide_patch
   for one closed shell alone): OUTWARD is AUTO without the evidence of
   open parts, the reversed scene, the weaker nesting vote of a shell
   wound one way as given and the fitted confidence. */
#define MESHFIX__DECIDE_PATCH 0  /* each patch by its own rule (meshfix__decide_patch) */
#define MESHFIX__DECIDE_SHELLS 1 /* units weighed against the prior (meshfix__decide_by_shells) */
#define MESHFIX__DECIDE_MERGE 2  /* VISIBILITY's greedy merge (meshfix__decide_by_visibility) */
#define MESHFIX__CONFIDENCE_MARGIN 0
#define MESHFIX__CONFIDENCE_PROBABILITY 1

#define MESHFIX__POLICY_FACTS(name, text, line, positions, normals, distance, up, decides, confidence) \
    {text, line, positions, normals, distance, up, MESHFIX__DECIDE_##decides != MESHFIX__DECIDE_PATCH},
static const meshfix_policy_facts meshfix__policies[MESHFIX_POLICY_COUNT] = {MESHFIX_POLICY_LIST(MESHFIX__POLICY_FACTS)};
#undef MESHFIX__POLICY_FACTS

typedef struct meshfix__policy_traits {
    int decides;    /* MESHFIX__DECIDE_* */
    int confidence; /* MESHFIX__CONFIDENCE_* */
} meshfix__policy_traits;

#define MESHFIX__POLICY_TRAITS(name, text, line, positions, normals, distance, up, decides, confidence) \
    {MESHFIX__DECIDE_##decides, MESHFIX__CONFIDENCE_##confidence},
static const meshfix__policy_traits meshfix__traits[MESHFIX_POLICY_COUNT] = {MESHFIX_POLICY_LIST(MESHFIX__POLICY_TRAITS)};
#undef MESHFIX__POLICY_TRAITS

/* ===== >>memory ===== */

/* The caller's mesh as given: formats resolved (sizes 2 or 4 and 4 or 8,
   stride never 0), nothing read yet. */
typedef struct meshfix__input {
    const unsigned char *indices;
    size_t index_count;
    unsigned int index_size;
    const unsigned char *positions; /* NULL when not given */
    size_t vertex_count, stride;
    unsigned int position_size;
    int topology;                   /* MESHFIX_TOPOLOGY_*, INDICES without positions */
    float weld_tolerance;
} meshfix__input;

typedef struct meshfix__plan {
    size_t mate, work, tri_bits, vertex_work, patch_start, patch_link, patch_bits;
    size_t queue, tri_patch, component_bits; /* inside `work`, once the edges are linked */
    size_t corners, remap, weld, points; /* the input stage's (empty when not needed); weld: 3 words a triangle at least */
    size_t weld_buckets;
    size_t total;
} meshfix__plan;

/* Arrays start at multiples of `align` bytes (a power of two, 16 or more). */
MESHFIX__PRIVATE int meshfix__add_aligned(size_t *total, size_t count, size_t element_size, size_t align,
                                         size_t *offset)
{
    size_t bytes, aligned = (*total + align - 1) & ~(align - 1);
    if (aligned < *total || (element_size != 0 && count > ((size_t)-1) / element_size))
        return 0;
    bytes = count * element_size;
    if (aligned + bytes < aligned)
        return 0;
    *offset = aligned;
    *total = aligned + bytes;
    return 1;
}

MESHFIX__PRIVATE int meshfix__add_size(size_t *total, size_t count, size_t element_size, size_t *offset)
{
    return meshfix__add_aligned(total, count, element_size, 16, offset);
}

/* The input stage: corners joined by position (or 16-bit indices widened)
   need their own indices, the join a welder's arrays, double positions
   their float copy. */
MESHFIX__PRIVATE int meshfix__joins_positions(const meshfix__input *in)
{
    return in->positions != NULL && in->topology != MESHFIX_TOPOLOGY_INDICES;
}

/* The welder's one layout, for the pipeline's join and meshfix_weld
   alike: a power of two of buckets, at least the vertices; then in words
   the bucket ends, and per vertex order, home, rep_head and rep_next.
   meshfix__welder_words returns 0 when that many words overflow. */
MESHFIX__PRIVATE size_t meshfix__weld_buckets(size_t vertices)
{
    size_t buckets = 16;
    while (buckets < vertices)
        buckets *= 2;
    return buckets;
}

MESHFIX__PRIVATE size_t meshfix__welder_words(size_t vertices, size_t buckets)
{
    if (vertices > (((size_t)-1) / sizeof(unsigned int) - buckets) / 5)
        return 0; /* 5: room for meshfix_weld's result after the welder's four */
    return buckets + 4 * vertices;
}

/* What `work` (3 words per triangle and 16) holds once the edges are
   linked: the triangles in patch order, each triangle's patch, then a
   byte per component. */
MESHFIX__PRIVATE void meshfix__carve_work(meshfix__plan *plan, size_t triangle_count)
{
    plan->queue = plan->work;
    plan->tri_patch = plan->queue + 4 * triangle_count;
    plan->component_bits = plan->tri_patch + 4 * triangle_count;
}

/* One block holds every array. `work` holds the edge buckets, then the
   duplicate table, then the union-find parents, which become patch ids,
   and each patch's list of triangles. `mate` holds the half-edges by
   partition of their lower vertex until they are sorted into buckets,
   and groups patches by component at the end. On machines where a fresh
   page costs microseconds, these bytes are most of the time. */
MESHFIX__PRIVATE int meshfix__make_plan(meshfix__plan *plan, size_t vertex_range, size_t triangle_count,
                                        const meshfix__input *in)
{
    size_t total = 0, half_edges, buckets, joined, own_corners, points, welder;
    /* vertex_range + 1 must not wrap where size_t has 32 bits */
    if (triangle_count > MESHFIX__MAX_INDEX_COUNT / 3 || vertex_range >= ((size_t)-1) ||
        vertex_range > MESHFIX__MAX_VERTEX_COUNT)
        return 0;
    half_edges = triangle_count * 3;
    joined = meshfix__joins_positions(in) ? vertex_range : 0;
    own_corners = joined != 0 || in->index_size == 2 ? half_edges : 0;
    points = in->positions != NULL && in->position_size == 8 ? vertex_range : 0;
    buckets = joined != 0 ? meshfix__weld_buckets(joined) : 0;
    welder = joined != 0 ? meshfix__welder_words(joined, buckets) : 0;
    plan->weld_buckets = buckets;
    if (joined != 0 && welder == 0)
        return 0;
    /* once the input is read, the welder's room holds the edge map's buckets */
    welder = joined != 0 && welder < half_edges ? half_edges : welder;
    if (!(meshfix__add_size(&total, own_corners, 4, &plan->corners) &&
          meshfix__add_size(&total, joined, 4, &plan->remap) &&
          meshfix__add_size(&total, welder, 4, &plan->weld) &&
          meshfix__add_size(&total, points, 3 * sizeof(float), &plan->points) &&
          meshfix__add_size(&total, half_edges, 4, &plan->mate) &&
          meshfix__add_size(&total, half_edges + 16, 4, &plan->work) &&
          meshfix__add_size(&total, triangle_count, 2, &plan->tri_bits) &&
          meshfix__add_size(&total, vertex_range + 1, 4, &plan->vertex_work) &&
          meshfix__add_size(&total, triangle_count + 1, 4, &plan->patch_start) &&
          meshfix__add_size(&total, triangle_count, 4, &plan->patch_link) &&
          meshfix__add_size(&total, triangle_count, 1, &plan->patch_bits) &&
          meshfix__add_size(&total, 0, 1, &plan->total) && (plan->total = total + 16) > total))
        return 0;
    meshfix__carve_work(plan, triangle_count);
    return 1;
}

MESHFIX__PRIVATE void *meshfix__allocate(const meshfix_memory_options *a, size_t count, size_t size)
{
    /* one byte more, so that a zero-size request is not a NULL "failure" */
    if (size != 0 && count > (((size_t)-1) - 1) / size)
        return NULL;
    return a->alloc_func != NULL ? a->alloc_func(count * size + 1, a->user_data) : MESHFIX_MALLOC(count * size + 1, a->user_data);
}

/* The caller's allocator, or the MESHFIX_MALLOC / MESHFIX_FREE defaults
   (both NULL); never the scratch. */
MESHFIX__PRIVATE void meshfix__pick_allocator(const meshfix_options *options, meshfix_memory_options *allocator)
{
    MESHFIX_MEMSET(allocator, 0, sizeof(*allocator));
    if (options != NULL && options->memory.alloc_func != NULL) {
        allocator->alloc_func = options->memory.alloc_func;
        allocator->free_func = options->memory.free_func;
        allocator->user_data = options->memory.user_data;
    }
}

MESHFIX__PRIVATE void meshfix__release(const meshfix_memory_options *a, void *p)
{
    if (p == NULL)
        return;
    if (a->free_func != NULL)
        a->free_func(p, a->user_data);
    else
        MESHFIX_FREE(p, a->user_data);
}

/* The geometric stage's memory in one place: every array it uses, its
   element count from the mesh's counts (or the worst mesh's, for
   meshfix_scratch_size) and its offset in one block, laid out by
   meshfix__plan_geometry (>>geometry). Stages reach their arrays only
   through the plan (meshfix__array), so the block asked for is the block
   used: an array the plan forgot does not compile, and one asked longer
   than planned fails the assertion (and reads as out of memory). */
typedef struct meshfix__span {
    size_t offset, count;
} meshfix__span;

typedef struct meshfix__geometry_plan {
    /* the decisions: per patch, per triangle */
    meshfix__span confidence, patch_kind, patch_unit, patch_turn, triangle_unit;
    /* coherence: segments, pairs and their sort, a ring's radial order, the grid */
    meshfix__span segments, pairs, pair_scratch, ring_work, ring_members, ring_angles, grid_start, grid_items,
        grid_occupied;
    /* the merge; VISIBILITY's escapes and areas, the others' anchors */
    meshfix__span parent, parity, turn, front, back, merged_area, side, normals;
    /* the members' sides (not VISIBILITY) */
    meshfix__span member_asked, member_sides, member_samples, member_surface, unit_seams, first_unit;
    /* units, the tree over shells, the nets of rings, VISIBILITY's samples */
    meshfix__span units, unit_slots, unit_ids, shell_nodes, shell_ids, patch_first, patch_end, nets, samples;
    /* the trees over the slots */
    meshfix__span unit_first, unit_root, order, corners, by_index, cumulative_area, morton_sort, nodes, blocks;
    size_t total; /* bytes, with the slack that aligns the block's start */
} meshfix__geometry_plan;

typedef struct meshfix__arena {
    unsigned char *base; /* aligned to MESHFIX__ARENA_ALIGN */
    meshfix__geometry_plan plan;
} meshfix__arena;

/* Tree nodes start on a cache line; every other array on 16 bytes. */
#define MESHFIX__ARENA_ALIGN 64
#define MESHFIX__NODE_ALIGN 64

/* An array of the plan, `count` elements of it. */
MESHFIX__PRIVATE void *meshfix__array(const meshfix__arena *a, meshfix__span span, size_t count)
{
    MESHFIX_ASSERT(count <= span.count);
    return count <= span.count ? a->base + span.offset : NULL;
}

/* ===== >>validate ===== */

typedef struct meshfix__edge_entry {
    unsigned int high;      /* the higher vertex of the edge */
    unsigned int half_edge;
} meshfix__edge_entry;

typedef struct meshfix__mesh {
    const unsigned int *indices;  /* 3 per triangle: vertex ids after the topology (the caller's, or own) */
    const meshfix__input *input;  /* the caller's indices (written back) and positions */
    size_t triangle_count;
    size_t vertex_range;          /* highest index + 1 */
    const char *positions;        /* float x y z; NULL when not given */
    size_t stride;
    double offset[3];             /* double positions: subtracted before they became floats */
    unsigned int *mate;           /* 3 per triangle */
    unsigned int *work;           /* 3 per triangle: edge buckets, duplicate table, patches */
    unsigned int *queue;          /* triangles in patch order (inside `work`) */
    unsigned int *tri_patch;      /* union-find parent, then patch id (inside `work`) */
    unsigned short *tri_bits;
    int areas_marked;             /* MESHFIX__TRI_NO_AREA is set (the geometric stages ask often) */
    unsigned int *vertex_work;    /* sort counts, then vertex marks */
    unsigned int *input_room;     /* the join's room (3 words a triangle), free once the input is read; NULL: none */
    unsigned int *patch_start;    /* patch p owns queue[patch_start[p] .. patch_start[p + 1]) */
    unsigned int *patch_link;     /* union-find parent, then component id */
    unsigned char *patch_bits;
    unsigned char *component_bits; /* (inside `work`, after tri_patch) */
    size_t patch_count;
    size_t component_count;
    const meshfix_options *options; /* the SDF callbacks; may be NULL */
    meshfix_outputs *outputs;       /* never NULL (all NULL arrays when not asked) */
    unsigned int first_non_manifold_vertex; /* the lowest, for meshfix_check; NONE when none */
    unsigned int requirements;      /* meshfix_check: explain the first that fails into `failure` */
    meshfix_check_failure *failure;
    int policy;                     /* < 0: inspect */
    float *confidence;              /* per patch, from the geometric policies */
    unsigned char *patch_kind;      /* per patch: a meshfix_evidence, from the geometric policies */
} meshfix__mesh;

/* The last vertex's x y z (`bytes` at (vertex_count - 1) * stride) lie
   within an address range that size_t can describe. */
MESHFIX__PRIVATE int meshfix__vertices_addressable(size_t vertex_count, size_t stride, size_t bytes)
{
    size_t last;
    if (vertex_count == 0)
        return 1;
    if (vertex_count - 1 > ((size_t)-1) / stride)
        return 0;
    last = (vertex_count - 1) * stride;
    return last <= ((size_t)-1) - bytes;
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

MESHFIX__PRIVATE int meshfix__is_finite_double(double x)
{
    /* the word that holds the exponent: where 1.0 has its bits */
    double one = 1.0;
    unsigned int bits[2], high;
    MESHFIX_MEMCPY(bits, &one, sizeof(bits));
    high = bits[0] != 0 ? 0u : 1u;
    MESHFIX_MEMCPY(bits, &x, sizeof(bits));
    return (bits[high] & 0x7FF00000u) != 0x7FF00000u;
}

MESHFIX__PRIVATE int meshfix__is_finite_point(const float *p)
{
    return meshfix__is_finite(p[0]) && meshfix__is_finite(p[1]) && meshfix__is_finite(p[2]);
}

/* The call's buffers in the formats of the resolved options (>>public:
   meshfix__resolve_options), stride 0 packed x y z. Returns 0 for a
   stride it cannot read. */
MESHFIX__PRIVATE int meshfix__describe_input(meshfix__input *in, const void *indices, size_t index_count,
                                            const void *positions, size_t vertex_count, size_t stride,
                                            const meshfix_options *o)
{
    in->indices = (const unsigned char *)indices;
    in->index_count = index_count;
    in->index_size = o->index_size;
    in->positions = (const unsigned char *)positions;
    in->vertex_count = vertex_count;
    in->position_size = o->position_size;
    in->stride = stride != 0 ? stride : 3 * (size_t)in->position_size;
    in->topology = positions != NULL ? (int)o->topology : (int)MESHFIX_TOPOLOGY_INDICES;
    in->weld_tolerance = o->weld_tolerance;
    /* positions are read as floats, or doubles by copy: 4-byte steps */
    return positions == NULL || (in->stride >= 3 * (size_t)in->position_size && in->stride % 4 == 0);
}

MESHFIX__PRIVATE unsigned int meshfix__source_index(const meshfix__input *in, size_t i)
{
    if (in->index_size == 2)
        return ((const unsigned short *)(const void *)in->indices)[i];
    return ((const unsigned int *)(const void *)in->indices)[i];
}

/* Every check that needs no index is made before any index is read: a
   count the scratch plan cannot hold is refused without touching the
   buffer it claims to describe. */
MESHFIX__PRIVATE meshfix_result meshfix__validate(const meshfix__input *in, size_t *vertex_range,
                                                  meshfix__plan *plan)
{
    size_t i, index_count = in->index_count;
    unsigned int highest = 0;
    if (index_count % 3 != 0)
        return MESHFIX_ERROR_NOT_TRIANGLES;
    if (index_count > MESHFIX__MAX_INDEX_COUNT || in->vertex_count > MESHFIX__MAX_VERTEX_COUNT)
        return MESHFIX_ERROR_TOO_LARGE;
    if (index_count != 0 && in->indices == NULL)
        return MESHFIX_ERROR_INVALID_ARGUMENT;
    if (in->positions != NULL &&
        !meshfix__vertices_addressable(in->vertex_count, in->stride, 3 * (size_t)in->position_size))
        return MESHFIX_ERROR_TOO_LARGE;
    if (index_count == 0) {
        *vertex_range = 0;
        return MESHFIX_OK;
    }
    if (!meshfix__make_plan(plan, 0, index_count / 3, in))
        return MESHFIX_ERROR_TOO_LARGE;
    for (i = 0; i < index_count; ++i) {
        unsigned int v = meshfix__source_index(in, i);
        highest = v > highest ? v : highest;
    }
    if ((size_t)highest >= in->vertex_count)
        return MESHFIX_ERROR_INDEX_OUT_OF_RANGE;
    *vertex_range = (size_t)highest + 1;
    return meshfix__make_plan(plan, *vertex_range, index_count / 3, in) ? MESHFIX_OK : MESHFIX_ERROR_TOO_LARGE;
}

MESHFIX__PRIVATE const float *meshfix__position(const meshfix__mesh *m, unsigned int vertex)
{
    return (const float *)(const void *)(m->positions + (size_t)vertex * m->stride);
}


/* Whether the corners of a triangle span an area, in double. */
MESHFIX__PRIVATE int meshfix__spans_area(const float *a, const float *b, const float *c)
{
    double u[3], v[3], x, y, z;
    int k;
    for (k = 0; k < 3; ++k) {
        u[k] = (double)b[k] - (double)a[k];
        v[k] = (double)c[k] - (double)a[k];
    }
    x = u[1] * v[2] - u[2] * v[1];
    y = u[2] * v[0] - u[0] * v[2];
    z = u[0] * v[1] - u[1] * v[0];
    return x * x + y * y + z * z > 0.0;
}

/* Marks triangles that repeat a vertex (no topology) and, with positions,
   triangles with a NaN or infinite corner (no geometry: every geometric
   stage skips them, so no NaN reaches a comparison, a bin or a loop
   bound), and every triangle without an area (TRI_NO_AREA: the geometric
   stages ask meshfix__has_area again and again). In chunks; returns the
   degenerate count. */
MESHFIX__PRIVATE void meshfix__degenerate_chunk(void *stage, size_t chunk)
{
    meshfix__stage *s = (meshfix__stage *)stage;
    meshfix__mesh *m = (meshfix__mesh *)s->context;
    size_t t, end, count = 0;
    for (meshfix__chunk_range(s, chunk, &t, &end); t < end; ++t) {
        const unsigned int *v = m->indices + 3 * t;
        int degenerate = v[0] == v[1] || v[1] == v[2] || v[0] == v[2];
        unsigned int bits = degenerate ? MESHFIX__TRI_DEGENERATE : 0u;
        if (m->positions != NULL) {
            const float *a = meshfix__position(m, v[0]), *b = meshfix__position(m, v[1]);
            const float *c = meshfix__position(m, v[2]);
            if (!(meshfix__is_finite_point(a) && meshfix__is_finite_point(b) && meshfix__is_finite_point(c)))
                bits |= MESHFIX__TRI_NON_FINITE | MESHFIX__TRI_NO_AREA;
            else if (degenerate || !meshfix__spans_area(a, b, c))
                bits |= MESHFIX__TRI_NO_AREA;
        }
        m->tri_bits[t] = (unsigned short)bits;
        count += (size_t)degenerate;
    }
    s->count[chunk][0] = count;
}

MESHFIX__PRIVATE size_t meshfix__mark_degenerate(meshfix__mesh *m)
{
    m->areas_marked = m->positions != NULL;
    return meshfix__run_stage(m->options, meshfix__degenerate_chunk, m, m->triangle_count, NULL);
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

/* Sorts n values by their 32-bit keys, stably: four passes of a byte
   each, between (keys, values) and the scratch pair, so the result ends
   where it started. From MESHFIX__PARALLEL_UNIT values on, each pass
   counts and moves MESHFIX__RADIX_CHUNKS chunks as tasks of `parallel`
   (NULL: here): each chunk's values of a byte go after the earlier
   chunks' of that byte, so the order is the one pass's in one go. */
#define MESHFIX__RADIX_CHUNKS 8

typedef struct meshfix__radix {
    const unsigned int *from_keys, *from_values;
    unsigned int *to_keys, *to_values;
    size_t n, chunks;
    int shift, place;
    unsigned int at[MESHFIX__RADIX_CHUNKS][256]; /* [chunk][byte]: count, then next place */
} meshfix__radix;

MESHFIX__PRIVATE void meshfix__radix_chunk(void *context, size_t chunk)
{
    meshfix__radix *x = (meshfix__radix *)context;
    size_t i = meshfix__chunk_start(x->n, chunk, x->chunks), end = meshfix__chunk_start(x->n, chunk + 1, x->chunks);
    unsigned int at[256];
    int shift = x->shift;
    /* counted in locals, copied once: neighbouring chunks' counts share cache lines */
    MESHFIX_MEMCPY(at, x->at[chunk], sizeof(at));
    if (!x->place) {
        for (; i < end; ++i)
            at[(x->from_keys[i] >> shift) & 255u]++;
        MESHFIX_MEMCPY(x->at[chunk], at, sizeof(at));
        return;
    }
    for (; i < end; ++i) {
        unsigned int to = at[(x->from_keys[i] >> shift) & 255u]++;
        x->to_keys[to] = x->from_keys[i];
        x->to_values[to] = x->from_values[i];
    }
}

MESHFIX__PRIVATE void meshfix__radix_sort(unsigned int *keys, unsigned int *values, unsigned int *scratch_keys,
                                          unsigned int *scratch_values, size_t n, const meshfix_options *parallel)
{
    meshfix__radix x;
    unsigned int *from_keys = keys, *from_values = values, *to_keys = scratch_keys, *to_values = scratch_values, *t;
    size_t c, d;
    x.n = n;
    x.chunks = n >= MESHFIX__PARALLEL_UNIT ? MESHFIX__RADIX_CHUNKS : 1;
    for (x.shift = 0; x.shift < 32; x.shift += 8) {
        unsigned int sum = 0;
        x.from_keys = from_keys, x.from_values = from_values, x.to_keys = to_keys, x.to_values = to_values;
        MESHFIX_MEMSET(x.at, 0, sizeof(x.at));
        x.place = 0;
        meshfix__run_tasks(parallel, meshfix__radix_chunk, &x, x.chunks);
        for (d = 0; d < 256; ++d)
            for (c = 0; c < x.chunks; ++c) {
                unsigned int k = x.at[c][d];
                x.at[c][d] = sum;
                sum += k;
            }
        x.place = 1;
        meshfix__run_tasks(parallel, meshfix__radix_chunk, &x, x.chunks);
        t = from_keys, from_keys = to_keys, to_keys = t;
        t = from_values, from_values = to_values, to_values = t;
    }
}

/* A counting sort of (bucket, item) entries into buckets, in phases a
   caller's parallel_for may run side by side, that leaves each bucket's
   entries in the order one pass over the items would. The stage's
   `entries` hands a chunk's over, item by item, to meshfix__sort_entry,
   twice: entries cheap to find are found again, dear ones kept (`placing`
   tells the passes apart). The buckets lie in partitions of 2^shift or
   more, no more partitions than chunks, so a chunk's counts fit a row of
   `at`:
     1. per chunk of items: its entries counted by partition;
     2. here: the counts become places, partition by partition and chunk
        by chunk within each (item order);
     3. per chunk: its entries handed over again, moved to those places;
     4. per partition: its entries counted into its own buckets (no
        bucket crosses a partition) and placed there (their items into
        `sorted`, or by the stage's `place`), then the stage's `part`.
   The join by position, the edge map and the coherence grid run on it.
   Below MESHFIX__PARALLEL_UNIT items it is one chunk and one partition. */
typedef struct meshfix__bucket_sort meshfix__bucket_sort;
struct meshfix__bucket_sort {
    /* the stage's */
    const meshfix_options *parallel; /* whose parallel_for runs the phases (NULL: here) */
    void *context;                   /* for entries and part */
    /* the entries of items [first, end), each through meshfix__sort_entry(s, next, ...) */
    void (*entries)(meshfix__bucket_sort *s, size_t first, size_t end, unsigned int *next);
    /* moves entries [begin, last) of a partition, each to end[its bucket]++; NULL: their items to `sorted` */
    void (*place)(const meshfix__bucket_sort *s, unsigned int begin, unsigned int last);
    /* its work on buckets [first, end), once placed, their entries from `begin` on; NULL: none */
    void (*part)(const meshfix__bucket_sort *s, size_t first, size_t end, unsigned int begin);
    size_t items, buckets;
    size_t shift;                      /* a partition's buckets: 2^shift at least */
    unsigned int *entry_bucket, *entry_item; /* room for the entries, partition by partition */
    unsigned int *end;                 /* per bucket: where it ends */
    unsigned int *sorted;              /* the entries' items bucket by bucket (with no `place`) */
    /* the sort's own */
    size_t chunks, parts;
    int placing;                       /* 0: phase 1, counting; 1: phase 3 */
    unsigned int at[MESHFIX__STAGE_CHUNKS][MESHFIX__STAGE_CHUNKS]; /* [chunk][partition]: count, then next place */
    unsigned int part_start[MESHFIX__STAGE_CHUNKS + 1];
};

/* The least shift, `shift` or more, that cuts `buckets` (1 or more) into
   `most` partitions of 2^shift at most: partition p is
   [p << shift, (p + 1) << shift). */
MESHFIX__PRIVATE size_t meshfix__partition_shift(size_t buckets, size_t most, size_t shift)
{
    while (((buckets - 1) >> shift) >= most)
        ++shift;
    return shift;
}

/* The bucket after partition p's last. */
MESHFIX__PRIVATE size_t meshfix__partition_end(size_t p, size_t shift, size_t buckets)
{
    size_t end = (p + 1) << shift;
    return end < buckets ? end : buckets;
}

/* A sort of the entries of `items` items into `buckets` buckets, handed
   over by `entries` with `context`, its phases run on parallel's tasks;
   no `place` or `part` and partitions of any size until the stage says. */
MESHFIX__PRIVATE void meshfix__sort_setup(meshfix__bucket_sort *s, const meshfix_options *parallel, void *context,
                                         void (*entries)(meshfix__bucket_sort *, size_t, size_t, unsigned int *),
                                         size_t items, size_t buckets)
{
    MESHFIX_MEMSET(s, 0, sizeof(*s));
    s->parallel = parallel;
    s->context = context;
    s->entries = entries;
    s->items = items;
    s->buckets = buckets;
}

/* The stage's arrays: room for the entries (a bucket and an item each),
   the bucket ends, and the items bucket by bucket (NULL with `place`). */
MESHFIX__PRIVATE void meshfix__sort_arrays(meshfix__bucket_sort *s, unsigned int *entry_bucket, unsigned int *entry_item,
                                          unsigned int *end, unsigned int *sorted)
{
    s->entry_bucket = entry_bucket;
    s->entry_item = entry_item;
    s->end = end;
    s->sorted = sorted;
}

/* An entry of `item` in `bucket`, from the stage's `entries`: counted in
   phase 1, moved to its place in phase 3 (`next`: the chunk's count or
   next place per partition). */
MESHFIX__PRIVATE void meshfix__sort_entry(const meshfix__bucket_sort *s, unsigned int *next, unsigned int bucket,
                                         unsigned int item)
{
    unsigned int at = next[bucket >> s->shift]++;
    if (s->placing) {
        s->entry_bucket[at] = bucket;
        s->entry_item[at] = item;
    }
}

/* Phases 1 and 3 for one chunk. */
MESHFIX__PRIVATE void meshfix__sort_chunk(void *context, size_t chunk)
{
    meshfix__bucket_sort *s = (meshfix__bucket_sort *)context;
    unsigned int next[MESHFIX__STAGE_CHUNKS] = {0};
    if (s->placing)
        MESHFIX_MEMCPY(next, s->at[chunk], sizeof(next));
    s->entries(s, meshfix__chunk_start(s->items, chunk, s->chunks), meshfix__chunk_start(s->items, chunk + 1, s->chunks),
               next);
    /* counted in locals, copied once: neighbouring chunks' counts share cache lines */
    if (!s->placing)
        MESHFIX_MEMCPY(s->at[chunk], next, sizeof(next));
}

/* Phase 4 for one partition. */
MESHFIX__PRIVATE void meshfix__sort_partition(void *context, size_t part)
{
    meshfix__bucket_sort *s = (meshfix__bucket_sort *)context;
    size_t b, first = part << s->shift, after = meshfix__partition_end(part, s->shift, s->buckets);
    unsigned int i, begin = s->part_start[part], last = s->part_start[part + 1], sum = begin;
    MESHFIX_MEMSET(s->end + first, 0, (after - first) * sizeof(unsigned int));
    for (i = begin; i < last; ++i)
        s->end[s->entry_bucket[i]]++;
    for (b = first; b < after; ++b) {
        unsigned int n = s->end[b];
        s->end[b] = sum;
        sum += n;
    }
    if (s->place != NULL)
        s->place(s, begin, last);
    else
        for (i = begin; i < last; ++i)
            s->sorted[s->end[s->entry_bucket[i]]++] = s->entry_item[i];
    /* end[b] is now where bucket b ends */
    if (s->part != NULL)
        s->part(s, first, after, begin);
}

/* Phase 2: each partition's entries chunk by chunk, in item order.
   Returns how many entries there are. */
MESHFIX__PRIVATE unsigned int meshfix__sort_places(meshfix__bucket_sort *s)
{
    size_t c, p;
    unsigned int sum = 0;
    for (p = 0; p < s->parts; ++p) {
        s->part_start[p] = sum;
        for (c = 0; c < s->chunks; ++c) {
            unsigned int n = s->at[c][p];
            s->at[c][p] = sum;
            sum += n;
        }
    }
    s->part_start[s->parts] = sum;
    return sum;
}

/* Runs the sort, the stage's fields set; returns how many entries there
   are (where the last bucket ends). */
MESHFIX__PRIVATE unsigned int meshfix__sort_buckets(meshfix__bucket_sort *s)
{
    unsigned int entries;
    s->chunks = meshfix__stage_chunks(s->items);
    s->shift = meshfix__partition_shift(s->buckets, s->chunks, s->shift);
    s->parts = ((s->buckets - 1) >> s->shift) + 1;
    s->placing = 0;
    meshfix__run_tasks(s->parallel, meshfix__sort_chunk, s, s->chunks);
    entries = meshfix__sort_places(s);
    s->placing = 1;
    meshfix__run_tasks(s->parallel, meshfix__sort_chunk, s, s->chunks);
    meshfix__run_tasks(s->parallel, meshfix__sort_partition, s, s->parts);
    return entries;
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
    const unsigned char *positions;
    size_t stride;
    unsigned int position_size; /* 4: float, 8: double */
    int skip_non_finite;     /* the pipeline's: a NaN or infinite vertex joins nothing */
    double cell;             /* 0: exact equality */
    size_t mask;             /* buckets - 1 */
    unsigned int *bucket_end; /* per bucket: end of its run in `order` */
    unsigned int *order;     /* vertices bucket by bucket, each sorted by (cell, vertex) */
    unsigned int *home;      /* per vertex: where its cell's run starts in `order` */
    unsigned int *rep_head;  /* per run start: the cell's latest representative */
    unsigned int *rep_next;  /* per representative: the previous one in its cell */
} meshfix__welder;

/* The welder's arrays from `words` (sized by meshfix__welder_words). */
MESHFIX__PRIVATE void meshfix__carve_welder(meshfix__welder *w, unsigned int *words, size_t vertices, size_t buckets)
{
    w->mask = buckets - 1;
    w->bucket_end = words;
    w->order = words + buckets;
    w->home = w->order + vertices;
    w->rep_head = w->home + vertices;
    w->rep_next = w->rep_head + vertices;
}

/* A vertex's x y z as given, float or double, in double; 0 when one is
   NaN or infinite. */
MESHFIX__PRIVATE int meshfix__read_point(const unsigned char *positions, size_t stride, unsigned int size, size_t v,
                                        double p[3])
{
    const unsigned char *q = positions + v * stride;
    int k, finite = 1;
    for (k = 0; k < 3; ++k) {
        if (size == 8) {
            MESHFIX_MEMCPY(&p[k], q + 8 * k, sizeof(double));
            finite = finite && meshfix__is_finite_double(p[k]);
        } else {
            float x;
            MESHFIX_MEMCPY(&x, q + 4 * k, sizeof(float));
            finite = finite && meshfix__is_finite(x);
            p[k] = (double)x;
        }
    }
    return finite;
}

MESHFIX__PRIVATE void meshfix__weld_load(const meshfix__welder *w, size_t v, double p[3])
{
    int k;
    meshfix__read_point(w->positions, w->stride, w->position_size, v, p);
    for (k = 0; k < 3; ++k)
        p[k] = p[k] == 0.0 ? 0.0 : p[k]; /* -0 welds to +0 */
}

MESHFIX__PRIVATE void meshfix__weld_cell(const meshfix__welder *w, const double p[3], double cell[3])
{
    int k;
    for (k = 0; k < 3; ++k)
        cell[k] = w->cell > 0 ? MESHFIX_FLOOR(p[k] / w->cell) : p[k];
}

MESHFIX__PRIVATE void meshfix__vertex_cell(const meshfix__welder *w, unsigned int v, double cell[3])
{
    double p[3];
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
        double c[3], p[3];
        int k;
        if (!meshfix__read_point(w->positions, w->stride, w->position_size, v, p) && w->skip_non_finite) {
            w->home[v] = MESHFIX__NONE; /* in no bucket */
            continue;
        }
        for (k = 0; k < 3; ++k)
            p[k] = p[k] == 0.0 ? 0.0 : p[k]; /* -0 welds to +0 (meshfix__weld_load) */
        meshfix__weld_cell(w, p, c);
        w->home[v] = (unsigned int)meshfix__weld_hash(c, w->mask);
        w->bucket_end[w->home[v]]++;
    }
    for (b = 0; b < buckets; ++b) {
        unsigned int n = w->bucket_end[b];
        w->bucket_end[b] = sum;
        sum += n;
    }
    for (v = 0; v < vertex_count; ++v)
        if (w->home[v] != MESHFIX__NONE)
            w->order[w->bucket_end[w->home[v]]++] = (unsigned int)v;
    for (b = 0; b < buckets; begin = w->bucket_end[b++])
        meshfix__sort_ids(w->order + begin, w->bucket_end[b] - begin, meshfix__weld_before, w);
    /* runs of one cell: each vertex learns where its run starts */
    previous[0] = previous[1] = previous[2] = 0.0;
    for (i = 0; i < sum; ++i) {
        double c[3];
        meshfix__vertex_cell(w, w->order[i], c);
        if (i == 0 || meshfix__compare_cells(c, previous) != 0)
            w->rep_head[i] = i; /* a run starts here; rep_head is set up below */
        else
            w->rep_head[i] = w->rep_head[i - 1];
        w->home[w->order[i]] = w->rep_head[i];
        previous[0] = c[0], previous[1] = c[1], previous[2] = c[2];
    }
    for (i = 0; i < sum; ++i)
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
MESHFIX__PRIVATE unsigned int meshfix__weld_nearest(const meshfix__welder *w, unsigned int run, const double p[3],
                                                   double tolerance_squared, unsigned int best)
{
    unsigned int r;
    for (r = w->rep_head[run]; r != MESHFIX__NONE; r = w->rep_next[r]) {
        double q[3], dx, dy, dz;
        meshfix__weld_load(w, r, q);
        dx = p[0] - q[0], dy = p[1] - q[1], dz = p[2] - q[2];
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
        double p[3], c[3], n[3];
        unsigned int best = MESHFIX__NONE, run;
        int dx, dy, dz;
        if (w->home[v] == MESHFIX__NONE) { /* skipped: joins nothing */
            remap[v] = (unsigned int)v;
            unique++;
            continue;
        }
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

/* The pipeline's join at tolerance 0 (remap[v]: the lowest vertex at v's
   position, bit for bit once -0 is +0; a NaN or infinite vertex joins
   nothing): the vertices counting-sorted into the welder's buckets by
   position (meshfix__sort_buckets, in chunks a caller's parallel_for may
   run), then each partition's buckets sorted and their runs found alone.
   Equal positions share a bucket, so no run crosses a partition, and a
   bucket of one vertex is a run without reading its position again (most
   buckets: the table is half empty). The remap is meshfix__weld_run's:
   a bucket's vertices sorted by (position, vertex) whatever sorted them. */
typedef struct meshfix__joiner {
    meshfix__welder *w;
    unsigned int *remap;
} meshfix__joiner;

/* Vertex v's bucket; NONE for a NaN or infinite one, which joins nothing. */
MESHFIX__PRIVATE unsigned int meshfix__join_home(meshfix__joiner *j, size_t v)
{
    double p[3];
    int k;
    if (!meshfix__read_point(j->w->positions, j->w->stride, j->w->position_size, v, p)) {
        j->remap[v] = (unsigned int)v;
        return MESHFIX__NONE;
    }
    for (k = 0; k < 3; ++k)
        p[k] = p[k] == 0.0 ? 0.0 : p[k]; /* -0 joins +0 (meshfix__weld_load) */
    return (unsigned int)meshfix__weld_hash(p, j->w->mask);
}

/* The vertices of [first, end) into their buckets: hashed when counted,
   kept in home[v] for when they are placed. */
MESHFIX__PRIVATE void meshfix__join_entries(meshfix__bucket_sort *s, size_t first, size_t end, unsigned int *next)
{
    meshfix__joiner *j = (meshfix__joiner *)s->context;
    unsigned int *home = j->w->home;
    size_t v;
    for (v = first; v < end; ++v) {
        if (!s->placing)
            home[v] = meshfix__join_home(j, v);
        if (home[v] != MESHFIX__NONE)
            meshfix__sort_entry(s, next, home[v], (unsigned int)v);
    }
}

/* The runs of one bucket's vertices, sorted: each takes its run's first. */
MESHFIX__PRIVATE void meshfix__join_bucket(const meshfix__welder *w, unsigned int *ids, size_t n, unsigned int *remap)
{
    double previous[3], c[3];
    unsigned int first = ids[0];
    size_t i;
    remap[first] = first;
    if (n == 1)
        return;
    meshfix__sort_ids(ids, n, meshfix__weld_before, w);
    first = ids[0];
    remap[first] = first;
    meshfix__vertex_cell(w, first, previous);
    for (i = 1; i < n; ++i) {
        meshfix__vertex_cell(w, ids[i], c);
        if (meshfix__compare_cells(c, previous) != 0)
            first = ids[i];
        remap[ids[i]] = first;
        previous[0] = c[0], previous[1] = c[1], previous[2] = c[2];
    }
}

/* The runs of buckets [first, end), sorted. */
MESHFIX__PRIVATE void meshfix__join_runs(const meshfix__bucket_sort *s, size_t first, size_t end, unsigned int begin)
{
    const meshfix__joiner *j = (const meshfix__joiner *)s->context;
    size_t b;
    for (b = first; b < end; begin = s->end[b++])
        if (s->end[b] != begin)
            meshfix__join_bucket(j->w, s->sorted + begin, s->end[b] - begin, j->remap);
}

/* w carved and set up for tolerance 0 with skip_non_finite; `parallel`:
   the options whose parallel_for may run the phases (NULL: here). */
MESHFIX__PRIVATE void meshfix__join_exact(meshfix__welder *w, size_t vertices, unsigned int *remap,
                                         const meshfix_options *parallel)
{
    meshfix__joiner j;
    meshfix__bucket_sort s;
    j.w = w;
    j.remap = remap;
    meshfix__sort_setup(&s, parallel, &j, meshfix__join_entries, vertices, w->mask + 1);
    meshfix__sort_arrays(&s, w->rep_head, w->rep_next, w->bucket_end, w->order);
    s.part = meshfix__join_runs;
    meshfix__sort_buckets(&s);
}

/* ===== >>input ===== */

/* What the pipeline reads: 32-bit vertex ids after the topology, and float
   positions. The caller's buffers serve as they are when they already are
   that (32-bit indices with TOPOLOGY_INDICES, float positions). */

/* Double positions become floats about the centre of their box, so a
   model far from the origin keeps its small features. A coordinate
   beyond float range after that becomes infinite, and its triangles are
   left out of the geometry like any non-finite one. */
MESHFIX__PRIVATE void meshfix__convert_points(meshfix__mesh *m, const meshfix__input *in, float *points)
{
    double low[3] = {0, 0, 0}, high[3] = {0, 0, 0}, p[3];
    size_t v;
    int k, seen = 0;
    for (v = 0; v < m->vertex_range; ++v) {
        if (!meshfix__read_point(in->positions, in->stride, 8, v, p))
            continue;
        for (k = 0; k < 3; ++k) {
            low[k] = !seen || p[k] < low[k] ? p[k] : low[k];
            high[k] = !seen || p[k] > high[k] ? p[k] : high[k];
        }
        seen = 1;
    }
    for (k = 0; k < 3; ++k)
        m->offset[k] = 0.5 * low[k] + 0.5 * high[k];
    for (v = 0; v < m->vertex_range; ++v) {
        meshfix__read_point(in->positions, in->stride, 8, v, p);
        for (k = 0; k < 3; ++k)
            points[3 * v + (size_t)k] = (float)(p[k] - m->offset[k]);
    }
    m->positions = (const char *)points;
    m->stride = 3 * sizeof(float);
}

/* remap[v]: the lowest vertex whose position is bit-identical to v's (or,
   with TOPOLOGY_WELD, within the tolerance: meshfix_weld's rule), read
   from the caller's positions, float or double. A NaN or infinite vertex
   joins nothing. */
MESHFIX__PRIVATE void meshfix__join_vertices(const meshfix__mesh *m, const meshfix__input *in,
                                            const meshfix__plan *plan, unsigned char *block, unsigned int *remap)
{
    meshfix__welder w;
    size_t vertices = m->vertex_range;
    double tolerance = in->topology == MESHFIX_TOPOLOGY_WELD ? (double)in->weld_tolerance : 0.0;
    MESHFIX_MEMSET(&w, 0, sizeof(w));
    w.positions = in->positions;
    w.stride = in->stride;
    w.position_size = in->position_size;
    w.skip_non_finite = 1;
    w.cell = tolerance * (1.0 + 1e-9);
    meshfix__carve_welder(&w, (unsigned int *)(void *)(block + plan->weld), vertices, plan->weld_buckets);
    if (tolerance == 0.0)
        meshfix__join_exact(&w, vertices, remap, m->options);
    else
        meshfix__weld_run(&w, vertices, tolerance, remap);
}

/* The corners of a chunk of triangles: the caller's indices, through
   remap when it is not NULL. */
typedef struct meshfix__corner_task {
    const meshfix__input *in;
    const unsigned int *remap;
    unsigned int *corners;
} meshfix__corner_task;

MESHFIX__PRIVATE void meshfix__corner_chunk(void *stage, size_t chunk)
{
    meshfix__stage *s = (meshfix__stage *)stage;
    const meshfix__corner_task *task = (const meshfix__corner_task *)s->context;
    size_t t, end, i;
    meshfix__chunk_range(s, chunk, &t, &end);
    for (i = 3 * t; i < 3 * end; ++i) {
        unsigned int v = meshfix__source_index(task->in, i);
        task->corners[i] = task->remap != NULL ? task->remap[v] : v;
    }
}

/* Sets up m->indices and m->positions from the caller's mesh. With
   `count_joined` (a report is asked), returns the used indices that
   became another vertex (report.mesh.vertices_joined): a count over
   distinct vertices, made in one pass in order (two chunks may share a
   vertex), while the corners are written; else the corners are written
   in chunks, and it returns 0. */
MESHFIX__PRIVATE size_t meshfix__read_input(meshfix__mesh *m, const meshfix__input *in, const meshfix__plan *plan,
                                           unsigned char *block, int count_joined)
{
    unsigned int *corners = (unsigned int *)(void *)(block + plan->corners);
    unsigned int *remap = (unsigned int *)(void *)(block + plan->remap), *seen = m->vertex_work;
    size_t i, joined = 0, index_count = 3 * m->triangle_count;
    meshfix__corner_task task;
    if (in->positions != NULL && in->position_size == 8)
        meshfix__convert_points(m, in, (float *)(void *)(block + plan->points));
    task.in = in;
    task.remap = NULL;
    task.corners = corners;
    m->indices = corners;
    if (!meshfix__joins_positions(in)) {
        if (in->index_size == 4)
            m->indices = (const unsigned int *)(const void *)in->indices;
        else
            meshfix__run_stage(m->options, meshfix__corner_chunk, &task, m->triangle_count, NULL);
        return 0;
    }
    meshfix__join_vertices(m, in, plan, block, remap);
    task.remap = remap;
    if (!count_joined) {
        meshfix__run_stage(m->options, meshfix__corner_chunk, &task, m->triangle_count, NULL);
        return 0;
    }
    MESHFIX_MEMSET(seen, 0, m->vertex_range * sizeof(unsigned int));
    for (i = 0; i < index_count; ++i) {
        unsigned int v = meshfix__source_index(in, i);
        corners[i] = remap[v];
        joined += (size_t)(seen[v] == 0 && remap[v] != v);
        seen[v] = 1;
    }
    return joined;
}

/* ===== >>edges ===== */

typedef struct meshfix__edge_counts {
    size_t edges, boundary, manifold, non_manifold;
} meshfix__edge_counts;

/* The vertices of half-edge h's edge, the lower and the higher. */
MESHFIX__PRIVATE unsigned int meshfix__edge_low(const unsigned int *indices, unsigned int h)
{
    unsigned int a = indices[h], b = indices[h % 3 == 2 ? h - 2 : h + 1];
    return a < b ? a : b;
}

MESHFIX__PRIVATE unsigned int meshfix__edge_high(const unsigned int *indices, unsigned int h)
{
    unsigned int a = indices[h], b = indices[h % 3 == 2 ? h - 2 : h + 1];
    return a < b ? b : a;
}

MESHFIX__PRIVATE int meshfix__half_edge_before(const void *context, unsigned int a, unsigned int b)
{
    const meshfix__mesh *m = (const meshfix__mesh *)context;
    unsigned int ka = meshfix__edge_high(m->indices, a), kb = meshfix__edge_high(m->indices, b);
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
   place, O(k log k) with no memory. Both give the same links. */
#define MESHFIX__SMALL_BUCKET 32
MESHFIX__PRIVATE void meshfix__link_bucket(meshfix__mesh *m, unsigned int *ids, size_t n,
                                           meshfix__edge_counts *counts)
{
    size_t i, j;
    if (n <= MESHFIX__SMALL_BUCKET) {
        meshfix__edge_entry e[MESHFIX__SMALL_BUCKET];
        for (i = 0; i < n; ++i) {
            meshfix__edge_entry x;
            x.high = meshfix__edge_high(m->indices, ids[i]);
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
        unsigned int high = meshfix__edge_high(m->indices, ids[i]);
        for (j = i + 1; j < n && meshfix__edge_high(m->indices, ids[j]) == high; ++j) {
        }
        meshfix__link_edge(m, ids + i, j - i, counts);
    }
}

/* Groups the half-edges by undirected edge into one bucket per lower
   vertex, each bucket in half-edge order, then links each bucket (sorted
   by its higher vertex and cut into runs) and ends the degenerate
   triangles' half-edges. On the caller's threads, where the join left its
   room (positions joined the corners: m->input_room), the buckets are
   meshfix__sort_buckets' in chunks, in the input's room, the half-edges
   on their way in `work`, their lower vertex beside them in `mate` (its
   room until the edges are linked). Else one counting sort of them all
   into `work`, here, its own loops (a pass less: on one thread the phases
   cost the 1M cut sphere 12.4 -> 18.8 ms; and one pass handing entries
   to the shared sort cost 30% more than these). Either way the same
   buckets, and then the partitions of vertices link theirs and the
   chunks end their degenerate triangles. */
typedef struct meshfix__edge_build {
    meshfix__mesh *m;
    unsigned int *ids;           /* the buckets */
    size_t chunks, parts, shift; /* vertex v lies in partition v >> shift */
    meshfix__edge_counts counts[MESHFIX__STAGE_CHUNKS]; /* per partition */
} meshfix__edge_build;

/* The half-edges of triangles [first, end), each into the bucket of its
   lower vertex (a degenerate triangle's into none), found again when
   placed: cheaper than keeping them. */
MESHFIX__PRIVATE void meshfix__edges_entries(meshfix__bucket_sort *s, size_t first, size_t end, unsigned int *next)
{
    const meshfix__mesh *m = (const meshfix__mesh *)s->context;
    size_t t;
    unsigned int k;
    for (t = first; t < end; ++t) {
        const unsigned int *v = m->indices + 3 * t;
        if (m->tri_bits[t] & MESHFIX__TRI_DEGENERATE)
            continue;
        for (k = 0; k < 3; ++k) {
            unsigned int a = v[k], b = v[k == 2 ? 0 : k + 1];
            meshfix__sort_entry(s, next, a < b ? a : b, (unsigned int)(3 * t) + k);
        }
    }
}

/* The half-edges into their buckets in the input's room, on the caller's
   threads. */
MESHFIX__PRIVATE void meshfix__edges_by_partition(meshfix__edge_build *e)
{
    meshfix__mesh *m = e->m;
    meshfix__bucket_sort s;
    e->ids = m->input_room;
    meshfix__sort_setup(&s, m->options, m, meshfix__edges_entries, m->triangle_count, m->vertex_range);
    meshfix__sort_arrays(&s, m->mate, m->work, m->vertex_work, e->ids);
    meshfix__sort_buckets(&s);
}

/* All the half-edges into their buckets in `work`, here. */
MESHFIX__PRIVATE void meshfix__edges_sort_all(meshfix__edge_build *e)
{
    meshfix__mesh *m = e->m;
    unsigned int *end = m->vertex_work, sum = 0, h;
    size_t t, v;
    e->ids = m->work;
    MESHFIX_MEMSET(end, 0, m->vertex_range * sizeof(unsigned int));
    for (t = 0; t < m->triangle_count; ++t) {
        const unsigned int *tri = m->indices + 3 * t;
        if (m->tri_bits[t] & MESHFIX__TRI_DEGENERATE)
            continue;
        end[tri[0] < tri[1] ? tri[0] : tri[1]]++;
        end[tri[1] < tri[2] ? tri[1] : tri[2]]++;
        end[tri[2] < tri[0] ? tri[2] : tri[0]]++;
    }
    for (v = 0; v < m->vertex_range; ++v) {
        unsigned int n = end[v];
        end[v] = sum;
        sum += n;
    }
    for (t = 0; t < m->triangle_count; ++t)
        if (!(m->tri_bits[t] & MESHFIX__TRI_DEGENERATE))
            for (h = (unsigned int)(3 * t); h < 3 * t + 3; ++h)
                e->ids[end[meshfix__edge_low(m->indices, h)]++] = h;
    /* end[v] is now where bucket v ends */
}

/* Task `task`: the links of partition `task` of vertices (its buckets
   start where the one before it ends), and the degenerate triangles of
   chunk `task`. */
MESHFIX__PRIVATE void meshfix__edges_link(void *context, size_t task)
{
    meshfix__edge_build *e = (meshfix__edge_build *)context;
    meshfix__mesh *m = e->m;
    size_t t, end, v, after;
    if (task < e->parts) {
        unsigned int *bucket_end = m->vertex_work, begin;
        v = task << e->shift;
        begin = v == 0 ? 0 : bucket_end[v - 1];
        after = meshfix__partition_end(task, e->shift, m->vertex_range);
        MESHFIX_MEMSET(&e->counts[task], 0, sizeof(e->counts[task]));
        for (; v < after; begin = bucket_end[v++])
            meshfix__link_bucket(m, e->ids + begin, bucket_end[v] - begin, &e->counts[task]);
    }
    if (task >= e->chunks)
        return;
    end = meshfix__chunk_start(m->triangle_count, task + 1, e->chunks);
    for (t = meshfix__chunk_start(m->triangle_count, task, e->chunks); t < end; ++t)
        if (m->tri_bits[t] & MESHFIX__TRI_DEGENERATE)
            m->mate[3 * t] = m->mate[3 * t + 1] = m->mate[3 * t + 2] = MESHFIX__NONE;
}

MESHFIX__PRIVATE void meshfix__build_edges(meshfix__mesh *m, meshfix__edge_counts *counts)
{
    meshfix__edge_build e;
    size_t k;
    e.m = m;
    e.chunks = meshfix__stage_chunks(m->triangle_count);
    MESHFIX_MEMSET(counts, 0, sizeof(*counts));
    if (m->vertex_range == 0)
        return;
    e.shift = meshfix__partition_shift(m->vertex_range, e.chunks, 0);
    e.parts = ((m->vertex_range - 1) >> e.shift) + 1;
    if (m->input_room != NULL && e.chunks > 1 && meshfix__threads(m->options))
        meshfix__edges_by_partition(&e);
    else
        meshfix__edges_sort_all(&e);
    meshfix__run_tasks(m->options, meshfix__edges_link, &e, e.parts > e.chunks ? e.parts : e.chunks);
    for (k = 0; k < e.parts; ++k) {
        counts->edges += e.counts[k].edges;
        counts->boundary += e.counts[k].boundary;
        counts->manifold += e.counts[k].manifold;
        counts->non_manifold += e.counts[k].non_manifold;
    }
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
    m->first_non_manifold_vertex = MESHFIX__NONE;
    for (v = m->vertex_range; v-- > 0;)
        if (fans[v] > 1) {
            count++;
            m->first_non_manifold_vertex = (unsigned int)v;
        }
    return count;
}

/* ===== >>normals ===== */

/* A triangle's geometric normal, and the caller's normals as evidence
   (options.evidence): the flood fill asks them where an edge disagrees,
   the decision where a patch or a unit faces. */

/* Corners of t relative to origin, and its normal (b - a) x (c - a), twice
   its area long. The normal comes from the positions as given, in the
   operations of meshfix__spans_area: about a far origin the corners of a
   small triangle round together, and the report would count as without
   an area a triangle that meshfix_check does not find. */
MESHFIX__PRIVATE void meshfix__load_triangle(const meshfix__mesh *m, unsigned int t, const double origin[3],
                                            double a[3], double b[3], double c[3], double n[3])
{
    const float *p = meshfix__position(m, m->indices[3 * t]), *q = meshfix__position(m, m->indices[3 * t + 1]);
    const float *r = meshfix__position(m, m->indices[3 * t + 2]);
    double u[3], v[3];
    int k;
    for (k = 0; k < 3; ++k) {
        a[k] = (double)p[k] - origin[k];
        b[k] = (double)q[k] - origin[k];
        c[k] = (double)r[k] - origin[k];
        u[k] = (double)q[k] - (double)p[k];
        v[k] = (double)r[k] - (double)p[k];
    }
    n[0] = u[1] * v[2] - u[2] * v[1];
    n[1] = u[2] * v[0] - u[0] * v[2];
    n[2] = u[0] * v[1] - u[1] * v[0];
}

/* The caller's normal of triangle t: its own (triangle normals), or the
   sum of its corners' (vertex normals); 0 when it is not usable (none
   given, zero or not finite). */
MESHFIX__PRIVATE int meshfix__authored_normal(const meshfix__mesh *m, unsigned int t, double out[3])
{
    const meshfix_options *o = m->options;
    unsigned int c;
    int k;
    out[0] = out[1] = out[2] = 0.0;
    if (o->evidence.triangle_normals != NULL) {
        size_t stride = o->evidence.triangle_normals_stride;
        const float *n = (const float *)(const void *)((const char *)o->evidence.triangle_normals + (size_t)t * stride);
        if (!meshfix__is_finite_point(n))
            return 0;
        for (k = 0; k < 3; ++k)
            out[k] = (double)n[k];
    } else if (o->evidence.vertex_normals != NULL) {
        size_t stride = o->evidence.vertex_normals_stride;
        for (c = 0; c < 3; ++c) {
            /* by the caller's index: its normal, not the joined vertex's */
            size_t v = meshfix__source_index(m->input, 3 * (size_t)t + c);
            const float *n = (const float *)(const void *)((const char *)o->evidence.vertex_normals + v * stride);
            if (!meshfix__is_finite_point(n))
                return 0;
            for (k = 0; k < 3; ++k)
                out[k] += (double)n[k];
        }
    } else {
        return 0;
    }
    return out[0] != 0 || out[1] != 0 || out[2] != 0;
}

MESHFIX__PRIVATE int meshfix__normal_usable(const meshfix__mesh *m, unsigned int t)
{
    double n[3];
    return meshfix__authored_normal(m, t, n);
}

/* +1 when the caller's normal of t points the way n (t's normal as
   given) does, -1 against it, 0 when it is missing or too oblique (less
   than 0.3 of its length along n) to say. */
MESHFIX__PRIVATE double meshfix__normal_vote(const meshfix__mesh *m, unsigned int t, const double n[3])
{
    double a[3], dot, lengths;
    if (!meshfix__authored_normal(m, t, a))
        return 0.0;
    dot = a[0] * n[0] + a[1] * n[1] + a[2] * n[2];
    lengths = MESHFIX_SQRT((a[0] * a[0] + a[1] * a[1] + a[2] * a[2]) * (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]));
    return dot > 0.3 * lengths ? 1.0 : dot < -0.3 * lengths ? -1.0 : 0.0;
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

/* Whether the caller's normals keep two triangles that run their shared
   edge the same way apart: each has a clear normal (meshfix__normal_vote)
   that agrees with its own winding as given (a fold, a double-sided part,
   two sheets facing apart). The flood fill would turn one of them against
   its author's normal; the edge ends both patches instead. */
MESHFIX__PRIVATE int meshfix__normal_agrees(const meshfix__mesh *m, unsigned int t)
{
    double a[3], b[3], c[3], n[3], origin[3] = {0, 0, 0};
    if (m->positions == NULL || !meshfix__has_geometry(m, t))
        return 0;
    meshfix__load_triangle(m, t, origin, a, b, c, n);
    return meshfix__normal_vote(m, t, n) > 0;
}

MESHFIX__PRIVATE int meshfix__normals_keep_apart(const meshfix__mesh *m, unsigned int t, unsigned int u)
{
    const meshfix_options *o = m->options;
    if (o->evidence.triangle_normals == NULL && o->evidence.vertex_normals == NULL)
        return 0;
    return meshfix__normal_agrees(m, t) && meshfix__normal_agrees(m, u);
}

/* Joins t to its manifold neighbours u with from <= u < to (to <= t), in
   order of neighbour; marks t when it has other kinds of edges (with
   `mark`). Returns 1 when t has a manifold neighbour below `from`. */
MESHFIX__PRIVATE int meshfix__join_lower_neighbours(meshfix__mesh *m, unsigned int t, unsigned int from,
                                                   unsigned int to, int mark)
{
    unsigned int h, n = 0, i, j, u[3], opposite[3];
    int below = 0;
    for (h = 3 * t; h < 3 * t + 3; ++h) {
        unsigned int g = m->mate[h];
        if (!meshfix__is_mate(g)) {
            if (mark)
                m->tri_bits[t] |= g == MESHFIX__NONE ? MESHFIX__TRI_OPEN : MESHFIX__TRI_NOT_MANIFOLD;
            continue;
        }
        if (g / 3 >= to)
            continue;
        if (g / 3 < from) {
            below = 1;
            continue;
        }
        for (j = n++; j > 0 && u[j - 1] > g / 3; --j) {
            u[j] = u[j - 1];
            opposite[j] = opposite[j - 1];
        }
        u[j] = g / 3;
        /* two triangles that run an edge the same way disagree */
        opposite[j] = (unsigned int)meshfix__same_direction(m, h, g);
    }
    for (i = 0; i < n; ++i) {
        if (opposite[i] && meshfix__normals_keep_apart(m, t, u[i])) {
            m->tri_bits[t] |= MESHFIX__TRI_CUT;
            m->tri_bits[u[i]] |= MESHFIX__TRI_CUT;
            continue;
        }
        meshfix__join_triangles(m, t, u[i], opposite[i]);
    }
    return below;
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
        if (bits & (MESHFIX__TRI_OPEN | MESHFIX__TRI_CUT))
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
MESHFIX__PRIVATE void meshfix__flood_in_order(meshfix__mesh *m)
{
    unsigned int t, triangles = (unsigned int)m->triangle_count;
    for (t = 0; t < triangles; ++t) {
        if (m->tri_bits[t] & MESHFIX__TRI_DEGENERATE) {
            m->tri_patch[t] = MESHFIX__NONE;
            continue;
        }
        m->tri_patch[t] = t;
        meshfix__join_lower_neighbours(m, t, 0, t, 1);
    }
}

/* A chunk of triangles joined among themselves; those with a neighbour
   in an earlier chunk wait in `queue` from the chunk's first slot on
   (count[chunk][0] of them); count[chunk][1]: a seam was found. */
MESHFIX__PRIVATE void meshfix__flood_chunk(void *stage, size_t chunk)
{
    meshfix__stage *s = (meshfix__stage *)stage;
    meshfix__mesh *m = (meshfix__mesh *)s->context;
    size_t begin, end, t, waiting = 0, seam = 0;
    meshfix__chunk_range(s, chunk, &begin, &end);
    for (t = begin; t < end; ++t) {
        if (m->tri_bits[t] & MESHFIX__TRI_DEGENERATE) {
            m->tri_patch[t] = MESHFIX__NONE;
            continue;
        }
        m->tri_patch[t] = (unsigned int)t;
        if (meshfix__join_lower_neighbours(m, (unsigned int)t, (unsigned int)begin, (unsigned int)t, 1))
            m->queue[begin + waiting++] = (unsigned int)t;
        seam |= (size_t)((m->tri_bits[t] & MESHFIX__TRI_SEAM) != 0);
    }
    s->count[chunk][0] = waiting;
    s->count[chunk][1] = seam;
}

/* The same classes by chunks on the caller's threads: each chunk's
   triangles joined among themselves, then, here, each joined to its
   neighbours in earlier chunks. A class whose edges agree (an orientable
   patch) comes out with the same triangles, cuts and windings relative
   to its seed whatever the order of its joins; only where a join
   contradicts the others (a seam: a non-orientable patch) does the order
   say which triangle carries it, and then the fill runs again in
   triangle order. (Without threads the fill runs in order at once.) */
MESHFIX__PRIVATE void meshfix__flood_by_chunks(meshfix__mesh *m)
{
    meshfix__stage s;
    size_t c, i, t;
    int seam = 0;
    s.context = m;
    s.n = m->triangle_count;
    s.chunks = meshfix__stage_chunks(s.n);
    for (c = 0; c < s.chunks; ++c)
        s.count[c][0] = s.count[c][1] = 0;
    meshfix__run_tasks(m->options, meshfix__flood_chunk, &s, s.chunks);
    for (c = 0; c < s.chunks; ++c) {
        size_t first = meshfix__chunk_start(s.n, c, s.chunks);
        seam |= s.count[c][1] != 0;
        for (i = 0; i < s.count[c][0]; ++i) {
            t = m->queue[first + i];
            meshfix__join_lower_neighbours(m, (unsigned int)t, 0, (unsigned int)first, 0);
        }
    }
    for (c = 0; c < s.chunks && !seam; ++c)
        for (i = 0; i < s.count[c][0] && !seam; ++i)
            seam = (m->tri_bits[m->queue[meshfix__chunk_start(s.n, c, s.chunks) + i]] & MESHFIX__TRI_SEAM) != 0;
    if (!seam)
        return;
    for (t = 0; t < m->triangle_count; ++t)
        m->tri_bits[t] &= (unsigned short)~(MESHFIX__TRI_RELATIVE | MESHFIX__TRI_OPEN | MESHFIX__TRI_NOT_MANIFOLD |
                                            MESHFIX__TRI_SEAM | MESHFIX__TRI_CUT);
    meshfix__flood_in_order(m);
}

MESHFIX__PRIVATE void meshfix__find_patches(meshfix__mesh *m)
{
    if (meshfix__stage_chunks(m->triangle_count) > 1 && meshfix__threads(m->options))
        meshfix__flood_by_chunks(m);
    else
        meshfix__flood_in_order(m);
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
    /* each entry's parent is lower than it: in patch order, one step makes
       every entry its root; then the roots are numbered, and each patch
       takes its root's number (the root comes first) */
    for (p = 0; p < m->patch_count; ++p)
        m->patch_link[p] = m->patch_link[m->patch_link[p]];
    for (p = 0; p < m->patch_count; ++p) {
        unsigned int root = m->patch_link[p];
        m->patch_link[p] = root == p ? count++ : m->patch_link[root];
    }
    m->component_count = count;
}

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
    if (o->sdf.gradient != NULL) {
        float out[3];
        o->sdf.gradient(p, out, o->sdf.user);
        (*evaluations)++;
        finite = meshfix__is_finite_point(out);
        g[0] = (double)out[0], g[1] = (double)out[1], g[2] = (double)out[2];
    } else {
        for (axis = 0; axis < 3; ++axis) {
            float q[3], ahead, behind;
            q[0] = p[0], q[1] = p[1], q[2] = p[2];
            q[axis] = p[axis] + step;
            ahead = o->sdf.distance(q, o->sdf.user);
            q[axis] = p[axis] - step;
            behind = o->sdf.distance(q, o->sdf.user);
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
    float centroid[3], step = o->sdf.step;
    double g[3], dot;
    int k, vote;
    /* in the caller's coordinates (double positions were re-centred) */
    for (k = 0; k < 3; ++k)
        centroid[k] = (float)(m->offset[k] + origin[k] + (a[k] + b[k] + c[k]) / 3.0);
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
        r->evidence.triangles_sdf_disagree++;
    /* the plain rule: a triangle with no vote (zero area, no gradient) stays as given */
    return m->options->sdf.mode == MESHFIX_SDF_PER_TRIANGLE ? own_flip : patch_flip;
}

/* ===== >>sums ===== */

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
    double normals;         /* the caller's normals: area-weighted vote, relative frame */
    double normals_area;    /* area of the triangles with a usable normal */
} meshfix__patch_sums;

MESHFIX__PRIVATE double meshfix__edge_length(const meshfix__mesh *m, unsigned int h)
{
    const float *a = meshfix__position(m, m->indices[h]);
    const float *b = meshfix__position(m, m->indices[h % 3 == 2 ? h - 2 : h + 1]);
    double x = (double)b[0] - (double)a[0], y = (double)b[1] - (double)a[1], z = (double)b[2] - (double)a[2];
    return MESHFIX_SQRT(x * x + y * y + z * z);
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
        if (m->policy >= 0 && meshfix__policies[m->policy].needs_distance) {
            int vote = meshfix__sdf_vote(m, t, origin, a, b, c, n, &s->sdf_evaluations);
            s->sdf_vote += (m->tri_bits[t] & MESHFIX__TRI_RELATIVE) ? -vote * area : vote * area;
        }
        {
            double vote = meshfix__normal_vote(m, t, n) * area;
            s->normals += (m->tri_bits[t] & MESHFIX__TRI_RELATIVE) ? -vote : vote;
            s->normals_area += meshfix__normal_usable(m, t) ? area : 0.0;
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

/* ===== >>rays ===== */

/* A bounding volume hierarchy in two levels: a tree over the triangles of
   each unit (a patch, or a super-patch of them), built only when a ray
   needs it, and a tree over the units' trees for rays through the whole
   model. A ray that asks about one unit (its own surface, or a shell that
   may enclose another) walks that unit's tree alone, so its cost does not
   grow with the rest of the scene. Trees are built by binned SAH, large
   ones from Morton-ordered clusters (below); the ray test is watertight
   (Woop, Benthin, Wald, "Watertight Ray/Triangle Intersection", JCGT
   2013): rays neither leak through nor hit twice at shared edges and
   vertices, so crossing counts of closed surfaces are exact parities. */

/* The trees rays walk have nodes of up to eight children, their boxes
   side by side, so that one ray tests all eight in a few SIMD
   instructions (AVX2 at once, SSE2 and NEON four at a time, the scalar
   path in a loop: the same float operations in the same order, so every
   path takes the same steps). A child is a node (in the tree over units,
   the root of a unit's tree), a leaf (a run of at most MESHFIX__LEAF
   slots) or empty (its box inside out, and no bit in the node's masks).
   A node's children lie in slot order, so that its leaves are tested a
   block at a time (below); nodes lie depth first. Why this shape, measured
   against Embree 3 in `make bench`: the traversal waits on loads, and
   eight-wide nodes take a third fewer of them than four-wide ones; boxes
   quantized to bytes (Ylitie, Karras, Laine 2017) halved the bytes of a
   node but cost 13-20% in decoding on the bench's meshes. */
#define MESHFIX__WIDE 8
#define MESHFIX__EMPTY 0xFFu

/* 256 bytes, four cache lines when the array is aligned to 64 */
typedef struct meshfix__wide {
    float bounds[6][MESHFIX__WIDE];      /* low x y z, then high x y z; each per child */
    unsigned int child[MESHFIX__WIDE];   /* a node, or a leaf's first slot */
    unsigned char count[MESHFIX__WIDE];  /* 0: a node; 1 ..: a leaf of that many slots; EMPTY */
    unsigned char inner, leaves;         /* a bit per child that is a node, a leaf */
    unsigned char unused[22];
} meshfix__wide;

/* The corners of eight consecutive slots side by side: corner c's axis k
   of slot 8 * b + i is corner[3 * c + k][i] of block b, so that a leaf's
   triangles are tested with aligned loads and no transposes. The slots'
   triangles travel with them (a ray's own triangle is skipped). */
typedef struct meshfix__leaf_block {
    float corner[9][MESHFIX__WIDE];
    unsigned int triangle[MESHFIX__WIDE];
} meshfix__leaf_block;

/* The tree over the boxes of closed shells (and the builder's own view of
   a tree) has nodes of four: a query walks it by box overlap alone. */
#define MESHFIX__WIDTH 4

/* 128 bytes, two cache lines when the array is aligned to 64 */
typedef struct meshfix__node {
    float bounds[6][MESHFIX__WIDTH]; /* low x y z, then high x y z; each per child */
    unsigned int child[MESHFIX__WIDTH];   /* a node, or a leaf's first slot */
    unsigned char count[MESHFIX__WIDTH];  /* 0: a node; 1 ..: a leaf of that many slots; EMPTY */
    unsigned int unused[3];
} meshfix__node;

typedef struct meshfix__bvh {
    meshfix__wide *nodes;      /* unit u's tree from meshfix__unit_nodes(b, u) on; the top tree after them */
    meshfix__leaf_block *blocks;    /* the corners of slot i in block i / 8, lane i % 8 */
    unsigned int *order;       /* per slot: its triangle; the slots of a unit lie together */
    unsigned int *by_index;    /* the same triangles, each unit's patch by patch (the geometric stage's
                                  order; index order as prepared): the trees reorder `order` by float
                                  arithmetic, which builds round differently, and samples must not
                                  depend on it */
    float *corners;            /* per slot: 9 floats, the corners in the frame */
    double *cumulative_area;   /* per entry of by_index: its unit's area up to it (sampling) */
    unsigned int *sort;        /* per slot 4: scratch of the builds (the Morton codes and their sort; the
                                  SAH tree's ids and triangles) */
    unsigned int *unit_first;  /* per unit + 1: its first slot */
    unsigned int *unit_root;   /* per unit: its tree's root, NONE until built */
    unsigned int unit_count;
    unsigned int count;        /* slots: triangles with an area */
    unsigned int top;          /* root of the tree over the units, NONE until built */
    float low[3], high[3];     /* the frame's box */
    double diagonal;
    double center[3], scale;   /* the frame: corners are (position - center) * scale */
} meshfix__bvh;

typedef struct meshfix__ray {
    float origin[3], direction[3], inverse[3];
    float shear[3];
    int kx, ky, kz;
    unsigned int near_plane[3], far_plane[3]; /* per axis, the row of a node's bounds on the near and far side */
    float t_min, t_max;
} meshfix__ray;

MESHFIX__PRIVATE void meshfix__grow_box(float low[3], float high[3], const float p[3])
{
    int k;
    for (k = 0; k < 3; ++k) {
        low[k] = p[k] < low[k] ? p[k] : low[k];
        high[k] = p[k] > high[k] ? p[k] : high[k];
    }
}

MESHFIX__PRIVATE void meshfix__empty_box(float box[6])
{
    box[0] = box[1] = box[2] = 1e30f;
    box[3] = box[4] = box[5] = -1e30f;
}

MESHFIX__PRIVATE int meshfix__box_contains(const float outer[6], const float inner[6])
{
    int k;
    for (k = 0; k < 3; ++k)
        if (!(outer[k] <= inner[k] && inner[3 + k] <= outer[3 + k]))
            return 0;
    return 1;
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

/* The box of a chunk of triangles' corners (those with geometry), in
   float: the least and greatest of floats are floats, the same whatever
   the chunks (a box in double, kept in arrays, was a store and a load per
   corner and axis). count[chunk][0]: 1 when it saw a triangle. */
typedef struct meshfix__frame_task {
    const meshfix__mesh *m;
    float box[MESHFIX__STAGE_CHUNKS][6];
} meshfix__frame_task;

MESHFIX__PRIVATE void meshfix__frame_chunk(void *stage, size_t chunk)
{
    meshfix__stage *s = (meshfix__stage *)stage;
    meshfix__frame_task *task = (meshfix__frame_task *)s->context;
    const meshfix__mesh *m = task->m;
    float low[3] = {0, 0, 0}, high[3] = {0, 0, 0};
    size_t t, end;
    unsigned int c;
    int seen = 0;
    for (meshfix__chunk_range(s, chunk, &t, &end); t < end; ++t) {
        if (!meshfix__has_geometry(m, (unsigned int)t))
            continue;
        if (!seen) {
            MESHFIX_MEMCPY(low, meshfix__position(m, m->indices[3 * t]), sizeof(low));
            MESHFIX_MEMCPY(high, low, sizeof(high));
            seen = 1;
        }
        for (c = 0; c < 3; ++c)
            meshfix__grow_box(low, high, meshfix__position(m, m->indices[3 * t + c]));
    }
    MESHFIX_MEMCPY(task->box[chunk], low, sizeof(low));
    MESHFIX_MEMCPY(task->box[chunk] + 3, high, sizeof(high));
    s->count[chunk][0] = (size_t)seen;
}

/* Float geometry (the trees, rays, sample points, coherence) works in a
   frame that maps the box of the model into [-1, 1]: re-centred, so a
   model far from the origin keeps its small features, and scaled by a
   power of two, which rounds nothing, so no difference or product of
   corners can overflow a float. The box by chunks of triangles, a
   caller's parallel_for may run them. */
MESHFIX__PRIVATE void meshfix__fit_frame(meshfix__bvh *b, const meshfix__mesh *m)
{
    meshfix__frame_task task;
    meshfix__stage s;
    float box_low[3] = {0, 0, 0}, box_high[3] = {0, 0, 0};
    double low[3], high[3], half = 0;
    size_t c;
    int k, seen = 0;
    task.m = m;
    s.context = &task;
    s.n = m->triangle_count;
    s.chunks = meshfix__stage_chunks(s.n);
    meshfix__run_tasks(m->options, meshfix__frame_chunk, &s, s.chunks);
    for (c = 0; c < s.chunks; ++c) {
        if (!s.count[c][0])
            continue;
        if (!seen) {
            MESHFIX_MEMCPY(box_low, task.box[c], sizeof(box_low));
            MESHFIX_MEMCPY(box_high, task.box[c] + 3, sizeof(box_high));
            seen = 1;
        }
        meshfix__grow_box(box_low, box_high, task.box[c]);
        meshfix__grow_box(box_low, box_high, task.box[c] + 3);
    }
    for (k = 0; k < 3; ++k) {
        low[k] = (double)box_low[k];
        high[k] = (double)box_high[k];
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
    b->diagonal = 0;
    for (k = 0; k < 3; ++k) {
        b->low[k] = (float)((low[k] - b->center[k]) * b->scale);
        b->high[k] = (float)((high[k] - b->center[k]) * b->scale);
        b->diagonal += ((double)b->high[k] - (double)b->low[k]) * ((double)b->high[k] - (double)b->low[k]);
    }
    b->diagonal = MESHFIX_SQRT(b->diagonal);
}

MESHFIX__PRIVATE void meshfix__frame_point(const meshfix__bvh *b, const float *p, double out[3])
{
    int k;
    for (k = 0; k < 3; ++k)
        out[k] = ((double)p[k] - b->center[k]) * b->scale;
}

MESHFIX__PRIVATE void meshfix__frame_float(const meshfix__bvh *b, const float *p, float out[3])
{
    double x[3];
    meshfix__frame_point(b, p, x);
    out[0] = (float)x[0], out[1] = (float)x[1], out[2] = (float)x[2];
}

MESHFIX__PRIVATE void meshfix__frame_vertex(const meshfix__bvh *b, const meshfix__mesh *m, unsigned int v, float out[3])
{
    meshfix__frame_float(b, meshfix__position(m, v), out);
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

/* ===== >>trees ===== */

/* Building the trees: a unit's by binned SAH (large ones from Morton
   clusters), in phases a caller's parallel_for may run, and the tree over
   the units; their room in the plan. */

#define MESHFIX__BINS 12
/* A range of up to three blocks' worth of slots is not split into nodes:
   an eight-wide test costs the same for one triangle as for eight, and a
   range of 9 to 16 slots split in two leaves took a node of two children,
   a load of four cache lines, where its triangles take two block tests.
   Leaves of eight put a level fewer of nodes on a ray's path than leaves
   of four (3-7% faster on small meshes, 16-28% on a million triangles);
   of sixteen against eight, the SAH build of head.stl traces 0-5% faster
   and builds 5-16% faster; of 24 against 16, with a node's free slots
   filled by halving its leaves of more than MESHFIX__LEAF_SPLIT slots
   (meshfix__split_leaves), 3-7% faster rays and a 2-3% faster build
   (measured, one process, the trees side by side). At most 31: a leaf's
   lanes are a mask of that many bits (meshfix__window_add). */
#define MESHFIX__LEAF 24
#define MESHFIX__LEAF_SPLIT 8
/* slots after the last (the corners array keeps them zero) */
#define MESHFIX__SLOT_PAD 4
/* The depth of a tree is bounded, so the fixed stacks always hold it: SAH
   splits down to MESHFIX__BVH_SAH_LEVELS halvings (SAH can cut one
   triangle off a range at each: triangles shrinking toward a point make a
   chain as deep as they are many), then halving by count, which adds at
   most 31 for 2^31 triangles: under MESHFIX__BVH_LEVELS in all, and a
   node is at least one halving below its parent. Two trees (over units,
   then in a unit) lie on a ray's path, and a node leaves at most seven
   children pending. */
#define MESHFIX__BVH_SAH_LEVELS 28
#define MESHFIX__BVH_LEVELS 60
#define MESHFIX__BVH_STACK ((MESHFIX__WIDE - 1) * 2 * MESHFIX__BVH_LEVELS + 8)

/* The bin of a centroid, clamped before the conversion. */
MESHFIX__PRIVATE unsigned int meshfix__bin(double centroid, double low, double scale)
{
    double x = (centroid - low) * scale;
    if (x < 0.0)
        return 0;
    return x >= (double)(MESHFIX__BINS - 1) ? MESHFIX__BINS - 1 : (unsigned int)x;
}

/* A builder's primitives: per slot 9 floats (a box, low x y z and high
   x y z, and a centroid) and an id that moves with it. What the build
   knows of a range of slots: the box around them and the box around their
   centroids. A split gets both for its two halves from its bins, so no
   level re-reads its slots to fit boxes. */
#define MESHFIX__SLOT_CENTROID 6
typedef struct meshfix__builder {
    float *slots;
    unsigned int *ids;
    meshfix__node *nodes;
    unsigned int next_node;
    unsigned int leaf;     /* most primitives in a leaf */
} meshfix__builder;

/* Boxes of a range as four floats a corner (x y z and a lane nobody
   reads), so that SIMD grows them a corner at a time. */
typedef struct meshfix__range {
    float box[8];       /* low x y z -, high x y z - */
    float centroids[8]; /* the same for the centroids */
    unsigned int count;
} meshfix__range;

#define MESHFIX__HIGH 4 /* where a range box's high corner starts */

MESHFIX__PRIVATE void meshfix__empty_range(meshfix__range *r)
{
    int k;
    r->count = 0;
    for (k = 0; k < 4; ++k) {
        r->box[k] = r->centroids[k] = 1e30f;
        r->box[MESHFIX__HIGH + k] = r->centroids[MESHFIX__HIGH + k] = -1e30f;
    }
}

/* low = min(low, a), high = max(high, b), four lanes: the same bits
   with SIMD or without (no rounding, and nothing here is NaN). */
#if MESHFIX__SSE
MESHFIX__PRIVATE void meshfix__grow4(float *low, float *high, __m128 a, __m128 b)
{
    _mm_storeu_ps(low, _mm_min_ps(_mm_loadu_ps(low), a));
    _mm_storeu_ps(high, _mm_max_ps(_mm_loadu_ps(high), b));
}

/* A slot's nine floats as three corners of four lanes (the fourth lane
   never read), without reading past the slot. */
MESHFIX__PRIVATE void meshfix__range_add_slot(meshfix__range *r, const float *slot)
{
    __m128 centroid = _mm_loadu_ps(slot + 5); /* high z, then the centroid */
    r->count++;
    meshfix__grow4(r->box, r->box + MESHFIX__HIGH, _mm_loadu_ps(slot), _mm_loadu_ps(slot + 3));
    centroid = _mm_shuffle_ps(centroid, centroid, _MM_SHUFFLE(0, 3, 2, 1));
    meshfix__grow4(r->centroids, r->centroids + MESHFIX__HIGH, centroid, centroid);
}

MESHFIX__PRIVATE void meshfix__range_add_range(meshfix__range *r, const meshfix__range *other)
{
    if (other->count == 0)
        return; /* its box is inside out: its corners are not points */
    r->count += other->count;
    meshfix__grow4(r->box, r->box + MESHFIX__HIGH, _mm_loadu_ps(other->box), _mm_loadu_ps(other->box + MESHFIX__HIGH));
    meshfix__grow4(r->centroids, r->centroids + MESHFIX__HIGH, _mm_loadu_ps(other->centroids),
                   _mm_loadu_ps(other->centroids + MESHFIX__HIGH));
}
#else
MESHFIX__PRIVATE void meshfix__grow3(float *low, float *high, const float *a, const float *b)
{
    int k;
    for (k = 0; k < 3; ++k) {
        low[k] = a[k] < low[k] ? a[k] : low[k];
        high[k] = b[k] > high[k] ? b[k] : high[k];
    }
}

MESHFIX__PRIVATE void meshfix__range_add_slot(meshfix__range *r, const float *slot)
{
    r->count++;
    meshfix__grow3(r->box, r->box + MESHFIX__HIGH, slot, slot + 3);
    meshfix__grow3(r->centroids, r->centroids + MESHFIX__HIGH, slot + MESHFIX__SLOT_CENTROID,
                   slot + MESHFIX__SLOT_CENTROID);
}

MESHFIX__PRIVATE void meshfix__range_add_range(meshfix__range *r, const meshfix__range *other)
{
    if (other->count == 0)
        return; /* its box is inside out: its corners are not points */
    r->count += other->count;
    meshfix__grow3(r->box, r->box + MESHFIX__HIGH, other->box, other->box + MESHFIX__HIGH);
    meshfix__grow3(r->centroids, r->centroids + MESHFIX__HIGH, other->centroids, other->centroids + MESHFIX__HIGH);
}
#endif


MESHFIX__PRIVATE void meshfix__fit_range(const meshfix__builder *k, unsigned int first, unsigned int count,
                                         meshfix__range *r)
{
    unsigned int i;
    meshfix__empty_range(r);
    for (i = first; i < first + count; ++i)
        meshfix__range_add_slot(r, k->slots + 9 * (size_t)i);
}

/* Moves the slots whose centroid lies below `threshold` on the axis to
   the front; returns how many. A bin is a monotonic function of the
   centroid, so "in a bin below the split" is "below the least centroid
   of the bins above it", a float comparison. Every slot is swapped with
   the front's end and the end moves on when the slot stays in front:
   a branch on which side a centroid lies was lost half the time (the
   partition was a fifth of a cluster's build). */
MESHFIX__PRIVATE unsigned int meshfix__partition(meshfix__builder *k, unsigned int first, unsigned int count, int axis,
                                                 float threshold)
{
    unsigned int front = first, i, id;
    float tmp[9];
    for (i = first; i < first + count; ++i) {
        float *slot = k->slots + 9 * (size_t)i, *end = k->slots + 9 * (size_t)front;
        unsigned int below = slot[MESHFIX__SLOT_CENTROID + axis] < threshold;
        MESHFIX_MEMCPY(tmp, slot, sizeof(tmp));
        MESHFIX_MEMCPY(slot, end, sizeof(tmp));
        MESHFIX_MEMCPY(end, tmp, sizeof(tmp));
        id = k->ids[i];
        k->ids[i] = k->ids[front];
        k->ids[front] = id;
        front += below;
    }
    return front - first;
}

/* Splits slots [first, first + r->count) at the best of 12 centroid bins
   along the widest axis of their centroids, by the surface area
   heuristic, and describes the halves; returns the size of the left one,
   0 for a leaf. */
MESHFIX__PRIVATE unsigned int meshfix__split(meshfix__builder *k, unsigned int first, const meshfix__range *r,
                                             int use_sah, meshfix__range *left, meshfix__range *right)
{
    meshfix__range bins[MESHFIX__BINS], below[MESHFIX__BINS];
    unsigned int i, best = 0, j, count = r->count, half;
    float best_cost = 1e38f;
    double scale;
    int axis = 0, a;
    if (count <= k->leaf)
        return 0;
    for (a = 1; a < 3; ++a)
        axis = r->centroids[MESHFIX__HIGH + a] - r->centroids[a] >
                       r->centroids[MESHFIX__HIGH + axis] - r->centroids[axis]
                   ? a
                   : axis;
    if (use_sah && r->centroids[MESHFIX__HIGH + axis] > r->centroids[axis]) {
        scale = (double)MESHFIX__BINS / ((double)r->centroids[MESHFIX__HIGH + axis] - (double)r->centroids[axis]);
        for (j = 0; j < MESHFIX__BINS; ++j)
            meshfix__empty_range(&bins[j]);
        for (i = first; i < first + count; ++i) {
            const float *c = k->slots + 9 * (size_t)i;
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
            cost = meshfix__box_area(below[j].box, below[j].box + MESHFIX__HIGH) * (float)below[j].count +
                   meshfix__box_area(right->box, right->box + MESHFIX__HIGH) * (float)right->count;
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
            return meshfix__partition(k, first, count, axis, right->centroids[axis]);
        }
    }
    /* all centroids in one point, in one bin, or the tree already deep:
       halve by slot */
    half = count / 2;
    meshfix__fit_range(k, first, half, left);
    meshfix__fit_range(k, first + half, count - half, right);
    return half;
}

MESHFIX__PRIVATE void meshfix__empty_node(meshfix__node *n)
{
    int c, k;
    for (c = 0; c < MESHFIX__WIDTH; ++c) {
        for (k = 0; k < 3; ++k)
            n->bounds[k][c] = 1.0f, n->bounds[3 + k][c] = -1.0f;
        n->child[c] = MESHFIX__NONE;
        n->count[c] = MESHFIX__EMPTY;
    }
}

MESHFIX__PRIVATE void meshfix__set_child(meshfix__node *n, int c, unsigned int child, unsigned int count,
                                        const float low[3], const float high[3])
{
    int k;
    for (k = 0; k < 3; ++k)
        n->bounds[k][c] = low[k], n->bounds[3 + k][c] = high[k];
    n->child[c] = child;
    n->count[c] = (unsigned char)count;
}

MESHFIX__PRIVATE void meshfix__empty_wide(meshfix__wide *n)
{
    int c, k;
    for (c = 0; c < MESHFIX__WIDE; ++c) {
        for (k = 0; k < 3; ++k)
            n->bounds[k][c] = 1.0f, n->bounds[3 + k][c] = -1.0f;
        n->child[c] = MESHFIX__NONE;
        n->count[c] = MESHFIX__EMPTY;
    }
    n->inner = n->leaves = 0;
    MESHFIX_MEMSET(n->unused, 0, sizeof(n->unused));
}

/* Points child c at a node (count 0) or a leaf of `count` slots from
   slot `child` on. */
MESHFIX__PRIVATE void meshfix__link_wide(meshfix__wide *n, int c, unsigned int child, unsigned int count)
{
    unsigned char bit = (unsigned char)(1u << c);
    n->child[c] = child;
    n->count[c] = (unsigned char)count;
    n->inner = (unsigned char)(count == 0 ? n->inner | bit : n->inner & ~bit);
    n->leaves = (unsigned char)(count != 0 ? n->leaves | bit : n->leaves & ~bit);
}

MESHFIX__PRIVATE void meshfix__set_wide(meshfix__wide *n, int c, unsigned int child, unsigned int count,
                                       const float low[3], const float high[3])
{
    int k;
    for (k = 0; k < 3; ++k)
        n->bounds[k][c] = low[k], n->bounds[3 + k][c] = high[k];
    meshfix__link_wide(n, c, child, count);
}

/* A range of slots that becomes a node: where it starts, how many
   halvings it lies below the root, what the build knows of it, and the
   parent's child entry that will point at it. */
typedef struct meshfix__pending {
    unsigned int first, level, parent;
    int slot;
    meshfix__range range;
} meshfix__pending;

/* Splits a leaf's slots at the middle of their centroids' widest extent
   (no bins: binning the leaves cost the build 13% where this costs it
   under 5%, for the same rays); returns the size of the first half, 0
   when all the centroids lie on one side. */
MESHFIX__PRIVATE unsigned int meshfix__split_middle(meshfix__builder *k, unsigned int first, const meshfix__range *r,
                                                   meshfix__range *left, meshfix__range *right)
{
    unsigned int split;
    int axis = 0, a;
    for (a = 1; a < 3; ++a)
        axis = r->centroids[MESHFIX__HIGH + a] - r->centroids[a] >
                       r->centroids[MESHFIX__HIGH + axis] - r->centroids[axis]
                   ? a
                   : axis;
    split = meshfix__partition(k, first, r->count, axis,
                               0.5f * (r->centroids[axis] + r->centroids[MESHFIX__HIGH + axis]));
    if (split == 0 || split == r->count)
        return 0;
    meshfix__fit_range(k, first, split, left);
    meshfix__fit_range(k, first + split, r->count - split, right);
    return split;
}

/* The part with the largest box among those not `done` and of more than
   `more_than` slots; -1 when there is none. */
MESHFIX__PRIVATE int meshfix__largest_part(const meshfix__pending parts[MESHFIX__WIDE], const int done[MESHFIX__WIDE],
                                          int n, unsigned int more_than)
{
    float largest = -1.0f;
    int i, best = -1;
    for (i = 0; i < n; ++i) {
        float area = meshfix__box_area(parts[i].range.box, parts[i].range.box + MESHFIX__HIGH);
        if (!done[i] && parts[i].range.count > more_than && area > largest)
            best = i, largest = area;
    }
    return best;
}

/* The room a node has left once its parts are leaves: its largest leaves
   of more than a block's worth halved into two leaves each while it
   lasts. The node is read anyway, so the rays lose nothing and cull more
   (halving a leaf of a block or less saved no block test). Returns the
   parts. */
MESHFIX__PRIVATE int meshfix__split_leaves(meshfix__builder *k, meshfix__pending parts[MESHFIX__WIDE],
                                          int leaf[MESHFIX__WIDE], int n, int width)
{
    int whole[MESHFIX__WIDE], i, best;
    for (i = 0; i < n; ++i)
        whole[i] = 0;
    while (n < width) {
        meshfix__range left, right;
        unsigned int split;
        best = meshfix__largest_part(parts, whole, n, MESHFIX__LEAF_SPLIT);
        if (best < 0)
            break;
        split = meshfix__split_middle(k, parts[best].first, &parts[best].range, &left, &right);
        if (split == 0) {
            whole[best] = 1; /* its centroids in one point: a leaf as it is */
            continue;
        }
        parts[n].first = parts[best].first + split;
        parts[n].level = ++parts[best].level;
        parts[n].range = right;
        parts[best].range = left;
        leaf[n] = 1;
        whole[n] = 0;
        n++;
    }
    return n;
}

/* Splits a node's range into up to `width` children: the part with the
   largest box is halved (binned SAH) until there are `width`, or none
   can be halved (leaves); in a tree over triangles, the slots left then go
   to halves of its leaves. Returns how many. */
MESHFIX__PRIVATE int meshfix__split_parts(meshfix__builder *k, const meshfix__pending *p, int width,
                                         meshfix__pending parts[MESHFIX__WIDE], int leaf[MESHFIX__WIDE])
{
    int n = 1, best;
    parts[0] = *p;
    leaf[0] = p->range.count <= k->leaf;
    while (n < width) {
        meshfix__range left, right;
        unsigned int split;
        best = meshfix__largest_part(parts, leaf, n, 0);
        if (best < 0)
            break;
        split = meshfix__split(k, parts[best].first, &parts[best].range, parts[best].level < MESHFIX__BVH_SAH_LEVELS,
                               &left, &right);
        if (split == 0 || split == parts[best].range.count) {
            leaf[best] = 1; /* cannot be halved: a leaf as it is */
            continue;
        }
        parts[n].first = parts[best].first + split;
        parts[n].level = ++parts[best].level;
        parts[n].range = right;
        parts[best].range = left;
        leaf[n] = right.count <= k->leaf;
        leaf[best] = left.count <= k->leaf;
        n++;
    }
    return k->leaf > 1 ? meshfix__split_leaves(k, parts, leaf, n, width) : n;
}

/* The parts of a wide node in slot order (insertion sort; ranges do not
   overlap), so that its leaves lie in the order they are tested. */
MESHFIX__PRIVATE void meshfix__parts_in_slot_order(meshfix__pending parts[MESHFIX__WIDE], int leaf[MESHFIX__WIDE], int n)
{
    int i, j;
    for (i = 1; i < n; ++i) {
        meshfix__pending p = parts[i];
        int l = leaf[i];
        for (j = i; j > 0 && parts[j - 1].first > p.first; --j) {
            parts[j] = parts[j - 1];
            leaf[j] = leaf[j - 1];
        }
        parts[j] = p;
        leaf[j] = l;
    }
}

/* A part of slots that a build leaves for later (meshfix__build_top):
   where its slots start, how many, its level, the child entry that will
   point at its tree; then the room for its nodes and where they end. */
typedef struct meshfix__deferred {
    unsigned int first, count, level, parent;
    int slot;
    unsigned int base, end;
} meshfix__deferred;

/* meshfix__build_nodes from `level` halvings below a root on; parts of
   `defer` slots or fewer that are not leaves are not built but written to
   `deferred` (eight-wide trees; defer 0: none), counted in *deferred_count. */
MESHFIX__PRIVATE unsigned int meshfix__build_top(meshfix__builder *k, meshfix__wide *wide, unsigned int first,
                                                unsigned int count, unsigned int level, unsigned int defer,
                                                meshfix__deferred *deferred, unsigned int *deferred_count)
{
    meshfix__pending stack[(MESHFIX__WIDE - 1) * MESHFIX__BVH_LEVELS + 8], parts[MESHFIX__WIDE];
    unsigned int depth = 1, root = k->next_node;
    int leaf[MESHFIX__WIDE], n, c, width = wide != NULL ? MESHFIX__WIDE : MESHFIX__WIDTH;
    stack[0].first = first;
    stack[0].level = level;
    stack[0].parent = MESHFIX__NONE;
    stack[0].slot = 0;
    meshfix__fit_range(k, first, count, &stack[0].range);
    while (depth > 0) {
        meshfix__pending p = stack[--depth];
        unsigned int index = k->next_node++;
        n = meshfix__split_parts(k, &p, width, parts, leaf);
        if (wide != NULL) {
            if (p.parent != MESHFIX__NONE)
                meshfix__link_wide(&wide[p.parent], p.slot, index, 0);
            meshfix__parts_in_slot_order(parts, leaf, n);
            meshfix__empty_wide(&wide[index]);
        } else {
            if (p.parent != MESHFIX__NONE)
                k->nodes[p.parent].child[p.slot] = index;
            meshfix__empty_node(&k->nodes[index]);
        }
        for (c = n; c-- > 0;) { /* pushed last to first: the first child is built next */
            unsigned int size = leaf[c] ? parts[c].range.count : 0u;
            if (wide != NULL)
                meshfix__set_wide(&wide[index], c, parts[c].first, size, parts[c].range.box,
                                  parts[c].range.box + MESHFIX__HIGH);
            else
                meshfix__set_child(&k->nodes[index], c, parts[c].first, size, parts[c].range.box,
                                   parts[c].range.box + MESHFIX__HIGH);
            if (leaf[c])
                continue;
            parts[c].parent = index;
            parts[c].slot = c;
            if (parts[c].range.count <= defer) {
                meshfix__deferred *d = &deferred[(*deferred_count)++];
                d->first = parts[c].first;
                d->count = parts[c].range.count;
                d->level = parts[c].level;
                d->parent = index;
                d->slot = c;
                continue;
            }
            MESHFIX_ASSERT(depth < sizeof(stack) / sizeof(stack[0]));
            stack[depth++] = parts[c];
        }
    }
    return root;
}

/* Builds a tree over slots [first, first + count) into nodes from
   k->next_node on, depth first (a node's first child's subtree follows
   it); returns its root. Four-wide nodes into k->nodes, or, when `wide`
   is given, eight-wide ones there. Deterministic: no randomness, splits
   depend only on the slots and their order. At most `count` nodes: each
   has two children or more, but a root over a single leaf; eight-wide,
   at most meshfix__wide_budget(count). */
MESHFIX__PRIVATE unsigned int meshfix__build_nodes(meshfix__builder *k, meshfix__wide *wide, unsigned int first,
                                                  unsigned int count)
{
    return meshfix__build_top(k, wide, first, count, 0, 0, NULL, NULL);
}

/* The four-wide tree of the builder's slots (the tree over shells). */
MESHFIX__PRIVATE unsigned int meshfix__build_tree(meshfix__builder *k, unsigned int first, unsigned int count)
{
    return meshfix__build_nodes(k, NULL, first, count);
}

/* A triangle's builder slot from its corners: its box, then the box's
   centre as the point it is binned by (against the triangle's centroid:
   on head.stl 6% fewer nodes and 8% fewer blocks a closest-hit ray,
   1-6% faster rays, the same build time; measured in one process). */
MESHFIX__PRIVATE void meshfix__box_slot(const float corners[9], float slot[9])
{
    int c;
    MESHFIX_MEMCPY(slot, corners, 3 * sizeof(float));
    MESHFIX_MEMCPY(slot + 3, corners, 3 * sizeof(float));
    meshfix__grow_box(slot, slot + 3, corners + 3);
    meshfix__grow_box(slot, slot + 3, corners + 6);
    for (c = 0; c < 3; ++c)
        slot[MESHFIX__SLOT_CENTROID + c] = 0.5f * (slot[c] + slot[3 + c]);
}

/* Asks for the cache line at p ahead of its use, where the compiler can
   (a hint: nothing changes but the time); MESHFIX__AHEAD: how far ahead
   a gather asks. */
#if defined(__GNUC__) || defined(__clang__)
#define MESHFIX__PREFETCH(p) __builtin_prefetch(p)
#else
#define MESHFIX__PREFETCH(p) ((void)0)
#endif
#define MESHFIX__AHEAD 16

/* Large units are built the way of HLBVH (Pantaleoni and Luebke, 2010):
   their triangles sorted once by the Morton codes of their centroids, cut
   along the codes' bits into clusters of a few dozen, binned SAH over the
   clusters' boxes and binned SAH again inside each cluster. SAH alone
   reads every triangle of a range at every level; the large units are the
   ones that ask few rays per triangle (a closed shell of a million
   triangles settles its side with a hundred). Inside the clusters SAH
   where the first version split at the codes' bits (a spatial median):
   the rays' cost is mostly in the lowest levels, which SAH shapes (on a
   million-triangle sphere 35% faster incoherent rays, on head.stl 18%).
   Below MESHFIX__MORTON_MIN triangles binned SAH alone builds about as
   fast (its corners read once, larger leaves) and its tree is the better:
   against this build at 16-slot leaves, in one process, the 40k sphere
   builds in 0.95x the time and traces 12-14% faster, head.stl (118k)
   builds in 1.05x and traces 13-25% faster; on the 1M sphere binned SAH
   traced 6-13% faster but built in 1.25x the time (one thread each). */
#ifndef MESHFIX__MORTON_MIN /* the fuzzers lower both to reach these paths with small meshes */
#define MESHFIX__MORTON_MIN 262144
#endif
#define MESHFIX__CLUSTER 64
#define MESHFIX__CLUSTER_MOST (2 * MESHFIX__CLUSTER) /* small pieces join a cluster up to this */

/* A 10-bit coordinate spread to every third bit. */
MESHFIX__PRIVATE unsigned int meshfix__spread_bits(unsigned int x)
{
    x = (x | (x << 16)) & 0x030000FFu;
    x = (x | (x << 8)) & 0x0300F00Fu;
    x = (x | (x << 4)) & 0x030C30C3u;
    x = (x | (x << 2)) & 0x09249249u;
    return x;
}

/* The size of the front part of slots [first, first + count) of a sorted
   range: those without the highest bit in which its codes differ; half
   of it when all codes are equal. */
MESHFIX__PRIVATE unsigned int meshfix__morton_split(const unsigned int *codes, unsigned int first, unsigned int count)
{
    unsigned int differ = codes[first] ^ codes[first + count - 1], bit = 1u << 31, lo = first,
                 hi = first + count - 1;
    if (differ == 0)
        return count / 2;
    while (!(differ & bit))
        bit >>= 1;
    /* codes[lo] lacks the bit, codes[hi] has it */
    while (lo + 1 < hi) {
        unsigned int mid = lo + (hi - lo) / 2;
        if (codes[mid] & bit)
            hi = mid;
        else
            lo = mid;
    }
    return hi - first;
}

/* Starts a cluster at `first`, counted always, written while there is
   room for it. */
MESHFIX__PRIVATE void meshfix__start_cluster(unsigned int first, unsigned int capacity, unsigned int *starts,
                                            unsigned int *clusters)
{
    if (*clusters < capacity)
        starts[*clusters] = first;
    (*clusters)++;
}

/* The most clusters meshfix__cut_clusters makes of `count` slots when
   small pieces join the cluster before them. */
MESHFIX__PRIVATE unsigned int meshfix__cluster_bound(unsigned int count)
{
    return count / MESHFIX__LEAF + count / MESHFIX__CLUSTER + 1;
}

/* Cuts the sorted range [first, first + count) along its codes' bits into
   clusters of at most MESHFIX__CLUSTER slots, writing where each starts
   (the first `capacity` of them; all are counted). A range that a cut
   would leave a piece smaller than a leaf of stays whole, up to
   MESHFIX__CLUSTER_MOST slots: the piece's sibling is its neighbour in
   space. Other such pieces are clusters of their own (`tiny_alone`: one
   leaf each in the tree over clusters), or join the cluster before, up to
   MESHFIX__CLUSTER_MOST slots, which may lie across the model: every
   cluster but the last then has a leaf's worth or more, or follows one of
   more than MESHFIX__CLUSTER, so there are at most
   meshfix__cluster_bound(count). Joined pieces cost head.stl's
   incoherent closest-hit rays a tenth more nodes (10.2 a ray, against 9.2
   with both rules here). */
MESHFIX__PRIVATE void meshfix__cut_clusters(const unsigned int *codes, unsigned int first, unsigned int count,
                                           int tiny_alone, unsigned int capacity, unsigned int *starts,
                                           unsigned int *clusters)
{
    unsigned int split, last;
    if (count > MESHFIX__CLUSTER) {
        split = meshfix__morton_split(codes, first, count);
        if (count <= MESHFIX__CLUSTER_MOST && (split < MESHFIX__LEAF || count - split < MESHFIX__LEAF)) {
            meshfix__start_cluster(first, capacity, starts, clusters);
            return;
        }
        meshfix__cut_clusters(codes, first, split, tiny_alone, capacity, starts, clusters);
        meshfix__cut_clusters(codes, first + split, count - split, tiny_alone, capacity, starts, clusters);
        return;
    }
    if (!tiny_alone && *clusters != 0) {
        last = first - starts[*clusters - 1];
        if (last < MESHFIX__LEAF || (count < MESHFIX__LEAF && last + count <= MESHFIX__CLUSTER_MOST))
            return; /* joins the cluster before */
    }
    meshfix__start_cluster(first, capacity, starts, clusters);
}

/* The most eight-wide nodes a tree over `count` slots takes, by binned
   SAH (or over clusters, leaf 1: count - 1). A node of fewer than eight
   children has only leaves, of more than a leaf's worth of slots between
   them (else it were a leaf); the children of all nodes number the nodes
   less one plus the leaves, at most `count`. So 7 full nodes + 1 per
   other node <= count - 1, and the others are at most count / 9. */
MESHFIX__PRIVATE unsigned int meshfix__wide_budget(unsigned int count)
{
    unsigned int most = (count - 1 + 6 * (count / (MESHFIX__LEAF + 1))) / (MESHFIX__WIDE - 1);
    return count == 0 ? 0 : most > 1 ? most : 1;
}

/* Where unit u's nodes start, and the top tree's: a unit of s slots has
   s / 2 + 2 nodes' room, which its tree never fills: its own SAH tree
   takes at most meshfix__wide_budget(s), under s / 5 with leaves of 24; a
   Morton-cluster tree at most the clusters (s / 24 + s / 64 + 1) and
   their SAH trees (under s / 5 in all). Both builds' corners wait in that
   room too (36 bytes a slot, in 128): the Morton build's from its start,
   before any node is written; the SAH build's at its end, past the most
   nodes it writes. */
MESHFIX__PRIVATE unsigned int meshfix__unit_nodes(const meshfix__bvh *b, unsigned int u)
{
    return b->unit_first[u] / 2 + 2 * u;
}

MESHFIX__PRIVATE size_t meshfix__ray_nodes(size_t slots, size_t units)
{
    /* every unit's room, then the tree over units (a node per unit at most) */
    return slots / 2 + 3 * units + 1;
}

MESHFIX__PRIVATE size_t meshfix__ray_blocks(size_t slots)
{
    return slots / MESHFIX__WIDE + 1;
}

/* The plan's room for the ray trees (>>geometry lays out the rest):
   nodes and blocks on cache lines. Returns 0 when the sizes overflow. */
MESHFIX__PRIVATE int meshfix__place_ray_trees(size_t *total, meshfix__span *nodes, meshfix__span *blocks, size_t slots,
                                             size_t units)
{
    nodes->count = meshfix__ray_nodes(slots, units);
    blocks->count = meshfix__ray_blocks(slots);
    return slots <= ((size_t)-1) / 4 && units <= ((size_t)-1) / 4 &&
           meshfix__add_aligned(total, nodes->count, sizeof(meshfix__wide), MESHFIX__NODE_ALIGN, &nodes->offset) &&
           meshfix__add_aligned(total, blocks->count, sizeof(meshfix__leaf_block), MESHFIX__NODE_ALIGN, &blocks->offset);
}

/* A large unit's build in phases, each a loop over equal chunks of its
   triangles or clusters that touch only their own slots and nodes: the
   caller's parallel_for runs them side by side when the unit is built on
   its own (never from inside another task), and every chunk writes the
   same bits wherever it runs. */
#define MESHFIX__BUILD_CHUNKS 64 /* from MESHFIX__PARALLEL_UNIT triangles on (>>config) a unit's own build is parallel */
#define MESHFIX__BUILD_CENTROIDS 0   /* corners into waiting, centroids, each chunk's box of them */
#define MESHFIX__BUILD_CODES 1
#define MESHFIX__BUILD_GATHER 2      /* corners in code order */
#define MESHFIX__BUILD_CLUSTERS 3    /* the clusters' boxes */
#define MESHFIX__BUILD_SUBTREES 4    /* binned SAH inside each cluster */

typedef struct meshfix__morton_build {
    meshfix__bvh *b;
    const meshfix__mesh *m;
    unsigned int first, n;          /* the unit's slots */
    unsigned int *order, *codes, *slot_of, *scratch;
    float *slots, *waiting;         /* final corners; corners in triangle order (in the unit's nodes) */
    float chunk_box[MESHFIX__BUILD_CHUNKS][6];
    float low[3];
    double scale[3];
    unsigned int clusters, *starts, *ids, *bases; /* cluster c: slots from starts[c], room for nodes from bases[c] */
    unsigned int *built;            /* cluster c's nodes start (as built; then where they moved) */
    unsigned int *ends;             /* and end, as built */
    float *cluster_slots;
    int phase;
} meshfix__morton_build;

/* Slot i's corners and triangle into its lane of the blocks. */
MESHFIX__PRIVATE void meshfix__fill_lane(meshfix__bvh *b, unsigned int i)
{
    meshfix__leaf_block *k = &b->blocks[i / MESHFIX__WIDE];
    const float *corners = b->corners + 9 * (size_t)i;
    unsigned int lane = i % MESHFIX__WIDE;
    int j;
    for (j = 0; j < 9; ++j)
        k->corner[j][lane] = corners[j];
    k->triangle[lane] = b->order[i];
}

/* Slots [first, end) into the blocks, once their corners are final. */
MESHFIX__PRIVATE void meshfix__fill_lanes(meshfix__bvh *b, unsigned int first, unsigned int end)
{
    unsigned int i;
    for (i = first; i < end; ++i)
        meshfix__fill_lane(b, i);
}

/* Binned SAH over cluster c's slots, into nodes from built[c] on: the
   triangles' boxes in a buffer of the cluster's own (its slots hold final
   corners), then the slots (corners and triangles) moved into the tree's
   order and its leaves pointed at them. */
MESHFIX__PRIVATE void meshfix__cluster_subtree(meshfix__morton_build *k, unsigned int c)
{
    float boxes[9 * MESHFIX__CLUSTER_MOST], corners[9 * MESHFIX__CLUSTER_MOST];
    unsigned int ids[MESHFIX__CLUSTER_MOST], triangles[MESHFIX__CLUSTER_MOST];
    unsigned int start = k->starts[c], size = k->starts[c + 1] - start, i, node, slot = k->first + start;
    meshfix__builder sub;
    int j;
    MESHFIX_ASSERT(size <= MESHFIX__CLUSTER_MOST);
    for (i = 0; i < size; ++i) {
        MESHFIX_MEMCPY(corners + 9 * i, k->slots + 9 * (size_t)(start + i), 9 * sizeof(float));
        meshfix__box_slot(corners + 9 * i, boxes + 9 * i);
        ids[i] = i;
        triangles[i] = k->order[start + i];
    }
    sub.slots = boxes;
    sub.ids = ids;
    sub.nodes = NULL;
    sub.next_node = k->built[c];
    sub.leaf = MESHFIX__LEAF;
    meshfix__build_nodes(&sub, k->b->nodes, 0, size);
    MESHFIX_ASSERT(sub.next_node - k->built[c] <= meshfix__wide_budget(size));
    k->ends[c] = sub.next_node;
    for (i = 0; i < size; ++i) {
        MESHFIX_MEMCPY(k->slots + 9 * (size_t)(start + i), corners + 9 * ids[i], 9 * sizeof(float));
        k->order[start + i] = triangles[ids[i]];
    }
    for (node = k->built[c]; node < sub.next_node; ++node)
        for (j = 0; j < MESHFIX__WIDE; ++j)
            if (k->b->nodes[node].leaves & (1u << j))
                k->b->nodes[node].child[j] += slot;
}

MESHFIX__PRIVATE void meshfix__morton_chunk(void *context, size_t chunk)
{
    meshfix__morton_build *k = (meshfix__morton_build *)context;
    unsigned int total = k->phase >= MESHFIX__BUILD_CLUSTERS ? k->clusters : k->n, i, j;
    unsigned int per = (total + MESHFIX__BUILD_CHUNKS - 1) / MESHFIX__BUILD_CHUNKS;
    unsigned int from = (unsigned int)chunk * per, to = from + per < total ? from + per : total;
    float box[6];
    int c;
    /* the chunk's box grows here and is stored once: the chunks' boxes
       share cache lines, and two threads growing neighbouring ones took
       turns at them (the 1M sphere's centroids: 1.56x on two threads) */
    MESHFIX_MEMCPY(box, k->chunk_box[chunk], sizeof(box));
    for (i = from; i < to; ++i) {
        if (k->phase == MESHFIX__BUILD_CENTROIDS) {
            float *corners = k->waiting + 9 * (size_t)i, *centroid = k->slots + 3 * (size_t)i;
            meshfix__load_corners(k->b, k->m, k->order[i], corners);
            for (c = 0; c < 3; ++c)
                centroid[c] = meshfix__centroid(corners, c);
            meshfix__grow_box(box, box + 3, centroid);
        } else if (k->phase == MESHFIX__BUILD_CODES) {
            const float *centroid = k->slots + 3 * (size_t)i;
            unsigned int code = 0;
            for (c = 0; c < 3; ++c)
                code |= meshfix__spread_bits((unsigned int)(((double)centroid[c] - (double)k->low[c]) * k->scale[c]))
                        << (2 - c);
            k->codes[i] = code;
            k->slot_of[i] = i;
        } else if (k->phase == MESHFIX__BUILD_GATHER) {
            if (i + MESHFIX__AHEAD < to) /* the corners are read at random */
                MESHFIX__PREFETCH(k->waiting + 9 * (size_t)k->slot_of[i + MESHFIX__AHEAD]);
            k->order[i] = k->scratch[k->slot_of[i]];
            MESHFIX_MEMCPY(k->slots + 9 * (size_t)i, k->waiting + 9 * (size_t)k->slot_of[i], 9 * sizeof(float));
        } else if (k->phase == MESHFIX__BUILD_CLUSTERS) {
            float *slot = k->cluster_slots + 9 * (size_t)i;
            meshfix__empty_box(slot);
            for (j = 3 * k->starts[i]; j < 3 * k->starts[i + 1]; ++j)
                meshfix__grow_box(slot, slot + 3, k->slots + 3 * (size_t)j);
            for (c = 0; c < 3; ++c)
                slot[MESHFIX__SLOT_CENTROID + c] = 0.5f * (slot[c] + slot[3 + c]);
            k->ids[i] = i;
        } else if (k->phase == MESHFIX__BUILD_SUBTREES) {
            /* a chunk's clusters one after the other from the room of its
               first: nodes spread at their bounds' distance touched a
               fresh page every cluster or so */
            k->built[i] = k->ends[i] = i == from ? k->bases[i] : k->ends[i - 1];
            if (k->starts[i + 1] - k->starts[i] > MESHFIX__LEAF)
                meshfix__cluster_subtree(k, i);
            /* into the blocks while the cluster's corners are in the cache
               (a pass of its own over the unit's corners cost the build of
               the 1M sphere 8%) */
            meshfix__fill_lanes(k->b, k->first + k->starts[i], k->first + k->starts[i + 1]);
        }
    }
    if (k->phase == MESHFIX__BUILD_CENTROIDS)
        MESHFIX_MEMCPY(k->chunk_box[chunk], box, sizeof(box));
}

MESHFIX__PRIVATE void meshfix__morton_phase(meshfix__morton_build *k, int phase, const meshfix_options *parallel)
{
    k->phase = phase;
    meshfix__run_tasks(parallel, meshfix__morton_chunk, k, MESHFIX__BUILD_CHUNKS);
}

/* The cluster whose nodes started at `node` (as built): the last whose
   start is not above it (those without nodes share the next one's). */
MESHFIX__PRIVATE unsigned int meshfix__cluster_at(const meshfix__morton_build *k, unsigned int node)
{
    unsigned int lo = 0, hi = k->clusters; /* bases[lo] <= node < bases[hi] */
    while (lo + 1 < hi) {
        unsigned int mid = lo + (hi - lo) / 2;
        if (k->bases[mid] <= node)
            lo = mid;
        else
            hi = mid;
    }
    return lo;
}

/* Moves the clusters' nodes together after the tree over them, in
   cluster order, and points the tree at them: each chunk of the build
   put its clusters' nodes one after the other in the room of all their
   bounds, about four times what they take, and rays that crossed the
   gaps missed the TLB and the caches (on the 1M sphere with 5% more nodes
   a ray than binned SAH, 30% less its rate). Nodes only move down, so a
   forward copy is safe. */
MESHFIX__PRIVATE void meshfix__pack_clusters(meshfix__morton_build *k, unsigned int root, unsigned int top_end)
{
    meshfix__wide *nodes = k->b->nodes;
    unsigned int c, node, next = top_end, used, delta;
    int i;
    for (c = 0; c < k->clusters; ++c) {
        used = k->ends[c] - k->built[c];
        delta = k->built[c] - next;
        for (node = next; node < next + used; ++node) {
            nodes[node] = nodes[node + delta];
            for (i = 0; i < MESHFIX__WIDE; ++i)
                if (nodes[node].inner & (1u << i))
                    nodes[node].child[i] -= delta;
        }
        k->built[c] = next; /* where its root is now */
        next += used;
    }
    for (node = root; node < top_end; ++node)
        for (i = 0; i < MESHFIX__WIDE; ++i)
            if ((nodes[node].inner & (1u << i)) && nodes[node].child[i] >= top_end)
                nodes[node].child[i] = k->built[meshfix__cluster_at(k, nodes[node].child[i])];
}

/* The tree over the clusters (binned SAH, a cluster a leaf) from node
   `base` on, whose leaves then point at the clusters' triangles (a
   leaf's worth) or the SAH trees under them, each in the nodes budgeted
   for it, one after the other. Returns the root. */
MESHFIX__PRIVATE unsigned int meshfix__cluster_tree(meshfix__morton_build *k, unsigned int base,
                                                   const meshfix_options *parallel)
{
    unsigned int c, node, top_end, root, next;
    meshfix__builder top;
    int i;
    unsigned int bound = meshfix__cluster_bound(k->n);
    k->starts = k->slot_of; /* free since the gather */
    /* small pieces alone where they leave room for the clusters' nodes
       and boxes, else joined */
    k->clusters = 0;
    meshfix__cut_clusters(k->codes, 0, k->n, 1, bound, k->starts, &k->clusters);
    if (k->clusters > bound) {
        k->clusters = 0;
        meshfix__cut_clusters(k->codes, 0, k->n, 0, bound, k->starts, &k->clusters);
    }
    MESHFIX_ASSERT(k->clusters <= bound);
    k->starts[k->clusters] = k->n;
    k->cluster_slots = (float *)(void *)(k->starts + k->clusters + 1);
    k->ids = (unsigned int *)(void *)(k->cluster_slots + 9 * (size_t)k->clusters);
    meshfix__morton_phase(k, MESHFIX__BUILD_CLUSTERS, parallel);
    top.slots = k->cluster_slots;
    top.ids = k->ids;
    top.nodes = NULL;
    top.next_node = base;
    top.leaf = 1;
    root = meshfix__build_nodes(&top, k->b->nodes, 0, k->clusters);
    top_end = top.next_node;
    /* the clusters' slots are read: their first floats hold where each
       one's nodes start, one after the other */
    k->bases = (unsigned int *)(void *)k->cluster_slots;
    k->built = k->bases + k->clusters;
    k->ends = k->built + k->clusters;
    for (c = 0, next = top_end; c < k->clusters; ++c) {
        unsigned int size = k->starts[c + 1] - k->starts[c];
        k->bases[c] = next;
        next += size > MESHFIX__LEAF ? meshfix__wide_budget(size) : 0u;
    }
    MESHFIX_ASSERT(next - base <= k->n / 2 + 2);
    for (node = root; node < top_end; ++node)
        for (i = 0; i < MESHFIX__WIDE; ++i) {
            meshfix__wide *x = &k->b->nodes[node];
            unsigned int size;
            if (!(x->leaves & (1u << i)))
                continue;
            c = k->ids[x->child[i]];
            size = k->starts[c + 1] - k->starts[c];
            meshfix__link_wide(x, i, size <= MESHFIX__LEAF ? k->first + k->starts[c] : k->bases[c],
                               size <= MESHFIX__LEAF ? size : 0u);
        }
    meshfix__morton_phase(k, MESHFIX__BUILD_SUBTREES, parallel);
    meshfix__pack_clusters(k, root, top_end);
    return root;
}

/* The tree of slots [first, end) from node `base` on: Morton codes of
   their centroids in the box of the centroids, sorted with the slots'
   triangles, corners moved into that order, then the nodes. `parallel`:
   the options whose parallel_for may run the phases (NULL: here). Returns
   its root. */
MESHFIX__PRIVATE unsigned int meshfix__morton_tree(meshfix__bvh *b, const meshfix__mesh *m, unsigned int first,
                                                  unsigned int end, unsigned int base, const meshfix_options *parallel)
{
    meshfix__morton_build k;
    float high[3];
    double extent = 0.0;
    unsigned int chunk;
    int c;
    k.b = b;
    k.m = m;
    k.first = first;
    k.n = end - first;
    k.order = b->order + first;
    k.codes = b->sort + 4 * (size_t)first;
    k.slot_of = k.codes + k.n;
    k.scratch = k.codes + 2 * (size_t)k.n;
    k.slots = b->corners + 9 * (size_t)first;
    /* the corners wait where the unit's nodes will be, until they are
       moved into code order */
    k.waiting = (float *)(void *)(b->nodes + base);
    for (chunk = 0; chunk < MESHFIX__BUILD_CHUNKS; ++chunk)
        meshfix__empty_box(k.chunk_box[chunk]);
    meshfix__morton_phase(&k, MESHFIX__BUILD_CENTROIDS, parallel);
    for (c = 0; c < 3; ++c) {
        k.low[c] = 1e30f, high[c] = -1e30f;
        for (chunk = 0; chunk < MESHFIX__BUILD_CHUNKS; ++chunk) {
            k.low[c] = k.chunk_box[chunk][c] < k.low[c] ? k.chunk_box[chunk][c] : k.low[c];
            high[c] = k.chunk_box[chunk][3 + c] > high[c] ? k.chunk_box[chunk][3 + c] : high[c];
        }
        extent = (double)high[c] - (double)k.low[c] > extent ? (double)high[c] - (double)k.low[c] : extent;
    }
    /* one scale for the three axes: the codes' cells are cubes whatever
       the box's shape (a scale per axis stretched them with it) */
    for (c = 0; c < 3; ++c)
        k.scale[c] = extent > 0.0 ? 1023.0 / extent : 0.0;
    meshfix__morton_phase(&k, MESHFIX__BUILD_CODES, parallel);
    meshfix__radix_sort(k.codes, k.slot_of, k.scratch, k.scratch + k.n, k.n, parallel);
    /* the triangles in code order: the old order waits in the scratch */
    MESHFIX_MEMCPY(k.scratch, k.order, k.n * sizeof(unsigned int));
    meshfix__morton_phase(&k, MESHFIX__BUILD_GATHER, parallel);
    return meshfix__cluster_tree(&k, base, parallel);
}

/* Sets up the slots of the triangles with an area, unit by unit (a
   counting sort: each unit's slots in triangle order), and the frame.
   Trees come later, per unit, as rays need them. Returns 0 when out of
   memory. */
MESHFIX__PRIVATE int meshfix__prepare_bvh(meshfix__bvh *b, const meshfix__mesh *m, const meshfix__arena *a,
                                         const unsigned int *triangle_unit, unsigned int unit_count)
{
    unsigned int t, u, n = 0, sum = 0;
    /* the frame was fitted before (coherence works in it too) */
    b->unit_count = unit_count;
    b->top = MESHFIX__NONE;
    b->unit_first = (unsigned int *)meshfix__array(a, a->plan.unit_first, (size_t)unit_count + 1);
    b->unit_root = (unsigned int *)meshfix__array(a, a->plan.unit_root, unit_count);
    if (b->unit_first == NULL || b->unit_root == NULL)
        return 0;
    MESHFIX_MEMSET(b->unit_first, 0, ((size_t)unit_count + 1) * sizeof(unsigned int));
    for (t = 0; t < m->triangle_count; ++t)
        if (triangle_unit[t] != MESHFIX__NONE) {
            b->unit_first[triangle_unit[t]]++;
            n++;
        }
    for (u = 0; u <= unit_count; ++u) {
        unsigned int k = u < unit_count ? b->unit_first[u] : 0;
        b->unit_first[u] = sum;
        sum += k;
        if (u < unit_count)
            b->unit_root[u] = MESHFIX__NONE;
    }
    b->count = n;
    b->order = (unsigned int *)meshfix__array(a, a->plan.order, n);
    b->corners = (float *)meshfix__array(a, a->plan.corners, 9 * ((size_t)n + MESHFIX__SLOT_PAD));
    b->by_index = (unsigned int *)meshfix__array(a, a->plan.by_index, n);
    b->cumulative_area = (double *)meshfix__array(a, a->plan.cumulative_area, n);
    b->sort = (unsigned int *)meshfix__array(a, a->plan.morton_sort, 4 * (size_t)n);
    b->nodes = (meshfix__wide *)meshfix__array(a, a->plan.nodes, meshfix__ray_nodes(n, unit_count));
    b->blocks = (meshfix__leaf_block *)meshfix__array(a, a->plan.blocks, meshfix__ray_blocks(n));
    if (b->order == NULL || b->by_index == NULL || b->corners == NULL || b->cumulative_area == NULL ||
        b->sort == NULL || b->nodes == NULL || b->blocks == NULL)
        return 0;
    /* unit_first[u] moves to the end of unit u while slots are placed */
    for (t = 0; t < m->triangle_count; ++t)
        if (triangle_unit[t] != MESHFIX__NONE)
            b->order[b->unit_first[triangle_unit[t]]++] = t;
    for (u = unit_count; u > 0; --u)
        b->unit_first[u] = b->unit_first[u - 1];
    b->unit_first[0] = 0;
    MESHFIX_MEMCPY(b->by_index, b->order, n * sizeof(unsigned int));
    MESHFIX_MEMSET(b->corners + 9 * (size_t)n, 0, 9 * MESHFIX__SLOT_PAD * sizeof(float));
    return 1;
}

/* A unit's SAH build in phases, as the Morton build's: each a loop over
   equal chunks of its slots, or over the parts it left for later, that
   touch only their own slots and nodes. A unit of MESHFIX__PARALLEL_UNIT
   slots or more is built as its top, then every part of a quarter of its
   slots or fewer as a task of its own, whether the caller runs tasks side
   by side or not: the same tree either way (a part's tree is the tree its
   slots would have had in place, only its nodes lie elsewhere). */
#define MESHFIX__SAH_SLOTS 0  /* corners into waiting, each triangle's box and centroid into its slot */
#define MESHFIX__SAH_PARTS 1  /* a part's tree a task */
#define MESHFIX__SAH_GATHER 2 /* corners and triangles in the tree's order, then into the blocks */

typedef struct meshfix__sah_build {
    meshfix__bvh *b;
    const meshfix__mesh *m;
    unsigned int first, n;           /* the unit's slots */
    unsigned int *ids, *triangles;   /* per slot: where its corners wait; the unit's triangles as given */
    float *slots, *waiting;          /* the builder's slots; the corners in the order given */
    meshfix__deferred *parts;        /* what the top left for later */
    unsigned int part_count;
    int phase;
} meshfix__sah_build;

/* The builder over the unit's slots, its nodes from `next_node` on. */
MESHFIX__PRIVATE void meshfix__sah_builder(const meshfix__sah_build *k, unsigned int next_node, meshfix__builder *sub)
{
    sub->slots = k->slots;
    sub->ids = k->ids;
    sub->nodes = NULL;
    sub->next_node = next_node;
    sub->leaf = MESHFIX__LEAF;
}

/* Slots [from, to) of the unit: their triangles' corners into waiting,
   each one's box and centroid into its slot. */
MESHFIX__PRIVATE void meshfix__sah_slots(const meshfix__sah_build *k, unsigned int from, unsigned int to)
{
    const unsigned int *order = k->b->order + k->first;
    float *waiting = k->waiting, *slots = k->slots;
    unsigned int i;
    for (i = from; i < to; ++i) {
        k->triangles[i] = order[i];
        k->ids[i] = i;
        meshfix__load_corners(k->b, k->m, order[i], waiting + 9 * (size_t)i);
        meshfix__box_slot(waiting + 9 * (size_t)i, slots + 9 * (size_t)i);
    }
}

/* Slots [from, to) in the tree's order: their corners, read at random
   (asked for a few slots ahead), and triangles, then into the blocks. */
MESHFIX__PRIVATE void meshfix__sah_gather(const meshfix__sah_build *k, unsigned int from, unsigned int to)
{
    const unsigned int *ids = k->ids, *triangles = k->triangles;
    const float *waiting = k->waiting;
    unsigned int *order = k->b->order + k->first, i;
    float *slots = k->slots;
    for (i = from; i < to; ++i) {
        if (i + MESHFIX__AHEAD < to)
            MESHFIX__PREFETCH(waiting + 9 * (size_t)ids[i + MESHFIX__AHEAD]);
        MESHFIX_MEMCPY(slots + 9 * (size_t)i, waiting + 9 * (size_t)ids[i], 9 * sizeof(float));
        order[i] = triangles[ids[i]];
    }
    meshfix__fill_lanes(k->b, k->first + from, k->first + to);
}

/* Part p's tree, in the room from its base on. */
MESHFIX__PRIVATE void meshfix__sah_part(const meshfix__sah_build *k, meshfix__deferred *d)
{
    meshfix__builder sub;
    meshfix__sah_builder(k, d->base, &sub);
    meshfix__build_top(&sub, k->b->nodes, d->first, d->count, d->level, 0, NULL, NULL);
    MESHFIX_ASSERT(sub.next_node - d->base <= meshfix__wide_budget(d->count));
    d->end = sub.next_node;
}

MESHFIX__PRIVATE void meshfix__sah_chunk(void *context, size_t chunk)
{
    meshfix__sah_build *k = (meshfix__sah_build *)context;
    unsigned int per = (k->n + MESHFIX__BUILD_CHUNKS - 1) / MESHFIX__BUILD_CHUNKS;
    unsigned int from = (unsigned int)chunk * per, to = from + per < k->n ? from + per : k->n;
    if (k->phase == MESHFIX__SAH_PARTS)
        meshfix__sah_part(k, &k->parts[chunk]);
    else if (from >= to)
        return;
    else if (k->phase == MESHFIX__SAH_SLOTS)
        meshfix__sah_slots(k, from, to);
    else
        meshfix__sah_gather(k, from, to);
}

/* A phase as tasks where the unit is built on the caller's threads, else
   in one go (a unit of a few triangles, of which a model may have
   thousands, paid for 64 calls a phase); the same bits either way. */
MESHFIX__PRIVATE void meshfix__sah_phase(meshfix__sah_build *k, int phase, size_t tasks, const meshfix_options *parallel)
{
    k->phase = phase;
    if (k->n >= MESHFIX__PARALLEL_UNIT)
        meshfix__run_tasks(parallel, meshfix__sah_chunk, k, tasks);
    else if (phase == MESHFIX__SAH_SLOTS)
        meshfix__sah_slots(k, 0, k->n);
    else if (phase == MESHFIX__SAH_GATHER)
        meshfix__sah_gather(k, 0, k->n);
}

/* Moves the parts' nodes together from node `next` on (the top's end), in
   part order, and points the top at them: each was built in the room of
   its bound. Nodes only move down, so a forward copy is safe. Returns the
   end of the unit's nodes. */
MESHFIX__PRIVATE unsigned int meshfix__pack_parts(meshfix__sah_build *k, unsigned int next)
{
    meshfix__wide *nodes = k->b->nodes;
    unsigned int p, node, used, delta;
    int i;
    for (p = 0; p < k->part_count; ++p) {
        const meshfix__deferred *d = &k->parts[p];
        used = d->end - d->base;
        delta = d->base - next;
        for (node = next; node < next + used; ++node) {
            nodes[node] = nodes[node + delta];
            for (i = 0; i < MESHFIX__WIDE; ++i)
                if (nodes[node].inner & (1u << i))
                    nodes[node].child[i] -= delta;
        }
        meshfix__link_wide(&nodes[d->parent], d->slot, next, 0);
        next += used;
    }
    return next;
}

/* The tree of slots [first, end) by binned SAH alone, from node `base`
   on, in the unit's room for nodes that ends at `room_end`; `parallel`:
   the options whose parallel_for may run the phases (NULL: here). Returns
   its root. The slots hold each triangle's box and centroid while it is
   built. Its corners are read from the mesh once: they wait at the end of
   the room (the nodes take under half of it) and move into the tree's
   order after (reading them again was a tenth of the build). */
MESHFIX__PRIVATE unsigned int meshfix__sah_tree(meshfix__bvh *b, const meshfix__mesh *m, unsigned int first,
                                               unsigned int end, unsigned int base, unsigned int room_end,
                                               const meshfix_options *parallel)
{
    meshfix__sah_build k;
    meshfix__builder top;
    unsigned int n = end - first, root, node, next, p;
    int c;
    k.b = b;
    k.m = m;
    k.first = first;
    k.n = n;
    k.ids = b->sort + 4 * (size_t)first;
    k.triangles = k.ids + n;
    k.parts = (meshfix__deferred *)(void *)(k.triangles + n); /* the rest of the unit's scratch */
    k.part_count = 0;
    k.slots = b->corners + 9 * (size_t)first;
    k.waiting = (float *)(void *)(b->nodes + room_end) - 9 * (size_t)n;
    meshfix__sah_phase(&k, MESHFIX__SAH_SLOTS, MESHFIX__BUILD_CHUNKS, parallel);
    meshfix__sah_builder(&k, base, &top);
    root = meshfix__build_top(&top, b->nodes, 0, n, 0, n >= MESHFIX__PARALLEL_UNIT ? n / 4 : 0, k.parts,
                              &k.part_count);
    /* parts have more than a leaf's worth of slots each */
    MESHFIX_ASSERT(k.part_count * sizeof(meshfix__deferred) <= 2 * (size_t)n * sizeof(unsigned int));
    for (p = 0, next = top.next_node; p < k.part_count; ++p) {
        k.parts[p].base = next;
        next += meshfix__wide_budget(k.parts[p].count);
    }
    MESHFIX_ASSERT(next <= room_end &&
                   (size_t)(room_end - next) * sizeof(meshfix__wide) >= 9 * (size_t)n * sizeof(float));
    meshfix__sah_phase(&k, MESHFIX__SAH_PARTS, k.part_count, parallel);
    next = meshfix__pack_parts(&k, top.next_node);
    MESHFIX_ASSERT(next - base <= meshfix__wide_budget(n) + k.part_count);
    for (node = base; node < next; ++node)
        for (c = 0; c < MESHFIX__WIDE; ++c)
            if (b->nodes[node].leaves & (1u << c))
                b->nodes[node].child[c] += first;
    meshfix__sah_phase(&k, MESHFIX__SAH_GATHER, MESHFIX__BUILD_CHUNKS, parallel);
    return root;
}

/* How a unit's tree is built: binned SAH below MESHFIX__MORTON_MIN slots
   and Morton clusters from there (AUTO), or one of the two whatever the
   size (the bench and the tests compare them). */
#define MESHFIX__BUILD_AUTO 0
#define MESHFIX__BUILD_SAH 1
#define MESHFIX__BUILD_MORTON 2

/* The tree of unit u, built the first time it is asked for; NONE when the
   unit has no triangle with an area. `parallel`: options whose
   parallel_for may run a large unit's build (NULL: here). */
MESHFIX__PRIVATE unsigned int meshfix__build_unit_by(meshfix__bvh *b, const meshfix__mesh *m, unsigned int u,
                                                    const meshfix_options *parallel, int builder)
{
    unsigned int first = b->unit_first[u], end = b->unit_first[u + 1], base = meshfix__unit_nodes(b, u);
    if (b->unit_root[u] != MESHFIX__NONE || first == end)
        return b->unit_root[u];
    /* each builder fills the unit's blocks as its corners become final */
    b->unit_root[u] = builder == MESHFIX__BUILD_MORTON ||
                              (builder == MESHFIX__BUILD_AUTO && end - first >= MESHFIX__MORTON_MIN)
                          ? meshfix__morton_tree(b, m, first, end, base, parallel)
                          : meshfix__sah_tree(b, m, first, end, base, meshfix__unit_nodes(b, u + 1), parallel);
    return b->unit_root[u];
}

MESHFIX__PRIVATE unsigned int meshfix__build_unit(meshfix__bvh *b, const meshfix__mesh *m, unsigned int u,
                                                 const meshfix_options *parallel)
{
    return meshfix__build_unit_by(b, m, u, parallel, MESHFIX__BUILD_AUTO);
}

MESHFIX__PRIVATE unsigned int meshfix__unit_tree(meshfix__bvh *b, const meshfix__mesh *m, unsigned int u)
{
    return meshfix__build_unit(b, m, u, NULL);
}

/* The box around a node's children. */
MESHFIX__PRIVATE void meshfix__node_box(const meshfix__wide *n, float box[6])
{
    int c, k;
    meshfix__empty_box(box);
    for (c = 0; c < MESHFIX__WIDE; ++c) {
        if (!((n->inner | n->leaves) & (1u << c)))
            continue;
        for (k = 0; k < 3; ++k) {
            box[k] = n->bounds[k][c] < box[k] ? n->bounds[k][c] : box[k];
            box[3 + k] = n->bounds[3 + k][c] > box[3 + k] ? n->bounds[3 + k][c] : box[3 + k];
        }
    }
}

/* The tree over all units' trees (each unit's tree built first), after
   the units' nodes; its leaves are unit nodes. `slots` and `ids` are
   scratch for one slot and id per unit. */
MESHFIX__PRIVATE unsigned int meshfix__top_tree(meshfix__bvh *b, const meshfix__mesh *m, float *slots,
                                               unsigned int *ids)
{
    meshfix__builder k;
    unsigned int u, n = 0, node;
    int c;
    if (b->top != MESHFIX__NONE)
        return b->top;
    for (u = 0; u < b->unit_count; ++u) {
        unsigned int root = meshfix__unit_tree(b, m, u);
        float *slot = slots + 9 * (size_t)n;
        if (root == MESHFIX__NONE)
            continue;
        meshfix__node_box(&b->nodes[root], slot);
        for (c = 0; c < 3; ++c)
            slot[MESHFIX__SLOT_CENTROID + c] = 0.5f * (slot[c] + slot[3 + c]);
        ids[n++] = u;
    }
    if (n == 0)
        return MESHFIX__NONE;
    k.slots = slots;
    k.ids = ids;
    k.nodes = NULL;
    k.next_node = b->count / 2 + 2 * b->unit_count;
    k.leaf = 1;
    b->top = meshfix__build_nodes(&k, b->nodes, 0, n);
    /* each leaf holds one unit: it becomes a link to that unit's tree */
    for (node = b->top; node < k.next_node; ++node)
        for (c = 0; c < MESHFIX__WIDE; ++c) {
            meshfix__wide *x = &b->nodes[node];
            if (x->leaves & (1u << c))
                meshfix__link_wide(x, c, b->unit_root[ids[x->child[c]]], 0);
        }
    return b->top;
}

/* ===== >>traverse ===== */

/* Walking the trees: a ray's setup, the watertight triangle test, the
   SIMD box and leaf tests, and the three queries (any hit, the closest
   hit, every crossing counted), and the walk of a tree over boxes. */

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
        r->near_plane[k] = (unsigned int)(r->inverse[k] < 0 ? 3 + k : k);
        r->far_plane[k] = (unsigned int)(r->inverse[k] < 0 ? k : 3 + k);
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

/* What a traversal looks for: the first hit, the closest, or the number of
   surfaces crossed (a parity). The library asks for the first and the
   count; the closest (and its distance) is what the bench and the tests
   measure the tree by against Embree and brute force. */
#define MESHFIX__ANY_HIT 0
#define MESHFIX__CLOSEST_HIT 1
#define MESHFIX__COUNT_HITS 2

typedef struct meshfix__query {
    int mode;
    unsigned int skip;      /* a triangle to ignore (the ray's own), or NONE */
    unsigned int hits;      /* COUNT_HITS: crossings, each counted once */
    float t;                /* ANY / CLOSEST: the distance of the hit */
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

/* The lowest set bit of a non-zero mask. */
MESHFIX__PRIVATE unsigned int meshfix__lowest_bit(unsigned int mask)
{
#if defined(__GNUC__) || defined(__clang__)
    return (unsigned int)__builtin_ctz(mask);
#else
    unsigned int i = 0;
    while (!(mask & 1u))
        mask >>= 1, ++i;
    return i;
#endif
}

/* The highest set bit of a non-zero mask. */
MESHFIX__PRIVATE unsigned int meshfix__highest_bit(unsigned int mask)
{
#if defined(__GNUC__) || defined(__clang__)
    return 31u - (unsigned int)__builtin_clz(mask);
#else
    unsigned int i = 0;
    while (mask >>= 1)
        ++i;
    return i;
#endif
}

/* The node and block tests, in as many versions as there are SIMD paths.
   Each computes the same float operations in the same order as the scalar
   one, lane by lane, so every path gives the same bits (nothing here is
   ever NaN); a path is a matter of speed only.

   Slab test of a node's eight boxes: a bit per box the ray enters within
   (t_min, t_max), and the entry distances. A ray aimed at a vertex on a
   box's face has an empty interval by rounding alone: the far side is
   widened by a few ulps (Ize, "Robust BVH Ray Traversal", JCGT 2013). */
MESHFIX__INLINE_ALWAYS static unsigned int meshfix__boxes_scalar(const meshfix__ray *r, const meshfix__wide *n,
                                                                 float t_max, float entry[MESHFIX__WIDE])
{
    float t0[MESHFIX__WIDE], t1[MESHFIX__WIDE];
    unsigned int mask = 0;
    int c, k;
    for (c = 0; c < MESHFIX__WIDE; ++c)
        t0[c] = r->t_min, t1[c] = t_max;
    for (k = 0; k < 3; ++k) {
        const float *near_plane = n->bounds[r->near_plane[k]];
        const float *far_plane = n->bounds[r->far_plane[k]];
        for (c = 0; c < MESHFIX__WIDE; ++c) {
            float tn = (near_plane[c] - r->origin[k]) * r->inverse[k];
            float tf = (far_plane[c] - r->origin[k]) * r->inverse[k] * 1.0000004f;
            t0[c] = tn > t0[c] ? tn : t0[c];
            t1[c] = tf < t1[c] ? tf : t1[c];
        }
    }
    for (c = 0; c < MESHFIX__WIDE; ++c) {
        entry[c] = t0[c];
        mask |= (unsigned int)(t0[c] <= t1[c]) << c;
    }
    return mask;
}

/* The corners of lane i of block k, as meshfix__hit_triangle reads them. */
MESHFIX__INLINE_ALWAYS static void meshfix__lane_corners(const meshfix__leaf_block *k, unsigned int i, float corners[9])
{
    int j;
    for (j = 0; j < 9; ++j)
        corners[j] = k->corner[j][i];
}

/* Watertight test of the lanes `want` of block k: a bit per lane hit
   within (t_min, t_max), with its distance and zero count in t[] and
   zeros[] as meshfix__hit_triangle gives them. */
MESHFIX__INLINE_ALWAYS static unsigned int meshfix__lanes_scalar(const meshfix__ray *r, const meshfix__leaf_block *k,
                                                                 unsigned int want, float t[MESHFIX__WIDE],
                                                                 int zeros[MESHFIX__WIDE])
{
    unsigned int mask = 0, i;
    float corners[9];
    for (; want != 0; want &= want - 1) {
        i = meshfix__lowest_bit(want);
        meshfix__lane_corners(k, i, corners);
        if (meshfix__hit_triangle(r, corners, &t[i], &zeros[i]))
            mask |= 1u << i;
    }
    return mask;
}

/* The lanes of `edge` (those with an edge function exactly 0: a hit on an
   edge or vertex, or a miss beside one) by the scalar test and its double
   fallback; returns the ones hit. */
MESHFIX__PRIVATE unsigned int meshfix__edge_lanes(const meshfix__ray *r, const meshfix__leaf_block *k, unsigned int edge,
                                                 float t[MESHFIX__WIDE], int zeros[MESHFIX__WIDE])
{
    return meshfix__lanes_scalar(r, k, edge, t, zeros);
}

#if MESHFIX__SSE
/* Four lanes from `half` (0 or 4) on, side by side. */
MESHFIX__INLINE_ALWAYS static unsigned int meshfix__boxes_half_sse(const meshfix__ray *r, const meshfix__wide *n,
                                                                   int half, float t_max, float *entry)
{
    __m128 t0 = _mm_set1_ps(r->t_min), t1 = _mm_set1_ps(t_max), widen = _mm_set1_ps(1.0000004f);
    int k;
    for (k = 0; k < 3; ++k) {
        __m128 origin = _mm_set1_ps(r->origin[k]), inverse = _mm_set1_ps(r->inverse[k]);
        __m128 tn = _mm_mul_ps(_mm_sub_ps(_mm_loadu_ps(n->bounds[r->near_plane[k]] + half), origin), inverse);
        __m128 tf =
            _mm_mul_ps(_mm_mul_ps(_mm_sub_ps(_mm_loadu_ps(n->bounds[r->far_plane[k]] + half), origin), inverse), widen);
        t0 = _mm_max_ps(tn, t0);
        t1 = _mm_min_ps(tf, t1);
    }
    _mm_storeu_ps(entry, t0);
    return (unsigned int)_mm_movemask_ps(_mm_cmple_ps(t0, t1));
}

MESHFIX__INLINE_ALWAYS static unsigned int meshfix__boxes_sse(const meshfix__ray *r, const meshfix__wide *n,
                                                              float t_max, float entry[MESHFIX__WIDE])
{
    return meshfix__boxes_half_sse(r, n, 0, t_max, entry) | meshfix__boxes_half_sse(r, n, 4, t_max, entry + 4) << 4;
}

/* Four lanes of block k from `half` on (`want`: the wanted among them). */
MESHFIX__INLINE_ALWAYS static unsigned int meshfix__lanes_half_sse(const meshfix__ray *r, const meshfix__leaf_block *k,
                                                                   int half, unsigned int want, float *t)
{
    /* the rows in the ray's axis order, loaded by index: the same
       differences and products as through an array, none spilled */
    const float(*rows)[MESHFIX__WIDE] = k->corner;
    __m128 ox = _mm_set1_ps(r->origin[r->kx]), oy = _mm_set1_ps(r->origin[r->ky]);
    __m128 oz = _mm_set1_ps(r->origin[r->kz]), az, bz, cz, ax, ay, bx, by, cx, cy, u, v, w, det;
    __m128 zero = _mm_setzero_ps(), sx = _mm_set1_ps(r->shear[0]), sy = _mm_set1_ps(r->shear[1]);
    unsigned int mask, edge;
    az = _mm_sub_ps(_mm_loadu_ps(rows[r->kz] + half), oz);
    bz = _mm_sub_ps(_mm_loadu_ps(rows[3 + r->kz] + half), oz);
    cz = _mm_sub_ps(_mm_loadu_ps(rows[6 + r->kz] + half), oz);
    ax = _mm_sub_ps(_mm_sub_ps(_mm_loadu_ps(rows[r->kx] + half), ox), _mm_mul_ps(sx, az));
    ay = _mm_sub_ps(_mm_sub_ps(_mm_loadu_ps(rows[r->ky] + half), oy), _mm_mul_ps(sy, az));
    bx = _mm_sub_ps(_mm_sub_ps(_mm_loadu_ps(rows[3 + r->kx] + half), ox), _mm_mul_ps(sx, bz));
    by = _mm_sub_ps(_mm_sub_ps(_mm_loadu_ps(rows[3 + r->ky] + half), oy), _mm_mul_ps(sy, bz));
    cx = _mm_sub_ps(_mm_sub_ps(_mm_loadu_ps(rows[6 + r->kx] + half), ox), _mm_mul_ps(sx, cz));
    cy = _mm_sub_ps(_mm_sub_ps(_mm_loadu_ps(rows[6 + r->ky] + half), oy), _mm_mul_ps(sy, cz));
    u = _mm_sub_ps(_mm_mul_ps(cx, by), _mm_mul_ps(cy, bx));
    v = _mm_sub_ps(_mm_mul_ps(ax, cy), _mm_mul_ps(ay, cx));
    w = _mm_sub_ps(_mm_mul_ps(bx, ay), _mm_mul_ps(by, ax));
    edge = (unsigned int)_mm_movemask_ps(
               _mm_or_ps(_mm_or_ps(_mm_cmpeq_ps(u, zero), _mm_cmpeq_ps(v, zero)), _mm_cmpeq_ps(w, zero))) & want;
    /* a hit has no edge function below 0, or none above */
    mask = ~(unsigned int)_mm_movemask_ps(_mm_and_ps(
               _mm_or_ps(_mm_or_ps(_mm_cmplt_ps(u, zero), _mm_cmplt_ps(v, zero)), _mm_cmplt_ps(w, zero)),
               _mm_or_ps(_mm_or_ps(_mm_cmpgt_ps(u, zero), _mm_cmpgt_ps(v, zero)), _mm_cmpgt_ps(w, zero))));
    det = _mm_add_ps(_mm_add_ps(u, v), w);
    mask &= ~(unsigned int)_mm_movemask_ps(_mm_cmpeq_ps(det, zero)) & want & ~edge;
    if (mask != 0) {
        __m128 sz = _mm_set1_ps(r->shear[2]), nonzero = _mm_cmpneq_ps(det, zero), dist;
        __m128 distance = _mm_add_ps(
            _mm_add_ps(_mm_mul_ps(u, _mm_mul_ps(sz, az)), _mm_mul_ps(v, _mm_mul_ps(sz, bz))),
            _mm_mul_ps(w, _mm_mul_ps(sz, cz)));
        /* a lane that fails is not divided by 0: its det is replaced */
        dist = _mm_div_ps(distance,
                          _mm_or_ps(_mm_and_ps(nonzero, det), _mm_andnot_ps(nonzero, _mm_set1_ps(1.0f))));
        mask &= (unsigned int)_mm_movemask_ps(
            _mm_and_ps(_mm_cmpgt_ps(dist, _mm_set1_ps(r->t_min)), _mm_cmplt_ps(dist, _mm_set1_ps(r->t_max))));
        _mm_storeu_ps(t, dist);
    }
    return mask | edge << 4; /* the edge lanes, for the caller to test */
}

#define meshfix__boxes_simd meshfix__boxes_sse
#define meshfix__lanes_half_simd meshfix__lanes_half_sse
#define MESHFIX__LANES_FUNCTION MESHFIX__INLINE_ALWAYS static
#elif MESHFIX__NEON
MESHFIX__PRIVATE unsigned int meshfix__movemask_neon(uint32x4_t x)
{
    static const unsigned int bits[4] = {1, 2, 4, 8};
    uint32x4_t b = vandq_u32(x, vld1q_u32(bits));
    return vgetq_lane_u32(b, 0) | vgetq_lane_u32(b, 1) | vgetq_lane_u32(b, 2) | vgetq_lane_u32(b, 3);
}

MESHFIX__PRIVATE unsigned int meshfix__boxes_half_neon(const meshfix__ray *r, const meshfix__wide *n, int half,
                                                      float t_max, float *entry)
{
    float32x4_t t0 = vdupq_n_f32(r->t_min), t1 = vdupq_n_f32(t_max), widen = vdupq_n_f32(1.0000004f);
    int k;
    for (k = 0; k < 3; ++k) {
        float32x4_t origin = vdupq_n_f32(r->origin[k]), inverse = vdupq_n_f32(r->inverse[k]);
        float32x4_t tn = vmulq_f32(vsubq_f32(vld1q_f32(n->bounds[r->near_plane[k]] + half), origin), inverse);
        float32x4_t tf =
            vmulq_f32(vmulq_f32(vsubq_f32(vld1q_f32(n->bounds[r->far_plane[k]] + half), origin), inverse), widen);
        t0 = vmaxq_f32(tn, t0);
        t1 = vminq_f32(tf, t1);
    }
    vst1q_f32(entry, t0);
    return meshfix__movemask_neon(vcleq_f32(t0, t1));
}

MESHFIX__PRIVATE unsigned int meshfix__boxes_neon(const meshfix__ray *r, const meshfix__wide *n, float t_max,
                                                 float entry[MESHFIX__WIDE])
{
    return meshfix__boxes_half_neon(r, n, 0, t_max, entry) | meshfix__boxes_half_neon(r, n, 4, t_max, entry + 4) << 4;
}

MESHFIX__PRIVATE unsigned int meshfix__lanes_half_neon(const meshfix__ray *r, const meshfix__leaf_block *k, int half,
                                                      unsigned int want, float *t)
{
    float32x4_t p[3][3], *a = p[0], *b = p[1], *c = p[2], ax, ay, bx, by, cx, cy, u, v, w, det;
    float32x4_t zero = vdupq_n_f32(0.0f), sx = vdupq_n_f32(r->shear[0]), sy = vdupq_n_f32(r->shear[1]);
    uint32x4_t below, above;
    unsigned int mask, edge;
    int j, m;
    for (j = 0; j < 3; ++j)
        for (m = 0; m < 3; ++m)
            p[j][m] = vsubq_f32(vld1q_f32(k->corner[3 * j + m] + half), vdupq_n_f32(r->origin[m]));
    ax = vsubq_f32(a[r->kx], vmulq_f32(sx, a[r->kz]));
    ay = vsubq_f32(a[r->ky], vmulq_f32(sy, a[r->kz]));
    bx = vsubq_f32(b[r->kx], vmulq_f32(sx, b[r->kz]));
    by = vsubq_f32(b[r->ky], vmulq_f32(sy, b[r->kz]));
    cx = vsubq_f32(c[r->kx], vmulq_f32(sx, c[r->kz]));
    cy = vsubq_f32(c[r->ky], vmulq_f32(sy, c[r->kz]));
    u = vsubq_f32(vmulq_f32(cx, by), vmulq_f32(cy, bx));
    v = vsubq_f32(vmulq_f32(ax, cy), vmulq_f32(ay, cx));
    w = vsubq_f32(vmulq_f32(bx, ay), vmulq_f32(by, ax));
    edge = meshfix__movemask_neon(vorrq_u32(vorrq_u32(vceqq_f32(u, zero), vceqq_f32(v, zero)), vceqq_f32(w, zero))) &
           want;
    below = vorrq_u32(vorrq_u32(vcltq_f32(u, zero), vcltq_f32(v, zero)), vcltq_f32(w, zero));
    above = vorrq_u32(vorrq_u32(vcgtq_f32(u, zero), vcgtq_f32(v, zero)), vcgtq_f32(w, zero));
    mask = ~meshfix__movemask_neon(vandq_u32(below, above));
    det = vaddq_f32(vaddq_f32(u, v), w);
    mask &= ~meshfix__movemask_neon(vceqq_f32(det, zero)) & want & ~edge;
    if (mask != 0) {
        float32x4_t sz = vdupq_n_f32(r->shear[2]), dist;
        float32x4_t az = vmulq_f32(sz, a[r->kz]), bz = vmulq_f32(sz, b[r->kz]), cz = vmulq_f32(sz, c[r->kz]);
        float32x4_t distance = vaddq_f32(vaddq_f32(vmulq_f32(u, az), vmulq_f32(v, bz)), vmulq_f32(w, cz));
        /* a lane that fails is not divided by 0: its det is replaced */
        dist = vdivq_f32(distance, vbslq_f32(vceqq_f32(det, zero), vdupq_n_f32(1.0f), det));
        mask &= meshfix__movemask_neon(
            vandq_u32(vcgtq_f32(dist, vdupq_n_f32(r->t_min)), vcltq_f32(dist, vdupq_n_f32(r->t_max))));
        vst1q_f32(t, dist);
    }
    return mask | edge << 4;
}

#define meshfix__boxes_simd meshfix__boxes_neon
#define meshfix__lanes_half_simd meshfix__lanes_half_neon
#define MESHFIX__LANES_FUNCTION MESHFIX__PRIVATE
#endif

#if MESHFIX__SSE || MESHFIX__NEON
/* A block's eight lanes as two halves of four (SSE2 and NEON: the
   first path's test is inlined, as it was measured to want; NEON's is
   a call, as it has been). The lanes with an edge function exactly 0
   go to the scalar test. */
MESHFIX__LANES_FUNCTION unsigned int meshfix__lanes_simd(const meshfix__ray *r, const meshfix__leaf_block *k,
                                                         unsigned int want, float t[MESHFIX__WIDE],
                                                         int zeros[MESHFIX__WIDE])
{
    unsigned int mask = 0, edge = 0, low, high, i;
    if ((want & 15u) != 0) {
        low = meshfix__lanes_half_simd(r, k, 0, want & 15u, t);
        mask |= low & 15u, edge |= low >> 4;
    }
    if ((want >> 4) != 0) {
        high = meshfix__lanes_half_simd(r, k, 4, want >> 4, t + 4);
        mask |= (high & 15u) << 4, edge |= (high >> 4) << 4;
    }
    for (i = 0; i < MESHFIX__WIDE; ++i)
        zeros[i] = 0;
    return mask | (edge != 0 ? meshfix__edge_lanes(r, k, edge, t, zeros) : 0u);
}
#else
#define meshfix__boxes_simd meshfix__boxes_scalar
#define meshfix__lanes_simd meshfix__lanes_scalar
#endif

#if MESHFIX__AVX2
/* Inlined into the traversal as the other paths' tests are: a call per
   node and per block halved the closest-hit rate (measured). */
#define MESHFIX__AVX2_INLINE static __attribute__((target("avx2"), always_inline, unused)) __inline__

/* The eight lanes at once, where the CPU has AVX2 (meshfix__trace asks). */
MESHFIX__AVX2_INLINE unsigned int meshfix__boxes_avx2(const meshfix__ray *r, const meshfix__wide *n, float t_max,
                                                      float entry[MESHFIX__WIDE])
{
    __m256 t0 = _mm256_set1_ps(r->t_min), t1 = _mm256_set1_ps(t_max), widen = _mm256_set1_ps(1.0000004f);
    int k;
    for (k = 0; k < 3; ++k) {
        __m256 origin = _mm256_set1_ps(r->origin[k]), inverse = _mm256_set1_ps(r->inverse[k]);
        __m256 tn = _mm256_mul_ps(_mm256_sub_ps(_mm256_loadu_ps(n->bounds[r->near_plane[k]]), origin), inverse);
        __m256 tf = _mm256_mul_ps(
            _mm256_mul_ps(_mm256_sub_ps(_mm256_loadu_ps(n->bounds[r->far_plane[k]]), origin), inverse), widen);
        t0 = _mm256_max_ps(tn, t0);
        t1 = _mm256_min_ps(tf, t1);
    }
    _mm256_storeu_ps(entry, t0);
    return (unsigned int)_mm256_movemask_ps(_mm256_cmp_ps(t0, t1, _CMP_LE_OQ));
}

MESHFIX__AVX2_INLINE unsigned int meshfix__lanes_avx2(const meshfix__ray *r, const meshfix__leaf_block *k,
                                                      unsigned int want, float t[MESHFIX__WIDE],
                                                      int zeros[MESHFIX__WIDE])
{
    /* the rows in the ray's axis order, loaded by index: the same
       differences and products as through an array, none spilled */
    const float(*rows)[MESHFIX__WIDE] = k->corner;
    __m256 ox = _mm256_set1_ps(r->origin[r->kx]), oy = _mm256_set1_ps(r->origin[r->ky]);
    __m256 oz = _mm256_set1_ps(r->origin[r->kz]), az, bz, cz, ax, ay, bx, by, cx, cy, u, v, w, det;
    __m256 zero = _mm256_setzero_ps(), sx = _mm256_set1_ps(r->shear[0]), sy = _mm256_set1_ps(r->shear[1]);
    unsigned int mask, edge, i;
    az = _mm256_sub_ps(_mm256_loadu_ps(rows[r->kz]), oz);
    bz = _mm256_sub_ps(_mm256_loadu_ps(rows[3 + r->kz]), oz);
    cz = _mm256_sub_ps(_mm256_loadu_ps(rows[6 + r->kz]), oz);
    ax = _mm256_sub_ps(_mm256_sub_ps(_mm256_loadu_ps(rows[r->kx]), ox), _mm256_mul_ps(sx, az));
    ay = _mm256_sub_ps(_mm256_sub_ps(_mm256_loadu_ps(rows[r->ky]), oy), _mm256_mul_ps(sy, az));
    bx = _mm256_sub_ps(_mm256_sub_ps(_mm256_loadu_ps(rows[3 + r->kx]), ox), _mm256_mul_ps(sx, bz));
    by = _mm256_sub_ps(_mm256_sub_ps(_mm256_loadu_ps(rows[3 + r->ky]), oy), _mm256_mul_ps(sy, bz));
    cx = _mm256_sub_ps(_mm256_sub_ps(_mm256_loadu_ps(rows[6 + r->kx]), ox), _mm256_mul_ps(sx, cz));
    cy = _mm256_sub_ps(_mm256_sub_ps(_mm256_loadu_ps(rows[6 + r->ky]), oy), _mm256_mul_ps(sy, cz));
    u = _mm256_sub_ps(_mm256_mul_ps(cx, by), _mm256_mul_ps(cy, bx));
    v = _mm256_sub_ps(_mm256_mul_ps(ax, cy), _mm256_mul_ps(ay, cx));
    w = _mm256_sub_ps(_mm256_mul_ps(bx, ay), _mm256_mul_ps(by, ax));
    edge = (unsigned int)_mm256_movemask_ps(_mm256_or_ps(
               _mm256_or_ps(_mm256_cmp_ps(u, zero, _CMP_EQ_OQ), _mm256_cmp_ps(v, zero, _CMP_EQ_OQ)),
               _mm256_cmp_ps(w, zero, _CMP_EQ_OQ))) & want;
    /* a hit has no edge function below 0, or none above */
    mask = ~(unsigned int)_mm256_movemask_ps(_mm256_and_ps(
               _mm256_or_ps(_mm256_or_ps(_mm256_cmp_ps(u, zero, _CMP_LT_OQ), _mm256_cmp_ps(v, zero, _CMP_LT_OQ)),
                            _mm256_cmp_ps(w, zero, _CMP_LT_OQ)),
               _mm256_or_ps(_mm256_or_ps(_mm256_cmp_ps(u, zero, _CMP_GT_OQ), _mm256_cmp_ps(v, zero, _CMP_GT_OQ)),
                            _mm256_cmp_ps(w, zero, _CMP_GT_OQ))));
    det = _mm256_add_ps(_mm256_add_ps(u, v), w);
    mask &= ~(unsigned int)_mm256_movemask_ps(_mm256_cmp_ps(det, zero, _CMP_EQ_OQ)) & want & ~edge;
    if (mask != 0) {
        __m256 sz = _mm256_set1_ps(r->shear[2]), nonzero = _mm256_cmp_ps(det, zero, _CMP_NEQ_OQ), dist;
        __m256 distance = _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(u, _mm256_mul_ps(sz, az)),
                                                      _mm256_mul_ps(v, _mm256_mul_ps(sz, bz))),
                                        _mm256_mul_ps(w, _mm256_mul_ps(sz, cz)));
        /* a lane that fails is not divided by 0: its det is replaced */
        dist = _mm256_div_ps(distance, _mm256_blendv_ps(_mm256_set1_ps(1.0f), det, nonzero));
        mask &= (unsigned int)_mm256_movemask_ps(_mm256_and_ps(_mm256_cmp_ps(dist, _mm256_set1_ps(r->t_min), _CMP_GT_OQ),
                                                               _mm256_cmp_ps(dist, _mm256_set1_ps(r->t_max), _CMP_LT_OQ)));
        _mm256_storeu_ps(t, dist);
    }
    for (i = 0; i < MESHFIX__WIDE; ++i)
        zeros[i] = 0;
    return mask | (edge != 0 ? meshfix__edge_lanes(r, k, edge, t, zeros) : 0u);
}
#endif

/* The function types the traversal is instantiated with, once per path. */
typedef unsigned int (*meshfix__boxes_test)(const meshfix__ray *r, const meshfix__wide *n, float t_max,
                                            float entry[MESHFIX__WIDE]);
typedef unsigned int (*meshfix__lanes_test)(const meshfix__ray *r, const meshfix__leaf_block *k, unsigned int want,
                                            float t[MESHFIX__WIDE], int zeros[MESHFIX__WIDE]);

/* The hits `hit` of block k, in lane order: counted (COUNT_HITS) or kept
   when nearer than the best; returns 1 when an ANY_HIT query is
   answered. */
MESHFIX__INLINE_ALWAYS static int meshfix__take_hits(const meshfix__leaf_block *k, unsigned int hit,
                                                     const float t[MESHFIX__WIDE], const int zeros[MESHFIX__WIDE],
                                                     meshfix__query *q, float *best, meshfix__crossings *crossings)
{
    for (; hit != 0; hit &= hit - 1) {
        unsigned int i = meshfix__lowest_bit(hit), id = k->triangle[i];
        if (id == q->skip || t[i] >= *best)
            continue;
        if (q->mode == MESHFIX__COUNT_HITS) {
            meshfix__count_crossing(crossings, t[i], zeros[i]);
            continue;
        }
        q->t = t[i];
        q->hits = 1;
        if (q->mode == MESHFIX__ANY_HIT)
            return 1;
        *best = t[i];
    }
    return 0;
}

/* Lanes [offset, offset + count) of a window of eight blocks, as two
   words of four blocks' lanes each (C89 and C++98 have no 64-bit word);
   count is at most MESHFIX__LEAF, offset + count at most 64. */
MESHFIX__INLINE_ALWAYS static void meshfix__window_add(unsigned int window[2], unsigned int offset, unsigned int count)
{
    unsigned int mask = (1u << count) - 1u;
    if (offset >= 32u) {
        window[1] |= mask << (offset - 32u);
        return;
    }
    window[0] |= mask << offset;
    if (offset + count > 32u)
        window[1] |= mask >> (32u - offset);
}

/* The window of the leaves in `rest` from `block` on, as far as it
   reaches; returns the leaves past it. */
MESHFIX__INLINE_ALWAYS static unsigned int meshfix__leaf_window(const meshfix__wide *n, unsigned int rest,
                                                                unsigned int block, unsigned int window[2])
{
    unsigned int c, offset;
    window[0] = window[1] = 0;
    for (; rest != 0; rest &= rest - 1) {
        c = meshfix__lowest_bit(rest);
        offset = n->child[c] - MESHFIX__WIDE * block;
        if (offset > 64 - MESHFIX__LEAF)
            break;
        meshfix__window_add(window, offset, n->count[c]);
    }
    return rest;
}

/* The leaves `leaves` (a bit per child) of node n against the ray. The
   children lie in slot order, so the lanes of consecutive leaves are
   gathered into one test per block: the lanes of every leaf as bits of
   one window of eight blocks from the first leaf's block on, then a test
   per block with a lane set. A node whose leaves lie farther apart than
   the window (inner children's slots between them) takes a window more.
   Returns 1 when an ANY_HIT query is answered. */
MESHFIX__INLINE_ALWAYS static int meshfix__test_leaves(const meshfix__bvh *b, const meshfix__wide *n,
                                                       unsigned int leaves, const meshfix__ray *r, meshfix__query *q,
                                                       float *best, meshfix__crossings *crossings,
                                                       meshfix__lanes_test test)
{
    unsigned int block = n->child[meshfix__lowest_bit(leaves)] / MESHFIX__WIDE, hit, rest, window[2];
    float t[MESHFIX__WIDE];
    int zeros[MESHFIX__WIDE];
    rest = meshfix__leaf_window(n, leaves, block, window);
    for (;;) {
        for (; (window[0] | window[1]) != 0; ++block) {
            unsigned int want = window[0] & 0xFFu;
            window[0] = (window[0] >> 8) | (window[1] << 24);
            window[1] >>= 8;
            if (want == 0)
                continue;
            hit = test(r, &b->blocks[block], want, t, zeros);
            if (hit != 0 && meshfix__take_hits(&b->blocks[block], hit, t, zeros, q, best, crossings))
                return 1;
        }
        if (rest == 0)
            return 0;
        /* the leaves past the window: a window of their own */
        block = n->child[meshfix__lowest_bit(rest)] / MESHFIX__WIDE;
        rest = meshfix__leaf_window(n, rest, block, window);
    }
}

/* The child nodes `inner` (a bit each, at least two) that a ray enters,
   in order of their entry distance (ties: child order): the nearest is
   returned, the others wait on the stack, the farthest deepest. */
MESHFIX__INLINE_ALWAYS static unsigned int meshfix__nearest_child(const meshfix__wide *n,
                                                                  const float entry[MESHFIX__WIDE], unsigned int inner,
                                                                  unsigned int *stack, float *stack_t,
                                                                  unsigned int *depth)
{
    unsigned int next[MESHFIX__WIDE], count = 0, i, c;
    float near_t[MESHFIX__WIDE];
    for (; inner != 0; inner &= inner - 1) {
        c = meshfix__lowest_bit(inner);
        for (i = count++; i > 0 && near_t[i - 1] > entry[c]; --i) {
            near_t[i] = near_t[i - 1];
            next[i] = next[i - 1];
        }
        near_t[i] = entry[c];
        next[i] = c;
    }
    while (count > 1) {
        --count;
        stack_t[*depth] = near_t[count];
        stack[(*depth)++] = n->child[next[count]];
    }
    return n->child[next[0]];
}

/* The node to visit after n, whose child nodes `inner` the ray enters:
   for a CLOSEST_HIT query the nearest (the others on the stack with their
   entry distance), for the others the first in child order (the others
   on the stack, the next on top). */
MESHFIX__INLINE_ALWAYS static unsigned int meshfix__next_node(const meshfix__wide *n, unsigned int inner,
                                                              const float entry[MESHFIX__WIDE], int nearest_first,
                                                              float t_min, unsigned int *stack, float *stack_t,
                                                              unsigned int *depth)
{
    unsigned int first = meshfix__lowest_bit(inner), rest = inner & (inner - 1), second, c;
    if (rest == 0)
        return n->child[first];
    MESHFIX_ASSERT(*depth + MESHFIX__WIDE <= MESHFIX__BVH_STACK);
    if (!nearest_first) {
        /* the last first, so the next in child order is on top: by their
           bits (a test per child had the branch predictor guess each) */
        for (; rest != 0; rest &= ~(1u << c)) {
            c = meshfix__highest_bit(rest);
            stack_t[*depth] = t_min;
            stack[(*depth)++] = n->child[c];
        }
        return n->child[first];
    }
    if ((rest & (rest - 1)) != 0)
        return meshfix__nearest_child(n, entry, inner, stack, stack_t, depth);
    second = meshfix__lowest_bit(rest);
    if (entry[second] < entry[first])
        c = first, first = second, second = c;
    stack_t[*depth] = entry[second];
    stack[(*depth)++] = n->child[second];
    return n->child[first];
}

/* Traces r through the tree below node `root` (a unit's tree, or the top
   tree) with the node and block tests of one SIMD path. Leaves are tested
   as their node is visited. Of the child nodes the ray enters, a
   CLOSEST_HIT query visits the nearest next and leaves the others on the
   stack with their entry distance, so that it drops those beyond its best
   hit unread; the other queries must see every hit (COUNT_HITS) or any
   (ANY_HIT), and go in child order. Returns 1 when it hit something
   (COUNT_HITS: crossed a surface). */
MESHFIX__INLINE_ALWAYS static int meshfix__traverse(const meshfix__bvh *b, unsigned int root, const meshfix__ray *r,
                                                    meshfix__query *q, meshfix__boxes_test boxes,
                                                    meshfix__lanes_test lanes)
{
    unsigned int stack[MESHFIX__BVH_STACK], depth = 0, work = 0, node = root;
    float stack_t[MESHFIX__BVH_STACK], best = r->t_max;
    int nearest_first = q->mode == MESHFIX__CLOSEST_HIT;
    meshfix__crossings crossings;
    crossings.halves = crossings.vertex_count = 0;
    q->hits = 0;
    while (node != MESHFIX__NONE) {
        const meshfix__wide *n = &b->nodes[node];
        float entry[MESHFIX__WIDE];
        unsigned int mask;
        if (++work > MESHFIX__RAY_WORK) {
            if (q->mode == MESHFIX__ANY_HIT)
                q->hits = 1;
            break;
        }
        mask = boxes(r, n, best, entry);
        if ((mask & n->leaves) != 0 && meshfix__test_leaves(b, n, mask & n->leaves, r, q, &best, &crossings, lanes))
            return 1;
        if ((mask & n->inner) != 0) {
            node = meshfix__next_node(n, mask & n->inner, entry, nearest_first, r->t_min, stack, stack_t, &depth);
            continue;
        }
        /* a node the best hit has moved in front of holds nothing nearer */
        for (node = MESHFIX__NONE; depth > 0 && node == MESHFIX__NONE;)
            if (!(stack_t[--depth] > best))
                node = stack[depth];
    }
    if (q->mode == MESHFIX__COUNT_HITS)
        q->hits = (crossings.halves + 1) / 2;
    return q->hits != 0;
}

MESHFIX__PRIVATE int meshfix__trace_simd(const meshfix__bvh *b, unsigned int root, const meshfix__ray *r,
                                        meshfix__query *q)
{
    return meshfix__traverse(b, root, r, q, meshfix__boxes_simd, meshfix__lanes_simd);
}

#if MESHFIX__AVX2
MESHFIX__AVX2_FUNCTION int meshfix__trace_avx2(const meshfix__bvh *b, unsigned int root, const meshfix__ray *r,
                                              meshfix__query *q)
{
    return meshfix__traverse(b, root, r, q, meshfix__boxes_avx2, meshfix__lanes_avx2);
}
#endif

/* Traces r through the tree below node `root`, eight lanes at once where
   the CPU has AVX2 (asked on each call: no state is kept), else with the
   compiler's SIMD path; the same steps and answers either way. Returns 1
   when it hit something (COUNT_HITS: crossed a surface). */
MESHFIX__PRIVATE int meshfix__trace(const meshfix__bvh *b, unsigned int root, const meshfix__ray *r, meshfix__query *q)
{
#if MESHFIX__AVX2
    if (__builtin_cpu_supports("avx2"))
        return meshfix__trace_avx2(b, root, r, q);
#endif
    return meshfix__trace_simd(b, root, r, q);
}

MESHFIX__PRIVATE int meshfix__box_overlaps(const float a[6], const float b[6])
{
    int k;
    for (k = 0; k < 3; ++k)
        if (!(a[k] <= b[3 + k] && b[k] <= a[3 + k]))
            return 0;
    return 1;
}

/* The ids whose box contains `box` (or, with `overlapping`, meets it),
   from a tree over boxes built with leaf size 1: a walk that enters only
   children that do. Returns how many were written to out (at most
   `capacity`; the rest are dropped). */
MESHFIX__PRIVATE unsigned int meshfix__boxes_around(const meshfix__node *nodes, unsigned int root,
                                                   const unsigned int *ids, const float box[6], int overlapping,
                                                   unsigned int *out, unsigned int capacity)
{
    unsigned int stack[MESHFIX__BVH_STACK], depth = 0, found = 0;
    int c, k;
    if (root == MESHFIX__NONE)
        return 0;
    stack[depth++] = root;
    while (depth > 0) {
        const meshfix__node *n = &nodes[stack[--depth]];
        for (c = 0; c < MESHFIX__WIDTH; ++c) {
            float child[6];
            if (n->count[c] == MESHFIX__EMPTY)
                continue;
            for (k = 0; k < 3; ++k)
                child[k] = n->bounds[k][c], child[3 + k] = n->bounds[3 + k][c];
            if (!(overlapping ? meshfix__box_overlaps(child, box) : meshfix__box_contains(child, box)))
                continue;
            if (n->count[c] == 0)
                stack[depth++] = n->child[c];
            else if (found < capacity)
                out[found++] = ids[n->child[c]];
        }
    }
    return found;
}

/* ===== >>units ===== */

/* The geometric policies decide units: a patch, or a super-patch of
   patches that boundary coherence joined (the merge below). A unit has
   its own frame, its root patch's; each member patch is turned relative
   to it. Everything known about a unit when its side is decided: */
#define MESHFIX__OPEN 0
#define MESHFIX__GAPPED 1        /* most of its boundary is matched inside the unit: maybe closed up to gaps */
#define MESHFIX__GAPPED_UNMATCHED 0.2 /* GAPPED: less than this share of its boundary without a partner in it */
#define MESHFIX__NEARLY_CLOSED 2 /* gapped, and its own crossings say it has an inside and an outside */
#define MESHFIX__CLOSED 3        /* every edge is matched inside the unit */

/* The kinds of evidence are the public meshfix_evidence, in the order
   they are asked (report counts). */

typedef struct meshfix__unit {
    double kept, reversed;     /* area (count without positions) facing the frame's way as given, and against */
    double prior_kept, prior_reversed; /* the same, each patch weighing the square root of its area (meshfix__add_prior) */
    double normals;            /* the caller's normals: sum of area * (+1 along, -1 against the frame) */
    double normals_area;       /* area of triangles with a usable normal */
    double area, volume;       /* volume in the frame, about the unit's first vertex */
    double boundary;           /* length of its edges that are not manifold inside a patch */
    double unmatched;          /* the part of it with no partner in the unit */
    double origin[3];          /* volumes are taken about it: a vertex of the unit */
    unsigned char has_origin;
    float box[6];              /* in the frame */
    unsigned char closed;      /* MESHFIX__CLOSED, MESHFIX__NEARLY_CLOSED, MESHFIX__GAPPED, MESHFIX__OPEN */
    unsigned char cavity;
    signed char outward;       /* closed or nearly closed: +1 when its frame faces out of its own surface */
    unsigned char reversed_prior; /* a unit of a reversed scene: its majority is likely wrong */
    unsigned char kind;        /* a meshfix_evidence: what gave `mean` */
    double mean, error, weight; /* geometric vote for the frame's side in [-1, 1], its standard error, its weight */
    unsigned int turn;         /* the verdict: 1 turns the unit over, relative to its frame */
    float margin;              /* the weighing's bound on the side decided, 0 .. 1 */
    float confidence;          /* reported: AUTO's calibrated probability (meshfix__calibrate), else the margin */
    size_t rays;               /* cast for its evidence (report.evidence.rays_cast) */
} meshfix__unit;

typedef struct meshfix__geometry {
    meshfix__mesh *m;
    const meshfix_options *o;
    meshfix__arena arena;
    meshfix__bvh bvh;
    unsigned int seed;
    float t_min;
    double sigma;               /* the significance rule: z of the confidence bounds */
    size_t ray_budget;          /* meshfix__ray_budget */
    double length_unit;         /* a length in the frame, relative to the longest side: times this is raw */
    unsigned int unit_count;
    unsigned int *patch_unit;   /* per patch */
    unsigned char *patch_turn;  /* per patch: its frame relative to its unit's */
    unsigned int *triangle_unit; /* per triangle: its unit, NONE when it has no area */
    unsigned int *patch_first;  /* per patch: its first slot in by_index (a unit's slots lie patch by patch) */
    unsigned int *patch_end;    /* per patch: after its last slot */
    meshfix__unit *units;
    float *unit_slots;          /* scratch for trees over units: 9 floats per unit */
    unsigned int *unit_ids;
    meshfix__node *shell_nodes; /* a tree over the boxes of closed and nearly closed units */
    unsigned int *shell_ids;
    unsigned int shell_root;
    unsigned int reversed_scene; /* the closed parts were all inside out: so was the file */
} meshfix__geometry;

/* Normal of t in its patch's consistent frame (its relative bit applied),
   twice its area long; *area is 0 without geometry. */
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
    const unsigned int *v = m->indices + 3 * (size_t)t;
    if (!meshfix__has_geometry(m, t))
        return 0;
    if (m->areas_marked)
        return !(m->tri_bits[t] & MESHFIX__TRI_NO_AREA);
    return meshfix__spans_area(meshfix__position(m, v[0]), meshfix__position(m, v[1]), meshfix__position(m, v[2]));
}

/* Asked once for every triangle by the geometric stages, which ask
   whether a triangle has an area again and again. */
MESHFIX__PRIVATE void meshfix__mark_areas(meshfix__mesh *m)
{
    unsigned int t;
    for (t = 0; t < m->triangle_count; ++t)
        if (!meshfix__has_area(m, t))
            m->tri_bits[t] = (unsigned short)(m->tri_bits[t] | MESHFIX__TRI_NO_AREA);
    m->areas_marked = 1;
}

/* The frame of triangle t relative to its unit's: 1 when reversed. */
MESHFIX__PRIVATE unsigned int meshfix__unit_relative(const meshfix__geometry *g, unsigned int t)
{
    const meshfix__mesh *m = g->m;
    return (unsigned int)((m->tri_bits[t] & MESHFIX__TRI_RELATIVE) != 0) ^ g->patch_turn[m->tri_patch[t]];
}

/* ===== >>sampling ===== */

/* Rays from random points of a unit, in random directions. Every sample
   has its own random stream (seed, unit, kind, index), units are measured
   independently and votes summed in sample order, so results are
   bit-identical run to run and with or without the caller's parallel_for. */

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

MESHFIX__PRIVATE unsigned int meshfix__stream(const meshfix__geometry *g, unsigned int unit, unsigned int kind,
                                              unsigned int index)
{
    return meshfix__mix(g->seed ^ meshfix__mix(unit * 0x9E3779B1u ^ meshfix__mix(index * 8u + kind + 0x632BE5ABu)));
}

/* Areas of each unit's slots, cumulated, for drawing points by area. */
MESHFIX__PRIVATE void meshfix__area_chunk(void *stage, size_t chunk)
{
    const meshfix__stage *s = (const meshfix__stage *)stage;
    const meshfix__geometry *g = (const meshfix__geometry *)s->context;
    size_t i, end;
    double n[3];
    for (meshfix__chunk_range(s, chunk, &i, &end); i < end; ++i)
        meshfix__relative_normal(g->m, g->bvh.by_index[i], n, &g->bvh.cumulative_area[i]);
}

/* Each slot's area by chunks of slots (each written alone), then each
   unit's running sum of them in slot order: the sums of one pass. */
MESHFIX__PRIVATE void meshfix__cumulate_areas(meshfix__geometry *g)
{
    meshfix__bvh *b = &g->bvh;
    unsigned int u, i;
    meshfix__run_stage(g->o, meshfix__area_chunk, g, b->unit_first[b->unit_count], NULL);
    for (u = 0; u < b->unit_count; ++u) {
        double sum = 0;
        for (i = b->unit_first[u]; i < b->unit_first[u + 1]; ++i) {
            sum += b->cumulative_area[i];
            b->cumulative_area[i] = sum;
        }
    }
}

/* A random point of slots [first, end) of one unit (from `unit_first`),
   drawn by area: the triangle it lies on, and that triangle's normal in
   its patch's consistent frame. */
MESHFIX__PRIVATE unsigned int meshfix__sample_slots(const meshfix__geometry *g, unsigned int unit_first, unsigned int first,
                                                   unsigned int end, unsigned int *state, float point[3], double normal[3])
{
    const meshfix__bvh *b = &g->bvh;
    unsigned int lo = first, hi = end - 1, t;
    double below = first > unit_first ? b->cumulative_area[first - 1] : 0.0, area;
    double target = below + (double)meshfix__random(state) * (b->cumulative_area[hi] - below);
    float s = meshfix__random(state), v = meshfix__random(state), su, corners[9];
    int k;
    while (lo < hi) {
        unsigned int mid = lo + (hi - lo) / 2;
        if (b->cumulative_area[mid] <= target)
            lo = mid + 1;
        else
            hi = mid;
    }
    t = b->by_index[lo];
    /* corners by vertex id: the point must not move when t is flipped */
    meshfix__load_corners(b, g->m, t, corners);
    su = (float)MESHFIX_SQRT((double)s);
    for (k = 0; k < 3; ++k)
        point[k] = (1.0f - su) * corners[k] + su * (1.0f - v) * corners[3 + k] + su * v * corners[6 + k];
    meshfix__relative_normal(g->m, t, normal, &area);
    return t;
}

/* A random point of unit u, drawn by area, the triangle it lies on, and
   that triangle's normal in the unit's frame. */
MESHFIX__PRIVATE unsigned int meshfix__sample_point(const meshfix__geometry *g, unsigned int u, unsigned int *state,
                                                   float point[3], double normal[3])
{
    const meshfix__bvh *b = &g->bvh;
    unsigned int t = meshfix__sample_slots(g, b->unit_first[u], b->unit_first[u], b->unit_first[u + 1], state, point,
                                           normal);
    int k;
    if (g->patch_turn[g->m->tri_patch[t]]) {
        for (k = 0; k < 3; ++k)
            normal[k] = -normal[k];
    }
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

/* Votes of a measurement: +1 for the unit's frame, -1 against it, 0 for
   none. The significance rule: the mean vote m = (plus - minus) / n has
   the standard error sqrt(s^2 / n), s^2 its sample variance (at least
   1 / n, so that a few unanimous votes are not taken as certain); a
   vote counts as evidence within m +- sigma * error. */
typedef struct meshfix__votes {
    unsigned int n, plus, minus;
} meshfix__votes;

/* Samples are drawn a batch at a time, the verdict looked at between;
   units (and patches) are measured this many to a task of parallel_for. */
#define MESHFIX__BATCH 16
#define MESHFIX__UNITS_PER_TASK 64

MESHFIX__PRIVATE double meshfix__vote_mean(const meshfix__votes *v)
{
    return v->n ? ((double)v->plus - (double)v->minus) / (double)v->n : 0.0;
}

MESHFIX__PRIVATE double meshfix__vote_error(const meshfix__votes *v)
{
    double n = (double)v->n, m = meshfix__vote_mean(v), s2;
    if (v->n == 0)
        return 1.0;
    s2 = ((double)v->plus + (double)v->minus) / n - m * m;
    s2 = s2 > 1.0 / n ? s2 : 1.0 / n;
    return MESHFIX_SQRT(s2 / n);
}

MESHFIX__PRIVATE void meshfix__add_vote(meshfix__votes *v, int vote)
{
    v->n++;
    v->plus += (unsigned int)(vote > 0);
    v->minus += (unsigned int)(vote < 0);
}

/* Every measurement samples the same way: votes a batch at a time, up to
   `cap`, until `settled` says the votes so far answer what is asked. The
   measurements differ only in their vote and their rule. */
typedef int (*meshfix__vote_fn)(void *context, unsigned int index);
typedef int (*meshfix__settled_fn)(void *context, const meshfix__votes *votes);

MESHFIX__PRIVATE void meshfix__sample_until_settled(meshfix__votes *votes, unsigned int cap, meshfix__vote_fn vote,
                                                   meshfix__settled_fn settled, void *context)
{
    unsigned int i;
    MESHFIX_MEMSET(votes, 0, sizeof(*votes));
    for (i = 0; i < cap; ++i) {
        meshfix__add_vote(votes, vote(context, i));
        if ((i + 1) % MESHFIX__BATCH == 0 && settled(context, votes))
            break;
    }
}

/* The bounds of the size of the mean vote: |mean| -+ sigma * error. */
MESHFIX__PRIVATE void meshfix__size_bounds(const meshfix__votes *votes, double sigma, double *low, double *high)
{
    double mean = MESHFIX_FABS(meshfix__vote_mean(votes)), error = meshfix__vote_error(votes);
    *low = mean - sigma * error;
    *high = mean + sigma * error;
}

MESHFIX__PRIVATE int meshfix__level_reached(const meshfix__votes *votes, double sigma, double level)
{
    double low, high;
    meshfix__size_bounds(votes, sigma, &low, &high);
    return low >= level;
}

/* Whether the size of the mean vote is known to be at least `level` or
   known to be less (within its bounds): either way, more votes would not
   change which. */
MESHFIX__PRIVATE int meshfix__level_known(const meshfix__votes *votes, double sigma, double level)
{
    double low, high;
    meshfix__size_bounds(votes, sigma, &low, &high);
    return low >= level || high < level;
}

/* A side is inside when its ray crosses the surfaces asked about an odd
   number of times (or, for escape, hits anything). The pair votes for the
   frame when its front side is outside and its back side inside. */
MESHFIX__PRIVATE int meshfix__side_vote(int front_inside, int back_inside)
{
    return front_inside == back_inside ? 0 : back_inside ? 1 : -1;
}

/* Crossings of a ray with the trees of the units in `list`. */
MESHFIX__PRIVATE unsigned int meshfix__crossings_of(const meshfix__geometry *g, const meshfix__ray *ray,
                                                   const unsigned int *list, unsigned int count, unsigned int skip)
{
    unsigned int i, hits = 0;
    meshfix__query q;
    q.mode = MESHFIX__COUNT_HITS;
    q.skip = skip;
    for (i = 0; i < count; ++i) {
        meshfix__trace(&g->bvh, g->bvh.unit_root[list[i]], ray, &q);
        hits += q.hits;
    }
    return hits;
}

/* One sample of unit u: a point, a direction d, and a ray each way. Kind
   PARITY counts crossings of `list` (the unit itself, or the shells that
   may enclose it); ESCAPE asks whether anything at all blocks the ray. */
MESHFIX__PRIVATE int meshfix__sample_sides(const meshfix__geometry *g, unsigned int u, unsigned int kind,
                                          unsigned int index, const unsigned int *list, unsigned int count)
{
    unsigned int state = meshfix__stream(g, u, kind, index), t, side;
    float point[3], d[3], back[3];
    double n[3];
    int inside[2];
    meshfix__ray ray;
    meshfix__query q;
    t = meshfix__sample_point(g, u, &state, point, n);
    meshfix__random_direction(&state, d);
    back[0] = -d[0], back[1] = -d[1], back[2] = -d[2];
    for (side = 0; side < 2; ++side) {
        meshfix__setup_ray(&ray, point, side ? back : d, g->t_min, 1e30f);
        if (kind == MESHFIX_EVIDENCE_VISIBILITY) {
            q.mode = MESHFIX__ANY_HIT;
            q.skip = t;
            inside[side] = meshfix__trace(&g->bvh, g->bvh.top, &ray, &q);
        } else {
            inside[side] = (int)(meshfix__crossings_of(g, &ray, list, count, t) & 1u);
        }
    }
    /* inside[0] is the side d points to */
    if (n[0] * (double)d[0] + n[1] * (double)d[1] + n[2] * (double)d[2] >= 0)
        return meshfix__side_vote(inside[0], inside[1]);
    return meshfix__side_vote(inside[1], inside[0]);
}

/* Nesting: +1 when a ray from u crosses the enclosing candidates an odd
   number of times (u lies inside them), -1 when even. */
MESHFIX__PRIVATE int meshfix__sample_nesting(const meshfix__geometry *g, unsigned int u, unsigned int index,
                                            const unsigned int *list, unsigned int count)
{
    unsigned int state = meshfix__stream(g, u, 7, index);
    float point[3], d[3];
    double n[3];
    meshfix__ray ray;
    meshfix__sample_point(g, u, &state, point, n);
    meshfix__random_direction(&state, d);
    meshfix__setup_ray(&ray, point, d, g->t_min, 1e30f);
    return (meshfix__crossings_of(g, &ray, list, count, MESHFIX__NONE) & 1u) ? 1 : -1;
}

/* ===== >>coherence ===== */

/* Borodin et al.: boundary edges of different patches that run alongside
   each other say how the patches are wound relative to each other. Each
   boundary edge finds the edge of another patch that runs closest along
   it (a hash grid of cells at least the search distance wide); two
   edges give the local coherence -sgn(s) sqrt(|s|) / (1 + d), s the dot
   product of the edges as their patches' frames run them, d their
   distance, lengths relative to the longest side of the box. At an edge
   of three or more triangles, each triangle pairs with the ones beside it
   in the order they lie around the edge. Coherences are summed per pair
   of patches. Two sheets stacked on each other (their triangles on the
   same side of the edges) whose edges run the same way are two surfaces
   facing the same way, not one surface wound against itself: such a pair
   says nothing. */

typedef struct meshfix__pair {
    unsigned int a, b;     /* patches, a < b */
    unsigned int low, high; /* the vertices of the edge that gave it: a canonical order for sums */
    double c, length;      /* coherence, and the most it could be (c / length in [-1, 1]) */
    double from_a, from_b; /* the length of a's edges that found their partner in b, and of b's in a */
    unsigned char ring;    /* every edge of it is an edge of 3+ triangles: neighbours around it, no seam */
} meshfix__pair;

typedef struct meshfix__segment {
    double p[3], q[3];     /* its lower and higher vertex, in the frame, over the longest side */
    double inward[3];      /* toward its triangle's third corner, across the edge, unit length */
    double sign;           /* +1 when the patch's frame runs it from p to q */
    double length;
    unsigned int patch;
    unsigned int low, high; /* its vertices: ties break on these, not on winding or order */
    unsigned int partner;  /* the segment of another patch closest alongside, NONE */
    double distance;       /* to it */
    unsigned char matched; /* its partner gave a pair */
} meshfix__segment;

MESHFIX__PRIVATE double meshfix__dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

MESHFIX__PRIVATE void meshfix__edge_segment(const meshfix__geometry *g, unsigned int h, double scale,
                                           meshfix__segment *s)
{
    const meshfix__mesh *m = g->m;
    unsigned int t = h / 3, next = h % 3 == 2 ? h - 2 : h + 1;
    int reverse = (m->tri_bits[t] & MESHFIX__TRI_RELATIVE) != 0, k;
    double apex[3], along[3], len2, proj, across;
    /* geometry by vertex id, winding as a sign: distances and their
       rounding must not depend on which way the input ran the edge */
    s->low = m->indices[h] < m->indices[next] ? m->indices[h] : m->indices[next];
    s->high = m->indices[h] < m->indices[next] ? m->indices[next] : m->indices[h];
    s->sign = ((m->indices[h] < m->indices[next]) != reverse) ? 1.0 : -1.0;
    meshfix__frame_point(&g->bvh, meshfix__position(m, s->low), s->p);
    meshfix__frame_point(&g->bvh, meshfix__position(m, s->high), s->q);
    meshfix__frame_point(&g->bvh, meshfix__position(m, meshfix__apex(m, h)), apex);
    for (k = 0; k < 3; ++k) {
        s->p[k] *= scale;
        s->q[k] *= scale;
        apex[k] = apex[k] * scale - s->p[k];
        along[k] = s->q[k] - s->p[k];
    }
    len2 = meshfix__dot3(along, along);
    s->length = MESHFIX_SQRT(len2);
    proj = len2 > 0 ? meshfix__dot3(apex, along) / len2 : 0.0;
    for (k = 0; k < 3; ++k)
        s->inward[k] = apex[k] - proj * along[k];
    across = MESHFIX_SQRT(meshfix__dot3(s->inward, s->inward));
    for (k = 0; k < 3; ++k)
        s->inward[k] = across > 0 ? s->inward[k] / across : 0.0;
    s->patch = m->tri_patch[t];
    s->partner = MESHFIX__NONE;
    s->matched = 0;
}

MESHFIX__PRIVATE int meshfix__segment_before(const meshfix__segment *x, const meshfix__segment *y)
{
    return x->low < y->low || (x->low == y->low && (x->high < y->high || (x->high == y->high && x->patch < y->patch)));
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
   just as closely; this measure picks the edge that runs alongside. Where
   it surely exceeds `limit`, something above `limit` is returned sooner. */
MESHFIX__PRIVATE double meshfix__segment_distance(const meshfix__segment *e, const meshfix__segment *f, double limit)
{
    double mid[3], middle_distance;
    int k;
    for (k = 0; k < 3; ++k)
        mid[k] = 0.5 * (e->p[k] + e->q[k]);
    /* the distance to a segment is convex: the ends' mean is at least the
       middle's, and so is the measure (the margin covers rounding) */
    middle_distance = meshfix__point_segment_distance(mid, f);
    if (middle_distance > limit + 1e-12 * (1.0 + limit))
        return middle_distance;
    return (meshfix__point_segment_distance(e->p, f) + meshfix__point_segment_distance(e->q, f) + middle_distance) /
           3.0;
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

/* Stacked sheets: their triangles lie on the same side of the edges (they
   fold back onto each other: their directions across the edges within
   60 degrees). Two surfaces, not one: whichever way each is wound, the
   pair says nothing about it. */
#define MESHFIX__STACKED_COSINE 0.5
MESHFIX__PRIVATE int meshfix__stacked(const meshfix__segment *e, const meshfix__segment *f)
{
    return meshfix__dot3(e->inward, f->inward) > MESHFIX__STACKED_COSINE;
}

/* A pair of patches from two edges: their coherence, and the most it
   could be, sqrt(|e| |f|) (parallel edges at distance 0), so that the
   summed c / length of a pair of patches lies in [-1, 1]. */
MESHFIX__PRIVATE void meshfix__add_pair(meshfix__pair *pairs, size_t *count, const meshfix__segment *from,
                                        const meshfix__segment *to, double c)
{
    meshfix__pair *p = &pairs[(*count)++];
    p->a = from->patch < to->patch ? from->patch : to->patch;
    p->b = from->patch < to->patch ? to->patch : from->patch;
    p->low = from->low;
    p->high = from->high;
    p->c = c;
    p->length = MESHFIX_SQRT(from->length * to->length);
    p->from_a = from->patch == p->a ? from->length : 0.0;
    p->from_b = from->patch == p->a ? 0.0 : from->length;
    p->ring = 0;
}

/* Two patches that meet at a ring no winding can make consistent (a fin
   on a surface, a fold) have no relative winding to learn from their
   other edges either: their pair is marked (length -1) and its sum stays
   marked, so neither merge joins them. */
MESHFIX__PRIVATE void meshfix__add_veto(meshfix__pair *pairs, size_t *count, const meshfix__segment *from,
                                       const meshfix__segment *to)
{
    meshfix__add_pair(pairs, count, from, to, 0.0);
    pairs[*count - 1].length = -1.0;
}

#define MESHFIX__NEAREST_CANDIDATES 128

/* A segment in a cell: what a search needs to pass over it without
   reading the segment (most candidates are of the searcher's own patch,
   or too far). */
typedef struct meshfix__cell_item {
    float middle[3], half;  /* its middle and half its length */
    unsigned int segment, patch;
} meshfix__cell_item;

typedef struct meshfix__grid {
    double cell;
    size_t mask;
    unsigned int *start;       /* per bucket + 1 */
    meshfix__cell_item *items; /* bucket by bucket */
    unsigned char *occupied;   /* a bit per bucket: most cells a search walks are empty, and this is
                                  read from cache where `start` is not */
} meshfix__grid;

MESHFIX__PRIVATE int meshfix__bucket_occupied(const meshfix__grid *grid, size_t bucket)
{
    return (grid->occupied[bucket >> 3] >> (bucket & 7)) & 1;
}

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
   move. An edge that spans many cells does not search the grid: the
   long edges search a grid of their own (meshfix__too_long_for). */
MESHFIX__PRIVATE int meshfix__cells_usable(const double lo[3], const double hi[3])
{
    int k;
    for (k = 0; k < 3; ++k)
        if (!(lo[k] > -1e12 && hi[k] < 1e12 && hi[k] - lo[k] <= 16.0))
            return 0;
    return 1;
}

/* Whether segment s spans too many cells of width `cell` (within reach)
   to search that grid: such segments (the long edges of a box cut beside
   a finely meshed part) get a grid of their own, a second pass with
   cells as wide as they are long. cell 0: none is. */
/* How far a segment looks for its partner: coherence_distance, or a
   twentieth of its own length when that is more. A gap is small or large
   next to the edges it separates: a CAD face three units wide whose seams
   opened by a tenth is still one surface, though a tenth is more than the
   scene's reach (a box around a fine hollow, cut so: its faces found no
   partners, it counted as open, and the hollow inside it was turned out). */
#define MESHFIX__REACH_PER_LENGTH 0.05
MESHFIX__PRIVATE double meshfix__segment_reach(const meshfix__segment *s, double reach)
{
    return meshfix__maxd(reach, MESHFIX__REACH_PER_LENGTH * s->length);
}

MESHFIX__PRIVATE int meshfix__too_long_for(double cell, const meshfix__segment *s, double reach)
{
    meshfix__grid grid;
    double lo[3], hi[3];
    if (cell == 0)
        return 1;
    grid.cell = cell;
    meshfix__segment_cells(&grid, s, meshfix__segment_reach(s, reach), lo, hi);
    return !meshfix__cells_usable(lo, hi);
}

/* The cell of a point; 0 when it is too far out to walk to. */
MESHFIX__PRIVATE int meshfix__point_cell(const meshfix__grid *grid, const double x[3], double cell[3])
{
    int k;
    for (k = 0; k < 3; ++k) {
        cell[k] = MESHFIX_FLOOR(x[k] / grid->cell);
        if (!(cell[k] > -1e12 && cell[k] < 1e12))
            return 0;
    }
    return 1;
}

/* The buckets segment s enters, for the cells of its two ends and middle
   (at most three entries a segment, however long it is: the search looks
   for segments running alongside, and those have a point near each of
   these), in that order; returns how many. `beyond` != 0: only a segment
   too long for cells that wide enters. */
MESHFIX__PRIVATE int meshfix__segment_buckets(const meshfix__grid *grid, const meshfix__segment *s, double beyond,
                                             double reach, size_t bucket[3])
{
    double points[3][3], cells[3][3];
    int j, k, n = 0;
    if (beyond != 0 && !meshfix__too_long_for(beyond, s, reach))
        return 0;
    for (k = 0; k < 3; ++k) {
        points[0][k] = s->p[k];
        points[1][k] = 0.5 * (s->p[k] + s->q[k]);
        points[2][k] = s->q[k];
    }
    for (j = 0; j < 3; ++j) {
        if (!meshfix__point_cell(grid, points[j], cells[j]) ||
            (j > 0 && meshfix__compare_cells(cells[j], cells[j - 1]) == 0) ||
            (j > 1 && meshfix__compare_cells(cells[j], cells[0]) == 0))
            continue;
        bucket[n++] = meshfix__grid_bucket(grid, cells[j][0], cells[j][1], cells[j][2]);
    }
    return n;
}

/* Segment i as an entry of a cell. */
MESHFIX__PRIVATE void meshfix__cell_item_of(const meshfix__segment *segments, unsigned int i, meshfix__cell_item *item)
{
    int k;
    for (k = 0; k < 3; ++k) {
        double middle = 0.5 * (segments[i].p[k] + segments[i].q[k]); /* a double first, as the search's middle */
        item->middle[k] = (float)middle;
    }
    item->half = (float)(0.5 * segments[i].length);
    item->segment = i;
    item->patch = segments[i].patch;
}

/* Fills the grid: a counting sort of (bucket, segment), segment by
   segment, each's entries in the order of meshfix__segment_buckets. Pass
   0 counts, pass 1 places. */
MESHFIX__PRIVATE void meshfix__grid_pass(meshfix__grid *grid, const meshfix__segment *segments, unsigned int count,
                                        double beyond, double reach, int place)
{
    unsigned int i;
    int j, n;
    size_t bucket[3];
    for (i = 0; i < count; ++i) {
        n = meshfix__segment_buckets(grid, &segments[i], beyond, reach, bucket);
        for (j = 0; j < n; ++j) {
            if (place)
                meshfix__cell_item_of(segments, i, &grid->items[grid->start[bucket[j]]++]);
            else
                grid->start[bucket[j] + 1]++;
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

/* A stable sort of pairs over the chunks of meshfix__stage_chunks: each
   chunk sorted alone, then neighbouring runs merged, a round at a time
   (a run's pairs before the next's at a tie). A stable sort by a strict
   order has one result: the pairs end as the one-pass sort leaves them. */
typedef struct meshfix__pair_sorter {
    meshfix__pair *pairs, *tmp, *from, *to;
    size_t n, chunks, width; /* merging: runs of `width` chunks, two a task */
    int (*before)(const meshfix__pair *, const meshfix__pair *);
    int into_tmp;            /* sorting: each chunk ends in tmp, not pairs */
} meshfix__pair_sorter;

MESHFIX__PRIVATE void meshfix__pair_sort_task(void *context, size_t index)
{
    meshfix__pair_sorter *k = (meshfix__pair_sorter *)context;
    if (k->width == 0) {
        size_t lo = meshfix__chunk_start(k->n, index, k->chunks), hi = meshfix__chunk_start(k->n, index + 1, k->chunks);
        meshfix__sort_pairs(k->pairs + lo, k->tmp + lo, hi - lo, k->before);
        if (k->into_tmp)
            MESHFIX_MEMCPY(k->tmp + lo, k->pairs + lo, (hi - lo) * sizeof(meshfix__pair));
    } else {
        size_t first = 2 * index * k->width, middle = first + k->width, last = middle + k->width;
        size_t lo = meshfix__chunk_start(k->n, first, k->chunks);
        size_t mid = meshfix__chunk_start(k->n, middle < k->chunks ? middle : k->chunks, k->chunks);
        size_t hi = meshfix__chunk_start(k->n, last < k->chunks ? last : k->chunks, k->chunks);
        size_t a = lo, b = mid, at = lo;
        while (a < mid && b < hi)
            k->to[at++] = k->before(&k->from[b], &k->from[a]) ? k->from[b++] : k->from[a++];
        while (a < mid)
            k->to[at++] = k->from[a++];
        while (b < hi)
            k->to[at++] = k->from[b++];
    }
}

MESHFIX__PRIVATE void meshfix__sort_pairs_in_chunks(const meshfix_options *o, meshfix__pair *pairs, meshfix__pair *tmp,
                                                   size_t n, int (*before)(const meshfix__pair *, const meshfix__pair *))
{
    meshfix__pair_sorter k;
    size_t width, rounds = 0;
    k.pairs = pairs;
    k.tmp = tmp;
    k.n = n;
    k.chunks = meshfix__stage_chunks(n);
    k.before = before;
    if (k.chunks == 1) {
        meshfix__sort_pairs(pairs, tmp, n, before);
        return;
    }
    for (width = 1; width < k.chunks; width *= 2)
        rounds++;
    /* the rounds alternate between the arrays: they end in `pairs` */
    k.into_tmp = rounds % 2 == 1;
    k.width = 0;
    meshfix__run_tasks(o, meshfix__pair_sort_task, &k, k.chunks);
    k.from = k.into_tmp ? tmp : pairs;
    k.to = k.into_tmp ? pairs : tmp;
    for (k.width = 1; k.width < k.chunks; k.width *= 2) {
        meshfix__pair *next = k.from;
        meshfix__run_tasks(o, meshfix__pair_sort_task, &k, (k.chunks + 2 * k.width - 1) / (2 * k.width));
        k.from = k.to;
        k.to = next;
    }
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

/* What the coherence stage hands on: the boundary segments (each with its
   partner), and the pairs of patches with their summed coherence. */
typedef struct meshfix__coherence {
    meshfix__segment *segments;
    unsigned int segment_count;
    meshfix__pair *pairs;
    size_t pair_count;
} meshfix__coherence;

/* Stage 1: every boundary edge of a triangle with geometry, in the
   frame scaled by 1 / scale, triangle by triangle and, in a triangle, by
   vertex id: flipping a triangle renumbers its half-edges, and the order
   of the segments must not depend on the winding (it decides which
   candidates a crowded search looks at). Triangles [first, end); with
   segments NULL, only counts them. */
MESHFIX__PRIVATE unsigned int meshfix__collect_segments(const meshfix__geometry *g, double scale, size_t first,
                                                        size_t end, meshfix__segment *segments)
{
    const meshfix__mesh *m = g->m;
    unsigned int t, n = 0, c, sorted[3];
    for (t = (unsigned int)first; t < end; ++t) {
        if (!meshfix__has_area(m, t))
            continue;
        meshfix__sorted_triangle(m, t, sorted);
        for (c = 0; c < 3; ++c) {
            /* the edges (s0, s1), (s0, s2), (s1, s2), each by its half-edge */
            unsigned int a = sorted[c == 2 ? 1 : 0], b = sorted[c == 0 ? 1 : 2], h;
            for (h = 3 * t; h < 3 * t + 3; ++h) {
                unsigned int next = h % 3 == 2 ? h - 2 : h + 1;
                if ((m->indices[h] == a && m->indices[next] == b) || (m->indices[h] == b && m->indices[next] == a))
                    break;
            }
            if (m->mate[h] == MESHFIX__NONE) {
                if (segments != NULL)
                    meshfix__edge_segment(g, h, scale, &segments[n]);
                n++;
            }
        }
    }
    return n;
}

/* The boundary (count[0]) and ring (count[1]) half-edges of triangles
   [t, end) into chunk `chunk` of stage s. */
MESHFIX__PRIVATE void meshfix__count_boundary(const meshfix__mesh *m, meshfix__stage *s, size_t chunk, size_t t,
                                             size_t end)
{
    size_t h, boundary = 0, rings = 0;
    for (h = 3 * t; h < 3 * end; ++h) {
        boundary += m->mate[h] == MESHFIX__NONE;
        rings += (size_t)meshfix__is_ring(m->mate[h]);
    }
    s->count[chunk][0] = boundary;
    s->count[chunk][1] = rings;
}

/* A stage over the mesh's triangles: their boundary and ring half-edges. */
MESHFIX__PRIVATE void meshfix__boundary_chunk(void *stage, size_t chunk)
{
    meshfix__stage *s = (meshfix__stage *)stage;
    size_t t, end;
    meshfix__chunk_range(s, chunk, &t, &end);
    meshfix__count_boundary((const meshfix__mesh *)s->context, s, chunk, t, end);
}

/* Stage 1 over chunks of triangles (meshfix__run_stage): each chunk
   counts its boundary and ring half-edges, then writes its segments (at
   most one a boundary half-edge) from where the chunks before it end
   their boundary half-edges; the chunks' segments are then moved
   together in chunk order (where no triangle without area had a boundary
   edge, they are already): in triangle order, as one pass lays them. */
typedef struct meshfix__collect_task {
    const meshfix__geometry *g;
    double scale;
    meshfix__segment *segments;         /* NULL: the counting pass */
    size_t first[MESHFIX__STAGE_CHUNKS]; /* per chunk: its boundary half-edges, then where its segments go */
} meshfix__collect_task;

MESHFIX__PRIVATE void meshfix__collect_chunk(void *stage, size_t chunk)
{
    meshfix__stage *s = (meshfix__stage *)stage;
    meshfix__collect_task *task = (meshfix__collect_task *)s->context;
    size_t t, end;
    meshfix__chunk_range(s, chunk, &t, &end);
    if (task->segments == NULL) {
        meshfix__count_boundary(task->g->m, s, chunk, t, end);
        task->first[chunk] = s->count[chunk][0];
    } else
        s->count[chunk][0] = meshfix__collect_segments(task->g, task->scale, t, end, task->segments + task->first[chunk]);
}

/* The boundary segments of the mesh into `segments` (room for `boundary`,
   the boundary half-edges counted by the first pass of `task`). Returns
   how many. */
MESHFIX__PRIVATE unsigned int meshfix__collect_all(const meshfix_options *o, meshfix__collect_task *task,
                                                  meshfix__segment *segments)
{
    meshfix__stage s;
    size_t c, sum = 0, at = 0, i;
    s.n = task->g->m->triangle_count;
    s.chunks = meshfix__stage_chunks(s.n);
    s.context = task;
    for (c = 0; c < s.chunks; ++c) {
        size_t count = task->first[c];
        task->first[c] = sum;
        sum += count;
        s.count[c][0] = s.count[c][1] = 0;
    }
    task->segments = segments;
    meshfix__run_tasks(o, meshfix__collect_chunk, &s, s.chunks);
    for (c = 0; c < s.chunks; ++c) {
        /* down, never over what is still to move: a forward copy */
        if (task->first[c] != at)
            for (i = 0; i < s.count[c][0]; ++i)
                segments[at + i] = segments[task->first[c] + i];
        at += s.count[c][0];
    }
    return (unsigned int)at;
}

/* Stage 2: a hash grid of cells at least the search distance and the
   mean edge wide; each segment is entered at most three times (what
   meshfix__plan_geometry lays out). Returns 0 when out of memory. */
MESHFIX__PRIVATE size_t meshfix__grid_buckets(size_t segments)
{
    size_t buckets = 16;
    while (buckets < 2 * segments)
        buckets *= 2;
    return buckets;
}

/* The grid over chunks of segments (from MESHFIX__PARALLEL_UNIT
   segments on), a meshfix__sort_buckets whose partitions cover whole
   bytes of `occupied`: a bucket ends with the entries one pass gives it,
   in the same order. */
typedef struct meshfix__grid_task {
    meshfix__grid *grid;
    const meshfix__segment *segments;
    double beyond, reach;
    unsigned int *bucket_of; /* 3 per segment: the buckets it enters, NONE after the last */
} meshfix__grid_task;

/* The segments of [first, end) into the buckets of meshfix__segment_buckets:
   found when counted, kept in bucket_of for when they are placed. */
MESHFIX__PRIVATE void meshfix__grid_entries(meshfix__bucket_sort *s, size_t first, size_t end, unsigned int *next)
{
    const meshfix__grid_task *k = (const meshfix__grid_task *)s->context;
    size_t i, j, n, bucket[3];
    for (i = first; i < end; ++i) {
        unsigned int *of = k->bucket_of + 3 * i;
        if (!s->placing) {
            n = (size_t)meshfix__segment_buckets(k->grid, &k->segments[i], k->beyond, k->reach, bucket);
            for (j = 0; j < 3; ++j)
                of[j] = j < n ? (unsigned int)bucket[j] : MESHFIX__NONE;
        }
        for (j = 0; j < 3 && of[j] != MESHFIX__NONE; ++j)
            meshfix__sort_entry(s, next, of[j], (unsigned int)i);
    }
}

/* A partition's entries as the grid's items, in their buckets, taken in
   segment order: the segments are read in the order they lie (sorting
   their ids first and reading them in bucket order cost the grid of 400k
   segments some 8%). */
MESHFIX__PRIVATE void meshfix__grid_place(const meshfix__bucket_sort *s, unsigned int begin, unsigned int last)
{
    const meshfix__grid_task *k = (const meshfix__grid_task *)s->context;
    unsigned int i;
    for (i = begin; i < last; ++i)
        meshfix__cell_item_of(k->segments, s->entry_item[i], &k->grid->items[s->end[s->entry_bucket[i]]++]);
}

/* Which of buckets [first, end) are occupied, once placed. */
MESHFIX__PRIVATE void meshfix__grid_occupied(const meshfix__bucket_sort *s, size_t first, size_t end, unsigned int begin)
{
    unsigned char *occupied = ((const meshfix__grid_task *)s->context)->grid->occupied;
    size_t b;
    for (b = first; b < end; begin = s->end[b++])
        if (s->end[b] != begin)
            occupied[b >> 3] = (unsigned char)(occupied[b >> 3] | (1u << (b & 7)));
}

/* The grid's buckets and items over chunks (grid->start and occupied
   zeroed, grid->cell, mask and items set). `entries`: scratch for 9
   unsigned ints per segment (each segment's buckets, then the sort's
   entries: a bucket and an item each). */
MESHFIX__PRIVATE void meshfix__index_in_chunks(const meshfix_options *o, meshfix__grid *grid, const meshfix__segment *segments,
                                              unsigned int n, double reach, double beyond, unsigned int *entries)
{
    meshfix__grid_task k;
    meshfix__bucket_sort s;
    size_t buckets = grid->mask + 1;
    k.grid = grid;
    k.segments = segments;
    k.beyond = beyond;
    k.reach = reach;
    k.bucket_of = entries;
    meshfix__sort_setup(&s, o, &k, meshfix__grid_entries, n, buckets);
    meshfix__sort_arrays(&s, entries + 3 * (size_t)n, entries + 6 * (size_t)n, grid->start, NULL);
    s.place = meshfix__grid_place;
    s.part = meshfix__grid_occupied;
    s.shift = 3; /* a partition covers whole bytes of `occupied` */
    grid->start[buckets] = meshfix__sort_buckets(&s);
}

/* `entries`: scratch for meshfix__index_in_chunks (NULL: one pass here). */
MESHFIX__PRIVATE int meshfix__index_segments(meshfix__geometry *g, const meshfix__segment *segments,
                                            unsigned int n, double reach, double beyond, meshfix__grid *grid,
                                            unsigned int *entries)
{
    double average = 0;
    size_t buckets, k, indexed = 0;
    unsigned int i;
    for (i = 0; i < n; ++i)
        if (beyond == 0 || meshfix__too_long_for(beyond, &segments[i], reach))
            average += segments[i].length, indexed++;
    average /= (double)(indexed ? indexed : 1);
    grid->cell = meshfix__maxd(reach, average);
    buckets = meshfix__grid_buckets(n);
    grid->mask = buckets - 1;
    grid->start = (unsigned int *)meshfix__array(&g->arena, g->arena.plan.grid_start, buckets + 1);
    grid->occupied = (unsigned char *)meshfix__array(&g->arena, g->arena.plan.grid_occupied, buckets / 8);
    /* three entries a segment at most */
    grid->items = (meshfix__cell_item *)meshfix__array(&g->arena, g->arena.plan.grid_items, 3 * (size_t)n);
    if (grid->start == NULL || grid->occupied == NULL || grid->items == NULL)
        return 0;
    MESHFIX_MEMSET(grid->start, 0, (buckets + 1) * sizeof(unsigned int));
    MESHFIX_MEMSET(grid->occupied, 0, buckets / 8);
    /* buckets below NONE: each fits an entry */
    if (entries != NULL && meshfix__stage_chunks(n) > 1 && grid->mask < MESHFIX__NONE) {
        meshfix__index_in_chunks(g->o, grid, segments, n, reach, beyond, entries);
        return 1;
    }
    meshfix__grid_pass(grid, segments, n, beyond, reach, 0);
    for (k = 0; k < buckets; ++k) {
        if (grid->start[k + 1] != 0)
            grid->occupied[k >> 3] = (unsigned char)(grid->occupied[k >> 3] | (1u << (k & 7)));
        grid->start[k + 1] += grid->start[k];
    }
    meshfix__grid_pass(grid, segments, n, beyond, reach, 1); /* start[b] now ends bucket b */
    return 1;
}

/* Whether the segment of `item` lies farther than `best` from the one
   with this middle, by their middles alone: each point of the item's
   segment is within its half length of its middle, so a point's distance
   to the segment is at least its distance to that middle less the half;
   and the two ends of a segment are together at least twice as far from
   any point as its middle is. So the mean distance of the three points is
   at least the distance of the middles less the item's half. The margin
   covers the rounding of the item's floats, so nothing the exact measure
   would keep is pruned. */
MESHFIX__PRIVATE int meshfix__surely_farther(const double middle[3], const meshfix__cell_item *item, double best)
{
    double d2 = 0, slack = (double)item->half + best + 1e-5 * (1.0 + best);
    int k;
    for (k = 0; k < 3; ++k) {
        double x = middle[k] - (double)item->middle[k];
        d2 += x * x;
    }
    return d2 > slack * slack;
}

/* Whether cell (x, y, z) comes within `radius` of point p: its items'
   middles lie in it, with a margin for rounding. */
MESHFIX__PRIVATE int meshfix__cell_within(const meshfix__grid *grid, double x, double y, double z, const double p[3],
                                         double radius)
{
    double cell[3], d2 = 0, slack = radius + 1e-5 * (1.0 + radius) + 1e-9 * grid->cell;
    int k;
    cell[0] = x, cell[1] = y, cell[2] = z;
    for (k = 0; k < 3; ++k) {
        double low = cell[k] * grid->cell, high = (cell[k] + 1.0) * grid->cell;
        double out = p[k] < low ? low - p[k] : p[k] > high ? p[k] - high : 0.0;
        d2 += out * out;
    }
    return d2 <= slack * slack;
}

/* Stage 3: each segment's partner, the segment of another patch that
   runs closest alongside it within `reach`: first in the cells the
   segment touches, then in the margin around them, and at most
   MESHFIX__NEAREST_CANDIDATES segments in all, so that where thousands of
   boundary edges crowd one place (a huge fan, a soup of large triangles)
   the search stays linear; what it drops is far. A cell whose items'
   middles are all too far to beat the best so far (meshfix__surely_farther
   with the longest segment) is not read. */
typedef struct meshfix__partner_task {
    meshfix__segment *segments;
    unsigned int count;
    const meshfix__grid *grid;
    double reach, longest_half;
    double beyond; /* the second pass: only segments too long for cells this wide (0: the first, all) */
} meshfix__partner_task;

/* Segments [first, end): each reads the others' geometry and writes only
   its own partner and distance, so chunks can run side by side. */
MESHFIX__PRIVATE void meshfix__find_partners(const meshfix__partner_task *task, unsigned int first, unsigned int end)
{
    meshfix__segment *segments = task->segments;
    const meshfix__grid *grid = task->grid;
    double reach = task->reach, longest_half = task->longest_half;
    unsigned int i;
    for (i = first; i < end; ++i) {
        meshfix__segment *s = &segments[i];
        double own = meshfix__segment_reach(s, reach);
        double lo[3], hi[3], inner_lo[3], inner_hi[3], x, y, z, best = own;
        unsigned int best_id = MESHFIX__NONE, looked = 0;
        double middle[3];
        int ring, axis;
        if (task->beyond != 0 && !meshfix__too_long_for(task->beyond, s, reach))
            continue; /* found its partner in the first pass */
        meshfix__segment_cells(grid, s, own, lo, hi);
        meshfix__segment_cells(grid, s, 0.0, inner_lo, inner_hi);
        /* a segment too long for the grid searches nothing: as if it found
           nothing within reach (others may still choose it) */
        s->distance = own;
        for (axis = 0; axis < 3; ++axis)
            middle[axis] = 0.5 * (s->p[axis] + s->q[axis]);
        if (!meshfix__cells_usable(lo, hi))
            continue;
        /* past the candidate limit nothing more is read: the walk stops */
        for (ring = 0; ring < 2 && looked < MESHFIX__NEAREST_CANDIDATES; ++ring) {
            double from[3], to[3];
            if (ring == 1) {
                /* the cells of the margin that come near enough to the middle */
                double radius = longest_half + best + 1e-5 * (1.0 + best);
                for (axis = 0; axis < 3; ++axis) {
                    from[axis] = meshfix__maxd(lo[axis], MESHFIX_FLOOR((middle[axis] - radius) / grid->cell));
                    to[axis] = meshfix__mind(hi[axis], MESHFIX_FLOOR((middle[axis] + radius) / grid->cell));
                }
            } else {
                MESHFIX_MEMCPY(from, inner_lo, sizeof(from));
                MESHFIX_MEMCPY(to, inner_hi, sizeof(to));
            }
            for (x = from[0]; x <= to[0] && looked < MESHFIX__NEAREST_CANDIDATES; ++x)
                for (y = from[1]; y <= to[1] && looked < MESHFIX__NEAREST_CANDIDATES; ++y)
                    for (z = from[2]; z <= to[2] && looked < MESHFIX__NEAREST_CANDIDATES; ++z) {
                        size_t bucket, j;
                        int inner = x >= inner_lo[0] && x <= inner_hi[0] && y >= inner_lo[1] && y <= inner_hi[1] &&
                                    z >= inner_lo[2] && z <= inner_hi[2];
                        if (inner != (ring == 0) ||
                            !meshfix__cell_within(grid, x, y, z, middle, longest_half + best))
                            continue;
                        bucket = meshfix__grid_bucket(grid, x, y, z);
                        if (!meshfix__bucket_occupied(grid, bucket))
                            continue;
                        for (j = bucket == 0 ? 0 : grid->start[bucket - 1];
                             j < grid->start[bucket] && looked < MESHFIX__NEAREST_CANDIDATES; ++j, ++looked) {
                            const meshfix__cell_item *item = &grid->items[j];
                            unsigned int f = item->segment;
                            double d;
                            if (item->patch == s->patch || meshfix__surely_farther(middle, item, best))
                                continue;
                            d = meshfix__segment_distance(s, &segments[f], best);
                            if (d < best || (d == best && (best_id == MESHFIX__NONE ||
                                                           meshfix__segment_before(&segments[f], &segments[best_id])))) {
                                best = d;
                                best_id = f;
                            }
                        }
                    }
        }
        s->partner = best_id;
        s->distance = best;
    }
}

#define MESHFIX__SEGMENTS_PER_TASK 4096
MESHFIX__PRIVATE void meshfix__partner_chunk(void *context, size_t chunk)
{
    const meshfix__partner_task *task = (const meshfix__partner_task *)context;
    size_t first = chunk * MESHFIX__SEGMENTS_PER_TASK, end = first + MESHFIX__SEGMENTS_PER_TASK;
    meshfix__find_partners(task, (unsigned int)first, (unsigned int)(end < task->count ? end : task->count));
}

/* Every segment's partner, on the caller's threads if it gave a
   parallel_for (the same partners however the chunks run). */
MESHFIX__PRIVATE void meshfix__find_all_partners(const meshfix__geometry *g, meshfix__segment *segments,
                                                unsigned int n, const meshfix__grid *grid, double reach, double beyond)
{
    meshfix__partner_task task;
    size_t chunks = ((size_t)n + MESHFIX__SEGMENTS_PER_TASK - 1) / MESHFIX__SEGMENTS_PER_TASK;
    unsigned int i;
    task.segments = segments;
    task.count = n;
    task.grid = grid;
    task.reach = reach;
    task.beyond = beyond;
    task.longest_half = 0;
    for (i = 0; i < n; ++i)
        if (beyond == 0 || meshfix__too_long_for(beyond, &segments[i], reach))
            task.longest_half = meshfix__maxd(task.longest_half, 0.5 * segments[i].length);
    meshfix__run_tasks(g->o, meshfix__partner_chunk, &task, chunks);
}

MESHFIX__PRIVATE int meshfix__any_too_long(const meshfix__segment *segments, unsigned int n, double cell, double reach)
{
    unsigned int i;
    for (i = 0; i < n; ++i)
        if (meshfix__too_long_for(cell, &segments[i], reach))
            return 1;
    return 0;
}

/* Stage 4: the pairs the partners give. A boundary edge with no real
   counterpart (a hole, a sliver) still finds the nearest edge across the
   way, whose own partner is much closer: such a choice is dropped (kept
   only when it is mutual, or at most twice as far as the partner's own
   and a twentieth of its length), and so is a choice between stacked
   sheets. */
#define MESHFIX__ONE_WAY_FARTHER 2.0
#define MESHFIX__ONE_WAY_SLACK 0.05
/* Whether segment i's choice gives a pair (sets its `matched`). */
MESHFIX__PRIVATE int meshfix__partner_pairs(meshfix__segment *segments, unsigned int i)
{
    meshfix__segment *s = &segments[i], *f;
    if (s->partner == MESHFIX__NONE)
        return 0;
    f = &segments[s->partner];
    s->matched = !((f->partner != i && s->distance > MESHFIX__ONE_WAY_FARTHER * f->distance + MESHFIX__ONE_WAY_SLACK * s->length) ||
                   meshfix__stacked(s, f));
    return s->matched;
}

/* Over chunks of segments (meshfix__run_stage): first each chunk marks
   and counts its segments that give a pair, then each writes their pairs
   from where the chunks before it end: in segment order. A segment
   writes only its own mark, and reads only its partner's choice. */
typedef struct meshfix__pairing_task {
    meshfix__segment *segments;
    meshfix__pair *pairs; /* NULL: the counting pass */
    size_t first[MESHFIX__STAGE_CHUNKS]; /* per chunk: its pairs, then where they start */
} meshfix__pairing_task;

MESHFIX__PRIVATE void meshfix__pairing_chunk(void *stage, size_t chunk)
{
    meshfix__stage *s = (meshfix__stage *)stage;
    meshfix__pairing_task *task = (meshfix__pairing_task *)s->context;
    meshfix__segment *segments = task->segments;
    size_t i, end, count = 0;
    meshfix__chunk_range(s, chunk, &i, &end);
    for (; i < end; ++i) {
        if (task->pairs == NULL)
            count += (size_t)meshfix__partner_pairs(segments, (unsigned int)i);
        else if (segments[i].matched) {
            const meshfix__segment *f = &segments[segments[i].partner];
            meshfix__add_pair(task->pairs, &task->first[chunk], &segments[i], f,
                              meshfix__local_coherence(&segments[i], f, segments[i].distance));
        }
    }
    if (task->pairs == NULL)
        task->first[chunk] = count;
}

MESHFIX__PRIVATE void meshfix__pair_partners(const meshfix_options *o, meshfix__segment *segments, unsigned int n,
                                            meshfix__pair *pairs, size_t *pair_count)
{
    meshfix__pairing_task task;
    size_t c, chunks = meshfix__stage_chunks(n);
    task.segments = segments;
    task.pairs = NULL;
    meshfix__run_stage(o, meshfix__pairing_chunk, &task, n, NULL);
    for (c = 0; c < chunks; ++c) {
        size_t count = task.first[c];
        task.first[c] = *pair_count;
        *pair_count += count;
    }
    task.pairs = pairs;
    meshfix__run_stage(o, meshfix__pairing_chunk, &task, n, NULL);
}

/* Where the triangle of half-edge h lies around its edge: an angle in
   [0, 4) on the circle of directions normal to the edge (quadrant plus a
   monotone fraction: no trigonometry, and the same on every machine),
   taken by the direction of its third corner in the basis u, v. */
MESHFIX__PRIVATE double meshfix__angle_around(const meshfix__geometry *g, unsigned int h, const double u[3],
                                             const double v[3], const double origin[3])
{
    double apex[3], x, y, ax, ay;
    int k;
    meshfix__frame_point(&g->bvh, meshfix__position(g->m, meshfix__apex(g->m, h)), apex);
    for (k = 0; k < 3; ++k)
        apex[k] -= origin[k];
    x = meshfix__dot3(apex, u), y = meshfix__dot3(apex, v);
    ax = x < 0 ? -x : x, ay = y < 0 ? -y : y;
    if (ax + ay == 0)
        return 0.0;
    if (x >= 0 && y >= 0)
        return y / (ax + ay);
    if (x < 0 && y >= 0)
        return 1.0 + ax / (ax + ay);
    if (x < 0)
        return 2.0 + ay / (ax + ay);
    return 3.0 + ax / (ax + ay);
}

typedef struct meshfix__ring_order {
    const double *angle; /* per ring member, by position */
    const unsigned int *members;
} meshfix__ring_order;

MESHFIX__PRIVATE int meshfix__angle_before(const void *context, unsigned int a, unsigned int b)
{
    const meshfix__ring_order *r = (const meshfix__ring_order *)context;
    return r->angle[a] < r->angle[b] || (r->angle[a] == r->angle[b] && r->members[a] < r->members[b]);
}

/* Whether a ring can be wound without contradiction: the members in
   radial order, each with the next, disagree an even number of times.
   Turning a member over changes two of those, so the count's parity does
   not depend on how the input was wound. A sheet attached to a surface
   (a T: a baffle on a duct's wall, three members) always contradicts
   itself: its pairs say nothing. */
MESHFIX__PRIVATE int meshfix__ring_windable(const double *c, unsigned int n)
{
    unsigned int i, against = 0;
    for (i = 0; i < n; ++i)
        against += c[i] < 0;
    return against % 2 == 0;
}

/* Stage 5: at an edge of three or more triangles, each member pairs with
   the one beside it around the edge (radial order), the only neighbour
   a surface can continue into: pairing members by their order in memory
   joined touching bodies wound correctly as if they were wound against
   each other. `work` holds positions, `angle` the angles of one ring. */
MESHFIX__PRIVATE void meshfix__ring_pairs(const meshfix__geometry *g, double scale, unsigned int *work, double *angle,
                                         unsigned int *members, meshfix__pair *pairs, size_t *pair_count)
{
    const meshfix__mesh *m = g->m;
    unsigned int h, half_edges = (unsigned int)(3 * m->triangle_count);
    for (h = 0; h < half_edges; ++h) {
        meshfix__ring_order order;
        double p[3], q[3], axis[3], u[3], v[3], len;
        unsigned int n = 0, cur, i;
        int k, windable;
        if (!meshfix__is_ring_last(m, h))
            continue;
        cur = h;
        do {
            cur = m->mate[cur] & ~MESHFIX__RING;
            if (meshfix__has_area(m, cur / 3))
                members[n++] = cur;
        } while (cur != h);
        if (n < 2)
            continue;
        {
            unsigned int next = members[0] % 3 == 2 ? members[0] - 2 : members[0] + 1;
            unsigned int lo = m->indices[members[0]] < m->indices[next] ? m->indices[members[0]] : m->indices[next];
            unsigned int hi = m->indices[members[0]] < m->indices[next] ? m->indices[next] : m->indices[members[0]];
            meshfix__frame_point(&g->bvh, meshfix__position(m, lo), p);
            meshfix__frame_point(&g->bvh, meshfix__position(m, hi), q);
        }
        for (k = 0; k < 3; ++k)
            axis[k] = q[k] - p[k];
        len = MESHFIX_SQRT(meshfix__dot3(axis, axis));
        if (!(len > 0))
            continue;
        for (k = 0; k < 3; ++k)
            axis[k] /= len;
        /* u: any unit vector normal to the axis; v = axis x u */
        k = (axis[0] < 0 ? -axis[0] : axis[0]) < 0.6 ? 0 : 1;
        u[0] = k == 0 ? 0.0 : -axis[2], u[1] = k == 0 ? axis[2] : 0.0, u[2] = k == 0 ? -axis[1] : axis[0];
        len = MESHFIX_SQRT(meshfix__dot3(u, u));
        for (k = 0; k < 3; ++k)
            u[k] /= len;
        v[0] = axis[1] * u[2] - axis[2] * u[1];
        v[1] = axis[2] * u[0] - axis[0] * u[2];
        v[2] = axis[0] * u[1] - axis[1] * u[0];
        for (i = 0; i < n; ++i) {
            angle[i] = meshfix__angle_around(g, members[i], u, v, p);
            work[i] = i;
        }
        order.angle = angle;
        order.members = members;
        meshfix__sort_ids(work, n, meshfix__angle_before, &order);
        /* faces that coincide (two bodies touching along a face) have no
           order around the edge that winding could not change: the ring
           says nothing */
        for (i = 0; i + 1 < n && angle[work[i]] != angle[work[i + 1]]; ++i) {
        }
        if (i + 1 < n)
            continue;
        /* angle[i] now holds the coherence of the i-th and the next */
        for (i = 0; i < n; ++i) {
            meshfix__segment sa, sb;
            meshfix__edge_segment(g, members[work[i]], scale, &sa);
            meshfix__edge_segment(g, members[work[(i + 1) % n]], scale, &sb);
            angle[i] = meshfix__local_coherence(&sa, &sb, 0.0);
        }
        windable = n <= 2 || meshfix__ring_windable(angle, n);
        for (i = 0; i < n && !(n == 2 && i == 1); ++i) {
            unsigned int next = (i + 1) % n;
            meshfix__segment sa, sb;
            meshfix__edge_segment(g, members[work[i]], scale, &sa);
            meshfix__edge_segment(g, members[work[next]], scale, &sb);
            if (sa.patch == sb.patch)
                continue;
            if (!windable)
                meshfix__add_veto(pairs, pair_count, &sa, &sb);
            else if (!meshfix__stacked(&sa, &sb)) {
                meshfix__add_pair(pairs, pair_count, &sa, &sb, angle[i]);
                /* neighbours around an edge: each is the other's */
                pairs[*pair_count - 1].from_a = pairs[*pair_count - 1].from_b = sa.length;
                pairs[*pair_count - 1].ring = 1;
            }
        }
    }
}

/* Stage 6: one pair per two patches, coherences and lengths summed in a
   canonical order, strongest first. */
MESHFIX__PRIVATE size_t meshfix__sum_pairs(const meshfix_options *o, meshfix__pair *pairs, meshfix__pair *tmp, size_t n)
{
    size_t k, out = 0;
    meshfix__sort_pairs_in_chunks(o, pairs, tmp, n, meshfix__pair_key_before);
    for (k = 0; k < n; ++k) {
        if (out > 0 && pairs[out - 1].a == pairs[k].a && pairs[out - 1].b == pairs[k].b) {
            meshfix__pair *sum = &pairs[out - 1];
            int veto = sum->length < 0 || pairs[k].length < 0;
            sum->c = veto ? 0.0 : sum->c + pairs[k].c;
            sum->length = veto ? -1.0 : sum->length + pairs[k].length;
            sum->from_a += pairs[k].from_a;
            sum->from_b += pairs[k].from_b;
            sum->ring = (unsigned char)(sum->ring & pairs[k].ring);
        } else {
            pairs[out++] = pairs[k];
        }
    }
    meshfix__sort_pairs(pairs, tmp, out, meshfix__pair_strength_before);
    return out;
}

/* The largest ring: the scratch of the radial sort. */
MESHFIX__PRIVATE unsigned int meshfix__largest_ring(const meshfix__mesh *m)
{
    unsigned int h, half_edges = (unsigned int)(3 * m->triangle_count), largest = 0;
    for (h = 0; h < half_edges; ++h) {
        unsigned int n = 0, cur = h;
        if (!meshfix__is_ring_last(m, h))
            continue;
        do {
            cur = m->mate[cur] & ~MESHFIX__RING;
            n++;
        } while (cur != h);
        largest = n > largest ? n : largest;
    }
    return largest;
}

/* The whole stage: segments, partners, ring neighbours, sums. Returns 0
   when out of memory. */
MESHFIX__PRIVATE int meshfix__measure_coherence(meshfix__geometry *g, meshfix__coherence *out)
{
    meshfix__mesh *m = g->m;
    const meshfix_options *o = g->o;
    unsigned int boundary, rings, largest;
    double longest = 0, scale, reach;
    meshfix__pair *tmp = NULL;
    meshfix__grid grid;
    meshfix__collect_task collect;
    unsigned int *work = NULL, *members = NULL, *entries;
    double *angle = NULL;
    size_t ring_edges;
    int axis, ok = 0;
    MESHFIX_MEMSET(out, 0, sizeof(*out));
    MESHFIX_MEMSET(&grid, 0, sizeof(grid));
    for (axis = 0; axis < 3; ++axis)
        longest = meshfix__maxd(longest, (double)g->bvh.high[axis] - (double)g->bvh.low[axis]);
    scale = longest > 0 ? 1.0 / longest : 1.0;
    g->length_unit = (longest > 0 ? longest : 1.0) / g->bvh.scale;
    reach = (double)o->visibility.coherence_distance;
    collect.g = g;
    collect.scale = scale;
    collect.segments = NULL;
    boundary = (unsigned int)meshfix__run_stage(o, meshfix__collect_chunk, &collect, m->triangle_count, &ring_edges);
    rings = (unsigned int)ring_edges;
    largest = rings != 0 ? meshfix__largest_ring(m) : 0;
    out->segments = (meshfix__segment *)meshfix__array(&g->arena, g->arena.plan.segments, boundary);
    out->pairs = (meshfix__pair *)meshfix__array(&g->arena, g->arena.plan.pairs, (size_t)boundary + rings);
    tmp = (meshfix__pair *)meshfix__array(&g->arena, g->arena.plan.pair_scratch, (size_t)boundary + rings);
    work = (unsigned int *)meshfix__array(&g->arena, g->arena.plan.ring_work, largest);
    members = (unsigned int *)meshfix__array(&g->arena, g->arena.plan.ring_members, largest);
    angle = (double *)meshfix__array(&g->arena, g->arena.plan.ring_angles, largest);
    if (!out->segments || !out->pairs || !tmp || !work || !members || !angle)
        goto done;
    out->segment_count = meshfix__collect_all(o, &collect, out->segments);
    /* the pairs' scratch, free until their sort, holds the grid's entries
       while it is built in chunks */
    entries = 9 * sizeof(unsigned int) <= sizeof(meshfix__pair) ? (unsigned int *)(void *)tmp : NULL;
    if (out->segment_count != 0) {
        double first_cell;
        if (!meshfix__index_segments(g, out->segments, out->segment_count, reach, 0.0, &grid, entries))
            goto done;
        meshfix__find_all_partners(g, out->segments, out->segment_count, &grid, reach, 0.0);
        first_cell = grid.cell;
        if (meshfix__any_too_long(out->segments, out->segment_count, first_cell, reach)) {
            /* the same arrays again, for the long segments alone */
            if (!meshfix__index_segments(g, out->segments, out->segment_count, reach, first_cell, &grid, entries))
                goto done;
            meshfix__find_all_partners(g, out->segments, out->segment_count, &grid, reach, first_cell);
        }
        meshfix__pair_partners(o, out->segments, out->segment_count, out->pairs, &out->pair_count);
    }
    /* without ring edges, no ring */
    if (rings != 0)
        meshfix__ring_pairs(g, scale, work, angle, members, out->pairs, &out->pair_count);
    out->pair_count = meshfix__sum_pairs(o, out->pairs, tmp, out->pair_count);
    ok = 1;
done:
    return ok;
}

/* ===== >>merge ===== */

/* Super-patches: a union-find with orientation parity. Each node's
   frame is stored relative to its parent's; a root's `turn` is its frame
   relative to its own patch's consistent frame. */
typedef struct meshfix__merge {
    unsigned int *parent;
    unsigned char *parity;  /* frame of a node relative to its parent */
    unsigned char *turn;    /* roots: frame relative to their own patch's consistent frame */
    double *front, *back, *area; /* VISIBILITY: escape shares and area per super-patch */
    /* AUTO, OUTWARD: what the members' own evidence says of a root's frame
       as it is turned now, +1, -1 or 0 for nothing: `side`, whether its
       front is outside the surface of the unit the members were measured
       in (their crossings); `normals`, whether the caller's normals agree
       with it. A join they contradict is refused (NULL: no anchors). */
    signed char *side, *normals;
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

/* An anchor of a root turned by `flip`, and two anchors as one: the
   known one (they agree, or the join was refused). */
MESHFIX__PRIVATE signed char meshfix__anchor_turned(signed char anchor, unsigned int flip)
{
    return (signed char)(flip ? -anchor : anchor);
}

MESHFIX__PRIVATE signed char meshfix__anchor_joined(signed char a, signed char b)
{
    return a != 0 ? a : b;
}

/* Joins the super-patches of A and B, turned by flip_a and flip_b. */
MESHFIX__PRIVATE void meshfix__join(meshfix__merge *g, unsigned int a, unsigned int b, unsigned int flip_a,
                                   unsigned int flip_b)
{
    unsigned int root = a < b ? a : b, child = a < b ? b : a;
    g->turn[a] ^= (unsigned char)flip_a;
    g->turn[b] ^= (unsigned char)flip_b;
    g->parent[child] = root;
    g->parity[child] = (unsigned char)(g->turn[child] ^ g->turn[root]);
    if (g->area != NULL)
        g->area[root] = g->area[a] + g->area[b];
    if (g->side != NULL) {
        g->side[root] = meshfix__anchor_joined(meshfix__anchor_turned(g->side[a], flip_a),
                                               meshfix__anchor_turned(g->side[b], flip_b));
        g->normals[root] = meshfix__anchor_joined(meshfix__anchor_turned(g->normals[a], flip_a),
                                                  meshfix__anchor_turned(g->normals[b], flip_b));
    }
}

/* Whether the members' own evidence forbids joining roots a and b with b
   turned by `flip`: both know their side, or both have clear normals, and
   the turned ones disagree. */
MESHFIX__PRIVATE int meshfix__anchors_conflict(const meshfix__merge *g, unsigned int a, unsigned int b, unsigned int flip)
{
    signed char sb, nb;
    if (g->side == NULL)
        return 0;
    sb = meshfix__anchor_turned(g->side[b], flip);
    nb = meshfix__anchor_turned(g->normals[b], flip);
    return (g->side[a] != 0 && sb != 0 && g->side[a] != sb) || (g->normals[a] != 0 && nb != 0 && g->normals[a] != nb);
}

/* The coherence of a pair between the super-patches as they are turned
   now; sets *a and *b to their roots. */
MESHFIX__PRIVATE double meshfix__pair_coherence(meshfix__merge *g, const meshfix__pair *pair, unsigned int *a,
                                               unsigned int *b)
{
    unsigned int pa, pb;
    *a = meshfix__merge_find(g, pair->a, &pa);
    *b = meshfix__merge_find(g, pair->b, &pb);
    return pair->c * ((pa ^ g->turn[*a]) ? -1.0 : 1.0) * ((pb ^ g->turn[*b]) ? -1.0 : 1.0);
}

/* AUTO and OUTWARD: coherence alone joins, strongest pairs first, the
   pairs whose edges run closely along each other (|c| / l above 0.9:
   within a few degrees, across a gap small next to the edges) and are
   paired both ways (the edges of each that found the other as their
   partner at least half as long as the other's: a seam of one surface is
   matched from both sides, where a part touching another finds edges
   whose own partners lie elsewhere). The rule does not look at how the
   input is wound, so the units and their members' relative turns are the
   same for any winding of the input, and a second repair finds what the
   first left. Returns the joins. */
#define MESHFIX__JOIN_STRENGTH 0.8
#define MESHFIX__TURN_STRENGTH 0.9 /* a join that turns one side against the other, neither side known */
#define MESHFIX__BOTH_WAYS 0.5

/* A weak pair: paired one way only (the edges of one found the other's,
   whose own partners lie elsewhere: a part touching another, or a seam of
   long slivers along short edges), or related only around edges of three
   or more triangles (a slot whose walls lie on each other, a fin). It
   joins members as they are wound; it turns one against the other only
   when both sides' own crossings say where they face. */
MESHFIX__PRIVATE int meshfix__weak_may_join(const meshfix__merge *g, const meshfix__pair *p, unsigned int a,
                                           unsigned int b, unsigned int flip);

MESHFIX__PRIVATE int meshfix__paired_both_ways(const meshfix__pair *p)
{
    double least = p->from_a < p->from_b ? p->from_a : p->from_b, most = p->from_a < p->from_b ? p->from_b : p->from_a;
    return least >= MESHFIX__BOTH_WAYS * most && most > 0;
}

MESHFIX__PRIVATE int meshfix__weak_may_join(const meshfix__merge *g, const meshfix__pair *p, unsigned int a,
                                           unsigned int b, unsigned int flip)
{
    if (!p->ring && meshfix__paired_both_ways(p))
        return 1;
    return !flip || (g->side != NULL && g->side[a] != 0 && g->side[b] != 0);
}
/* How closely a pair's edges must run along each other (|c| / l): a join
   that turns one side against the other while neither side's own
   evidence is known asks for edges within a few degrees; the rest, 0.8. */
MESHFIX__PRIVATE double meshfix__join_strength(const meshfix__merge *g, unsigned int a, unsigned int b, unsigned int flip)
{
    int known = g->side != NULL && (g->side[a] != 0 || g->side[b] != 0 || g->normals[a] != 0 || g->normals[b] != 0);
    return flip && !known ? MESHFIX__TURN_STRENGTH : MESHFIX__JOIN_STRENGTH;
}

MESHFIX__PRIVATE size_t meshfix__merge_by_coherence(meshfix__merge *g, const meshfix__pair *pairs, size_t count)
{
    size_t i, joins = 0;
    for (i = 0; i < count; ++i) {
        unsigned int a, b;
        double c = meshfix__pair_coherence(g, &pairs[i], &a, &b);
        if (a == b || !(pairs[i].length > 0) || MESHFIX_FABS(c) <= meshfix__join_strength(g, a, b, c < 0) * pairs[i].length ||
            !meshfix__weak_may_join(g, &pairs[i], a, b, c < 0) || meshfix__anchors_conflict(g, a, b, c < 0))
            continue;
        meshfix__join(g, a, b, 0, c < 0);
        joins++;
    }
    return joins;
}

MESHFIX__PRIVATE int meshfix__hardly_visible(double vmax, double vmin, double eps, double kv)
{
    return (vmin > eps && vmax / vmin < kv) || (vmin < eps && vmax < eps);
}

typedef struct meshfix__merge_params {
    double c0, eps, kv;
    int use_visibility;
} meshfix__merge_params;

/* VISIBILITY: the greedy merge of Borodin et al. 3.5. Each super-patch
   keeps its visibility (front and back escape shares in its current frame)
   and area. Conforming pairs merge, each side to its more visible face;
   conflicting pairs merge along the coherence when it is strong
   (|c| / l > C0), or when one side's visibility hardly matters (both below
   eps_v, or their ratio below k_v); otherwise they stay apart. Unlike the
   paper, a merged super-patch keeps its members' pairs rather than summing
   them into new ones: the queue is sorted once, O(P log P). Returns 1 when
   it merged. */
MESHFIX__PRIVATE int meshfix__merge_borodin(meshfix__merge *g, const meshfix__pair *pair, const meshfix__merge_params *k)
{
    unsigned int a, b, fa, fb, flip_to_cohere;
    double c = meshfix__pair_coherence(g, pair, &a, &b), area, va_max, va_min, vb_max, vb_min, v1, v2;
    if (a == b || c == 0.0)
        return 0; /* already one; or edges at right angles, which say nothing */
    flip_to_cohere = c < 0; /* turn one of them over to make c positive */
    if (!k->use_visibility) {
        meshfix__join(g, a, b, 0, flip_to_cohere);
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
        v1 = (va_max * g->area[a] + vb_max * g->area[b]) / area;
        v2 = (va_min * g->area[a] + vb_min * g->area[b]) / area;
        meshfix__join(g, a, b, fa, fb);
    } else {
        v1 = (va_max * g->area[a] + vb_min * g->area[b]) / area; /* A to its best side, B follows */
        v2 = (va_min * g->area[a] + vb_max * g->area[b]) / area; /* B to its best side, A follows */
        if (!((pair->length > 0 && (c < 0 ? -c : c) / pair->length > k->c0) ||
              (meshfix__hardly_visible(va_max, va_min, k->eps, k->kv) && v1 < v2) ||
              (meshfix__hardly_visible(vb_max, vb_min, k->eps, k->kv) && v2 < v1)))
            return 0;
        if (v1 >= v2) {
            meshfix__join(g, a, b, fa, fa ^ flip_to_cohere);
        } else {
            meshfix__join(g, a, b, fb ^ flip_to_cohere, fb);
            c = v1, v1 = v2, v2 = c;
        }
    }
    a = a < b ? a : b;
    g->front[a] = v1;
    g->back[a] = v2;
    return 1;
}

/* Every patch its own super-patch, no anchor. */
MESHFIX__PRIVATE void meshfix__reset_merge(meshfix__merge *merge, unsigned int patches)
{
    unsigned int p;
    for (p = 0; p < patches; ++p) {
        merge->parent[p] = p;
        merge->parity[p] = merge->turn[p] = 0;
    }
    if (merge->side != NULL) {
        MESHFIX_MEMSET(merge->side, 0, patches);
        MESHFIX_MEMSET(merge->normals, 0, patches);
    }
}

MESHFIX__PRIVATE int meshfix__alloc_merge(const meshfix__geometry *g, meshfix__merge *merge, int with_visibility)
{
    const meshfix__arena *a = &g->arena;
    size_t patches = g->m->patch_count;
    MESHFIX_MEMSET(merge, 0, sizeof(*merge));
    merge->parent = (unsigned int *)meshfix__array(a, a->plan.parent, patches);
    merge->parity = (unsigned char *)meshfix__array(a, a->plan.parity, patches);
    merge->turn = (unsigned char *)meshfix__array(a, a->plan.turn, patches);
    if (!with_visibility) {
        merge->side = (signed char *)meshfix__array(a, a->plan.side, patches);
        merge->normals = (signed char *)meshfix__array(a, a->plan.normals, patches);
        if (!merge->side || !merge->normals)
            return 0;
    }
    if (with_visibility) {
        merge->front = (double *)meshfix__array(a, a->plan.front, patches);
        merge->back = (double *)meshfix__array(a, a->plan.back, patches);
        merge->area = (double *)meshfix__array(a, a->plan.merged_area, patches);
        if (!merge->front || !merge->back || !merge->area)
            return 0;
    }
    if (!merge->parent || !merge->parity || !merge->turn)
        return 0;
    meshfix__reset_merge(merge, (unsigned int)patches);
    return 1;
}

/* Units from the merge: numbered by their lowest patch; each patch gets
   its unit and its frame relative to the unit's. Without a merge, every
   patch is its own unit. */
MESHFIX__PRIVATE void meshfix__number_units(meshfix__geometry *g, meshfix__merge *merge)
{
    meshfix__mesh *m = g->m;
    unsigned int p, count = 0, parity;
    for (p = 0; p < m->patch_count; ++p) {
        unsigned int root = merge != NULL ? meshfix__merge_find(merge, p, &parity) : p;
        if (merge == NULL)
            parity = 0;
        g->patch_unit[p] = root == p ? count++ : g->patch_unit[root];
        g->patch_turn[p] = (unsigned char)parity; /* the unit's frame is its root patch's */
    }
    g->unit_count = count;
}

/* ===== >>shells ===== */

/* The prior is the winding as given, and a unit's patches are its votes:
   a patch is one decision of whoever wound it (one face of a CAD export,
   one piece of a cut), whatever its area. By area, a unit of one large
   piece and one small one follows the large piece's coin; by count, a
   sliver outvotes a face. Each patch votes with the square root of its
   area, a length;
   chosen on the tune halves (models: cut256-gap 98.48% by area, 98.98% at
   0.5, 98.97% by count; cut256-jitter 99.25 / 99.25 / 99.22; assets and
   STL unchanged). Inside a patch the votes stay by area: there a flood
   fill joined the triangles, and the ones wound against it are the
   exporter's slips. */
MESHFIX__PRIVATE void meshfix__add_prior(meshfix__unit *u, double kept, double reversed)
{
    double total = kept + reversed, scale = total > 0 ? 1.0 / MESHFIX_SQRT(total) : 0.0;
    u->prior_kept += scale * kept;
    u->prior_reversed += scale * reversed;
}

/* What each unit adds up to: its area facing each way as given, the
   caller's normals, its volume, its box; whether it is closed. Volumes are
   taken about one point per unit (its first vertex), so patches that only
   together close a shell sum to its volume. */
MESHFIX__PRIVATE void meshfix__sum_unit_triangle(meshfix__geometry *g, unsigned int t, const double origin[3],
                                                meshfix__unit *u)
{
    const meshfix__mesh *m = g->m;
    double a[3], b[3], c[3], n[3], area, volume, sign = meshfix__unit_relative(g, t) ? -1.0 : 1.0;
    int k;
    if (!meshfix__has_geometry(m, t)) {
        if (m->positions == NULL) /* no positions: count triangles */
            *(sign > 0 ? &u->kept : &u->reversed) += 1.0;
        return;
    }
    meshfix__load_triangle(m, t, origin, a, b, c, n);
    area = 0.5 * MESHFIX_SQRT(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (!(area > 0.0))
        return;
    volume = (a[0] * (b[1] * c[2] - b[2] * c[1]) + a[1] * (b[2] * c[0] - b[0] * c[2]) +
              a[2] * (b[0] * c[1] - b[1] * c[0])) / 6.0;
    u->area += area;
    u->volume += sign * volume;
    *(sign > 0 ? &u->kept : &u->reversed) += area;
    u->normals += sign * meshfix__normal_vote(m, t, n) * area;
    u->normals_area += meshfix__normal_usable(m, t) ? area : 0.0;
    /* the box as given; into the frame once the unit is summed */
    for (k = 0; k < 3; ++k)
        meshfix__grow_box(u->box, u->box + 3, meshfix__position(m, m->indices[3 * t + (unsigned int)k]));
}

/* A unit is closed when no member has a boundary edge and, at every
   edge of three or more triangles, its members run the edge as often one
   way as the other (and its volume means something); gapped when the
   edges without a partner in the unit (boundary edges, and ring edges
   where its sides do not meet) are less than a fifth of its boundary: a
   sphere cut into patches whose seams opened by a gap, or a terrain cut
   into many, which its own crossings tell apart later. `net` holds a zero
   per unit. */
MESHFIX__PRIVATE void meshfix__close_units(meshfix__geometry *g, const meshfix__coherence *c, int *net)
{
    const meshfix__mesh *m = g->m;
    unsigned int h, half_edges = (unsigned int)(3 * m->triangle_count), i, u;
    for (u = 0; u < g->unit_count; ++u)
        g->units[u].closed = MESHFIX__CLOSED;
    for (i = 0; i < c->segment_count; ++i) {
        const meshfix__segment *s = &c->segments[i];
        meshfix__unit *x = &g->units[g->patch_unit[s->patch]];
        x->closed = MESHFIX__OPEN;
        x->boundary += s->length;
        if (!s->matched || g->patch_unit[c->segments[s->partner].patch] != g->patch_unit[s->patch])
            x->unmatched += s->length;
    }
    for (h = 0; h < half_edges; ++h) {
        unsigned int cur = h;
        double length;
        if (!meshfix__is_ring_last(m, h))
            continue;
        length = meshfix__edge_length(m, h) / g->length_unit;
        do { /* the net direction per unit */
            unsigned int next, t;
            cur = m->mate[cur] & ~MESHFIX__RING;
            t = cur / 3;
            next = cur % 3 == 2 ? cur - 2 : cur + 1;
            if (m->tri_patch[t] != MESHFIX__NONE)
                net[g->patch_unit[m->tri_patch[t]]] +=
                    ((m->indices[cur] < m->indices[next]) != (meshfix__unit_relative(g, t) != 0)) ? 1 : -1;
        } while (cur != h);
        do { /* read back, and zero again */
            unsigned int t;
            cur = m->mate[cur] & ~MESHFIX__RING;
            t = cur / 3;
            if (m->tri_patch[t] == MESHFIX__NONE)
                continue;
            u = g->patch_unit[m->tri_patch[t]];
            if (net[u] != 0) {
                g->units[u].closed = MESHFIX__OPEN;
                g->units[u].unmatched += length * (double)(net[u] < 0 ? -net[u] : net[u]);
                g->units[u].boundary += length * (double)(net[u] < 0 ? -net[u] : net[u]);
                net[u] = 0;
            }
        } while (cur != h);
    }
    for (u = 0; u < g->unit_count; ++u) {
        meshfix__unit *x = &g->units[u];
        if (x->closed == MESHFIX__OPEN && x->unmatched < MESHFIX__GAPPED_UNMATCHED * x->boundary)
            x->closed = MESHFIX__GAPPED;
        if (x->closed == MESHFIX__CLOSED && !meshfix__volume_is_meaningful(x->volume, x->area))
            x->closed = MESHFIX__OPEN;
    }
}

/* Sums every unit: an origin each (its first vertex with geometry), then
   its triangles patch by patch. */
MESHFIX__PRIVATE void meshfix__sum_units(meshfix__geometry *g)
{
    const meshfix__mesh *m = g->m;
    unsigned int p, i, u;
    MESHFIX_MEMSET(g->units, 0, g->unit_count * sizeof(meshfix__unit));
    for (u = 0; u < g->unit_count; ++u)
        meshfix__empty_box(g->units[u].box);
    for (p = 0; p < m->patch_count; ++p) {
        meshfix__unit *x = &g->units[g->patch_unit[p]];
        double kept = x->kept, reversed = x->reversed;
        for (i = m->patch_start[p]; i < m->patch_start[p + 1]; ++i) {
            unsigned int t = m->queue[i];
            if (!x->has_origin && meshfix__has_geometry(m, t)) {
                double zero[3] = {0, 0, 0};
                meshfix__load_corner(m, m->indices[3 * t], zero, x->origin);
                x->has_origin = 1;
            }
            meshfix__sum_unit_triangle(g, t, x->origin, x);
        }
        meshfix__add_prior(x, x->kept - kept, x->reversed - reversed);
    }
    /* the frame is monotonic: the box of the corners' images is the image
       of their box */
    for (u = 0; u < g->unit_count; ++u) {
        float *box = g->units[u].box;
        if (box[0] <= box[3]) {
            meshfix__frame_float(&g->bvh, box, box);
            meshfix__frame_float(&g->bvh, box + 3, box + 3);
        }
    }
}

/* ===== >>members ===== */

/* A unit must be one part. Coherence joins patches whose boundary edges
   run side by side, and their relative turn is evidence; but the parts of
   an assembly touch (a tower stands on its podium, a washer lies on the
   end of a tube), their edges run side by side too, and a join across them
   turns one part against the other: the unit's volume, or its majority,
   then turns a correct part over. So where a unit turned some of its
   members against the others, every member is asked on its own whether
   its front, as given, faces out of the unit's surface or into it: the
   parity of its rays' crossings of that surface, both ways, which does not
   depend on how anything is wound. Only the members near a turn are
   asked: those with a pair to a member of their unit turned the other
   way, across which a wrong join can have turned a part, and their
   neighbours, which the joins made again may route through (elsewhere the
   members agree, and their sides only cost rays: on a head cut into 500
   patches with a few folded fins, a third of the whole call went to
   asking every member). A patch beside a unit whose seam runs only
   roughly along it (a turn the joins refuse while neither side is known:
   a patch of a cut head) is asked against that unit's surface, a hole of
   which it fills, when the unit is closed but for its holes; a seam
   matched one way only (a part touching another) is not. The joins are
   then made again, strongest first, and a join that would put two
   members whose sides are known on opposite sides of their unit is
   refused. Clear normals of the
   caller's on a patch anchor it from the start (meshfix__anchor_normals). */

#define MESHFIX__STREAM_MEMBER 6
#define MESHFIX__MEMBER_SAMPLES 64 /* at most, per member */
#define MESHFIX__SIDE_CLEAR 0.5    /* a side is known when the mean's bound nearest 0 is this far from it */

/* One sample of member p against the surface of unit u: +1 when its
   front is outside that surface and its back inside, -1 the other way
   round, 0 when both sides agree (an open surface, a ray through a gap). */
MESHFIX__PRIVATE int meshfix__member_vote(const meshfix__geometry *g, unsigned int p, unsigned int u, unsigned int index)
{
    unsigned int state = meshfix__stream(g, p, MESHFIX__STREAM_MEMBER, index), t, side;
    float point[3], d[3], back[3];
    double n[3];
    int inside[2];
    meshfix__ray ray;
    /* sampled from its own unit's slots, its crossings counted on u's surface */
    t = meshfix__sample_slots(g, g->bvh.unit_first[g->patch_unit[p]], g->patch_first[p], g->patch_end[p], &state,
                              point, n);
    meshfix__random_direction(&state, d);
    back[0] = -d[0], back[1] = -d[1], back[2] = -d[2];
    for (side = 0; side < 2; ++side) {
        meshfix__setup_ray(&ray, point, side ? back : d, g->t_min, 1e30f);
        inside[side] = (int)(meshfix__crossings_of(g, &ray, &u, 1, t) & 1u);
    }
    if (n[0] * (double)d[0] + n[1] * (double)d[1] + n[2] * (double)d[2] >= 0)
        return meshfix__side_vote(inside[0], inside[1]);
    return meshfix__side_vote(inside[1], inside[0]);
}

typedef struct meshfix__member_sampling {
    const meshfix__geometry *g;
    unsigned int member, surface;
} meshfix__member_sampling;

MESHFIX__PRIVATE int meshfix__member_sample(void *context, unsigned int index)
{
    const meshfix__member_sampling *s = (const meshfix__member_sampling *)context;
    return meshfix__member_vote(s->g, s->member, s->surface, index);
}

MESHFIX__PRIVATE int meshfix__member_settled(void *context, const meshfix__votes *votes)
{
    return meshfix__level_known(votes, ((const meshfix__member_sampling *)context)->g->sigma, MESHFIX__SIDE_CLEAR);
}

/* The side of member p's front, in its consistent frame: +1 out of the
   surface of unit u, -1 into it, 0 when its crossings do not tell.
   *samples gets the number drawn. */
MESHFIX__PRIVATE signed char meshfix__member_side(const meshfix__geometry *g, unsigned int p, unsigned int u,
                                                 unsigned int *samples)
{
    meshfix__member_sampling sampling;
    meshfix__votes votes;
    sampling.g = g, sampling.member = p, sampling.surface = u;
    meshfix__sample_until_settled(&votes, MESHFIX__MEMBER_SAMPLES, meshfix__member_sample, meshfix__member_settled,
                                  &sampling);
    *samples = votes.n;
    if (!meshfix__level_reached(&votes, g->sigma, MESHFIX__SIDE_CLEAR))
        return 0;
    return (signed char)(meshfix__vote_mean(&votes) > 0 ? 1 : -1);
}

/* Per unit, for the fills: its boundary edges' length, the part of it
   that found a partner, and whether a member (not a fill) knows its side. */
typedef struct meshfix__unit_seams {
    double boundary, partnered;
    unsigned char sided;
} meshfix__unit_seams;

#define MESHFIX__FILL_CLOSED 0.9 /* a unit a fill is asked against: this share of its seams partnered */

/* Why a member is asked its side (meshfix__mark_frontier). */
#define MESHFIX__ASK_TURN 1     /* an end of a pair turned against itself within a unit */
#define MESHFIX__ASK_PARTNER 2  /* a partner of one in its unit */
#define MESHFIX__ASK_FILL 3     /* the small end of a refused turn between units, against the other's surface */
#define MESHFIX__ASK_ANCHOR 4   /* the large end of one whose small end's side is known */

typedef struct meshfix__member_task {
    const meshfix__geometry *g;
    const signed char *asked;    /* per patch: MESHFIX__ASK_*, 0 when not asked */
    int first_round;             /* asks all but the anchors (which need the fills' sides); else the anchors */
    const unsigned int *surface; /* per patch: the unit whose surface it is asked against */
    signed char *sides;          /* per patch: written where asked */
    unsigned int *samples;       /* per patch: written where asked */
} meshfix__member_task;

MESHFIX__PRIVATE void meshfix__member_chunk(void *context, size_t chunk)
{
    const meshfix__member_task *task = (const meshfix__member_task *)context;
    const meshfix__geometry *g = task->g;
    size_t p, end = (chunk + 1) * MESHFIX__UNITS_PER_TASK;
    for (p = chunk * MESHFIX__UNITS_PER_TASK; p < end && p < g->m->patch_count; ++p) {
        int asked = task->first_round ? task->asked[p] != 0 && task->asked[p] != MESHFIX__ASK_ANCHOR
                                      : task->asked[p] == MESHFIX__ASK_ANCHOR;
        if (!asked && !task->first_round)
            continue;
        task->sides[p] = 0;
        task->samples[p] = 0;
        if (asked && g->patch_first[p] < g->patch_end[p] && g->bvh.unit_root[task->surface[p]] != MESHFIX__NONE)
            task->sides[p] = meshfix__member_side(g, (unsigned int)p, task->surface[p], &task->samples[p]);
    }
}

/* Marks in `asked` the members near a turn: both ends of every pair
   within a unit whose members are turned against each other, then their
   partners in the unit. Also, of a pair between two units that would
   join them with one turned against the other but was refused for want
   of a known side (a patch alone beside a seam paired both ways that
   runs only roughly along), the end in the smaller unit, when the other
   unit is closed but for its holes (most of its seams partnered): it is
   asked against that unit's surface, a hole of which it fills (surface[p]
   gets the unit each is asked against). Returns 0 when there is none. */
MESHFIX__PRIVATE unsigned int meshfix__unit_slots(const meshfix__geometry *g, unsigned int u)
{
    return g->bvh.unit_first[u + 1] - g->bvh.unit_first[u];
}

/* Whether pair q is such a refused turn between units; its ends in the
   smaller and the larger unit. */
MESHFIX__PRIVATE int meshfix__refused_turn(const meshfix__geometry *g, const meshfix__pair *q, unsigned int *small,
                                          unsigned int *large)
{
    unsigned int ua = g->patch_unit[q->a], ub = g->patch_unit[q->b], na, nb;
    double c = q->c * (g->patch_turn[q->a] ? -1.0 : 1.0) * (g->patch_turn[q->b] ? -1.0 : 1.0);
    if (ua == ub || !(q->length > 0) || !(-c > MESHFIX__JOIN_STRENGTH * q->length) || q->ring ||
        !meshfix__paired_both_ways(q))
        return 0;
    na = meshfix__unit_slots(g, ua), nb = meshfix__unit_slots(g, ub);
    *small = na < nb || (na == nb && ua > ub) ? q->a : q->b;
    *large = *small == q->a ? q->b : q->a;
    return 1;
}

MESHFIX__PRIVATE int meshfix__mark_frontier(const meshfix__geometry *g, const meshfix__coherence *coherence,
                                           signed char *asked, unsigned int *surface, meshfix__unit_seams *seams)
{
    size_t i;
    unsigned int p, small, large;
    int any = 0;
    MESHFIX_MEMSET(asked, 0, g->m->patch_count);
    MESHFIX_MEMSET(seams, 0, g->unit_count * sizeof(meshfix__unit_seams));
    for (i = 0; i < coherence->segment_count; ++i) {
        const meshfix__segment *e = &coherence->segments[i];
        meshfix__unit_seams *x = &seams[g->patch_unit[e->patch]];
        x->boundary += e->length;
        x->partnered += e->partner != MESHFIX__NONE ? e->length : 0.0;
    }
    for (p = 0; p < g->m->patch_count; ++p)
        surface[p] = g->patch_unit[p];
    for (i = 0; i < coherence->pair_count; ++i) {
        unsigned int a = coherence->pairs[i].a, b = coherence->pairs[i].b;
        if (g->patch_unit[a] != g->patch_unit[b] || g->patch_turn[a] == g->patch_turn[b])
            continue;
        asked[a] = asked[b] = MESHFIX__ASK_TURN;
        any = 1;
    }
    for (i = 0; i < coherence->pair_count; ++i) {
        unsigned int a = coherence->pairs[i].a, b = coherence->pairs[i].b;
        if (g->patch_unit[a] != g->patch_unit[b])
            continue;
        if (asked[a] == MESHFIX__ASK_TURN && asked[b] == 0)
            asked[b] = MESHFIX__ASK_PARTNER;
        if (asked[b] == MESHFIX__ASK_TURN && asked[a] == 0)
            asked[a] = MESHFIX__ASK_PARTNER;
    }
    for (i = 0; i < coherence->pair_count; ++i)
        if (meshfix__refused_turn(g, &coherence->pairs[i], &small, &large) && asked[small] == 0 &&
            seams[g->patch_unit[large]].partnered >= MESHFIX__FILL_CLOSED * seams[g->patch_unit[large]].boundary) {
            asked[small] = MESHFIX__ASK_FILL;
            surface[small] = g->patch_unit[large];
            any = 1;
        }
    return any;
}

/* The large ends of the refused turns whose small end now knows its side,
   to be asked against their own unit: the join is checked only where both
   sides are known. Returns 0 when there is none. */
MESHFIX__PRIVATE int meshfix__mark_anchors(const meshfix__geometry *g, const meshfix__coherence *coherence,
                                          signed char *asked, const signed char *sides)
{
    size_t i;
    unsigned int small, large;
    int any = 0;
    for (i = 0; i < coherence->pair_count; ++i)
        if (meshfix__refused_turn(g, &coherence->pairs[i], &small, &large) && asked[small] == MESHFIX__ASK_FILL &&
            sides[small] != 0 && asked[large] == 0) {
            asked[large] = MESHFIX__ASK_ANCHOR;
            any = 1;
        }
    return any;
}

/* A fill forgets its side when no member of the other unit knows its own:
   the join is checked against the side its super-patch carries, and one
   known side alone would only lower the bar of the join. */
MESHFIX__PRIVATE void meshfix__drop_unanchored(const meshfix__geometry *g, const meshfix__coherence *coherence,
                                              const signed char *asked, signed char *sides, meshfix__unit_seams *seams)
{
    size_t i;
    unsigned int p, small, large;
    for (p = 0; p < g->m->patch_count; ++p)
        if (sides[p] != 0 && asked[p] != MESHFIX__ASK_FILL)
            seams[g->patch_unit[p]].sided = 1;
    for (i = 0; i < coherence->pair_count; ++i)
        if (meshfix__refused_turn(g, &coherence->pairs[i], &small, &large) && asked[small] == MESHFIX__ASK_FILL &&
            !seams[g->patch_unit[large]].sided)
            sides[small] = 0;
}

MESHFIX__PRIVATE void meshfix__ask_members(meshfix__member_task *task)
{
    size_t chunks = (task->g->m->patch_count + MESHFIX__UNITS_PER_TASK - 1) / MESHFIX__UNITS_PER_TASK;
    meshfix__run_tasks(task->g->o, meshfix__member_chunk, task, chunks);
}

/* The sides of the members near a turn (sides[p] 0 elsewhere);
   returns 0 when there is none, and adds the rays cast to *rays. */
MESHFIX__PRIVATE int meshfix__measure_members(const meshfix__geometry *g, const meshfix__coherence *coherence,
                                              signed char *asked, signed char *sides, unsigned int *surface,
                                              meshfix__unit_seams *seams, unsigned int *samples, size_t *rays)
{
    const meshfix__mesh *m = g->m;
    meshfix__member_task task;
    unsigned int p;
    if (!meshfix__mark_frontier(g, coherence, asked, surface, seams))
        return 0;
    task.g = g;
    task.asked = asked;
    task.surface = surface;
    task.sides = sides;
    task.samples = samples;
    task.first_round = 1;
    meshfix__ask_members(&task);
    task.first_round = 0;
    if (meshfix__mark_anchors(g, coherence, asked, sides))
        meshfix__ask_members(&task);
    meshfix__drop_unanchored(g, coherence, asked, sides, seams);
    for (p = 0; p < m->patch_count; ++p)
        *rays += 2 * (size_t)samples[p];
    return 1;
}

/* Clear normals of the caller's on a patch anchor it: the mean of their
   votes (area-weighted, in the patch's consistent frame) at least this. */
#define MESHFIX__NORMALS_CLEAR 0.5

MESHFIX__PRIVATE void meshfix__anchor_normals(const meshfix__geometry *g, meshfix__merge *merge)
{
    const meshfix__mesh *m = g->m;
    unsigned int p, i;
    if (m->options->evidence.triangle_normals == NULL && m->options->evidence.vertex_normals == NULL)
        return;
    for (p = 0; p < m->patch_count; ++p) {
        double vote = 0, usable = 0, n[3], area;
        for (i = m->patch_start[p]; i < m->patch_start[p + 1]; ++i) {
            unsigned int t = m->queue[i];
            meshfix__relative_normal(m, t, n, &area);
            if (!(area > 0) || !meshfix__normal_usable(m, t))
                continue;
            vote += meshfix__normal_vote(m, t, n) * area;
            usable += area;
        }
        if (usable > 0 && MESHFIX_FABS(vote) >= MESHFIX__NORMALS_CLEAR * usable)
            merge->normals[p] = (signed char)(vote > 0 ? 1 : -1);
    }
}

/* ===== >>evidence ===== */

/* How much each kind of evidence counts next to the prior (the area share
   facing the unit's majority side as given: 1 for a consistent unit):
   - the caller's normals, 2.5: they outweigh any geometry once the prior
     is gone, and lose to geometry and prior together (a file whose
     normals all point in while its winding and volume point out);
   - a volume (closed or nearly closed units), crossings of a shell around
     an open unit, or an open unit's own crossings when the scene was
     reversed, 2: enough to turn a consistent unit over;
   - an open unit's own crossings otherwise, and escaping rays, 1: they
     decide what its own triangles leave open, but never turn over a
     consistent open unit, because open surfaces face the way their
     authors chose (a terrain faces up although more rays escape below
     it; the walls of a pipe in a CFD case face the fluid inside). */
#define MESHFIX__WEIGHT_NORMALS 2.5
#define MESHFIX__WEIGHT_STRONG 2.0
#define MESHFIX__WEIGHT_WEAK 1.0

/* The weighing, in one place. Relative to the unit's majority side: the
   prior P in [0, 1], normals N in [-1, 1] and a geometric mean M in
   [-1, 1] with its standard error e give D = P + 2 N + W (M +- sigma e).
   The unit turns when even the bound that favours keeping is below 0;
   a tie keeps. Confidence is the bound on the side decided, up to 1. */
MESHFIX__PRIVATE void meshfix__weigh(const meshfix__unit *u, double sigma, double *low, double *high, int *majority)
{
    double total = u->prior_kept + u->prior_reversed, p = total > 0 ? (u->prior_kept - u->prior_reversed) / total : 0.0;
    double n = u->normals_area > 0 ? u->normals / u->normals_area : 0.0, d;
    *majority = p < 0 ? -1 : 1;
    d = (p < 0 ? -p : p) * (u->reversed_prior ? -1.0 : 1.0) + MESHFIX__WEIGHT_NORMALS * n * *majority +
        u->weight * u->mean * *majority;
    *low = d - u->weight * sigma * u->error;
    *high = d + u->weight * sigma * u->error;
}

MESHFIX__PRIVATE void meshfix__verdict_from_weights(meshfix__unit *u, double sigma)
{
    double low, high;
    int majority, flip;
    meshfix__weigh(u, sigma, &low, &high, &majority);
    flip = high < 0;
    u->turn = (unsigned int)((majority < 0) != flip);
    u->margin = u->confidence = (float)meshfix__mind(1.0, flip ? -high : meshfix__maxd(0.0, low));
}

/* AUTO's confidence: the probability that a unit's verdict is right. The
   weighing above decides; its margin is not a probability (a cut piece
   kept for lack of evidence has the margin of its consistent winding, 1,
   and is right as often as a coin). A logistic model over what was
   weighed, relative to the side decided, over how much of its seams
   found a partner, and over what the other units of the call say about
   the file gives one: its weights are fitted on the
   tune halves of the project's corpora (tests/eval/fit.c, `make fit`) and
   the held-out halves' reliability is in the README. The decision never
   reads it; min_confidence and the doubtful count do. */
#define MESHFIX__FEATURES 25
static const double meshfix__confidence_weights[MESHFIX__FEATURES] = {
    /* fitted: begin */
    3.9140, -0.4629, 0.7194, 0.2515, 0.3455, 0.5074, -1.6731, -2.0259,
    -0.2101, 2.6664, 7.9467, -0.7128, 1.2322, 7.2846, 0.8975, 0.2948,
    -0.4111, 0.8005, -0.3123, -1.8910, -1.0344, 1.5766, -1.8035, -1.2012,
    -0.2588
    /* fitted: end */
};

/* What the call's units say about the file as a whole: as shipped, few
   are turned or wound both ways; in a corrupted file many are. */
typedef struct meshfix__scene_context {
    double area, turned, inconsistent; /* all units' area; of it, turned against its majority; wound both ways */
} meshfix__scene_context;

MESHFIX__PRIVATE int meshfix__unit_turned(const meshfix__unit *u)
{
    return (u->kept < u->reversed) != (u->turn != 0);
}

MESHFIX__PRIVATE int meshfix__unit_inconsistent(const meshfix__unit *u)
{
    return u->kept > 0 && u->reversed > 0;
}

MESHFIX__PRIVATE void meshfix__add_to_context(meshfix__scene_context *c, const meshfix__unit *u)
{
    c->area += u->area;
    c->turned += meshfix__unit_turned(u) ? u->area : 0.0;
    c->inconsistent += meshfix__unit_inconsistent(u) ? u->area : 0.0;
}

MESHFIX__PRIVATE void meshfix__unit_features(const meshfix__unit *u, const meshfix__scene_context *c,
                                            double f[MESHFIX__FEATURES])
{
    double total = u->kept + u->reversed, side = u->turn ? -1.0 : 1.0;
    double given = total > 0 ? side * (u->kept - u->reversed) / total : 0.0;
    double others = c->area - u->area, share = c->area > 0 ? u->area / c->area : 1.0;
    double scale = share > 1e-12 ? MESHFIX_LOG(share) / MESHFIX_LOG(1e12) : -1.0;
    int none = u->kind == MESHFIX_EVIDENCE_NONE, consistent = !meshfix__unit_inconsistent(u);
    f[0] = 1.0;
    f[1] = (double)u->margin;
    f[2] = given;                     /* the winding as given, for the side decided */
    f[3] = (double)consistent;        /* one way throughout as given */
    f[4] = (double)(given < 0);       /* turned against its majority */
    f[5] = (double)(u->kind == MESHFIX_EVIDENCE_VOLUME);
    f[6] = (double)(u->kind == MESHFIX_EVIDENCE_PARITY);
    f[7] = (double)(u->kind == MESHFIX_EVIDENCE_VISIBILITY);
    f[8] = (double)(u->kind == MESHFIX_EVIDENCE_NORMALS);
    f[9] = u->weight > 0 ? side * u->mean : 0.0; /* the geometric vote, for the side decided */
    f[10] = u->normals_area > 0 ? side * u->normals / u->normals_area : 0.0;
    f[11] = (double)(u->closed == MESHFIX__CLOSED);
    f[12] = (double)(u->closed == MESHFIX__NEARLY_CLOSED || u->closed == MESHFIX__GAPPED);
    f[13] = scale < -1.0 ? 0.0 : scale; /* -1 .. 0: a millionth of the call's area is -0.5 */
    f[14] = (double)(u->cavity || u->reversed_prior);
    f[15] = (double)(none && consistent); /* kept as given for lack of evidence */
    f[16] = others > 0 ? (c->turned - (meshfix__unit_turned(u) ? u->area : 0.0)) / others : 0.0;
    f[17] = others > 0 ? (c->inconsistent - (consistent ? 0.0 : u->area)) / others : 0.0;
    f[18] = none ? f[16] : 0.0; /* kept as given where the file was turned elsewhere: a coin */
    f[19] = none ? f[17] : 0.0;
    f[20] = (double)(u->margin < 0.25f);
    f[21] = (double)(u->margin < 0.5f);
    f[22] = f[4] * (1.0 - f[16]); /* turned where the rest of the file was not */
    f[23] = f[6] * f[21];          /* crossings that barely outweighed the winding as given */
    f[24] = u->boundary > 0 ? u->unmatched / u->boundary : 0.0; /* share of its seams without a partner */
}

/* MESHFIX_FIT_ROW(patch, features, count): what tests/eval's programs
   record to fit the weights above, patch by patch (AUTO only). */
#ifdef MESHFIX_FIT_ROW
#define meshfix__fit_row(m, p, u, context)                                                                             \
    do {                                                                                                               \
        if ((m)->policy == MESHFIX_POLICY_AUTO) {                                                                      \
            double fit_features_[MESHFIX__FEATURES];                                                                   \
            meshfix__unit_features((u), (context), fit_features_);                                                     \
            MESHFIX_FIT_ROW((p), fit_features_, MESHFIX__FEATURES);                                                    \
        }                                                                                                              \
    } while (0)
#else
#define meshfix__fit_row(m, p, u, context) ((void)0)
#endif

MESHFIX__PRIVATE float meshfix__calibrate(const meshfix__unit *u, const meshfix__scene_context *c)
{
    double f[MESHFIX__FEATURES], z = 0.0;
    int i;
    meshfix__unit_features(u, c, f);
    for (i = 0; i < MESHFIX__FEATURES; ++i)
        z += meshfix__confidence_weights[i] * f[i];
    return (float)(1.0 / (1.0 + MESHFIX_EXP(-z)));
}

/* Whether evidence of weight w could turn the unit at all. */
MESHFIX__PRIVATE int meshfix__could_turn(const meshfix__unit *u, double w)
{
    meshfix__unit probe = *u;
    double low, high;
    int majority;
    probe.weight = w;
    probe.error = 0;
    probe.mean = u->prior_kept >= u->prior_reversed ? -1.0 : 1.0; /* all of it against the majority */
    meshfix__weigh(&probe, 0.0, &low, &high, &majority);
    return high < 0;
}

/* Samples per unit: a batch at a time until the verdict is settled, at
   most a share of the budget by area (at least 4 batches, at most 4096). */
MESHFIX__PRIVATE unsigned int meshfix__ray_cap(const meshfix__geometry *g, const meshfix__unit *u, double total_area)
{
    double share = total_area > 0 ? (double)g->ray_budget * u->area / total_area : 0.0;
    share = share < 4 * MESHFIX__BATCH ? 4 * MESHFIX__BATCH : share > 4096 ? 4096 : share;
    return (unsigned int)share;
}

/* Significant: the mean's bound nearest 0 is at least a tenth away; for
   escaping rays, about a third: hills hide part of a terrain's top from the sky
   and nothing hides its underside, yet it faces up. An enclosed side (the
   inside of a car body in a soup) blocks most of its rays. */
#define MESHFIX__SIGNIFICANT 0.1
#define MESHFIX__SIGNIFICANT_ESCAPE 0.35
MESHFIX__PRIVATE double meshfix__significance_floor(const meshfix__unit *u)
{
    return u->kind == MESHFIX_EVIDENCE_VISIBILITY ? MESHFIX__SIGNIFICANT_ESCAPE : MESHFIX__SIGNIFICANT;
}

MESHFIX__PRIVATE int meshfix__significant(const meshfix__unit *u, double sigma)
{
    return MESHFIX_FABS(u->mean) - sigma * u->error >= meshfix__significance_floor(u);
}

/* Whether sampling can stop: the verdict is settled and, where it turns
   the unit, the evidence is significant or cannot become so within its
   bounds. A turn on evidence short of significance is not taken (the
   unit keeps), so stopping at a settled turn threw away what a few more
   batches would have shown. */
MESHFIX__PRIVATE int meshfix__sampled_enough(const meshfix__unit *u, double sigma)
{
    double low, high;
    int majority;
    meshfix__weigh(u, sigma, &low, &high, &majority);
    if (low >= 0)
        return 1;
    if (high >= 0)
        return 0;
    return meshfix__significant(u, sigma) || MESHFIX_FABS(u->mean) + sigma * u->error < meshfix__significance_floor(u);
}

/* A unit's measurement: a sample of one kind of evidence (nesting for
   VOLUME, else both sides of a point), its unit described by the votes so
   far (their mean times `sign`) for the rule that stops. */
typedef struct meshfix__unit_sampling {
    const meshfix__geometry *g;
    meshfix__unit *u;
    unsigned int index, kind, count;
    const unsigned int *list;
    double sign;
} meshfix__unit_sampling;

MESHFIX__PRIVATE int meshfix__unit_sample(void *context, unsigned int i)
{
    const meshfix__unit_sampling *s = (const meshfix__unit_sampling *)context;
    if (s->kind == MESHFIX_EVIDENCE_VOLUME)
        return meshfix__sample_nesting(s->g, s->index, i, s->list, s->count);
    return meshfix__sample_sides(s->g, s->index, s->kind, i, s->list, s->count);
}

MESHFIX__PRIVATE void meshfix__describe_unit(const meshfix__unit_sampling *s, const meshfix__votes *votes)
{
    s->u->mean = s->sign * meshfix__vote_mean(votes);
    s->u->error = meshfix__vote_error(votes);
}

/* The verdict settled (meshfix__sampled_enough), or unanimous past 8
   batches: unanimous votes cannot move their mean, and more of them would
   only settle a tie, which keeps anyway. */
MESHFIX__PRIVATE int meshfix__verdict_settled(void *context, const meshfix__votes *votes)
{
    const meshfix__unit_sampling *s = (const meshfix__unit_sampling *)context;
    meshfix__describe_unit(s, votes);
    return meshfix__sampled_enough(s->u, s->g->sigma) ||
           (votes->n >= 8 * MESHFIX__BATCH && (votes->plus == votes->n || votes->minus == votes->n));
}

/* Samples evidence of one kind for unit u until its verdict is settled or
   the cap is reached; the unit's mean (the votes' mean times `sign`),
   error and weight describe it. Returns the votes' mean. */
MESHFIX__PRIVATE double meshfix__measure(const meshfix__geometry *g, unsigned int index, meshfix__unit *u,
                                        unsigned int kind, double weight, double sign, const unsigned int *list,
                                        unsigned int count, unsigned int cap)
{
    meshfix__unit_sampling sampling;
    meshfix__votes votes;
    sampling.g = g, sampling.u = u, sampling.index = index, sampling.kind = kind;
    sampling.list = list, sampling.count = count, sampling.sign = sign;
    u->weight = weight;
    u->kind = (unsigned char)kind;
    meshfix__sample_until_settled(&votes, cap, meshfix__unit_sample, meshfix__verdict_settled, &sampling);
    u->rays += (kind == MESHFIX_EVIDENCE_VOLUME ? 1u : 2u) * (size_t)votes.n;
    meshfix__describe_unit(&sampling, &votes);
    return meshfix__vote_mean(&votes);
}

/* An edge of unit u passes through a triangle of unit e. */
MESHFIX__PRIVATE int meshfix__crosses(const meshfix__geometry *g, unsigned int u, unsigned int e, size_t *rays)
{
    const meshfix__bvh *b = &g->bvh;
    unsigned int i, k;
    meshfix__query q;
    q.mode = MESHFIX__ANY_HIT;
    q.skip = MESHFIX__NONE;
    for (i = b->unit_first[u]; i < b->unit_first[u + 1]; ++i) {
        const float *c = b->corners + 9 * (size_t)i;
        for (k = 0; k < 3; ++k) {
            const float *a = c + 3 * k, *d = c + 3 * ((k + 1) % 3);
            float along[3];
            meshfix__ray ray;
            along[0] = d[0] - a[0], along[1] = d[1] - a[1], along[2] = d[2] - a[2];
            meshfix__setup_ray(&ray, a, along, 1e-4f, 1.0f - 1e-4f);
            ++*rays;
            if (meshfix__trace(b, b->unit_root[e], &ray, &q))
                return 1;
        }
    }
    return 0;
}

/* The closed and nearly closed units whose box contains unit u's: the
   only ones that can enclose it (a cost per unit that does not grow with
   the scene, where rays to infinity through thousands of shells did). */
#define MESHFIX__MOST_ENCLOSERS 64
MESHFIX__PRIVATE unsigned int meshfix__enclosers(const meshfix__geometry *g, unsigned int u, unsigned int *out)
{
    unsigned int n, i, kept = 0;
    n = meshfix__boxes_around(g->shell_nodes, g->shell_root, g->shell_ids, g->units[u].box, 0, out,
                              MESHFIX__MOST_ENCLOSERS);
    for (i = 0; i < n; ++i)
        if (out[i] != u && g->bvh.unit_root[out[i]] != MESHFIX__NONE)
            out[kept++] = out[i];
    return kept;
}

/* Whether unit u crosses a shell: the shells whose box meets u's, each
   asked whether an edge of u passes through it. */
MESHFIX__PRIVATE int meshfix__crosses_a_shell(const meshfix__geometry *g, unsigned int u)
{
    unsigned int list[MESHFIX__MOST_ENCLOSERS], n, i;
    n = meshfix__boxes_around(g->shell_nodes, g->shell_root, g->shell_ids, g->units[u].box, 1, list,
                              MESHFIX__MOST_ENCLOSERS);
    for (i = 0; i < n; ++i)
        if (list[i] != u && meshfix__crosses(g, u, list[i], &g->units[u].rays))
            return 1;
    return 0;
}

/* A gapped unit is nearly closed when its own crossings say that one of
   its sides is inside and the other outside: their mean vote, at least
   MESHFIX__GAP_CLOSED away from 0 within its bounds. Its sign then tells
   its outside. */
#define MESHFIX__GAP_CLOSED 0.6

MESHFIX__PRIVATE int meshfix__gap_settled(void *context, const meshfix__votes *votes)
{
    return meshfix__level_known(votes, ((const meshfix__unit_sampling *)context)->g->sigma, MESHFIX__GAP_CLOSED);
}

MESHFIX__PRIVATE void meshfix__gap_evidence(const meshfix__geometry *g, unsigned int index, double total_area)
{
    meshfix__unit *u = &g->units[index];
    meshfix__unit_sampling sampling;
    meshfix__votes votes;
    sampling.g = g, sampling.u = u, sampling.index = index, sampling.kind = MESHFIX_EVIDENCE_PARITY;
    sampling.list = &index, sampling.count = 1, sampling.sign = 1.0;
    meshfix__sample_until_settled(&votes, meshfix__ray_cap(g, u, total_area), meshfix__unit_sample,
                                  meshfix__gap_settled, &sampling);
    u->rays += 2 * (size_t)votes.n;
    meshfix__describe_unit(&sampling, &votes);
    u->closed = (unsigned char)(meshfix__level_reached(&votes, g->sigma, MESHFIX__GAP_CLOSED) ? MESHFIX__NEARLY_CLOSED
                                                                                           : MESHFIX__OPEN);
}

/* A closed or nearly closed unit faces out (positive volume, or the side
   its own crossings found outside) unless it is a cavity: inside an odd
   number of the shells around it, crossing no shell (shells that cross
   each other are separate bodies: each faces out). Its evidence is that
   side times the nesting vote. Under AUTO a shell inside another that is
   wound one way throughout, as given, keeps that way: facing out (an eye
   in a head, a sealed slot in a part) or in (a cavity), it is what its
   author made; its nesting counts with the weight of open evidence, which
   turns it only when the scene was reversed (its prior then counts
   against it). A shell wound both ways as given, and every shell under
   OUTWARD, faces as its nesting says. */
MESHFIX__PRIVATE void meshfix__shell_evidence(const meshfix__geometry *g, unsigned int index, double total_area)
{
    meshfix__unit *u = &g->units[index];
    unsigned int list[MESHFIX__MOST_ENCLOSERS], n = meshfix__enclosers(g, index, list);
    double side = (u->closed == MESHFIX__CLOSED ? u->volume : u->mean) > 0 ? 1.0 : -1.0, inside;
    int authored;
    u->outward = (signed char)side;
    u->kind = MESHFIX_EVIDENCE_VOLUME;
    u->weight = MESHFIX__WEIGHT_STRONG;
    u->mean = side;
    u->error = 0.0;
    if (n == 0)
        return;
    /* the nesting vote (+1 inside) turns the side around */
    authored = g->m->policy == MESHFIX_POLICY_AUTO && (u->kept == 0 || u->reversed == 0);
    inside = meshfix__measure(g, index, u, MESHFIX_EVIDENCE_VOLUME, authored ? MESHFIX__WEIGHT_WEAK : MESHFIX__WEIGHT_STRONG,
                              -side, list, n, meshfix__ray_cap(g, u, total_area));
    /* inside: unless it crosses a shell (asked only now: it costs a ray per edge) */
    if (inside > 0 && meshfix__crosses_a_shell(g, index))
        inside = -1.0;
    u->cavity = (unsigned char)(inside - g->sigma * u->error > 0);
    if (!u->cavity) { /* not surely inside (a part in a pocket sees out): its volume, at full weight */
        u->mean = side;
        u->error = 0.0;
        u->weight = MESHFIX__WEIGHT_STRONG;
    }
}

/* An open unit (AUTO): the first kind of evidence that is significant,
   each asked only if it could still change the verdict. In a reversed
   scene its majority counts against it, and its own crossings as much as
   a volume. */
MESHFIX__PRIVATE void meshfix__open_evidence(const meshfix__geometry *g, unsigned int index, double total_area)
{
    meshfix__unit *u = &g->units[index];
    unsigned int list[MESHFIX__MOST_ENCLOSERS], n = meshfix__enclosers(g, index, list);
    unsigned int cap = meshfix__ray_cap(g, u, total_area);
    double own_weight = g->reversed_scene ? MESHFIX__WEIGHT_STRONG : MESHFIX__WEIGHT_WEAK;
    u->reversed_prior = (unsigned char)g->reversed_scene;
    u->kind = MESHFIX_EVIDENCE_NONE;
    u->mean = u->error = u->weight = 0.0;
    if (n != 0 && meshfix__could_turn(u, MESHFIX__WEIGHT_STRONG)) {
        meshfix__measure(g, index, u, MESHFIX_EVIDENCE_PARITY, MESHFIX__WEIGHT_STRONG, 1.0, list, n, cap);
        if (meshfix__significant(u, g->sigma))
            return;
    }
    if (meshfix__could_turn(u, own_weight)) {
        meshfix__measure(g, index, u, MESHFIX_EVIDENCE_PARITY, own_weight, 1.0, &index, 1, cap);
        if (meshfix__significant(u, g->sigma))
            return;
    }
    if (g->bvh.top != MESHFIX__NONE && meshfix__could_turn(u, MESHFIX__WEIGHT_WEAK)) {
        meshfix__measure(g, index, u, MESHFIX_EVIDENCE_VISIBILITY, MESHFIX__WEIGHT_WEAK, 1.0, NULL, 0, cap);
        if (meshfix__significant(u, g->sigma))
            return;
    }
    u->kind = MESHFIX_EVIDENCE_NONE;
    u->mean = u->error = u->weight = 0.0;
}

/* The phases of gathering, in order: gapped units to nearly closed or
   open; then shells (nesting); then open units. */
#define MESHFIX__PHASE_GAPS 0
#define MESHFIX__PHASE_SHELLS 1
#define MESHFIX__PHASE_OPEN 2

typedef struct meshfix__evidence_task {
    meshfix__geometry *g;
    double total_area;
    int phase;
} meshfix__evidence_task;

MESHFIX__PRIVATE void meshfix__evidence_chunk(void *context, size_t chunk)
{
    const meshfix__evidence_task *task = (const meshfix__evidence_task *)context;
    meshfix__geometry *g = task->g;
    size_t u, end = (chunk + 1) * MESHFIX__UNITS_PER_TASK;
    for (u = chunk * MESHFIX__UNITS_PER_TASK; u < end && u < g->unit_count; ++u) {
        int closed = g->units[u].closed;
        if (g->bvh.unit_first[u] == g->bvh.unit_first[u + 1])
            continue;
        if (task->phase == MESHFIX__PHASE_GAPS && closed == MESHFIX__GAPPED)
            meshfix__gap_evidence(g, (unsigned int)u, task->total_area);
        else if (task->phase == MESHFIX__PHASE_SHELLS && closed >= MESHFIX__NEARLY_CLOSED)
            meshfix__shell_evidence(g, (unsigned int)u, task->total_area);
        else if (task->phase == MESHFIX__PHASE_OPEN && closed == MESHFIX__OPEN)
            meshfix__open_evidence(g, (unsigned int)u, task->total_area);
    }
}

/* The units' evidence in chunks, on the caller's threads if it gave a
   parallel_for: each unit is measured alone, so the order does not
   matter. */
MESHFIX__PRIVATE void meshfix__gather_evidence(meshfix__geometry *g, int phase, double total_area)
{
    meshfix__evidence_task task;
    size_t chunks = (g->unit_count + MESHFIX__UNITS_PER_TASK - 1) / MESHFIX__UNITS_PER_TASK;
    task.g = g;
    task.total_area = total_area;
    task.phase = phase;
    meshfix__run_tasks(g->o, meshfix__evidence_chunk, &task, chunks);
}

/* The trees every measurement may walk, built before the measuring runs
   on several threads. A unit's tree reads and writes only its own slots
   and nodes, so the units are built as tasks of parallel_for (each the
   same tree however the tasks run). Units are dealt to tasks in strides,
   so that one task does not get all the large ones. */
#define MESHFIX__TREE_TASKS 64

typedef struct meshfix__tree_task {
    meshfix__bvh *bvh;
    const meshfix__mesh *m;
    unsigned int unit_count;
} meshfix__tree_task;

MESHFIX__PRIVATE void meshfix__tree_chunk(void *context, size_t chunk)
{
    const meshfix__tree_task *task = (const meshfix__tree_task *)context;
    unsigned int u;
    for (u = (unsigned int)chunk; u < task->unit_count; u += MESHFIX__TREE_TASKS)
        meshfix__unit_tree(task->bvh, task->m, u);
}

MESHFIX__PRIVATE void meshfix__build_unit_trees(meshfix__geometry *g)
{
    meshfix__tree_task task;
    size_t chunks = g->unit_count < MESHFIX__TREE_TASKS ? g->unit_count : MESHFIX__TREE_TASKS;
    unsigned int u;
    /* the large units first, one at a time, each build on every thread */
    if (g->o->parallel_for != NULL)
        for (u = 0; u < g->unit_count; ++u)
            if (g->bvh.unit_first[u + 1] - g->bvh.unit_first[u] >= MESHFIX__PARALLEL_UNIT)
                meshfix__build_unit(&g->bvh, g->m, u, g->o);
    task.bvh = &g->bvh;
    task.m = g->m;
    task.unit_count = g->unit_count;
    meshfix__run_tasks(g->o, meshfix__tree_chunk, &task, chunks);
}

/* The tree over the boxes of the closed and nearly closed units. */
MESHFIX__PRIVATE void meshfix__index_shells(meshfix__geometry *g)
{
    meshfix__builder k;
    unsigned int u, n = 0;
    int c;
    g->shell_root = MESHFIX__NONE;
    for (u = 0; u < g->unit_count; ++u) {
        float *slot = g->unit_slots + 9 * (size_t)n;
        if (g->units[u].closed < MESHFIX__NEARLY_CLOSED || g->bvh.unit_root[u] == MESHFIX__NONE)
            continue;
        MESHFIX_MEMCPY(slot, g->units[u].box, 6 * sizeof(float));
        for (c = 0; c < 3; ++c)
            slot[MESHFIX__SLOT_CENTROID + c] = 0.5f * (slot[c] + slot[3 + c]);
        g->shell_ids[n++] = u;
    }
    if (n == 0)
        return;
    k.slots = g->unit_slots;
    k.ids = g->shell_ids;
    k.nodes = g->shell_nodes;
    k.next_node = 0;
    k.leaf = 1;
    g->shell_root = meshfix__build_tree(&k, 0, n);
}

/* The scene was reversed when its closed parts were: at least two units
   with a volume decided, and at least 90% of their area turned over. Then
   the open parts are most likely reversed too: they turn over unless
   their own evidence says otherwise. A shell whose normals agree with its
   winding (their mean vote above a half) was authored facing that way
   (the rooms of a building model, wound and lit from inside): it counts
   as not turned, so it vetoes. */
#define MESHFIX__REVERSED_SHELLS 2
#define MESHFIX__REVERSED_SHARE 0.9
#define MESHFIX__AUTHORED_NORMALS 0.5
MESHFIX__PRIVATE unsigned int meshfix__scene_reversed(const meshfix__geometry *g)
{
    double turned = 0, all = 0;
    unsigned int u, count = 0;
    for (u = 0; u < g->unit_count; ++u) {
        const meshfix__unit *x = &g->units[u];
        int majority = x->prior_kept >= x->prior_reversed ? 1 : -1;
        double normals = x->normals_area > 0 ? x->normals / x->normals_area : 0.0;
        if (x->kind != MESHFIX_EVIDENCE_VOLUME || !meshfix__significant(x, g->sigma))
            continue;
        /* what the geometry says (a cavity in, the rest out), against the
           side most of it faces as given */
        count++;
        all += x->area;
        turned += x->mean * majority < 0 && normals * majority <= MESHFIX__AUTHORED_NORMALS ? x->area : 0.0;
    }
    return count >= MESHFIX__REVERSED_SHELLS && turned >= MESHFIX__REVERSED_SHARE * all;
}

/* VISIBILITY: one sample pair of patch p; counts the side(s) that escape. */
MESHFIX__PRIVATE int meshfix__sample_escape(const meshfix__geometry *g, unsigned int p, unsigned int index,
                                           unsigned int *front, unsigned int *back)
{
    unsigned int state = meshfix__stream(g, p, MESHFIX_EVIDENCE_VISIBILITY, index), t, side;
    float point[3], d[3], reverse[3];
    double n[3];
    int blocked[2], facing;
    meshfix__ray ray;
    meshfix__query q;
    t = meshfix__sample_point(g, p, &state, point, n);
    meshfix__random_direction(&state, d);
    reverse[0] = -d[0], reverse[1] = -d[1], reverse[2] = -d[2];
    q.mode = MESHFIX__ANY_HIT;
    q.skip = t;
    for (side = 0; side < 2; ++side) {
        meshfix__setup_ray(&ray, point, side ? reverse : d, g->t_min, 1e30f);
        blocked[side] = meshfix__trace(&g->bvh, g->bvh.top, &ray, &q);
    }
    facing = n[0] * (double)d[0] + n[1] * (double)d[1] + n[2] * (double)d[2] >= 0 ? 0 : 1; /* the front's ray */
    *front += (unsigned int)!blocked[facing];
    *back += (unsigned int)!blocked[1 - facing];
    return meshfix__side_vote(blocked[facing], blocked[1 - facing]);
}
/* ===== >>decide ===== */

/* A patch's turn, start to end. The policy's traits (meshfix__policies)
   say whether it needs the geometric stage. If it does (AUTO, OUTWARD,
   VISIBILITY), meshfix__decide_by_geometry (>>geometry) forms units,
   gathers their evidence (>>members, >>evidence) and decides each unit
   (meshfix__decide_unit, or VISIBILITY's merge); meshfix__apply_units
   writes every member's turn, confidence and evidence once, with
   meshfix__decide. Then, for every policy, meshfix__patch_verdict reads
   that decision or, for the policies that decide patch by patch (SEED,
   MAJORITY, SDF, UP, NORMALS, and one closed shell alone), makes it with
   meshfix__decide_patch; min_confidence is applied there, and only there;
   meshfix__turn_patch marks the triangles. The report (>>report) counts
   what was decided and never decides. */

/* One verdict per policy. Every policy weighs a unit (a patch, or for
   AUTO, OUTWARD and VISIBILITY a super-patch) from what it knows: its
   area facing each way as given (the prior), and the evidence the policy
   looks at. Policies that follow one kind of evidence alone (VISIBILITY,
   UP, NORMALS, SDF) take its side when it is significant and the
   majority otherwise; AUTO and OUTWARD weigh it against the prior. */

/* The side `mean` points to when |mean| - sigma * error exceeds `least`;
   otherwise the majority side, kept for lack of evidence. */
MESHFIX__PRIVATE void meshfix__verdict_follow(meshfix__unit *u, double sigma, double least)
{
    double margin = MESHFIX_FABS(u->mean) - sigma * u->error;
    if (margin > least) {
        u->turn = u->mean < 0;
        u->margin = u->confidence = (float)meshfix__mind(1.0, margin);
        return;
    }
    u->weight = 0;
    u->kind = MESHFIX_EVIDENCE_NONE;
    meshfix__verdict_from_weights(u, sigma);
}

/* A patch's unit from its sums, for the policies that decide patch by
   patch (its frame is its seed's). */
MESHFIX__PRIVATE void meshfix__patch_unit(const meshfix__patch_sums *s, meshfix__unit *u)
{
    MESHFIX_MEMSET(u, 0, sizeof(*u));
    u->kept = u->prior_kept = s->weight_kept;
    u->reversed = u->prior_reversed = s->weight_reversed;
    u->normals = s->normals;
    u->normals_area = s->normals_area;
    u->area = s->area;
    u->volume = s->volume_relative;
}

/* SEED: the seed triangle's way. MAJORITY: the prior alone. SDF: the
   gradient's vote over the patch. UP: the lean of its area-weighted normal
   along the axis (none for a closed shell: zero up to rounding). NORMALS:
   the caller's normals. The rest were decided per unit before. */
#define MESHFIX__UP_LEAST 1e-6     /* UP: a smaller lean is a closed shell's rounding */
#define MESHFIX__NORMALS_LEAST 0.05 /* NORMALS: the least mean agreement of the normals that decides */
MESHFIX__PRIVATE void meshfix__decide_patch(const meshfix__mesh *m, unsigned int p, int policy,
                                           const meshfix__patch_sums *s, double sigma, meshfix__unit *u)
{
    const meshfix_options *o = m->options;
    meshfix__patch_unit(s, u);
    u->kind = MESHFIX_EVIDENCE_POLICY;
    if (policy == MESHFIX_POLICY_SEED) {
        u->turn = 0;
        u->confidence = 1.0f;
    } else if (policy == MESHFIX_POLICY_SDF) {
        u->mean = s->area > 0 ? s->sdf_vote / s->area : 0.0;
        meshfix__verdict_follow(u, sigma, 0.0);
    } else if (policy == MESHFIX_POLICY_UP) {
        double up[3], length;
        up[0] = (double)o->up[0], up[1] = (double)o->up[1], up[2] = (double)o->up[2];
        length = MESHFIX_SQRT(meshfix__dot3(up, up));
        u->mean = s->area > 0 ? meshfix__dot3(s->normal, up) / length / s->area : 0.0;
        meshfix__verdict_follow(u, sigma, MESHFIX__UP_LEAST);
    } else if (policy == MESHFIX_POLICY_NORMALS) {
        u->mean = s->normals_area > 0 ? s->normals / s->normals_area : 0.0;
        u->kind = MESHFIX_EVIDENCE_NORMALS;
        meshfix__verdict_follow(u, sigma, MESHFIX__NORMALS_LEAST);
    } else {
        /* MAJORITY; AUTO and OUTWARD on one closed shell alone: its volume */
        u->kind = MESHFIX_EVIDENCE_NONE;
        if (policy != MESHFIX_POLICY_MAJORITY && meshfix__is_closed_orientable(m, p) &&
            meshfix__volume_is_meaningful(s->volume_relative, s->area)) {
            u->kind = MESHFIX_EVIDENCE_VOLUME;
            u->weight = MESHFIX__WEIGHT_STRONG;
            u->mean = s->volume_relative > 0 ? 1.0 : -1.0;
            u->closed = MESHFIX__CLOSED;
        }
        meshfix__verdict_from_weights(u, sigma);
        if (policy == MESHFIX_POLICY_AUTO) {
            meshfix__scene_context alone = {0, 0, 0};
            meshfix__add_to_context(&alone, u);
            u->confidence = meshfix__calibrate(u, &alone);
            meshfix__fit_row(m, p, u, &alone);
        }
    }
}

/* AUTO and OUTWARD weigh each unit's evidence against its prior; where
   no geometric vote was significant, the unit is said to be decided by the
   caller's normals when they agree this much either way. */
#define MESHFIX__NORMALS_DECIDE 0.1
MESHFIX__PRIVATE void meshfix__decide_unit(meshfix__unit *u, double sigma)
{
    meshfix__verdict_from_weights(u, sigma);
    if (!meshfix__significant(u, sigma)) {
        int by_normals = u->normals_area > 0 && MESHFIX_FABS(u->normals / u->normals_area) >= MESHFIX__NORMALS_DECIDE;
        u->kind = by_normals ? MESHFIX_EVIDENCE_NORMALS : MESHFIX_EVIDENCE_NONE;
    }
}

MESHFIX__PRIVATE void meshfix__decide(meshfix__mesh *m, unsigned int p, unsigned int turn, float confidence,
                                     unsigned char kind)
{
    m->patch_bits[p] = (unsigned char)(m->patch_bits[p] | MESHFIX__PATCH_DECIDED | (turn ? MESHFIX__PATCH_FLIP : 0u));
    m->confidence[p] = confidence;
    m->patch_kind[p] = kind;
}

/* Each patch takes its unit's verdict, through its frame in the unit. */
MESHFIX__PRIVATE void meshfix__apply_units(meshfix__geometry *g, const meshfix__scene_context *context)
{
    meshfix__mesh *m = g->m;
    unsigned int p;
    for (p = 0; p < m->patch_count; ++p) {
        const meshfix__unit *u = &g->units[g->patch_unit[p]];
        meshfix__decide(m, p, g->patch_turn[p] ^ u->turn, u->confidence, u->kind);
        meshfix__fit_row(m, p, u, context);
    }
    (void)context;
}

/* The verdict of patch p: the geometric policies decided it per unit
   before; the others decide it here from its sums. A verdict less
   confident than min_confidence leaves the patch facing the way most of
   its area faces. */
MESHFIX__PRIVATE void meshfix__patch_verdict(const meshfix__mesh *m, unsigned int p, int policy,
                                            const meshfix__patch_sums *s, meshfix__unit *u)
{
    const meshfix_options *o = m->options;
    double sigma = (double)o->evidence.sigma;
    if (m->patch_bits[p] & MESHFIX__PATCH_DECIDED) {
        meshfix__patch_unit(s, u);
        u->turn = (m->patch_bits[p] & MESHFIX__PATCH_FLIP) != 0;
        u->confidence = m->confidence[p];
        u->kind = m->patch_kind[p];
    } else {
        meshfix__decide_patch(m, p, policy, s, sigma, u);
    }
    if (u->confidence < o->evidence.min_confidence) {
        u->turn = s->weight_kept < s->weight_reversed;
        u->kind = MESHFIX_EVIDENCE_NONE;
    }
}

/* Marks the triangles of patch p that the verdict turns (each relative to
   its patch's consistent frame; SDF per triangle by its own gradient);
   returns how many flip. */
MESHFIX__PRIVATE size_t meshfix__turn_patch(meshfix__mesh *m, unsigned int p, int policy, unsigned int turn,
                                           meshfix_report *r)
{
    size_t i, flipped = 0;
    for (i = m->patch_start[p]; i < m->patch_start[p + 1]; ++i) {
        unsigned int t = m->queue[i];
        unsigned int flip = (m->tri_bits[t] & MESHFIX__TRI_RELATIVE) ^ turn;
        if (meshfix__policies[policy].needs_distance)
            flip = meshfix__sdf_flip(m, t, flip, r);
        m->tri_bits[t] = (unsigned short)(m->tri_bits[t] | (flip ? MESHFIX__TRI_FLIP : 0u));
        flipped += flip;
        if (flip && (m->options->evidence.triangle_normals != NULL || m->options->evidence.vertex_normals != NULL))
            r->evidence.triangles_against_normals += (size_t)meshfix__normal_agrees(m, t);
    }
    return flipped;
}

/* ===== >>geometry ===== */

/* A unit's slots patch by patch (each patch's in its flood-fill order),
   so that the samples of one member can be drawn from its own slots. */
MESHFIX__PRIVATE void meshfix__slots_by_patch(meshfix__geometry *g)
{
    const meshfix__mesh *m = g->m;
    meshfix__bvh *b = &g->bvh;
    unsigned int *next = g->unit_ids, p, i, u; /* scratch until the trees over units are built */
    for (u = 0; u < g->unit_count; ++u)
        next[u] = b->unit_first[u];
    for (p = 0; p < m->patch_count; ++p) {
        u = g->patch_unit[p];
        g->patch_first[p] = next[u];
        for (i = m->patch_start[p]; i < m->patch_start[p + 1]; ++i)
            if (g->triangle_unit[m->queue[i]] != MESHFIX__NONE)
                b->by_index[next[u]++] = m->queue[i];
        g->patch_end[p] = next[u];
    }
    MESHFIX_MEMCPY(b->order, b->by_index, b->count * sizeof(unsigned int));
}

/* Each triangle's unit (none without an area), by chunks of triangles. */
MESHFIX__PRIVATE void meshfix__unit_of_chunk(void *stage, size_t chunk)
{
    const meshfix__stage *s = (const meshfix__stage *)stage;
    const meshfix__geometry *g = (const meshfix__geometry *)s->context;
    const meshfix__mesh *m = g->m;
    size_t t, end;
    for (meshfix__chunk_range(s, chunk, &t, &end); t < end; ++t)
        g->triangle_unit[t] = meshfix__has_area(m, (unsigned int)t) ? g->patch_unit[m->tri_patch[t]] : MESHFIX__NONE;
}

/* Units known: the trees' slots, per unit, and the scratch for trees over
   units. Returns 0 when out of memory. */
MESHFIX__PRIVATE int meshfix__prepare_units(meshfix__geometry *g)
{
    meshfix__mesh *m = g->m;
    const meshfix__arena *a = &g->arena;
    size_t units = g->unit_count;
    meshfix__run_stage(g->o, meshfix__unit_of_chunk, g, m->triangle_count, NULL);
    g->units = (meshfix__unit *)meshfix__array(a, a->plan.units, units);
    g->unit_slots = (float *)meshfix__array(a, a->plan.unit_slots, 9 * units);
    g->unit_ids = (unsigned int *)meshfix__array(a, a->plan.unit_ids, units);
    g->shell_nodes = (meshfix__node *)meshfix__array(a, a->plan.shell_nodes, units);
    g->shell_ids = (unsigned int *)meshfix__array(a, a->plan.shell_ids, units);
    if (!g->units || !g->unit_slots || !g->unit_ids || !g->shell_nodes || !g->shell_ids)
        return 0;
    g->patch_first = (unsigned int *)meshfix__array(a, a->plan.patch_first, m->patch_count);
    g->patch_end = (unsigned int *)meshfix__array(a, a->plan.patch_end, m->patch_count);
    if (!g->patch_first || !g->patch_end || !meshfix__prepare_bvh(&g->bvh, m, &g->arena, g->triangle_unit, g->unit_count))
        return 0;
    meshfix__slots_by_patch(g);
    meshfix__cumulate_areas(g);
    return 1;
}

MESHFIX__PRIVATE double meshfix__total_area(const meshfix__geometry *g)
{
    double total = 0;
    unsigned int u;
    for (u = 0; u < g->unit_count; ++u)
        total += g->units[u].area;
    return total;
}

/* AUTO and OUTWARD: the units, their slots and trees. Coherence joins
   the patches (clear normals anchoring them); where a unit turned members
   against each other, each member's own side of the unit's surface is
   measured and the joins made again with those anchors; the units, slots
   and trees are made again when that changed them. Returns 0 when out of
   memory. */
MESHFIX__PRIVATE int meshfix__form_units(meshfix__geometry *g, const meshfix__coherence *coherence,
                                        meshfix__merge *merge, meshfix_report *r)
{
    const meshfix__mesh *m = g->m;
    size_t patches = m->patch_count, joins;
    signed char *sides = (signed char *)meshfix__array(&g->arena, g->arena.plan.member_sides, patches);
    unsigned int *samples = (unsigned int *)meshfix__array(&g->arena, g->arena.plan.member_samples, patches);
    signed char *asked = (signed char *)meshfix__array(&g->arena, g->arena.plan.member_asked, patches);
    unsigned int *surface = (unsigned int *)meshfix__array(&g->arena, g->arena.plan.member_surface, patches);
    /* a unit for each patch at most */
    meshfix__unit_seams *seams = (meshfix__unit_seams *)meshfix__array(&g->arena, g->arena.plan.unit_seams, patches);
    unsigned int *first_unit = (unsigned int *)meshfix__array(&g->arena, g->arena.plan.first_unit, patches);
    unsigned int p, same_units = 1;
    if (!asked || !sides || !samples || !surface || !seams || !first_unit)
        return 0;
    meshfix__anchor_normals(g, merge);
    joins = meshfix__merge_by_coherence(merge, coherence->pairs, coherence->pair_count);
    meshfix__number_units(g, merge);
    if (!meshfix__prepare_units(g))
        return 0;
    meshfix__build_unit_trees(g);
    if (meshfix__measure_members(g, coherence, asked, sides, surface, seams, samples, &r->evidence.rays_cast)) {
        MESHFIX_MEMCPY(first_unit, g->patch_unit, patches * sizeof(unsigned int));
        meshfix__reset_merge(merge, (unsigned int)patches);
        meshfix__anchor_normals(g, merge);
        MESHFIX_MEMCPY(merge->side, sides, patches);
        joins = meshfix__merge_by_coherence(merge, coherence->pairs, coherence->pair_count);
        meshfix__number_units(g, merge);
        for (p = 0; p < patches; ++p)
            same_units &= g->patch_unit[p] == first_unit[p];
        /* a refused join split a unit: its slots and trees are made again
           (they do not depend on turns: the sums, which do, come after) */
        if (!same_units) {
            if (!meshfix__prepare_units(g))
                return 0;
            meshfix__build_unit_trees(g);
        }
    }
    r->evidence.patch_pairs += coherence->pair_count;
    r->evidence.patches_merged += joins;
    return 1;
}

/* AUTO and OUTWARD: units by coherence; closed and nearly closed ones by
   volume and nesting; open ones (AUTO) by the first significant of the
   shells around them, their own crossings, escaping rays. */
MESHFIX__PRIVATE int meshfix__decide_by_shells(meshfix__geometry *g, meshfix_report *r)
{
    meshfix__mesh *m = g->m;
    meshfix__coherence coherence;
    meshfix__merge merge;
    double total_area;
    int *net = NULL, ok = 0;
    meshfix__scene_context context = {0, 0, 0};
    unsigned int u;
    MESHFIX_MEMSET(&merge, 0, sizeof(merge));
    if (!meshfix__measure_coherence(g, &coherence) || !meshfix__alloc_merge(g, &merge, 0) ||
        !meshfix__form_units(g, &coherence, &merge, r))
        goto done;
    net = (int *)meshfix__array(&g->arena, g->arena.plan.nets, g->unit_count);
    if (net == NULL)
        goto done;
    MESHFIX_MEMSET(net, 0, g->unit_count * sizeof(int));
    meshfix__sum_units(g);
    meshfix__close_units(g, &coherence, net);
    total_area = meshfix__total_area(g);
    meshfix__gather_evidence(g, MESHFIX__PHASE_GAPS, total_area);
    meshfix__index_shells(g);
    meshfix__gather_evidence(g, MESHFIX__PHASE_SHELLS, total_area);
    g->reversed_scene = m->policy == MESHFIX_POLICY_AUTO && meshfix__scene_reversed(g);
    for (u = 0; u < g->unit_count; ++u) /* the shells of a reversed scene: their majority counts against them */
        if (g->units[u].kind == MESHFIX_EVIDENCE_VOLUME)
            g->units[u].reversed_prior = (unsigned char)g->reversed_scene;
    if (m->policy == MESHFIX_POLICY_AUTO) {
        for (u = 0; u < g->unit_count; ++u)
            if (g->units[u].closed == MESHFIX__OPEN && meshfix__could_turn(&g->units[u], MESHFIX__WEIGHT_WEAK))
                break;
        if (u < g->unit_count)
            meshfix__top_tree(&g->bvh, m, g->unit_slots, g->unit_ids);
        meshfix__gather_evidence(g, MESHFIX__PHASE_OPEN, total_area);
    }
    for (u = 0; u < g->unit_count; ++u) {
        meshfix__decide_unit(&g->units[u], g->sigma);
        meshfix__add_to_context(&context, &g->units[u]);
    }
    for (u = 0; u < g->unit_count; ++u) {
        const meshfix__unit *x = &g->units[u];
        if (m->policy == MESHFIX_POLICY_AUTO)
            g->units[u].confidence = meshfix__calibrate(x, &context);
        r->evidence.shells_inward += (size_t)(x->outward * (x->turn ? -1 : 1) < 0);
        r->evidence.rays_cast += x->rays;
        MESHFIX_TRACE(("meshfix: unit %u: area %g, as given %g / %g, volume %g, closed %d, unmatched %g of %g; "
                       "evidence %d: %.3f +- %.3f x %g; turn %u, confidence %.2f%s\n",
                       u, x->area, x->kept, x->reversed, x->volume, (int)x->closed, x->unmatched, x->boundary,
                       (int)x->kind, x->mean,
                       x->error, x->weight, x->turn, (double)x->confidence, x->cavity ? ", cavity" : ""));
    }
    meshfix__apply_units(g, &context);
    for (u = 0; u < coherence.pair_count; ++u) {
        unsigned int a = meshfix__merge_turn(&merge, coherence.pairs[u].a), b = meshfix__merge_turn(&merge, coherence.pairs[u].b);
        r->evidence.pairs_conflicting += (size_t)(coherence.pairs[u].c * ((a ^ b) ? -1.0 : 1.0) < 0);
    }
    ok = 1;
done:
    return ok;
}

/* VISIBILITY per patch: front and back escape shares of sample pairs,
   with the budget shared by area and a floor per patch. */
MESHFIX__PRIVATE unsigned int meshfix__visibility_samples(const meshfix__geometry *g, unsigned int p, double total_area)
{
    const meshfix_options *o = g->o;
    size_t patches = g->m->patch_count, budget, floor_count;
    double area = g->units[p].area;
    budget = g->ray_budget / 2; /* a sample is a pair of rays */
    floor_count = o->visibility.min_samples;
    if (floor_count > budget / patches)
        floor_count = budget / patches;
    if (!(area > 0) || g->bvh.unit_first[p] == g->bvh.unit_first[p + 1])
        return 0;
    return (unsigned int)(floor_count + (size_t)((double)(budget - floor_count * patches) * (area / total_area)));
}

typedef struct meshfix__visibility_task {
    meshfix__geometry *g;
    meshfix__merge *merge;
    double total_area;
    unsigned int *samples; /* per patch */
} meshfix__visibility_task;

MESHFIX__PRIVATE void meshfix__visibility_chunk(void *context, size_t chunk)
{
    const meshfix__visibility_task *task = (const meshfix__visibility_task *)context;
    meshfix__geometry *g = task->g;
    size_t p, end = (chunk + 1) * MESHFIX__UNITS_PER_TASK;
    for (p = chunk * MESHFIX__UNITS_PER_TASK; p < end && p < g->m->patch_count; ++p) {
        unsigned int i, n = meshfix__visibility_samples(g, (unsigned int)p, task->total_area), front = 0, back = 0;
        meshfix__votes votes;
        MESHFIX_MEMSET(&votes, 0, sizeof(votes));
        for (i = 0; i < n; ++i) {
            int vote = meshfix__sample_escape(g, (unsigned int)p, i, &front, &back);
            meshfix__add_vote(&votes, vote);
        }
        task->merge->front[p] = n ? (double)front / n : 0.0;
        task->merge->back[p] = n ? (double)back / n : 0.0;
        task->merge->area[p] = g->units[p].area;
        task->samples[p] = 2 * n;
        g->units[p].mean = meshfix__vote_mean(&votes);
        g->units[p].error = meshfix__vote_error(&votes);
    }
}

/* The super-patches' verdicts: each root gathers, in the frame the merge
   turned it to, its members' area facing each way as given and its
   visibility (the merge's shares, with the members' sample count for the
   error); the members take its turn. */
MESHFIX__PRIVATE void meshfix__visibility_verdicts(meshfix__geometry *g, meshfix__merge *merge, unsigned int *samples)
{
    meshfix__mesh *m = g->m;
    unsigned int p, parity, root;
    /* a root is its super-patch's lowest patch: members come after it */
    for (p = 0; p < m->patch_count; ++p) {
        root = meshfix__merge_find(merge, p, &parity);
        if (root != p) {
            meshfix__unit *x = &g->units[p], *r = &g->units[root];
            r->kept += parity ? x->reversed : x->kept;
            r->reversed += parity ? x->kept : x->reversed;
            r->prior_kept += parity ? x->prior_reversed : x->prior_kept;
            r->prior_reversed += parity ? x->prior_kept : x->prior_reversed;
            samples[root] += samples[p];
        }
    }
    for (p = 0; p < m->patch_count; ++p) {
        meshfix__unit *r = &g->units[p];
        double n = (double)samples[p] / 2, m_f, m_b, s2;
        if (meshfix__merge_find(merge, p, &parity) != p)
            continue;
        if (merge->turn[p]) {
            double x = r->kept;
            r->kept = r->reversed, r->reversed = x;
            x = r->prior_kept;
            r->prior_kept = r->prior_reversed, r->prior_reversed = x;
        }
        m_f = merge->front[p], m_b = merge->back[p];
        r->normals = r->normals_area = 0;
        r->mean = m_f - m_b;
        s2 = meshfix__maxd(m_f + m_b - r->mean * r->mean, n > 0 ? 1.0 / n : 1.0);
        r->error = n > 0 ? MESHFIX_SQRT(s2 / n) : 1.0;
        r->kind = MESHFIX_EVIDENCE_VISIBILITY;
        meshfix__verdict_follow(r, g->sigma, 0.0);
        merge->turn[p] ^= (unsigned char)r->turn;
    }
    for (p = 0; p < m->patch_count; ++p) {
        const meshfix__unit *r;
        root = meshfix__merge_find(merge, p, &parity);
        r = &g->units[root];
        meshfix__decide(m, p, parity ^ merge->turn[root], r->confidence, r->kind);
    }
}

/* VISIBILITY (Borodin et al.): patches merged by coherence and
   visibility; each super-patch to its more visible side when the
   difference is significant, else to its majority. */
MESHFIX__PRIVATE int meshfix__decide_by_visibility(meshfix__geometry *g, meshfix_report *r)
{
    meshfix__mesh *m = g->m;
    const meshfix_options *o = g->o;
    meshfix__coherence coherence;
    meshfix__merge merge;
    meshfix__merge_params k;
    meshfix__visibility_task task;
    unsigned int p, *samples = NULL;
    size_t i, chunks;
    int ok = 0;
    MESHFIX_MEMSET(&merge, 0, sizeof(merge));
    MESHFIX_MEMSET(&coherence, 0, sizeof(coherence));
    k.c0 = (double)o->visibility.c0;
    k.eps = (double)o->visibility.eps;
    k.kv = (double)o->visibility.kv;
    k.use_visibility = !(o->visibility.flags & MESHFIX_VISIBILITY_COHERENCE_ONLY);
    meshfix__number_units(g, NULL);
    if (!meshfix__prepare_units(g) || !meshfix__alloc_merge(g, &merge, 1))
        goto done;
    samples = (unsigned int *)meshfix__array(&g->arena, g->arena.plan.samples, m->patch_count);
    if (samples == NULL)
        goto done;
    MESHFIX_MEMSET(samples, 0, m->patch_count * sizeof(unsigned int));
    meshfix__sum_units(g);
    for (p = 0; p < m->patch_count; ++p) {
        merge.front[p] = merge.back[p] = 0.0;
        merge.area[p] = g->units[p].area;
    }
    if (k.use_visibility) {
        meshfix__top_tree(&g->bvh, m, g->unit_slots, g->unit_ids);
        task.g = g;
        task.merge = &merge;
        task.total_area = meshfix__total_area(g);
        task.samples = samples;
        chunks = (m->patch_count + MESHFIX__UNITS_PER_TASK - 1) / MESHFIX__UNITS_PER_TASK;
        meshfix__run_tasks(o, meshfix__visibility_chunk, &task, chunks);
    }
    for (p = 0; p < m->patch_count; ++p)
        r->evidence.rays_cast += samples[p];
    if (!(o->visibility.flags & MESHFIX_VISIBILITY_ONLY)) {
        if (!meshfix__measure_coherence(g, &coherence))
            goto done;
        r->evidence.patch_pairs += coherence.pair_count;
        for (i = 0; i < coherence.pair_count; ++i)
            r->evidence.patches_merged += (size_t)meshfix__merge_borodin(&merge, &coherence.pairs[i], &k);
    }
    meshfix__visibility_verdicts(g, &merge, samples);
    for (i = 0; i < coherence.pair_count; ++i) {
        unsigned int a = meshfix__merge_turn(&merge, coherence.pairs[i].a), b = meshfix__merge_turn(&merge, coherence.pairs[i].b);
        r->evidence.pairs_conflicting += (size_t)(coherence.pairs[i].c * ((a ^ b) ? -1.0 : 1.0) < 0);
    }
    ok = 1;
done:
    return ok;
}

/* The rays a call may cast, shared by area among its units:
   visibility.rays, or by default 64 a triangle under 1024 triangles (a
   quad casts 128 rays, not a large mesh's floor), else VISIBILITY's 128
   per patch (at least 65536, at most 1048576), which it spends, and for
   AUTO and OUTWARD 1048576, which they only draw on until each unit's
   verdict is settled: a unit that stays unsettled buys more evidence. */
MESHFIX__PRIVATE size_t meshfix__ray_budget(const meshfix__mesh *m)
{
    size_t budget = m->options->visibility.rays;
    if (budget != 0)
        return budget;
    if (m->triangle_count < 1024)
        return 64 * m->triangle_count;
    if (meshfix__traits[m->policy].decides != MESHFIX__DECIDE_MERGE)
        return 1048576;
    budget = 128 * (size_t)m->patch_count;
    return budget < 65536 ? 65536 : budget > 1048576 ? 1048576 : budget;
}

/* What the geometric stage needs, counted from the mesh (or, for
   meshfix_scratch_size, the most any mesh of that size could need). */
typedef struct meshfix__geometry_counts {
    size_t triangles, patches, boundary, rings, largest_ring; /* boundary and ring half-edges */
} meshfix__geometry_counts;

MESHFIX__PRIVATE void meshfix__count_geometry(meshfix__mesh *m, meshfix__geometry_counts *c)
{
    c->triangles = m->triangle_count;
    c->patches = m->patch_count;
    c->boundary = meshfix__run_stage(m->options, meshfix__boundary_chunk, m, m->triangle_count, &c->rings);
    c->largest_ring = c->rings != 0 ? meshfix__largest_ring(m) : 0; /* without ring edges, no ring */
}

/* Lays out every array of the geometric stage (meshfix__geometry_plan)
   for meshes with these counts; 0 when the sizes overflow. VISIBILITY
   has escapes and areas where the others have anchors and members. */
MESHFIX__PRIVATE int meshfix__place(size_t *total, meshfix__span *span, size_t count, size_t size)
{
    span->count = count;
    return meshfix__add_size(total, count, size, &span->offset);
}

MESHFIX__PRIVATE int meshfix__place_nodes(size_t *total, meshfix__span *span, size_t count)
{
    span->count = count;
    return meshfix__add_aligned(total, count, sizeof(meshfix__node), MESHFIX__NODE_ALIGN, &span->offset);
}

MESHFIX__PRIVATE int meshfix__plan_geometry(const meshfix__geometry_counts *c, int policy, meshfix__geometry_plan *l)
{
    size_t t = 0, n = c->triangles, p = c->patches, b = c->boundary, pairs = c->boundary + c->rings;
    size_t ring = c->largest_ring, vis = meshfix__traits[policy].decides == MESHFIX__DECIDE_MERGE ? p : 0, rest = p - vis;
    int ok = meshfix__place(&t, &l->confidence, p, sizeof(float)) && meshfix__place(&t, &l->patch_kind, p, 1) &&
             meshfix__place(&t, &l->patch_unit, p, sizeof(unsigned int)) && meshfix__place(&t, &l->patch_turn, p, 1) &&
             meshfix__place(&t, &l->triangle_unit, n, sizeof(unsigned int)) &&
             /* a grid entry at most for each end and the middle of a segment */
             meshfix__place(&t, &l->segments, b, sizeof(meshfix__segment)) &&
             meshfix__place(&t, &l->pairs, pairs, sizeof(meshfix__pair)) &&
             meshfix__place(&t, &l->pair_scratch, pairs, sizeof(meshfix__pair)) &&
             meshfix__place(&t, &l->ring_work, ring, sizeof(unsigned int)) &&
             meshfix__place(&t, &l->ring_members, ring, sizeof(unsigned int)) &&
             meshfix__place(&t, &l->ring_angles, ring, sizeof(double)) &&
             meshfix__place(&t, &l->grid_start, meshfix__grid_buckets(b) + 1, sizeof(unsigned int)) &&
             meshfix__place(&t, &l->grid_occupied, meshfix__grid_buckets(b) / 8, 1) &&
             b <= ((size_t)-1) / 3 && meshfix__place(&t, &l->grid_items, 3 * b, sizeof(meshfix__cell_item)) &&
             meshfix__place(&t, &l->parent, p, sizeof(unsigned int)) && meshfix__place(&t, &l->parity, p, 1) &&
             meshfix__place(&t, &l->turn, p, 1) && meshfix__place(&t, &l->front, vis, sizeof(double)) &&
             meshfix__place(&t, &l->back, vis, sizeof(double)) && meshfix__place(&t, &l->merged_area, vis, sizeof(double)) &&
             meshfix__place(&t, &l->side, rest, 1) && meshfix__place(&t, &l->normals, rest, 1) &&
             meshfix__place(&t, &l->member_sides, rest, 1) &&
             meshfix__place(&t, &l->member_samples, rest, sizeof(unsigned int)) &&
             meshfix__place(&t, &l->member_surface, rest, sizeof(unsigned int)) &&
             meshfix__place(&t, &l->member_asked, rest, 1) &&
             meshfix__place(&t, &l->unit_seams, rest, sizeof(meshfix__unit_seams)) &&
             meshfix__place(&t, &l->first_unit, rest, sizeof(unsigned int)) &&
             /* a unit for each patch at most */
             meshfix__place(&t, &l->units, p, sizeof(meshfix__unit)) &&
             p <= ((size_t)-1) / 9 && meshfix__place(&t, &l->unit_slots, 9 * p, sizeof(float)) &&
             meshfix__place(&t, &l->unit_ids, p, sizeof(unsigned int)) &&
             meshfix__place_nodes(&t, &l->shell_nodes, p) &&
             meshfix__place(&t, &l->shell_ids, p, sizeof(unsigned int)) &&
             meshfix__place(&t, &l->patch_first, p, sizeof(unsigned int)) &&
             meshfix__place(&t, &l->patch_end, p, sizeof(unsigned int)) && meshfix__place(&t, &l->nets, p, sizeof(int)) &&
             meshfix__place(&t, &l->samples, vis, sizeof(unsigned int)) &&
             /* a slot for each triangle at most; the trees' nodes and
                blocks as meshfix__place_ray_trees counts them */
             meshfix__place(&t, &l->unit_first, p + 1, sizeof(unsigned int)) &&
             meshfix__place(&t, &l->unit_root, p, sizeof(unsigned int)) &&
             meshfix__place(&t, &l->order, n, sizeof(unsigned int)) &&
             n <= ((size_t)-1) / 9 - MESHFIX__SLOT_PAD &&
             meshfix__place(&t, &l->corners, 9 * (n + MESHFIX__SLOT_PAD), sizeof(float)) &&
             meshfix__place(&t, &l->by_index, n, sizeof(unsigned int)) &&
             meshfix__place(&t, &l->cumulative_area, n, sizeof(double)) && n <= ((size_t)-1) / 4 &&
             meshfix__place(&t, &l->morton_sort, 4 * n, sizeof(unsigned int)) &&
             meshfix__place_ray_trees(&t, &l->nodes, &l->blocks, n, p);
    l->total = t + MESHFIX__ARENA_ALIGN;
    return ok && l->total > t;
}

/* Decides the patches of the policies that need rays (OUTWARD, AUTO,
   VISIBILITY) with the arrays of `arena`; the others decide patch by
   patch when they are oriented. Returns 0 when out of memory. */
MESHFIX__PRIVATE int meshfix__decide_by_geometry(meshfix__mesh *m, const meshfix__arena *arena, meshfix_report *r)
{
    meshfix__geometry g;
    int policy = m->policy;
    MESHFIX_MEMSET(&g, 0, sizeof(g));
    g.m = m;
    g.o = m->options;
    g.arena = *arena;
    meshfix__mark_areas(m);
    g.seed = m->options->seed;
    g.sigma = (double)m->options->evidence.sigma;
    g.ray_budget = meshfix__ray_budget(m);
    m->confidence = (float *)meshfix__array(&g.arena, g.arena.plan.confidence, m->patch_count);
    m->patch_kind = (unsigned char *)meshfix__array(&g.arena, g.arena.plan.patch_kind, m->patch_count);
    g.patch_unit = (unsigned int *)meshfix__array(&g.arena, g.arena.plan.patch_unit, m->patch_count);
    g.patch_turn = (unsigned char *)meshfix__array(&g.arena, g.arena.plan.patch_turn, m->patch_count);
    g.triangle_unit = (unsigned int *)meshfix__array(&g.arena, g.arena.plan.triangle_unit, m->triangle_count);
    if (!m->confidence || !m->patch_kind || !g.patch_unit || !g.patch_turn || !g.triangle_unit)
        return 0;
    meshfix__fit_frame(&g.bvh, m);
    g.t_min = (float)(1e-5 * g.bvh.diagonal);
    return meshfix__traits[policy].decides == MESHFIX__DECIDE_MERGE ? meshfix__decide_by_visibility(&g, r)
                                                                     : meshfix__decide_by_shells(&g, r);
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

MESHFIX__PRIVATE meshfix_component *meshfix__component_out(const meshfix__mesh *m, unsigned int component)
{
    const meshfix_outputs *out = m->outputs;
    return out->components != NULL && component < out->components_capacity ? &out->components[component] : NULL;
}

/* Counts each edge once, for the component of its triangles. */
MESHFIX__PRIVATE void meshfix__count_component_edges(const meshfix__mesh *m)
{
    unsigned int h, half_edges = (unsigned int)(3 * m->triangle_count);
    for (h = 0; h < half_edges; ++h) {
        unsigned int g = m->mate[h];
        meshfix_component *c;
        if (m->tri_bits[h / 3] & MESHFIX__TRI_DEGENERATE)
            continue;
        c = meshfix__component_out(m, m->patch_link[m->tri_patch[h / 3]]);
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
MESHFIX__PRIVATE size_t meshfix__count_component_vertices(meshfix__mesh *m, meshfix_report *r)
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
        meshfix_component *out = meshfix__component_out(m, c);
        for (; i < m->patch_count && m->patch_link[order[i]] == c; ++i) {
            unsigned int q, patch = order[i];
            for (q = m->patch_start[patch]; q < m->patch_start[patch + 1]; ++q) {
                const unsigned int *v = m->indices + 3 * m->queue[q];
                int k;
                for (k = 0; k < 3; ++k) {
                    if (mark[v[k]] == 0) {
                        r->mesh.vertices_used++;
                        if (m->positions != NULL)
                            r->mesh.vertices_non_finite += (size_t)!meshfix__is_finite_point(meshfix__position(m, v[k]));
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


/* A verdict is doubtful below this confidence, or below min_confidence
   where that is higher. A fitted probability (AUTO's: the policy's
   confidence trait, >>policies): below 0.9 a verdict is wrong more than
   once in ten. The other policies' is the margin of their evidence,
   doubtful below half. */
#define MESHFIX__DOUBTFUL_PROBABILITY 0.9
#define MESHFIX__DOUBTFUL_MARGIN 0.5

MESHFIX__PRIVATE double meshfix__doubtful_below(const meshfix_options *o, int policy)
{
    int probability = policy >= 0 && policy < (int)MESHFIX_POLICY_COUNT &&
                      meshfix__traits[policy].confidence == MESHFIX__CONFIDENCE_PROBABILITY;
    double bar = probability ? MESHFIX__DOUBTFUL_PROBABILITY : MESHFIX__DOUBTFUL_MARGIN;
    return meshfix__maxd(bar, (double)o->evidence.min_confidence);
}

MESHFIX__PRIVATE void meshfix__count_verdict(const meshfix__unit *u, size_t triangles, double area, double doubtful,
                                            meshfix_report *r)
{
    r->evidence.patches_by_volume += u->kind == MESHFIX_EVIDENCE_VOLUME;
    r->evidence.patches_by_parity += u->kind == MESHFIX_EVIDENCE_PARITY;
    r->evidence.patches_by_visibility += u->kind == MESHFIX_EVIDENCE_VISIBILITY;
    r->evidence.patches_by_normals += u->kind == MESHFIX_EVIDENCE_NORMALS;
    r->evidence.patches_kept += u->kind == MESHFIX_EVIDENCE_NONE || u->kind == MESHFIX_EVIDENCE_POLICY;
    if ((double)u->confidence < doubtful) {
        r->patches_doubtful++;
        r->triangles_doubtful += triangles;
        r->area_doubtful += area;
    }
}

/* Patch p, its sums known: its verdict (>>decide: meshfix__patch_verdict,
   meshfix__turn_patch; policy < 0: inspect, no turns), and the report's
   totals as returned. */
MESHFIX__PRIVATE void meshfix__orient_patch(meshfix__mesh *m, unsigned int p, int policy, const meshfix_options *o,
                                           const meshfix__patch_sums *s, meshfix_report *r)
{
    unsigned int turn = 0, bits = m->patch_bits[p];
    size_t flipped = 0;
    double volume, given;
    meshfix_component *out = meshfix__component_out(m, m->patch_link[p]);
    r->evidence.sdf_evaluations += s->sdf_evaluations;
    if (policy >= 0) {
        meshfix__unit verdict;
        meshfix__patch_verdict(m, p, policy, s, &verdict);
        meshfix__count_verdict(&verdict, m->patch_start[p + 1] - m->patch_start[p], s->area,
                               meshfix__doubtful_below(o, policy), r);
        if (m->outputs->patch_confidence != NULL && p < m->outputs->patch_confidence_capacity)
            m->outputs->patch_confidence[p] = verdict.confidence;
        if (m->outputs->patch_evidence != NULL && p < m->outputs->patch_evidence_capacity)
            m->outputs->patch_evidence[p] = verdict.kind;
        turn = verdict.turn;
        flipped = meshfix__turn_patch(m, p, policy, turn, r);
        r->triangles_flipped += flipped;
        r->patches_flipped += (size_t)(flipped != 0);
    }
    given = s->volume_given;
    volume = policy < 0 ? given : turn ? -s->volume_relative : s->volume_relative;
    if (!meshfix__is_closed_orientable(m, p))
        volume = given = 0.0;
    r->signed_volume_before += given;
    /* inside-out only means something for a patch wound one way throughout */
    if (s->reversed == 0)
        r->patches_inside_out_before += (size_t)(given < 0.0 && meshfix__volume_is_meaningful(given, s->area));
    /* a shell decided alone (the geometric stage counts its units) */
    if (policy >= 0 && !(bits & MESHFIX__PATCH_DECIDED) && volume < 0.0 && meshfix__volume_is_meaningful(volume, s->area))
        r->evidence.shells_inward++;
    r->mesh.triangles_zero_area += s->zero_area;
    r->mesh.area += s->area;
    r->mesh.signed_volume += volume;
    r->mesh.patches_closed += (size_t)!(bits & MESHFIX__PATCH_OPEN);
    if (policy >= 0 || s->reversed == 0)
        r->mesh.patches_inside_out += (size_t)(volume < 0.0 && meshfix__volume_is_meaningful(volume, s->area));
    if (out != NULL)
        meshfix__add_patch_to_component(m, p, s, volume, out);
    m->component_bits[m->patch_link[p]] |= (unsigned char)bits;
}

/* The sums of a window of patches, by chunks of about equal triangles:
   each patch summed whole, alone, so the same bits wherever it runs. */
typedef struct meshfix__sums_task {
    meshfix__mesh *m;
    unsigned int first, end; /* the window's patches */
    meshfix__patch_sums *sums; /* per patch of the window */
} meshfix__sums_task;

/* The first patch of the window at or after `triangles` of its triangles. */
MESHFIX__PRIVATE unsigned int meshfix__patch_at(const meshfix__sums_task *task, size_t triangles)
{
    const unsigned int *start = task->m->patch_start;
    unsigned int lo = task->first, hi = task->end;
    while (lo < hi) {
        unsigned int mid = lo + (hi - lo) / 2;
        if ((size_t)(start[mid] - start[task->first]) < triangles)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo;
}

MESHFIX__PRIVATE void meshfix__sums_chunk(void *stage, size_t chunk)
{
    meshfix__stage *s = (meshfix__stage *)stage;
    const meshfix__sums_task *task = (const meshfix__sums_task *)s->context;
    size_t begin, end;
    unsigned int p, last;
    meshfix__chunk_range(s, chunk, &begin, &end);
    last = meshfix__patch_at(task, end);
    for (p = meshfix__patch_at(task, begin); p < last; ++p)
        meshfix__sum_patch(task->m, p, &task->sums[p - task->first]);
}

/* Each patch: its sums, then in patch order its verdict and the report.
   The sums are taken a window of patches at a time in the join's room,
   when it is free (positions joined the corners), in chunks a caller's
   parallel_for may run, except under a policy that calls
   options.sdf.distance (SDF: its callbacks were not promised to be
   reentrant); else each where it is used. */
MESHFIX__PRIVATE void meshfix__orient_patches(meshfix__mesh *m, int policy, const meshfix_options *o,
                                              meshfix_report *r)
{
    unsigned int p, c, window = 0;
    meshfix__sums_task task;
    MESHFIX_MEMSET(m->component_bits, 0, m->component_count);
    if (m->input_room != NULL && (policy < 0 || !meshfix__policies[policy].needs_distance))
        window = (unsigned int)(3 * m->triangle_count / (sizeof(meshfix__patch_sums) / sizeof(unsigned int)));
    task.m = m;
    task.sums = (meshfix__patch_sums *)(void *)m->input_room;
    for (p = 0; p < m->patch_count;) {
        meshfix__patch_sums s;
        if (window < 2) {
            meshfix__sum_patch(m, p, &s);
            meshfix__orient_patch(m, p, policy, o, &s, r);
            ++p;
            continue;
        }
        task.first = p;
        task.end = m->patch_count - p < window ? (unsigned int)m->patch_count : p + window;
        meshfix__run_stage(m->options, meshfix__sums_chunk, &task, m->patch_start[task.end] - m->patch_start[p], NULL);
        for (; p < task.end; ++p)
            meshfix__orient_patch(m, p, policy, o, &task.sums[p - task.first], r);
    }
    for (c = 0; c < m->component_count; ++c) {
        r->mesh.components_closed += (size_t)!(m->component_bits[c] & MESHFIX__PATCH_NOT_MANIFOLD);
        r->mesh.components_non_orientable += (size_t)((m->component_bits[c] & MESHFIX__PATCH_NON_ORIENTABLE) != 0);
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
        /* an edge the caller's normals kept apart stays as it is */
        if (meshfix__is_mate(g) && !(m->patch_bits[m->tri_patch[h / 3]] & MESHFIX__PATCH_NON_ORIENTABLE) &&
            !(m->tri_bits[h / 3] & m->tri_bits[g / 3] & MESHFIX__TRI_CUT))
            MESHFIX_ASSERT(((unsigned int)meshfix__same_direction(m, h, g) ^ meshfix__flip_of(m, h / 3) ^
                            meshfix__flip_of(m, g / 3)) == 0);
    }
}
#endif

/* ===== >>pipeline ===== */

MESHFIX__PRIVATE void meshfix__bind(meshfix__mesh *m, unsigned char *block, const meshfix__plan *plan,
                                    const meshfix__input *in, size_t vertex_range, const meshfix_options *options,
                                    meshfix_outputs *outputs, int policy)
{
    MESHFIX_MEMSET(m, 0, sizeof(*m));
    m->options = options;
    m->outputs = outputs;
    m->policy = policy;
    m->input = in;
    m->triangle_count = in->index_count / 3;
    m->vertex_range = vertex_range;
    m->positions = (const char *)in->positions;
    m->stride = in->stride;
    m->mate = (unsigned int *)(void *)(block + plan->mate);
    m->work = (unsigned int *)(void *)(block + plan->work);
    m->queue = (unsigned int *)(void *)(block + plan->queue);
    m->tri_patch = (unsigned int *)(void *)(block + plan->tri_patch);
    m->component_bits = block + plan->component_bits;
    m->tri_bits = (unsigned short *)(void *)(block + plan->tri_bits);
    m->vertex_work = (unsigned int *)(void *)(block + plan->vertex_work);
    m->patch_start = (unsigned int *)(void *)(block + plan->patch_start);
    m->patch_link = (unsigned int *)(void *)(block + plan->patch_link);
    m->patch_bits = block + plan->patch_bits;
    m->input_room = meshfix__joins_positions(in) ? (unsigned int *)(void *)(block + plan->weld) : NULL;
}

/* The policies that cast rays build units and trees, except for one
   closed shell alone under the shells decision (AUTO, OUTWARD): nothing
   can enclose it, its volume decides (meshfix__decide_patch). */
MESHFIX__PRIVATE int meshfix__needs_geometry(const meshfix__mesh *m, int policy)
{
    if (policy < 0 || !meshfix__policies[policy].casts_rays)
        return 0;
    if (meshfix__traits[policy].decides == MESHFIX__DECIDE_SHELLS && m->patch_count == 1 &&
        meshfix__is_closed_orientable(m, 0))
        return 0;
    return m->patch_count != 0;
}

/* meshfix_check's explanation (>>check) */
MESHFIX__PRIVATE void meshfix__explain(meshfix__mesh *m, const meshfix_report *r, unsigned int requirements,
                                      meshfix_check_failure *f);

/* The caller's scratch beyond the topology's arrays (base NULL: none). */
typedef struct meshfix__block {
    unsigned char *base;
    size_t size;
} meshfix__block;

/* Stages 2 to 5 on a bound mesh; fills r and the component outputs. The
   counts that only describe the mesh (duplicates, non-manifold vertices,
   inconsistent edges, Euler characteristic) are skipped when `full` is 0:
   the caller asked for neither a report nor components. */
MESHFIX__PRIVATE meshfix_result meshfix__analyze(meshfix__mesh *m, int policy, const meshfix_options *o, int full,
                                                 const meshfix_memory_options *allocator, const meshfix__block *rest,
                                                 meshfix_report *r)
{
    meshfix__edge_counts edges;
    unsigned char *own = NULL;
    size_t c, n;

    r->mesh.triangles_degenerate = meshfix__mark_degenerate(m);
    meshfix__build_edges(m, &edges);
    r->mesh.edges = edges.edges;
    r->mesh.edges_boundary = edges.boundary;
    r->mesh.edges_manifold = edges.manifold;
    r->mesh.edges_non_manifold = edges.non_manifold;
    if (full) {
        r->mesh.triangles_duplicate = meshfix__count_duplicates(m);
        r->edges_inconsistent_before = meshfix__count_inconsistent(m, 0);
        r->mesh.vertices_non_manifold = meshfix__count_non_manifold_vertices(m);
    }

    meshfix__find_patches(m);
    meshfix__join_components(m);
    r->mesh.patches = m->patch_count;
    r->mesh.components = m->component_count;

    n = m->outputs->components != NULL ? m->outputs->components_capacity : 0;
    n = m->component_count < n ? m->component_count : n;
    if (meshfix__needs_geometry(m, policy)) {
        /* units, trees and rays: the rest of the caller's scratch, or a
           second allocation */
        meshfix__geometry_counts counts;
        meshfix__arena arena;
        meshfix__count_geometry(m, &counts);
        if (!meshfix__plan_geometry(&counts, policy, &arena.plan))
            return MESHFIX_ERROR_TOO_LARGE;
        if (rest->base != NULL) {
            if (rest->size < arena.plan.total)
                return MESHFIX_ERROR_SCRATCH_TOO_SMALL;
            arena.base = rest->base;
            own = NULL;
        } else {
            own = (unsigned char *)meshfix__allocate(allocator, arena.plan.total, 1);
            if (own == NULL)
                return MESHFIX_ERROR_OUT_OF_MEMORY;
            arena.base = own;
        }
        /* offsets are aligned to up to 64: so is the start */
        arena.base += (MESHFIX__ARENA_ALIGN - (size_t)arena.base % MESHFIX__ARENA_ALIGN) % MESHFIX__ARENA_ALIGN;
        if (!meshfix__decide_by_geometry(m, &arena, r)) {
            meshfix__release(allocator, own);
            return MESHFIX_ERROR_OUT_OF_MEMORY;
        }
    }
    if (n != 0)
        MESHFIX_MEMSET(m->outputs->components, 0, n * sizeof(meshfix_component));
    meshfix__orient_patches(m, policy, o, r);
    meshfix__release(allocator, own);
    m->confidence = NULL;
    m->patch_kind = NULL;
#ifdef MESHFIX_DEBUG
    /* the plain per-triangle SDF rule does not promise consistency */
    if (policy >= 0 && !(meshfix__policies[policy].needs_distance && o->sdf.mode == MESHFIX_SDF_PER_TRIANGLE))
        meshfix__debug_check_orientation(m);
#endif
    if (!full)
        return MESHFIX_OK;
    r->mesh.edges_inconsistent = policy >= 0 ? meshfix__count_inconsistent(m, 1) : r->edges_inconsistent_before;
    meshfix__count_component_edges(m);
    /* while `mate` still links the edges (the vertex count reuses it) */
    if (m->failure != NULL)
        meshfix__explain(m, r, m->requirements, m->failure);
    r->mesh.euler_characteristic = (long)meshfix__count_component_vertices(m, r) - (long)r->mesh.edges +
                              (long)(r->mesh.triangles - r->mesh.triangles_degenerate);
    for (c = 0; c < n; ++c) {
        meshfix_component *k = &m->outputs->components[c];
        k->euler_characteristic = (long)k->vertices - (long)k->edges + (long)k->triangles;
    }
    return MESHFIX_OK;
}

/* The caller's triangle t, its last two corners swapped when it flips. */
MESHFIX__PRIVATE void meshfix__write_triangle(const meshfix__mesh *m, size_t t, unsigned char *destination)
{
    const meshfix__input *in = m->input;
    unsigned int a = meshfix__source_index(in, 3 * t), b = meshfix__source_index(in, 3 * t + 1);
    unsigned int c = meshfix__source_index(in, 3 * t + 2);
    int flip = (m->tri_bits[t] & MESHFIX__TRI_FLIP) != 0;
    if (in->index_size == 2) {
        unsigned short *d = (unsigned short *)(void *)destination + 3 * t;
        d[0] = (unsigned short)a, d[1] = (unsigned short)(flip ? c : b), d[2] = (unsigned short)(flip ? b : c);
    } else {
        unsigned int *d = (unsigned int *)(void *)destination + 3 * t;
        d[0] = a, d[1] = flip ? c : b, d[2] = flip ? b : c;
    }
}

/* What the call writes, by chunks of triangles: the indices (NULL: none),
   the flip marks and the patch ids asked for. */
typedef struct meshfix__write_task {
    const meshfix__mesh *m;
    unsigned char *destination;
    int policy;
} meshfix__write_task;

MESHFIX__PRIVATE void meshfix__write_chunk(void *stage, size_t chunk)
{
    meshfix__stage *s = (meshfix__stage *)stage;
    const meshfix__write_task *task = (const meshfix__write_task *)s->context;
    const meshfix__mesh *m = task->m;
    const meshfix_outputs *out = m->outputs;
    size_t t, begin, end;
    meshfix__chunk_range(s, chunk, &begin, &end);
    if (task->destination != NULL)
        for (t = begin; t < end; ++t)
            meshfix__write_triangle(m, t, task->destination);
    if (out->flipped != NULL && task->policy >= 0)
        for (t = begin; t < end; ++t)
            out->flipped[t] = (unsigned char)meshfix__flip_of(m, (unsigned int)t);
    if (out->patch_ids != NULL)
        for (t = begin; t < end; ++t)
            out->patch_ids[t] = m->tri_patch[t];
}

/* Each triangle is read whole before it is written, and each output
   triangle depends on its own input triangle only. A destination equal
   to the indices, or apart from them, is written by chunks; one that
   overlaps them shifted by any amount is written here first, in the
   direction memmove would copy, so that no index is overwritten before
   it is read. The addresses are compared as integers: the two pointers
   may belong to different arrays. */
MESHFIX__PRIVATE void meshfix__write_outputs(const meshfix__mesh *m, unsigned char *destination, int policy)
{
    size_t t, d = (size_t)destination, i = (size_t)m->input->indices;
    size_t bytes = 3 * m->triangle_count * m->input->index_size;
    meshfix__write_task task;
    task.m = m;
    task.destination = destination;
    task.policy = policy;
    if (destination != NULL && d != i && (d > i ? d - i : i - d) < bytes) {
        if (d < i)
            for (t = 0; t < m->triangle_count; ++t)
                meshfix__write_triangle(m, t, destination);
        else
            for (t = m->triangle_count; t-- > 0;)
                meshfix__write_triangle(m, t, destination);
        task.destination = NULL;
    }
    meshfix__run_stage(m->options, meshfix__write_chunk, &task, m->triangle_count, NULL);
}

/* Option values outside their documented ranges are refused, not
   clamped: a struct nobody zeroed must not become a 4 GB ray budget. */
#define MESHFIX__MAX_RAYS ((size_t)1 << 24)
#define MESHFIX__MAX_MIN_SAMPLES 65536u

MESHFIX__PRIVATE int meshfix__is_fraction(float x, float most)
{
    return meshfix__is_finite(x) && x >= 0.0f && x <= most;
}

/* A normals stride: 0 (12 bytes), or whole floats, at least three. */
MESHFIX__PRIVATE int meshfix__stride_valid(size_t stride)
{
    return stride == 0 || (stride >= 3 * sizeof(float) && stride % sizeof(float) == 0);
}

MESHFIX__PRIVATE int meshfix__options_valid(const meshfix_options *o, int policy)
{
    if (policy >= 0 && meshfix__policies[policy].needs_distance &&
        (o->sdf.distance == NULL || (unsigned int)o->sdf.mode > (unsigned int)MESHFIX_SDF_PER_TRIANGLE))
        return 0;
    if (o->memory.alloc_func != NULL && o->memory.free_func == NULL)
        return 0;
    if ((o->index_size != 0 && o->index_size != 2 && o->index_size != 4) ||
        (o->position_size != 0 && o->position_size != 4 && o->position_size != 8) ||
        (unsigned int)o->topology > (unsigned int)MESHFIX_TOPOLOGY_WELD ||
        !(meshfix__is_finite(o->weld_tolerance) && o->weld_tolerance >= 0.0f))
        return 0;
    if (!meshfix__stride_valid(o->evidence.triangle_normals_stride) ||
        !meshfix__stride_valid(o->evidence.vertex_normals_stride))
        return 0;
    return o->visibility.rays <= MESHFIX__MAX_RAYS && o->visibility.min_samples <= MESHFIX__MAX_MIN_SAMPLES &&
           meshfix__is_fraction(o->evidence.sigma, 1e6f) && meshfix__is_fraction(o->evidence.min_confidence, 1.0f) &&
           meshfix__is_fraction(o->visibility.coherence_distance, 1.0f) && meshfix__is_fraction(o->visibility.c0, 1e6f) &&
           meshfix__is_fraction(o->visibility.eps, 1.0f) && meshfix__is_fraction(o->visibility.kv, 1e6f) &&
           meshfix__is_fraction(o->sdf.step, 3e38f) && meshfix__is_finite_point(o->up);
}

/* Every option left 0 gets its default. (visibility.rays 0 stays: its
   default depends on the patches, meshfix__ray_budget; sdf.step 0 on
   each triangle, meshfix__sdf_gradient.) */
MESHFIX__PRIVATE void meshfix__fill_defaults(meshfix_options *o)
{
    if (o->index_size == 0)
        o->index_size = 4;
    if (o->position_size == 0)
        o->position_size = 4;
    if (o->evidence.triangle_normals_stride == 0)
        o->evidence.triangle_normals_stride = 3 * sizeof(float);
    if (o->evidence.vertex_normals_stride == 0)
        o->evidence.vertex_normals_stride = 3 * sizeof(float);
    if (o->evidence.sigma == 0)
        o->evidence.sigma = 3.0f;
    if (o->up[0] == 0 && o->up[1] == 0 && o->up[2] == 0)
        o->up[2] = 1.0f;
    if (o->seed == 0)
        o->seed = 0x5EEDu;
    if (o->visibility.min_samples == 0)
        o->visibility.min_samples = 16;
    if (o->visibility.coherence_distance == 0)
        o->visibility.coherence_distance = 0.02f;
    if (o->visibility.c0 == 0)
        o->visibility.c0 = 0.5f;
    if (o->visibility.eps == 0)
        o->visibility.eps = 0.02f;
    if (o->visibility.kv == 0)
        o->visibility.kv = 1.5f;
}

/* The options a call runs with, resolved once: the caller's copied (NULL:
   all zero), every field checked as given, then every default filled.
   Checked first: a NaN compares equal to 0 under -ffinite-math-only, and
   must not become a default. Every stage reads this copy and nothing
   else; no index has been read yet. */
MESHFIX__PRIVATE int meshfix__resolve_options(const meshfix_options *caller, int policy, meshfix_options *o)
{
    if (caller != NULL)
        *o = *caller;
    else
        MESHFIX_MEMSET(o, 0, sizeof(*o));
    if (!meshfix__options_valid(o, policy))
        return 0;
    meshfix__fill_defaults(o);
    return 1;
}

/* The policy a call runs (< 0: inspect): AUTO without positions is
   MAJORITY; a policy without what it needs is refused. */
MESHFIX__PRIVATE meshfix_result meshfix__resolve_policy(int *policy, const meshfix__input *in,
                                                      const meshfix_options *o)
{
    if (*policy == MESHFIX_POLICY_AUTO && in->positions == NULL)
        *policy = MESHFIX_POLICY_MAJORITY;
    if (*policy >= 0 && meshfix__policies[*policy].needs_positions && in->positions == NULL)
        return MESHFIX_ERROR_POSITIONS_REQUIRED;
    if (*policy >= 0 && meshfix__policies[*policy].needs_normals && o->evidence.triangle_normals == NULL &&
        o->evidence.vertex_normals == NULL)
        return MESHFIX_ERROR_NORMALS_REQUIRED;
    return MESHFIX_OK;
}

/* inspect's verdict, of the mesh as given */
MESHFIX__PRIVATE meshfix_verdict meshfix__verdict_before(const meshfix_report *r)
{
    if (r->mesh.components_non_orientable != 0)
        return MESHFIX_VERDICT_NOT_ORIENTABLE;
    return r->edges_inconsistent_before != 0  ? MESHFIX_VERDICT_INCONSISTENT
           : r->patches_inside_out_before != 0 ? MESHFIX_VERDICT_INSIDE_OUT
                                               : MESHFIX_VERDICT_CLEAN;
}

MESHFIX__PRIVATE meshfix_verdict meshfix__verdict(const meshfix_report *r, int policy)
{
    if (policy < 0)
        return meshfix__verdict_before(r);
    if (r->mesh.components_non_orientable != 0)
        return MESHFIX_VERDICT_NOT_ORIENTABLE;
    if (r->patches_doubtful != 0)
        return MESHFIX_VERDICT_DOUBTFUL;
    return r->triangles_flipped != 0 ? MESHFIX_VERDICT_REPAIRED : MESHFIX_VERDICT_CLEAN;
}

/* The state of a call: the caller's arguments, resolved, and what
   meshfix_check wants to know beyond the report. */
typedef struct meshfix__call {
    void *destination;
    meshfix_options options;         /* resolved: meshfix__resolve_options */
    meshfix__input input;
    int policy;                      /* < 0: inspect; as asked (the run resolves it: meshfix__resolve_policy) */
    meshfix_report *report;
    meshfix_outputs *outputs;
    unsigned int requirements;       /* meshfix_check: explain the first that fails */
    meshfix_check_failure *failure;
} meshfix__call;

/* The call's scratch in one layout, from its first byte: the topology's
   arrays (plan->total counts the skip to their 16-byte boundary), then
   the geometric stage's arena (its plan counts its own alignment). The
   run and meshfix_scratch_size both lay a call out by it. */
MESHFIX__PRIVATE size_t meshfix__geometry_offset(const meshfix__plan *plan)
{
    return plan->total;
}

/* The pipeline shared by orient, inspect (policy < 0) and check. Outputs
   are written only after every check has passed and the work is done. */
MESHFIX__PRIVATE meshfix_result meshfix__run(meshfix__call *call)
{
    meshfix_memory_options allocator;
    meshfix__plan plan;
    meshfix__mesh m;
    meshfix_report r;
    meshfix_options options;
    meshfix_outputs outputs;
    meshfix__block rest;
    unsigned char *raw, *block;
    size_t vertex_range = 0, joined;
    int policy = call->policy, full;
    const meshfix__input *in = &call->input;
    meshfix_result result;

    /* the options were resolved (meshfix__call_setup); the report may
       share memory with the caller's outputs (it is written last) */
    options = call->options;
    if (call->outputs != NULL)
        outputs = *call->outputs;
    else
        MESHFIX_MEMSET(&outputs, 0, sizeof(outputs));

    /* 1. validate the counts and the indices, then what the policy needs */
    result = meshfix__validate(in, &vertex_range, &plan);
    if (result == MESHFIX_OK)
        result = meshfix__resolve_policy(&policy, in, &options);
    if (result != MESHFIX_OK)
        return result;
    MESHFIX_MEMSET(&r, 0, sizeof(r));
    r.mesh.triangles = in->index_count / 3;
    if (in->index_count == 0) {
        if (call->failure != NULL)
            meshfix__explain(NULL, &r, call->requirements, call->failure);
        if (call->report != NULL)
            *call->report = r;
        return MESHFIX_OK;
    }

    /* one block holds all scratch: the caller's, or a single allocation */
    meshfix__pick_allocator(&options, &allocator);
    if (options.memory.scratch != NULL) {
        if (options.memory.scratch_size < plan.total)
            return MESHFIX_ERROR_SCRATCH_TOO_SMALL;
        raw = (unsigned char *)options.memory.scratch;
    } else {
        raw = (unsigned char *)(allocator.alloc_func != NULL ? allocator.alloc_func(plan.total, allocator.user_data)
                                                             : MESHFIX_MALLOC(plan.total, allocator.user_data));
        if (raw == NULL)
            return MESHFIX_ERROR_OUT_OF_MEMORY;
    }
    block = raw + (16u - (size_t)raw % 16u) % 16u;
    meshfix__bind(&m, block, &plan, in, vertex_range, &options, &outputs, policy);
    m.requirements = call->requirements;
    m.failure = call->failure;
    /* what the caller's scratch holds beyond the topology: the geometry's */
    MESHFIX_MEMSET(&rest, 0, sizeof(rest));
    if (options.memory.scratch != NULL) {
        rest.base = raw + meshfix__geometry_offset(&plan);
        rest.size = options.memory.scratch_size - meshfix__geometry_offset(&plan);
    }

    /* 2. input: vertex ids after the topology, float positions */
    full = call->report != NULL || outputs.components != NULL || call->failure != NULL;
    joined = meshfix__read_input(&m, in, &plan, block, full);

    /* 3-6. edges, patches, components, policy */
    result = meshfix__analyze(&m, policy, &options, full, &allocator, &rest, &r);

    /* 7. write: nothing can fail from here on */
    if (result == MESHFIX_OK) {
        r.mesh.vertices_joined = joined;
        r.verdict = meshfix__verdict(&r, policy);
        r.verdict_before = meshfix__verdict_before(&r);
        meshfix__write_outputs(&m, policy >= 0 ? (unsigned char *)call->destination : NULL, policy);
        if (call->report != NULL)
            *call->report = r;
    }
    if (raw != (unsigned char *)options.memory.scratch)
        meshfix__release(&allocator, raw);
    return result;
}

/* ===== >>check ===== */

/* A line of text in a caller's buffer: written as far as it fits (always
   terminated), its whole length counted, as snprintf would (which C89 and
   freestanding builds do not have). */
typedef struct meshfix__line {
    char *buffer;
    size_t size, length;
} meshfix__line;

MESHFIX__PRIVATE void meshfix__say(meshfix__line *l, const char *text)
{
    for (; *text != '\0'; ++text, ++l->length)
        if (l->length + 1 < l->size)
            l->buffer[l->length] = *text;
    if (l->size != 0)
        l->buffer[l->length + 1 < l->size ? l->length : l->size - 1] = '\0';
}

MESHFIX__PRIVATE void meshfix__say_number(meshfix__line *l, size_t n)
{
    char digits[24];
    int i = (int)sizeof(digits) - 1;
    digits[i] = '\0';
    do {
        digits[--i] = (char)('0' + (int)(n % 10));
        n /= 10;
    } while (n != 0);
    meshfix__say(l, digits + i);
}

/* "1 patch", "3 patches" */
MESHFIX__PRIVATE void meshfix__say_count(meshfix__line *l, size_t n, const char *one, const char *many)
{
    meshfix__say_number(l, n);
    meshfix__say(l, " ");
    meshfix__say(l, n == 1 ? one : many);
}

/* a share as a percentage with one decimal: "1.2%" */
MESHFIX__PRIVATE void meshfix__say_percent(meshfix__line *l, double share)
{
    size_t tenths = (size_t)(share * 1000.0 + 0.5);
    char decimal[3];
    meshfix__say_number(l, tenths / 10);
    decimal[0] = '.', decimal[1] = (char)('0' + (int)(tenths % 10)), decimal[2] = '\0';
    meshfix__say(l, decimal);
    meshfix__say(l, "%");
}

MESHFIX__PRIVATE void meshfix__say_edge(meshfix__line *l, const unsigned int ends[2])
{
    meshfix__say(l, "edge ");
    meshfix__say_number(l, ends[0]);
    meshfix__say(l, "-");
    meshfix__say_number(l, ends[1]);
}

/* meshfix_check's explanation: the first requirement that fails, the
   lowest triangle (or edge, vertex, patch) that fails it, in one line. */

MESHFIX__PRIVATE void meshfix__edge_ends(const meshfix__mesh *m, unsigned int h, unsigned int ends[2])
{
    unsigned int a = m->indices[h], b = m->indices[h % 3 == 2 ? h - 2 : h + 1];
    ends[0] = a < b ? a : b;
    ends[1] = a < b ? b : a;
}

/* The lowest half-edge on an inconsistent edge, and the triangle after it
   that runs it the same way (NONE for an edge of 3+ triangles). */
MESHFIX__PRIVATE unsigned int meshfix__first_inconsistent(const meshfix__mesh *m, unsigned int *other)
{
    unsigned int h, half_edges = (unsigned int)(3 * m->triangle_count);
    for (h = 0; h < half_edges; ++h) {
        unsigned int g = m->mate[h];
        if (meshfix__is_ring(g)) {
            *other = MESHFIX__NONE;
            return h;
        }
        if (meshfix__is_mate(g) &&
            ((unsigned int)meshfix__same_direction(m, h, g) ^ meshfix__flip_of(m, h / 3) ^ meshfix__flip_of(m, g / 3))) {
            *other = g / 3;
            return h;
        }
    }
    return MESHFIX__NONE;
}

MESHFIX__PRIVATE unsigned int meshfix__first_boundary(const meshfix__mesh *m)
{
    unsigned int h, half_edges = (unsigned int)(3 * m->triangle_count);
    for (h = 0; h < half_edges; ++h)
        if (m->mate[h] == MESHFIX__NONE && !(m->tri_bits[h / 3] & MESHFIX__TRI_DEGENERATE))
            return h;
    return MESHFIX__NONE;
}

MESHFIX__PRIVATE unsigned int meshfix__first_ring(const meshfix__mesh *m)
{
    unsigned int h, half_edges = (unsigned int)(3 * m->triangle_count);
    for (h = 0; h < half_edges; ++h)
        if (meshfix__is_ring(m->mate[h]))
            return h;
    return MESHFIX__NONE;
}

MESHFIX__PRIVATE unsigned int meshfix__first_with_vertex(const meshfix__mesh *m, unsigned int v)
{
    size_t i;
    for (i = 0; i < 3 * m->triangle_count; ++i)
        if (m->indices[i] == v)
            return (unsigned int)(i / 3);
    return MESHFIX__NONE;
}

/* The lowest triangle of a closed patch wound one way that faces inward. */
MESHFIX__PRIVATE unsigned int meshfix__first_inside_out(meshfix__mesh *m)
{
    unsigned int p, first = MESHFIX__NONE;
    for (p = 0; p < m->patch_count; ++p) {
        meshfix__patch_sums s;
        if (!meshfix__is_closed_orientable(m, p))
            continue;
        meshfix__sum_patch(m, p, &s);
        if (s.reversed == 0 && s.volume_given < 0.0 && meshfix__volume_is_meaningful(s.volume_given, s.area)) {
            unsigned int t = m->queue[m->patch_start[p]];
            first = t < first ? t : first;
        }
    }
    return first;
}

MESHFIX__PRIVATE unsigned int meshfix__first_degenerate(const meshfix__mesh *m)
{
    size_t t;
    for (t = 0; t < m->triangle_count; ++t)
        if ((m->tri_bits[t] & (MESHFIX__TRI_DEGENERATE | MESHFIX__TRI_DUPLICATE)) ||
            (m->positions != NULL && !meshfix__has_area(m, (unsigned int)t)))
            return (unsigned int)t;
    return MESHFIX__NONE;
}

/* The failure in one line: what fails, how often, the first place. */
MESHFIX__PRIVATE void meshfix__explain_text(const meshfix__mesh *m, meshfix_check_failure *f, unsigned int h,
                                           unsigned int other, unsigned int v, const meshfix_report *r)
{
    meshfix__line l;
    unsigned int ends[2];
    l.buffer = f->text, l.size = sizeof(f->text), l.length = 0;
    ends[0] = f->edge[0], ends[1] = f->edge[1];
    switch (f->requirement) {
    case MESHFIX_REQUIRE_CONSISTENT:
        meshfix__say(&l, "not consistent: ");
        meshfix__say_count(&l, f->count, "edge runs", "edges run");
        meshfix__say(&l, " the same way in two or more triangles");
        if (m != NULL && h != MESHFIX__NONE) {
            meshfix__say(&l, "; ");
            meshfix__say_edge(&l, ends);
            if (other != MESHFIX__NONE) {
                meshfix__say(&l, " runs ");
                meshfix__say_number(&l, m->indices[h]);
                meshfix__say(&l, "->");
                meshfix__say_number(&l, m->indices[h % 3 == 2 ? h - 2 : h + 1]);
                meshfix__say(&l, " in triangles ");
                meshfix__say_number(&l, f->triangle);
                meshfix__say(&l, " and ");
                meshfix__say_number(&l, other);
            } else {
                meshfix__say(&l, " (triangle ");
                meshfix__say_number(&l, f->triangle);
                meshfix__say(&l, ") has 3 or more triangles");
            }
        }
        break;
    case MESHFIX_REQUIRE_CLOSED:
        meshfix__say(&l, "not closed: ");
        meshfix__say_count(&l, f->count, "boundary edge", "boundary edges");
        if (h != MESHFIX__NONE) {
            meshfix__say(&l, "; ");
            meshfix__say_edge(&l, ends);
            meshfix__say(&l, " of triangle ");
            meshfix__say_number(&l, f->triangle);
            meshfix__say(&l, " has no neighbour");
        }
        break;
    case MESHFIX_REQUIRE_MANIFOLD:
        meshfix__say(&l, "not manifold: ");
        meshfix__say_count(&l, f->count, "edge or vertex", "edges and vertices");
        if (h != MESHFIX__NONE) {
            meshfix__say(&l, "; ");
            meshfix__say_edge(&l, ends);
            meshfix__say(&l, " (triangle ");
            meshfix__say_number(&l, f->triangle);
            meshfix__say(&l, ") has 3 or more triangles");
        } else if (v != MESHFIX__NONE) {
            meshfix__say(&l, "; vertex ");
            meshfix__say_number(&l, v);
            meshfix__say(&l, " (triangle ");
            meshfix__say_number(&l, f->triangle);
            meshfix__say(&l, ") joins separate fans of triangles");
        }
        break;
    case MESHFIX_REQUIRE_OUTWARD:
        meshfix__say(&l, "not outward: ");
        meshfix__say_count(&l, f->count, "closed patch faces", "closed patches face");
        meshfix__say(&l, " inward");
        if (f->triangle != (size_t)-1) {
            meshfix__say(&l, "; the first holds triangle ");
            meshfix__say_number(&l, f->triangle);
        }
        break;
    case MESHFIX_REQUIRE_NO_DEGENERATE:
        meshfix__say(&l, "degenerate: ");
        meshfix__say_count(&l, r->mesh.triangles_degenerate, "triangle repeats", "triangles repeat");
        meshfix__say(&l, " a vertex, ");
        meshfix__say_number(&l, r->mesh.triangles_zero_area);
        meshfix__say(&l, " have no area, ");
        meshfix__say_number(&l, r->mesh.triangles_duplicate);
        meshfix__say(&l, " are duplicates");
        if (f->triangle != (size_t)-1) {
            meshfix__say(&l, "; the first is triangle ");
            meshfix__say_number(&l, f->triangle);
        }
        break;
    default:
        meshfix__say(&l, "ok");
    }
}

MESHFIX__PRIVATE void meshfix__explain(meshfix__mesh *m, const meshfix_report *r, unsigned int requirements,
                                      meshfix_check_failure *f)
{
    const meshfix_mesh_facts *k = &r->mesh;
    unsigned int h = MESHFIX__NONE, t = MESHFIX__NONE, other = MESHFIX__NONE, v = MESHFIX__NONE, ends[2];
    f->result = MESHFIX_OK;
    f->requirement = 0;
    f->count = 0;
    f->triangle = (size_t)-1;
    f->edge[0] = f->edge[1] = MESHFIX__NONE;
    ends[0] = ends[1] = MESHFIX__NONE;
    if ((requirements & MESHFIX_REQUIRE_CONSISTENT) && k->edges_inconsistent != 0) {
        f->requirement = MESHFIX_REQUIRE_CONSISTENT, f->count = k->edges_inconsistent;
        h = m != NULL ? meshfix__first_inconsistent(m, &other) : MESHFIX__NONE;
    } else if ((requirements & MESHFIX_REQUIRE_CLOSED) && k->edges_boundary != 0) {
        f->requirement = MESHFIX_REQUIRE_CLOSED, f->count = k->edges_boundary;
        h = m != NULL ? meshfix__first_boundary(m) : MESHFIX__NONE;
    } else if ((requirements & MESHFIX_REQUIRE_MANIFOLD) && k->edges_non_manifold + k->vertices_non_manifold != 0) {
        f->requirement = MESHFIX_REQUIRE_MANIFOLD, f->count = k->edges_non_manifold + k->vertices_non_manifold;
        h = m != NULL ? meshfix__first_ring(m) : MESHFIX__NONE;
        if (m != NULL && h == MESHFIX__NONE) {
            v = m->first_non_manifold_vertex;
            t = meshfix__first_with_vertex(m, v);
        }
    } else if ((requirements & MESHFIX_REQUIRE_OUTWARD) && k->patches_inside_out != 0) {
        f->requirement = MESHFIX_REQUIRE_OUTWARD, f->count = k->patches_inside_out;
        t = m != NULL ? meshfix__first_inside_out(m) : MESHFIX__NONE;
    } else if ((requirements & MESHFIX_REQUIRE_NO_DEGENERATE) &&
               k->triangles_degenerate + k->triangles_zero_area + k->triangles_duplicate != 0) {
        f->requirement = MESHFIX_REQUIRE_NO_DEGENERATE;
        f->count = k->triangles_degenerate + k->triangles_zero_area + k->triangles_duplicate;
        t = m != NULL ? meshfix__first_degenerate(m) : MESHFIX__NONE;
    }
    if (h != MESHFIX__NONE) {
        t = h / 3;
        meshfix__edge_ends(m, h, ends);
        f->edge[0] = ends[0], f->edge[1] = ends[1];
    }
    if (t != MESHFIX__NONE)
        f->triangle = t;
    meshfix__explain_text(m, f, h, other, v, r);
}

/* ===== >>public ===== */

MESHFIX__PRIVATE meshfix_result meshfix__call_setup(meshfix__call *call, void *destination, const void *indices,
                                                  size_t index_count, const void *positions, size_t vertex_count,
                                                  size_t stride, const meshfix_options *options, int policy,
                                                  meshfix_report *report, meshfix_outputs *outputs)
{
    MESHFIX_MEMSET(call, 0, sizeof(*call));
    call->destination = destination;
    call->report = report;
    call->outputs = outputs;
    if (!meshfix__resolve_options(options, policy, &call->options) ||
        !meshfix__describe_input(&call->input, indices, index_count, positions, vertex_count, stride, &call->options))
        return MESHFIX_ERROR_INVALID_ARGUMENT;
    call->policy = policy;
    return MESHFIX_OK;
}

MESHFIX_API meshfix_result meshfix_orient(void *destination, const void *indices, size_t index_count,
                                          const void *positions, size_t vertex_count, size_t stride,
                                          const meshfix_options *options, meshfix_report *report,
                                          meshfix_outputs *outputs)
{
    meshfix__call call;
    int policy = options != NULL ? (int)options->policy : (int)MESHFIX_POLICY_AUTO;
    meshfix_result result;
    if (policy < 0 || policy >= (int)MESHFIX_POLICY_COUNT)
        return MESHFIX_ERROR_INVALID_ARGUMENT;
    result = meshfix__call_setup(&call, destination, indices, index_count, positions, vertex_count, stride, options,
                                 policy, report, outputs);
    return result != MESHFIX_OK ? result : meshfix__run(&call);
}

MESHFIX_API meshfix_result meshfix_inspect(const void *indices, size_t index_count, const void *positions,
                                           size_t vertex_count, size_t stride, const meshfix_options *options,
                                           meshfix_report *report, meshfix_outputs *outputs)
{
    meshfix__call call;
    meshfix_result result;
    if (report == NULL)
        return MESHFIX_ERROR_INVALID_ARGUMENT;
    result = meshfix__call_setup(&call, NULL, indices, index_count, positions, vertex_count, stride, options, -1,
                                 report, outputs);
    return result != MESHFIX_OK ? result : meshfix__run(&call);
}

MESHFIX_API int meshfix_check(const void *indices, size_t index_count, const void *positions, size_t vertex_count,
                              size_t stride, unsigned int requirements, const meshfix_options *options,
                              meshfix_check_failure *failure)
{
    meshfix__call call;
    meshfix_check_failure local;
    meshfix_report r;
    meshfix_result result;
    unsigned int needs_positions = MESHFIX_REQUIRE_OUTWARD | MESHFIX_REQUIRE_NO_DEGENERATE;
    meshfix_check_failure *f = failure != NULL ? failure : &local;
    if (requirements == 0)
        requirements = MESHFIX_REQUIRE_CONSISTENT;
    result = meshfix__call_setup(&call, NULL, indices, index_count, positions, vertex_count, stride, options, -1, &r,
                                 NULL);
    if (result == MESHFIX_OK && (requirements & needs_positions) && positions == NULL)
        result = MESHFIX_ERROR_POSITIONS_REQUIRED;
    if (result == MESHFIX_OK) {
        call.requirements = requirements;
        call.failure = f;
        result = meshfix__run(&call);
    }
    if (result != MESHFIX_OK) {
        MESHFIX_MEMSET(f, 0, sizeof(*f));
        f->result = result;
        f->triangle = (size_t)-1;
        f->edge[0] = f->edge[1] = MESHFIX__NONE;
        {
            meshfix__line l;
            l.buffer = f->text, l.size = sizeof(f->text), l.length = 0;
            meshfix__say(&l, "not valid input: ");
            meshfix__say(&l, meshfix_result_string(result));
            if (result == MESHFIX_ERROR_INDEX_OUT_OF_RANGE) {
                /* where: the first index that is out of range */
                size_t i = 0;
                while (meshfix__source_index(&call.input, i) < vertex_count)
                    ++i;
                f->triangle = i / 3;
                f->count = 1;
                meshfix__say(&l, "; index ");
                meshfix__say_number(&l, meshfix__source_index(&call.input, i));
                meshfix__say(&l, " in triangle ");
                meshfix__say_number(&l, i / 3);
                meshfix__say(&l, ", ");
                meshfix__say_count(&l, vertex_count, "vertex", "vertices");
            }
        }
        return 0;
    }
    return f->requirement == 0;
}

MESHFIX_API size_t meshfix_scratch_size(size_t index_count, size_t vertex_count, const meshfix_options *options)
{
    meshfix__plan plan;
    meshfix__geometry_counts worst;
    meshfix__geometry_plan geometry;
    meshfix__input in;
    meshfix_options resolved;
    size_t triangles = index_count / 3;
    int policy = options != NULL ? (int)options->policy : (int)MESHFIX_POLICY_AUTO;
    static const float some_position[3] = {0, 0, 0};
    /* the plan of a mesh with positions: the input stage's arrays included */
    if (policy < 0 || policy >= (int)MESHFIX_POLICY_COUNT)
        return 0;
    if (!meshfix__resolve_options(options, -1, &resolved) ||
        !meshfix__describe_input(&in, NULL, index_count, some_position, vertex_count, 0, &resolved))
        return 0;
    if (index_count == 0 || index_count > MESHFIX__MAX_INDEX_COUNT ||
        !meshfix__make_plan(&plan, vertex_count, triangles, &in))
        return 0;
    if (!meshfix__policies[policy].casts_rays)
        return plan.total;
    /* the worst mesh: a soup, every triangle its own patch, every edge a boundary or in a ring */
    worst.triangles = worst.patches = triangles;
    worst.boundary = worst.rings = worst.largest_ring = 3 * triangles;
    if (!meshfix__plan_geometry(&worst, policy, &geometry) ||
        meshfix__geometry_offset(&plan) + geometry.total < geometry.total)
        return 0;
    return meshfix__geometry_offset(&plan) + geometry.total;
}

MESHFIX_API meshfix_result meshfix_weld(unsigned int *remap, const void *positions, size_t vertex_count,
                                        size_t stride, float tolerance, const meshfix_options *options,
                                        size_t *unique_count)
{
    meshfix_memory_options allocator;
    meshfix_options resolved;
    meshfix__welder w;
    unsigned int *block, *result;
    unsigned int size;
    size_t v, buckets, unique, words;
    double p[3];
    if (vertex_count == 0) {
        if (unique_count != NULL)
            *unique_count = 0;
        return MESHFIX_OK;
    }
    if (!meshfix__resolve_options(options, -1, &resolved))
        return MESHFIX_ERROR_INVALID_ARGUMENT;
    size = resolved.position_size;
    if (stride == 0)
        stride = 3 * (size_t)size;
    if (remap == NULL || positions == NULL || stride < 3 * (size_t)size || stride % 4 != 0 ||
        !meshfix__is_finite(tolerance) || tolerance < 0.0f)
        return MESHFIX_ERROR_INVALID_ARGUMENT;
    if (vertex_count > MESHFIX__MAX_VERTEX_COUNT - 1 || !meshfix__vertices_addressable(vertex_count, stride, 3 * (size_t)size))
        return MESHFIX_ERROR_TOO_LARGE;
    for (v = 0; v < vertex_count; ++v)
        if (!meshfix__read_point((const unsigned char *)positions, stride, size, v, p))
            return MESHFIX_ERROR_NON_FINITE;
    meshfix__pick_allocator(&resolved, &allocator);
    /* the welder's words, then the result */
    buckets = meshfix__weld_buckets(vertex_count);
    words = meshfix__welder_words(vertex_count, buckets);
    if (words == 0)
        return MESHFIX_ERROR_TOO_LARGE;
    block = (unsigned int *)meshfix__allocate(&allocator, words + vertex_count, sizeof(unsigned int));
    if (block == NULL)
        return MESHFIX_ERROR_OUT_OF_MEMORY;
    MESHFIX_MEMSET(&w, 0, sizeof(w));
    w.positions = (const unsigned char *)positions;
    w.stride = stride;
    w.position_size = size;
    /* a hair wider than the tolerance, so rounding in the division never
       puts two vertices within it more than one cell apart */
    w.cell = (double)tolerance * (1.0 + 1e-9);
    meshfix__carve_welder(&w, block, vertex_count, buckets);
    result = block + words;
    unique = meshfix__weld_run(&w, vertex_count, (double)tolerance, result);
    MESHFIX_MEMCPY(remap, result, vertex_count * sizeof(unsigned int));
    if (unique_count != NULL)
        *unique_count = unique;
    meshfix__release(&allocator, block);
    return MESHFIX_OK;
}

/* The share of the area (or of the triangles, without positions) that
   the doubtful patches hold. */
MESHFIX__PRIVATE double meshfix__doubtful_share(const meshfix_report *r)
{
    if (r->mesh.area > 0.0)
        return r->area_doubtful / r->mesh.area;
    return r->mesh.triangles != 0 ? (double)r->triangles_doubtful / (double)r->mesh.triangles : 0.0;
}

MESHFIX__PRIVATE void meshfix__say_fixed(meshfix__line *l, const meshfix_report *r)
{
    meshfix__say(l, "fixed ");
    meshfix__say_count(l, r->triangles_flipped, "triangle", "triangles");
    meshfix__say(l, " in ");
    meshfix__say_count(l, r->patches_flipped, "patch", "patches");
}

MESHFIX_API size_t meshfix_summary(const meshfix_report *r, char *buffer, size_t size)
{
    meshfix__line l;
    l.buffer = buffer, l.size = buffer != NULL ? size : 0, l.length = 0;
    switch (r->verdict) {
    case MESHFIX_VERDICT_CLEAN:
        meshfix__say(&l, "clean: nothing to flip (");
        meshfix__say_count(&l, r->mesh.triangles, "triangle", "triangles");
        meshfix__say(&l, ", ");
        meshfix__say_count(&l, r->mesh.patches, "patch", "patches");
        if (r->mesh.triangles_degenerate != 0) { /* no patch for them: say why */
            meshfix__say(&l, ", ");
            meshfix__say_number(&l, r->mesh.triangles_degenerate);
            meshfix__say(&l, " degenerate");
        }
        meshfix__say(&l, ")");
        break;
    case MESHFIX_VERDICT_REPAIRED:
        meshfix__say_fixed(&l, r);
        break;
    case MESHFIX_VERDICT_DOUBTFUL:
        if (r->triangles_flipped != 0)
            meshfix__say_fixed(&l, r);
        else
            meshfix__say(&l, "nothing flipped");
        meshfix__say(&l, "; ");
        meshfix__say_count(&l, r->patches_doubtful, "patch", "patches");
        meshfix__say(&l, " (");
        meshfix__say_percent(&l, meshfix__doubtful_share(r));
        meshfix__say(&l, r->mesh.area > 0.0 ? " of the area) doubtful" : " of the triangles) doubtful");
        break;
    case MESHFIX_VERDICT_NOT_ORIENTABLE:
        meshfix__say(&l, "not orientable: ");
        meshfix__say_count(&l, r->mesh.components_non_orientable, "component (Moebius or Klein) keeps",
                           "components (Moebius or Klein) keep");
        meshfix__say(&l, " ");
        meshfix__say_count(&l, r->mesh.edges_inconsistent, "inconsistent edge", "inconsistent edges");
        meshfix__say(&l, "; ");
        meshfix__say_fixed(&l, r);
        break;
    case MESHFIX_VERDICT_INCONSISTENT:
        meshfix__say(&l, "inconsistent: ");
        meshfix__say_count(&l, r->mesh.edges_inconsistent, "edge runs", "edges run");
        meshfix__say(&l, " the same way in two or more triangles (");
        meshfix__say_count(&l, r->mesh.patches, "patch", "patches");
        meshfix__say(&l, ")");
        break;
    case MESHFIX_VERDICT_INSIDE_OUT:
        meshfix__say(&l, "inside out: ");
        meshfix__say_count(&l, r->mesh.patches_inside_out, "closed patch faces", "closed patches face");
        meshfix__say(&l, " inward");
        break;
    default:
        meshfix__say(&l, "unknown verdict");
    }
    return l.length;
}

MESHFIX_API const char *meshfix_verdict_string(meshfix_verdict verdict)
{
#define MESHFIX__VERDICT_TEXT(name, text, rank) text,
    static const char *const texts[] = {MESHFIX_VERDICT_LIST(MESHFIX__VERDICT_TEXT) "unknown verdict"};
#undef MESHFIX__VERDICT_TEXT
    unsigned int i = (unsigned int)verdict;
    return texts[i < (unsigned int)MESHFIX_VERDICT_COUNT ? i : (unsigned int)MESHFIX_VERDICT_COUNT];
}

MESHFIX_API meshfix_verdict meshfix_verdict_worst(meshfix_verdict a, meshfix_verdict b)
{
#define MESHFIX__VERDICT_RANK(name, text, rank) rank,
    static const unsigned char ranks[] = {MESHFIX_VERDICT_LIST(MESHFIX__VERDICT_RANK) 0};
#undef MESHFIX__VERDICT_RANK
    unsigned int i = (unsigned int)a, k = (unsigned int)b;
    if (k >= (unsigned int)MESHFIX_VERDICT_COUNT)
        return a;
    if (i >= (unsigned int)MESHFIX_VERDICT_COUNT)
        return b;
    return ranks[k] > ranks[i] ? b : a;
}

MESHFIX_API const meshfix_policy_facts *meshfix_policy_info(meshfix_policy policy)
{
    unsigned int i = (unsigned int)policy;
    return i < (unsigned int)MESHFIX_POLICY_COUNT ? &meshfix__policies[i] : NULL;
}

MESHFIX_API float meshfix_doubtful_below(const meshfix_options *options, meshfix_policy policy)
{
    meshfix_options defaults;
    if (options == NULL) {
        MESHFIX_MEMSET(&defaults, 0, sizeof(defaults));
        options = &defaults;
    }
    return (float)meshfix__doubtful_below(options, (int)policy);
}

MESHFIX_API const char *meshfix_policy_string(meshfix_policy policy)
{
    unsigned int i = (unsigned int)policy;
    return i < (unsigned int)MESHFIX_POLICY_COUNT ? meshfix__policies[i].name : "unknown policy";
}

MESHFIX_API meshfix_policy meshfix_policy_from_string(const char *name)
{
    unsigned int i, k;
    for (i = 0; name != NULL && i < (unsigned int)MESHFIX_POLICY_COUNT; ++i) {
        const char *known = meshfix__policies[i].name;
        for (k = 0; known[k] != 0 && name[k] == known[k]; ++k)
            ;
        if (known[k] == 0 && name[k] == 0)
            return (meshfix_policy)i;
    }
    return MESHFIX_POLICY_COUNT;
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
