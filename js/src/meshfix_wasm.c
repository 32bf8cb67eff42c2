/* meshfix_wasm.c - the WebAssembly face of meshfix.h for js/ (the npm package).

   Built by js/scripts/build.mjs with Emscripten into a standalone .wasm
   that the JavaScript API (js/src/api.js) loads from base64. JavaScript
   never sees a C struct: options go in, and the report, the components
   and a check failure come out, as flat arrays of doubles whose order is
   the field-name lists below (mfjs_*_fields), read by the JavaScript side
   at load time. So the struct layout stays the header's business, and
   adding a field is one line here. */
#define MESHFIX_IMPLEMENTATION
#include "meshfix.h"

#include <emscripten/emscripten.h>

#define MFJS_API EMSCRIPTEN_KEEPALIVE

/* ---- options: a double per field, in this order ---- */

static const char mfjs_option_names[] =
    "indexSize,positionSize,topology,weldTolerance,policy,up.0,up.1,up.2,seed,"
    "evidence.sigma,evidence.minConfidence,evidence.triangleNormals,evidence.triangleNormalsStride,"
    "evidence.vertexNormals,evidence.vertexNormalsStride,"
    "visibility.rays,visibility.minSamples,visibility.coherenceDistance,visibility.c0,visibility.eps,"
    "visibility.kv,visibility.flags";

MFJS_API const char *mfjs_option_fields(void) { return mfjs_option_names; }

static void mfjs_read_options(meshfix_options *o, const double *v)
{
    meshfix_options zero = {0};
    *o = zero;
    o->index_size = (unsigned int)v[0];
    o->position_size = (unsigned int)v[1];
    o->topology = (meshfix_topology)(int)v[2];
    o->weld_tolerance = (float)v[3];
    o->policy = (meshfix_policy)(int)v[4];
    o->up[0] = (float)v[5];
    o->up[1] = (float)v[6];
    o->up[2] = (float)v[7];
    o->seed = (unsigned int)v[8];
    o->evidence.sigma = (float)v[9];
    o->evidence.min_confidence = (float)v[10];
    o->evidence.triangle_normals = (const float *)(size_t)v[11];
    o->evidence.triangle_normals_stride = (size_t)v[12];
    o->evidence.vertex_normals = (const float *)(size_t)v[13];
    o->evidence.vertex_normals_stride = (size_t)v[14];
    o->visibility.rays = (size_t)v[15];
    o->visibility.min_samples = (unsigned int)v[16];
    o->visibility.coherence_distance = (float)v[17];
    o->visibility.c0 = (float)v[18];
    o->visibility.eps = (float)v[19];
    o->visibility.kv = (float)v[20];
    o->visibility.flags = (unsigned int)v[21];
}

/* ---- the report: a double per field, in this order ---- */

static const char mfjs_report_names[] =
    "verdict,trianglesFlipped,patchesFlipped,patchesDoubtful,trianglesDoubtful,areaDoubtful,"
    "edgesInconsistentBefore,"
    "mesh.triangles,mesh.trianglesDegenerate,mesh.trianglesZeroArea,mesh.trianglesDuplicate,"
    "mesh.verticesUsed,mesh.verticesJoined,mesh.verticesNonFinite,mesh.verticesNonManifold,"
    "mesh.edges,mesh.edgesBoundary,mesh.edgesManifold,mesh.edgesNonManifold,mesh.edgesInconsistent,"
    "mesh.patches,mesh.patchesClosed,mesh.patchesInsideOut,"
    "mesh.components,mesh.componentsClosed,mesh.componentsNonOrientable,"
    "mesh.eulerCharacteristic,mesh.area,mesh.signedVolume,"
    "evidence.patchesByVolume,evidence.patchesByParity,evidence.patchesByVisibility,"
    "evidence.patchesByNormals,evidence.patchesKept,evidence.shellsInward,evidence.raysCast,"
    "evidence.patchPairs,evidence.patchesMerged,evidence.pairsConflicting,evidence.sdfEvaluations,"
    "evidence.trianglesSdfDisagree";

MFJS_API const char *mfjs_report_fields(void) { return mfjs_report_names; }

static void mfjs_write_report(double *v, const meshfix_report *r)
{
    const meshfix_mesh_facts *m = &r->mesh;
    const meshfix_evidence_counts *e = &r->evidence;
    double values[] = {
        (double)r->verdict, (double)r->triangles_flipped, (double)r->patches_flipped,
        (double)r->patches_doubtful, (double)r->triangles_doubtful, r->area_doubtful,
        (double)r->edges_inconsistent_before,
        (double)m->triangles, (double)m->triangles_degenerate, (double)m->triangles_zero_area,
        (double)m->triangles_duplicate,
        (double)m->vertices_used, (double)m->vertices_joined, (double)m->vertices_non_finite,
        (double)m->vertices_non_manifold,
        (double)m->edges, (double)m->edges_boundary, (double)m->edges_manifold, (double)m->edges_non_manifold,
        (double)m->edges_inconsistent,
        (double)m->patches, (double)m->patches_closed, (double)m->patches_inside_out,
        (double)m->components, (double)m->components_closed, (double)m->components_non_orientable,
        (double)m->euler_characteristic, m->area, m->signed_volume,
        (double)e->patches_by_volume, (double)e->patches_by_parity, (double)e->patches_by_visibility,
        (double)e->patches_by_normals, (double)e->patches_kept, (double)e->shells_inward, (double)e->rays_cast,
        (double)e->patch_pairs, (double)e->patches_merged, (double)e->pairs_conflicting,
        (double)e->sdf_evaluations, (double)e->triangles_sdf_disagree};
    size_t i;
    for (i = 0; i < sizeof(values) / sizeof(values[0]); ++i)
        v[i] = values[i];
}

/* ---- components: a double per field, in this order, per component ---- */

static const char mfjs_component_names[] =
    "firstTriangle,triangles,vertices,edges,edgesBoundary,edgesNonManifold,patches,eulerCharacteristic,"
    "closed,orientable,area,signedVolume";

MFJS_API const char *mfjs_component_fields(void) { return mfjs_component_names; }

#define MFJS_COMPONENT_FIELDS 12

static void mfjs_write_component(double *v, const meshfix_component *c)
{
    v[0] = (double)c->first_triangle;
    v[1] = (double)c->triangles;
    v[2] = (double)c->vertices;
    v[3] = (double)c->edges;
    v[4] = (double)c->edges_boundary;
    v[5] = (double)c->edges_non_manifold;
    v[6] = (double)c->patches;
    v[7] = (double)c->euler_characteristic;
    v[8] = (double)c->closed;
    v[9] = (double)c->orientable;
    v[10] = c->area;
    v[11] = c->signed_volume;
}

/* ---- calls ---- */

/* What orient and inspect return besides the status. Every pointer may be 0. */
typedef struct mfjs_out {
    double *report;           /* the report's fields */
    char *summary;            /* meshfix_summary's line */
    size_t summary_size;
    unsigned char *flipped;   /* per triangle */
    unsigned int *patch_ids;  /* per triangle */
    float *patch_confidence;  /* per patch */
    size_t patch_confidence_capacity;
    double *components;       /* MFJS_COMPONENT_FIELDS per component */
    size_t components_capacity;
} mfjs_out;

/* The out-arguments, passed as an array of 9 addresses and sizes (JavaScript
   numbers) so that the call signature stays short. */
static void mfjs_read_out(mfjs_out *out, const double *v)
{
    out->report = (double *)(size_t)v[0];
    out->summary = (char *)(size_t)v[1];
    out->summary_size = (size_t)v[2];
    out->flipped = (unsigned char *)(size_t)v[3];
    out->patch_ids = (unsigned int *)(size_t)v[4];
    out->patch_confidence = (float *)(size_t)v[5];
    out->patch_confidence_capacity = (size_t)v[6];
    out->components = (double *)(size_t)v[7];
    out->components_capacity = (size_t)v[8];
}

static int mfjs_run(int inspect, void *destination, const void *indices, size_t index_count,
                    const void *positions, size_t vertex_count, size_t stride, const double *option_values,
                    const double *out_values)
{
    meshfix_options options;
    meshfix_outputs outputs = {0};
    meshfix_report report;
    meshfix_component *components = NULL;
    meshfix_result r;
    mfjs_out out;
    size_t i, count;
    mfjs_read_options(&options, option_values);
    mfjs_read_out(&out, out_values);
    if (out.components != NULL && out.components_capacity != 0) {
        components = (meshfix_component *)malloc(out.components_capacity * sizeof(meshfix_component));
        if (components == NULL)
            return (int)MESHFIX_ERROR_OUT_OF_MEMORY;
        outputs.components = components;
        outputs.components_capacity = out.components_capacity;
    }
    outputs.flipped = out.flipped;
    outputs.patch_ids = out.patch_ids;
    outputs.patch_confidence = out.patch_confidence;
    outputs.patch_confidence_capacity = out.patch_confidence_capacity;
    if (inspect)
        r = meshfix_inspect(indices, index_count, positions, vertex_count, stride, &options, &report, &outputs);
    else
        r = meshfix_orient(destination, indices, index_count, positions, vertex_count, stride, &options, &report,
                           &outputs);
    if (r == MESHFIX_OK) {
        if (out.report != NULL)
            mfjs_write_report(out.report, &report);
        if (out.summary != NULL)
            meshfix_summary(&report, out.summary, out.summary_size);
        count = report.mesh.components < out.components_capacity ? report.mesh.components : out.components_capacity;
        for (i = 0; components != NULL && i < count; ++i)
            mfjs_write_component(out.components + i * MFJS_COMPONENT_FIELDS, &components[i]);
    }
    free(components);
    return (int)r;
}

MFJS_API int mfjs_orient(void *destination, const void *indices, size_t index_count, const void *positions,
                         size_t vertex_count, size_t stride, const double *options, const double *out)
{
    return mfjs_run(0, destination, indices, index_count, positions, vertex_count, stride, options, out);
}

MFJS_API int mfjs_inspect(const void *indices, size_t index_count, const void *positions, size_t vertex_count,
                          size_t stride, const double *options, const double *out)
{
    return mfjs_run(1, NULL, indices, index_count, positions, vertex_count, stride, options, out);
}

/* check: returns 1 or 0 as meshfix_check; failure gets result, requirement,
   count, triangle (-1 for none), edge[0], edge[1] (-1 for none); text the
   line (200 bytes). */
MFJS_API int mfjs_check(const void *indices, size_t index_count, const void *positions, size_t vertex_count,
                        size_t stride, unsigned int requirements, const double *options, double *failure,
                        char *text)
{
    meshfix_options o;
    meshfix_check_failure why;
    int ok;
    mfjs_read_options(&o, options);
    ok = meshfix_check(indices, index_count, positions, vertex_count, stride, requirements, &o, &why);
    failure[0] = (double)why.result;
    failure[1] = (double)why.requirement;
    failure[2] = (double)why.count;
    failure[3] = why.triangle == (size_t)-1 ? -1.0 : (double)why.triangle;
    failure[4] = why.edge[0] == 0xFFFFFFFFu ? -1.0 : (double)why.edge[0];
    failure[5] = why.edge[1] == 0xFFFFFFFFu ? -1.0 : (double)why.edge[1];
    memcpy(text, why.text, sizeof(why.text));
    text[sizeof(why.text) - 1] = 0;
    return ok;
}

MFJS_API int mfjs_weld(unsigned int *remap, const void *positions, size_t vertex_count, size_t stride,
                       float tolerance, unsigned int position_size, double *unique_count)
{
    meshfix_options o = {0};
    size_t unique = 0;
    meshfix_result r;
    o.position_size = position_size;
    r = meshfix_weld(remap, positions, vertex_count, stride, tolerance, &o, &unique);
    *unique_count = (double)unique;
    return (int)r;
}

/* The result codes' names, "MESHFIX_OK,MESHFIX_ERROR_...", by value. */
#define MFJS_RESULT_NAME(name, text) #name ","
static const char mfjs_result_names[] = MESHFIX_RESULT_LIST(MFJS_RESULT_NAME);
#undef MFJS_RESULT_NAME

MFJS_API const char *mfjs_result_codes(void) { return mfjs_result_names; }
MFJS_API const char *mfjs_result_string(int result) { return meshfix_result_string((meshfix_result)result); }
MFJS_API const char *mfjs_verdict_string(int verdict) { return meshfix_verdict_string((meshfix_verdict)verdict); }
MFJS_API int mfjs_version(void) { return MESHFIX_VERSION; }
MFJS_API void *mfjs_malloc(size_t size) { return malloc(size != 0 ? size : 1); }
MFJS_API void mfjs_free(void *p) { free(p); }
