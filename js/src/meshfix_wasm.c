/* meshfix_wasm.c - the WebAssembly face of meshfix.h for js/ (the npm package).

   Built by js/scripts/build.mjs with Emscripten into a standalone .wasm
   that the JavaScript API (js/src/api.js) loads from base64. It exports
   meshfix.h's functions as they are, and an account of the public structs
   (mfjs_layout): each field's path, offset, size and kind of number, all
   from the compiler. JavaScript reads and writes the structs through that
   table alone, and checks it at load time (js/src/layout.js, as
   python/meshfix checks its ctypes mirror): the fields must tile each
   struct the way C lays it out, so a field added to meshfix.h but not
   listed here fails loudly instead of being skipped or misread. The list
   below is the only list of fields; JavaScript takes its names from it
   (visibility.min_samples becomes visibility.minSamples). */
#include <emscripten/emscripten.h>

#define MESHFIX_API EMSCRIPTEN_KEEPALIVE
#define MESHFIX_IMPLEMENTATION
#include "meshfix.h"

#include <stdio.h>

#define MFJS_API EMSCRIPTEN_KEEPALIVE

/* ---- the layout of the public structs ---- */

typedef struct mfjs_line {
    const char *record; /* "struct path", or "type name" */
    size_t offset, size;
    size_t element;     /* the size of one element: size / element elements (arrays) */
    char kind;          /* u, i: unsigned, signed integer; f: floating; c: char; p: anything else (pointers) */
} mfjs_line;

/* The kind of number a field holds, from its type (enums are integers);
   what no case names (pointers, and a nested struct listed by mistake)
   is 'p', whose size JavaScript checks. */
#define MFJS_KIND(x)                                                                                                   \
    __extension__ _Generic((x), char: 'c', signed char: 'i', short: 'i', int: 'i', long: 'i', long long: 'i',          \
                           _Bool: 'u', unsigned char: 'u', unsigned short: 'u', unsigned int: 'u', unsigned long: 'u', \
                           unsigned long long: 'u', float: 'f', double: 'f', default: 'p')
#define MFJS_MEMBER(type, path) (((type *)0)->path)
#define MFJS_STRUCT(type) {#type " -", 0, sizeof(type), sizeof(type), '-'},
#define MFJS_FIELD(type, path)                                                                                        \
    {#type " " #path, offsetof(type, path), sizeof(MFJS_MEMBER(type, path)), sizeof(MFJS_MEMBER(type, path)),          \
     MFJS_KIND(MFJS_MEMBER(type, path))},
#define MFJS_ARRAY(type, path)                                                                                        \
    {#type " " #path, offsetof(type, path), sizeof(MFJS_MEMBER(type, path)), sizeof(MFJS_MEMBER(type, path)[0]),       \
     MFJS_KIND(MFJS_MEMBER(type, path)[0])},
#define MFJS_TYPE(name, type) {"type " name, 0, sizeof(type), sizeof(type), MFJS_KIND((type)0)},

static const mfjs_line mfjs_lines[] = {
    MFJS_TYPE("size_t", size_t)
    MFJS_TYPE("pointer", void *)
    MFJS_STRUCT(meshfix_options)
    MFJS_FIELD(meshfix_options, index_size)
    MFJS_FIELD(meshfix_options, position_size)
    MFJS_FIELD(meshfix_options, topology)
    MFJS_FIELD(meshfix_options, weld_tolerance)
    MFJS_FIELD(meshfix_options, policy)
    MFJS_ARRAY(meshfix_options, up)
    MFJS_FIELD(meshfix_options, seed)
    MFJS_FIELD(meshfix_options, evidence.sigma)
    MFJS_FIELD(meshfix_options, evidence.min_confidence)
    MFJS_FIELD(meshfix_options, evidence.triangle_normals)
    MFJS_FIELD(meshfix_options, evidence.triangle_normals_stride)
    MFJS_FIELD(meshfix_options, evidence.vertex_normals)
    MFJS_FIELD(meshfix_options, evidence.vertex_normals_stride)
    MFJS_FIELD(meshfix_options, visibility.rays)
    MFJS_FIELD(meshfix_options, visibility.min_samples)
    MFJS_FIELD(meshfix_options, visibility.coherence_distance)
    MFJS_FIELD(meshfix_options, visibility.c0)
    MFJS_FIELD(meshfix_options, visibility.eps)
    MFJS_FIELD(meshfix_options, visibility.kv)
    MFJS_FIELD(meshfix_options, visibility.flags)
    MFJS_FIELD(meshfix_options, sdf.distance)
    MFJS_FIELD(meshfix_options, sdf.gradient)
    MFJS_FIELD(meshfix_options, sdf.user)
    MFJS_FIELD(meshfix_options, sdf.step)
    MFJS_FIELD(meshfix_options, sdf.mode)
    MFJS_FIELD(meshfix_options, memory.alloc_func)
    MFJS_FIELD(meshfix_options, memory.free_func)
    MFJS_FIELD(meshfix_options, memory.user_data)
    MFJS_FIELD(meshfix_options, memory.scratch)
    MFJS_FIELD(meshfix_options, memory.scratch_size)
    MFJS_FIELD(meshfix_options, parallel_for)
    MFJS_FIELD(meshfix_options, parallel_user)
    MFJS_STRUCT(meshfix_outputs)
    MFJS_FIELD(meshfix_outputs, flipped)
    MFJS_FIELD(meshfix_outputs, patch_ids)
    MFJS_FIELD(meshfix_outputs, patch_confidence)
    MFJS_FIELD(meshfix_outputs, patch_confidence_capacity)
    MFJS_FIELD(meshfix_outputs, components)
    MFJS_FIELD(meshfix_outputs, components_capacity)
    MFJS_FIELD(meshfix_outputs, patch_evidence)
    MFJS_FIELD(meshfix_outputs, patch_evidence_capacity)
    MFJS_STRUCT(meshfix_component)
    MFJS_FIELD(meshfix_component, first_triangle)
    MFJS_FIELD(meshfix_component, triangles)
    MFJS_FIELD(meshfix_component, vertices)
    MFJS_FIELD(meshfix_component, edges)
    MFJS_FIELD(meshfix_component, edges_boundary)
    MFJS_FIELD(meshfix_component, edges_non_manifold)
    MFJS_FIELD(meshfix_component, patches)
    MFJS_FIELD(meshfix_component, euler_characteristic)
    MFJS_FIELD(meshfix_component, closed)
    MFJS_FIELD(meshfix_component, orientable)
    MFJS_FIELD(meshfix_component, area)
    MFJS_FIELD(meshfix_component, signed_volume)
    MFJS_STRUCT(meshfix_report)
    MFJS_FIELD(meshfix_report, verdict)
    MFJS_FIELD(meshfix_report, triangles_flipped)
    MFJS_FIELD(meshfix_report, patches_flipped)
    MFJS_FIELD(meshfix_report, patches_doubtful)
    MFJS_FIELD(meshfix_report, triangles_doubtful)
    MFJS_FIELD(meshfix_report, area_doubtful)
    MFJS_FIELD(meshfix_report, edges_inconsistent_before)
    MFJS_FIELD(meshfix_report, verdict_before)
    MFJS_FIELD(meshfix_report, patches_inside_out_before)
    MFJS_FIELD(meshfix_report, signed_volume_before)
    MFJS_FIELD(meshfix_report, mesh.triangles)
    MFJS_FIELD(meshfix_report, mesh.triangles_degenerate)
    MFJS_FIELD(meshfix_report, mesh.triangles_zero_area)
    MFJS_FIELD(meshfix_report, mesh.triangles_duplicate)
    MFJS_FIELD(meshfix_report, mesh.vertices_used)
    MFJS_FIELD(meshfix_report, mesh.vertices_joined)
    MFJS_FIELD(meshfix_report, mesh.vertices_non_finite)
    MFJS_FIELD(meshfix_report, mesh.vertices_non_manifold)
    MFJS_FIELD(meshfix_report, mesh.edges)
    MFJS_FIELD(meshfix_report, mesh.edges_boundary)
    MFJS_FIELD(meshfix_report, mesh.edges_manifold)
    MFJS_FIELD(meshfix_report, mesh.edges_non_manifold)
    MFJS_FIELD(meshfix_report, mesh.edges_inconsistent)
    MFJS_FIELD(meshfix_report, mesh.patches)
    MFJS_FIELD(meshfix_report, mesh.patches_closed)
    MFJS_FIELD(meshfix_report, mesh.patches_inside_out)
    MFJS_FIELD(meshfix_report, mesh.components)
    MFJS_FIELD(meshfix_report, mesh.components_closed)
    MFJS_FIELD(meshfix_report, mesh.components_non_orientable)
    MFJS_FIELD(meshfix_report, mesh.euler_characteristic)
    MFJS_FIELD(meshfix_report, mesh.area)
    MFJS_FIELD(meshfix_report, mesh.signed_volume)
    MFJS_FIELD(meshfix_report, evidence.patches_by_volume)
    MFJS_FIELD(meshfix_report, evidence.patches_by_parity)
    MFJS_FIELD(meshfix_report, evidence.patches_by_visibility)
    MFJS_FIELD(meshfix_report, evidence.patches_by_normals)
    MFJS_FIELD(meshfix_report, evidence.patches_kept)
    MFJS_FIELD(meshfix_report, evidence.shells_inward)
    MFJS_FIELD(meshfix_report, evidence.rays_cast)
    MFJS_FIELD(meshfix_report, evidence.patch_pairs)
    MFJS_FIELD(meshfix_report, evidence.patches_merged)
    MFJS_FIELD(meshfix_report, evidence.pairs_conflicting)
    MFJS_FIELD(meshfix_report, evidence.sdf_evaluations)
    MFJS_FIELD(meshfix_report, evidence.triangles_sdf_disagree)
    MFJS_FIELD(meshfix_report, evidence.triangles_against_normals)
    MFJS_STRUCT(meshfix_check_failure)
    MFJS_FIELD(meshfix_check_failure, result)
    MFJS_FIELD(meshfix_check_failure, requirement)
    MFJS_FIELD(meshfix_check_failure, count)
    MFJS_FIELD(meshfix_check_failure, triangle)
    MFJS_ARRAY(meshfix_check_failure, edge)
    MFJS_ARRAY(meshfix_check_failure, text)
};

/* One line per record, "struct path offset size element kind" ("struct -
   0 sizeof sizeof -" for a struct itself, "type name 0 size size kind" for
   a C type). Writes at most size bytes (terminated); returns the length
   of the whole text, as meshfix_python_layout does. */
MFJS_API size_t mfjs_layout(char *buffer, size_t size)
{
    char line[160];
    size_t i, length = 0;
    for (i = 0; i < sizeof(mfjs_lines) / sizeof(mfjs_lines[0]); ++i) {
        const mfjs_line *l = &mfjs_lines[i];
        size_t n = (size_t)snprintf(line, sizeof(line), "%s %lu %lu %lu %c\n", l->record, (unsigned long)l->offset,
                                    (unsigned long)l->size, (unsigned long)l->element, l->kind);
        if (buffer != NULL && length + n < size)
            memcpy(buffer + length, line, n + 1);
        length += n;
    }
    return length;
}

/* The result codes' names, "MESHFIX_OK,MESHFIX_ERROR_...", by value. */
#define MFJS_RESULT_NAME(name, text) #name ","
static const char mfjs_result_names[] = MESHFIX_RESULT_LIST(MFJS_RESULT_NAME);
#undef MFJS_RESULT_NAME

MFJS_API const char *mfjs_result_codes(void) { return mfjs_result_names; }
MFJS_API int mfjs_policy_count(void) { return (int)MESHFIX_POLICY_COUNT; }
MFJS_API int mfjs_verdict_count(void) { return (int)MESHFIX_VERDICT_COUNT; }
/* Whether a policy calls a C function (the SDF's distance): not for JavaScript. */
MFJS_API int mfjs_policy_needs_distance(int policy)
{
    const meshfix_policy_facts *facts = meshfix_policy_info((meshfix_policy)policy);
    return facts != NULL && facts->needs_distance;
}
MFJS_API int mfjs_version(void) { return MESHFIX_VERSION; }
MFJS_API void *mfjs_malloc(size_t size) { return malloc(size != 0 ? size : 1); }
MFJS_API void mfjs_free(void *p) { free(p); }
