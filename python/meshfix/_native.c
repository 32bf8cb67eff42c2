/* The shared library the Python module loads with ctypes: meshfix.h's
   implementation, its public functions exported, and the layout of the
   public structs (meshfix_python_layout), which meshfix/__init__.py
   compares with its ctypes mirror at import so a changed header fails
   loudly instead of reading the wrong bytes, and the names of the result
   codes (meshfix_python_result_name). No Python headers needed. */
#if defined(_WIN32)
#define MESHFIX_API __declspec(dllexport)
#elif defined(__GNUC__) || defined(__clang__)
#define MESHFIX_API __attribute__((visibility("default")))
#endif
#define MESHFIX_IMPLEMENTATION
#include "meshfix.h"

#include <stdio.h>
#include <string.h>

typedef struct meshfix_python_line {
    const char *record; /* "struct field" */
    size_t offset, size;
} meshfix_python_line;

#define MESHFIX_PY_STRUCT(type) {#type " -", 0, sizeof(type)},
#define MESHFIX_PY_FIELD(type, field) {#type " " #field, offsetof(type, field), sizeof(((type *)0)->field)},

static const meshfix_python_line meshfix_python_lines[] = {
    MESHFIX_PY_STRUCT(meshfix_memory_options)
    MESHFIX_PY_FIELD(meshfix_memory_options, alloc_func)
    MESHFIX_PY_FIELD(meshfix_memory_options, free_func)
    MESHFIX_PY_FIELD(meshfix_memory_options, user_data)
    MESHFIX_PY_FIELD(meshfix_memory_options, scratch)
    MESHFIX_PY_FIELD(meshfix_memory_options, scratch_size)
    MESHFIX_PY_STRUCT(meshfix_evidence_options)
    MESHFIX_PY_FIELD(meshfix_evidence_options, sigma)
    MESHFIX_PY_FIELD(meshfix_evidence_options, min_confidence)
    MESHFIX_PY_FIELD(meshfix_evidence_options, triangle_normals)
    MESHFIX_PY_FIELD(meshfix_evidence_options, triangle_normals_stride)
    MESHFIX_PY_FIELD(meshfix_evidence_options, vertex_normals)
    MESHFIX_PY_FIELD(meshfix_evidence_options, vertex_normals_stride)
    MESHFIX_PY_STRUCT(meshfix_visibility_options)
    MESHFIX_PY_FIELD(meshfix_visibility_options, rays)
    MESHFIX_PY_FIELD(meshfix_visibility_options, min_samples)
    MESHFIX_PY_FIELD(meshfix_visibility_options, coherence_distance)
    MESHFIX_PY_FIELD(meshfix_visibility_options, c0)
    MESHFIX_PY_FIELD(meshfix_visibility_options, eps)
    MESHFIX_PY_FIELD(meshfix_visibility_options, kv)
    MESHFIX_PY_FIELD(meshfix_visibility_options, flags)
    MESHFIX_PY_STRUCT(meshfix_sdf_options)
    MESHFIX_PY_FIELD(meshfix_sdf_options, distance)
    MESHFIX_PY_FIELD(meshfix_sdf_options, gradient)
    MESHFIX_PY_FIELD(meshfix_sdf_options, user)
    MESHFIX_PY_FIELD(meshfix_sdf_options, step)
    MESHFIX_PY_FIELD(meshfix_sdf_options, mode)
    MESHFIX_PY_STRUCT(meshfix_options)
    MESHFIX_PY_FIELD(meshfix_options, index_size)
    MESHFIX_PY_FIELD(meshfix_options, position_size)
    MESHFIX_PY_FIELD(meshfix_options, topology)
    MESHFIX_PY_FIELD(meshfix_options, weld_tolerance)
    MESHFIX_PY_FIELD(meshfix_options, policy)
    MESHFIX_PY_FIELD(meshfix_options, up)
    MESHFIX_PY_FIELD(meshfix_options, seed)
    MESHFIX_PY_FIELD(meshfix_options, evidence)
    MESHFIX_PY_FIELD(meshfix_options, visibility)
    MESHFIX_PY_FIELD(meshfix_options, sdf)
    MESHFIX_PY_FIELD(meshfix_options, memory)
    MESHFIX_PY_FIELD(meshfix_options, parallel_for)
    MESHFIX_PY_FIELD(meshfix_options, parallel_user)
    MESHFIX_PY_STRUCT(meshfix_component)
    MESHFIX_PY_FIELD(meshfix_component, first_triangle)
    MESHFIX_PY_FIELD(meshfix_component, triangles)
    MESHFIX_PY_FIELD(meshfix_component, vertices)
    MESHFIX_PY_FIELD(meshfix_component, edges)
    MESHFIX_PY_FIELD(meshfix_component, edges_boundary)
    MESHFIX_PY_FIELD(meshfix_component, edges_non_manifold)
    MESHFIX_PY_FIELD(meshfix_component, patches)
    MESHFIX_PY_FIELD(meshfix_component, euler_characteristic)
    MESHFIX_PY_FIELD(meshfix_component, closed)
    MESHFIX_PY_FIELD(meshfix_component, orientable)
    MESHFIX_PY_FIELD(meshfix_component, area)
    MESHFIX_PY_FIELD(meshfix_component, signed_volume)
    MESHFIX_PY_STRUCT(meshfix_outputs)
    MESHFIX_PY_FIELD(meshfix_outputs, flipped)
    MESHFIX_PY_FIELD(meshfix_outputs, patch_ids)
    MESHFIX_PY_FIELD(meshfix_outputs, patch_confidence)
    MESHFIX_PY_FIELD(meshfix_outputs, patch_confidence_capacity)
    MESHFIX_PY_FIELD(meshfix_outputs, components)
    MESHFIX_PY_FIELD(meshfix_outputs, components_capacity)
    MESHFIX_PY_FIELD(meshfix_outputs, patch_evidence)
    MESHFIX_PY_FIELD(meshfix_outputs, patch_evidence_capacity)
    MESHFIX_PY_STRUCT(meshfix_mesh_facts)
    MESHFIX_PY_FIELD(meshfix_mesh_facts, triangles)
    MESHFIX_PY_FIELD(meshfix_mesh_facts, triangles_degenerate)
    MESHFIX_PY_FIELD(meshfix_mesh_facts, triangles_zero_area)
    MESHFIX_PY_FIELD(meshfix_mesh_facts, triangles_duplicate)
    MESHFIX_PY_FIELD(meshfix_mesh_facts, vertices_used)
    MESHFIX_PY_FIELD(meshfix_mesh_facts, vertices_joined)
    MESHFIX_PY_FIELD(meshfix_mesh_facts, vertices_non_finite)
    MESHFIX_PY_FIELD(meshfix_mesh_facts, vertices_non_manifold)
    MESHFIX_PY_FIELD(meshfix_mesh_facts, edges)
    MESHFIX_PY_FIELD(meshfix_mesh_facts, edges_boundary)
    MESHFIX_PY_FIELD(meshfix_mesh_facts, edges_manifold)
    MESHFIX_PY_FIELD(meshfix_mesh_facts, edges_non_manifold)
    MESHFIX_PY_FIELD(meshfix_mesh_facts, edges_inconsistent)
    MESHFIX_PY_FIELD(meshfix_mesh_facts, patches)
    MESHFIX_PY_FIELD(meshfix_mesh_facts, patches_closed)
    MESHFIX_PY_FIELD(meshfix_mesh_facts, patches_inside_out)
    MESHFIX_PY_FIELD(meshfix_mesh_facts, components)
    MESHFIX_PY_FIELD(meshfix_mesh_facts, components_closed)
    MESHFIX_PY_FIELD(meshfix_mesh_facts, components_non_orientable)
    MESHFIX_PY_FIELD(meshfix_mesh_facts, euler_characteristic)
    MESHFIX_PY_FIELD(meshfix_mesh_facts, area)
    MESHFIX_PY_FIELD(meshfix_mesh_facts, signed_volume)
    MESHFIX_PY_STRUCT(meshfix_evidence_counts)
    MESHFIX_PY_FIELD(meshfix_evidence_counts, patches_by_volume)
    MESHFIX_PY_FIELD(meshfix_evidence_counts, patches_by_parity)
    MESHFIX_PY_FIELD(meshfix_evidence_counts, patches_by_visibility)
    MESHFIX_PY_FIELD(meshfix_evidence_counts, patches_by_normals)
    MESHFIX_PY_FIELD(meshfix_evidence_counts, patches_kept)
    MESHFIX_PY_FIELD(meshfix_evidence_counts, shells_inward)
    MESHFIX_PY_FIELD(meshfix_evidence_counts, rays_cast)
    MESHFIX_PY_FIELD(meshfix_evidence_counts, patch_pairs)
    MESHFIX_PY_FIELD(meshfix_evidence_counts, patches_merged)
    MESHFIX_PY_FIELD(meshfix_evidence_counts, pairs_conflicting)
    MESHFIX_PY_FIELD(meshfix_evidence_counts, sdf_evaluations)
    MESHFIX_PY_FIELD(meshfix_evidence_counts, triangles_sdf_disagree)
    MESHFIX_PY_FIELD(meshfix_evidence_counts, triangles_against_normals)
    MESHFIX_PY_STRUCT(meshfix_report)
    MESHFIX_PY_FIELD(meshfix_report, verdict)
    MESHFIX_PY_FIELD(meshfix_report, triangles_flipped)
    MESHFIX_PY_FIELD(meshfix_report, patches_flipped)
    MESHFIX_PY_FIELD(meshfix_report, patches_doubtful)
    MESHFIX_PY_FIELD(meshfix_report, triangles_doubtful)
    MESHFIX_PY_FIELD(meshfix_report, area_doubtful)
    MESHFIX_PY_FIELD(meshfix_report, edges_inconsistent_before)
    MESHFIX_PY_FIELD(meshfix_report, verdict_before)
    MESHFIX_PY_FIELD(meshfix_report, patches_inside_out_before)
    MESHFIX_PY_FIELD(meshfix_report, signed_volume_before)
    MESHFIX_PY_FIELD(meshfix_report, mesh)
    MESHFIX_PY_FIELD(meshfix_report, evidence)
    MESHFIX_PY_STRUCT(meshfix_check_failure)
    MESHFIX_PY_FIELD(meshfix_check_failure, result)
    MESHFIX_PY_FIELD(meshfix_check_failure, requirement)
    MESHFIX_PY_FIELD(meshfix_check_failure, count)
    MESHFIX_PY_FIELD(meshfix_check_failure, triangle)
    MESHFIX_PY_FIELD(meshfix_check_failure, edge)
    MESHFIX_PY_FIELD(meshfix_check_failure, text)
    MESHFIX_PY_STRUCT(meshfix_policy_facts)
    MESHFIX_PY_FIELD(meshfix_policy_facts, name)
    MESHFIX_PY_FIELD(meshfix_policy_facts, description)
    MESHFIX_PY_FIELD(meshfix_policy_facts, needs_positions)
    MESHFIX_PY_FIELD(meshfix_policy_facts, needs_normals)
    MESHFIX_PY_FIELD(meshfix_policy_facts, needs_distance)
    MESHFIX_PY_FIELD(meshfix_policy_facts, reads_up)
    MESHFIX_PY_FIELD(meshfix_policy_facts, casts_rays)
};

/* One line per struct ("type - 0 sizeof") and per field ("type field
   offset size"), plus the version: "version MAJOR MINOR PATCH". Writes
   at most size bytes (terminated); returns the length of the whole text. */
MESHFIX_API size_t meshfix_python_layout(char *buffer, size_t size);
MESHFIX_API size_t meshfix_python_layout(char *buffer, size_t size)
{
    char line[160];
    size_t i, length = 0;
    for (i = 0; i <= sizeof(meshfix_python_lines) / sizeof(meshfix_python_lines[0]); ++i) {
        size_t n;
        if (i == 0)
            n = (size_t)sprintf(line, "version %d %d %d\n", MESHFIX_VERSION_MAJOR, MESHFIX_VERSION_MINOR,
                                MESHFIX_VERSION_PATCH);
        else
            n = (size_t)sprintf(line, "%s %lu %lu\n", meshfix_python_lines[i - 1].record,
                                (unsigned long)meshfix_python_lines[i - 1].offset,
                                (unsigned long)meshfix_python_lines[i - 1].size);
        if (buffer != NULL && length + n < size)
            memcpy(buffer + length, line, n + 1);
        length += n;
    }
    return length;
}

/* The name of a meshfix_result ("MESHFIX_OK", ...), from the header's own
   MESHFIX_RESULT_LIST; NULL past the last code. The module names the codes
   from this, so a code added to the header is named without a copy of the
   list to keep up. */
MESHFIX_API const char *meshfix_python_result_name(int result);
MESHFIX_API const char *meshfix_python_result_name(int result)
{
#define MESHFIX_PY_RESULT_NAME(name, text) #name,
    static const char *const names[] = {MESHFIX_RESULT_LIST(MESHFIX_PY_RESULT_NAME) NULL};
#undef MESHFIX_PY_RESULT_NAME
    return result >= 0 && result < (int)MESHFIX_RESULT_COUNT ? names[result] : NULL;
}
