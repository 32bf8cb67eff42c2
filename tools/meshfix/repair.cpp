/* meshfix command-line tool: one unit through the library.

   The library decides per triangle; a polygon is one face of the file, so
   it turns whole, the way most of its triangles turned. Flat normals (a
   normal the file stores for one face only) are then compared with their
   face as it will be written. */
#include "tool.h"

#include <cmath>

namespace tool {
namespace {

meshfix_options options_for(const Unit &u, const Settings &s)
{
    meshfix_options o = {};
    o.position_size = 8;
    o.policy = s.policy;
    for (int k = 0; k < 3; ++k)
        o.up[k] = s.up[k];
    if (s.weld_tolerance >= 0.0f) {
        o.topology = MESHFIX_TOPOLOGY_WELD;
        o.weld_tolerance = s.weld_tolerance;
    }
    /* the file's own normals are evidence of which way it was meant to face */
    if (!u.triangle_normals.empty() && !s.ignore_normals)
        o.evidence.triangle_normals = u.triangle_normals.data();
    if (!u.vertex_normals.empty() && !s.ignore_normals)
        o.evidence.vertex_normals = u.vertex_normals.data();
    return o;
}

/* Each face turns the way most of its (non-degenerate) triangles did. */
void decide_faces(const Unit &u, UnitResult &r)
{
    std::vector<unsigned> turned(u.face_count, 0), kept(u.face_count, 0);
    for (size_t t = 0; t < u.triangle_face.size(); ++t) {
        if (r.patch_ids[t] == 0xFFFFFFFFu)
            continue;
        (r.triangle_flipped[t] ? turned : kept)[u.triangle_face[t]]++;
    }
    r.changes.face_flipped.assign(u.face_count, 0);
    for (size_t f = 0; f < u.face_count; ++f) {
        r.changes.face_flipped[f] = turned[f] > kept[f];
        r.faces_flipped += r.changes.face_flipped[f];
        r.faces_split += turned[f] != 0 && kept[f] != 0;
    }
}

/* Flat normals that point away from their face as it will be written. */
void check_normals(const Unit &u, const Settings &s, UnitResult &r)
{
    r.changes.negate_flat.assign(u.flat_normals.size(), 0);
    r.changes.flat_disagree.assign(u.flat_normals.size(), 0);
    r.changes.fix_normals = s.fix_normals && !s.inspect;
    if (u.flat_normals.empty())
        return;
    std::vector<double> faces = face_normals(u);
    for (size_t k = 0; k < u.flat_normals.size(); ++k) {
        const FlatNormal &fn = u.flat_normals[k];
        bool flipped = r.changes.face_flipped[fn.face] != 0;
        double dot = 0.0;
        for (int i = 0; i < 3; ++i)
            dot += (flipped ? -1.0 : 1.0) * faces[3 * fn.face + (size_t)i] * (double)fn.normal[i];
        if (!(dot < 0.0))
            continue;
        if (flipped && u.flat_normals_follow_faces) {
            /* an STL facet's normal turns with it when it agreed with the
               old winding (one that was right all along is kept) */
            r.changes.negate_flat[k] = 1;
            r.normals_turned++;
            continue;
        }
        r.normals_disagree++;
        r.changes.flat_disagree[k] = 1;
        if (s.fix_normals && !s.inspect) {
            r.changes.negate_flat[k] = 1;
            r.normals_fixed++;
        }
    }
}

/* What meshfix_inspect would report of the unit as given, from the
   repair's report: the facts the repair does not change, and its record
   of those it does. */
meshfix_report as_given(const meshfix_report &after)
{
    meshfix_report before = {};
    before.verdict = before.verdict_before = after.verdict_before;
    before.edges_inconsistent_before = after.edges_inconsistent_before;
    before.patches_inside_out_before = after.patches_inside_out_before;
    before.signed_volume_before = after.signed_volume_before;
    before.mesh = after.mesh;
    before.mesh.edges_inconsistent = after.edges_inconsistent_before;
    before.mesh.patches_inside_out = after.patches_inside_out_before;
    before.mesh.signed_volume = after.signed_volume_before;
    return before;
}

} // namespace

UnitResult repair_unit(const Unit &u, const Settings &s)
{
    UnitResult r;
    meshfix_options o = options_for(u, s);
    size_t triangles = u.indices.size() / 3, vertices = u.positions.size() / 3;
    r.doubtful_below = meshfix_doubtful_below(&o, s.policy);
    r.triangle_flipped.assign(triangles, 0);
    r.patch_ids.assign(triangles, 0);
    r.patch_confidence.assign(triangles + 1, 1.0f);
    meshfix_outputs out = {};
    out.flipped = r.triangle_flipped.data();
    out.patch_ids = r.patch_ids.data();
    out.patch_confidence = r.patch_confidence.data();
    out.patch_confidence_capacity = r.patch_confidence.size();
    /* report only: the format writes the faces, whole polygons at a time */
    r.status = meshfix_orient(nullptr, u.indices.data(), u.indices.size(), u.positions.data(), vertices, 0, &o,
                              &r.after, &out);
    if (r.status != MESHFIX_OK)
        return r;
    r.before = as_given(r.after);
    decide_faces(u, r);
    check_normals(u, s, r);
    return r;
}

bool doubtful(const UnitResult &r, unsigned int patch)
{
    return patch < r.patch_confidence.size() && r.patch_confidence[patch] < r.doubtful_below;
}

meshfix_report combined_report(const std::vector<UnitResult> &results, bool after)
{
    meshfix_report sum = {};
    for (const UnitResult &u : results) {
        if (u.status != MESHFIX_OK)
            continue;
        const meshfix_report &r = after ? u.after : u.before;
        sum.verdict = meshfix_verdict_worst(sum.verdict, r.verdict);
        sum.triangles_flipped += r.triangles_flipped;
        sum.patches_flipped += r.patches_flipped;
        sum.patches_doubtful += r.patches_doubtful;
        sum.triangles_doubtful += r.triangles_doubtful;
        sum.area_doubtful += r.area_doubtful;
        sum.edges_inconsistent_before += r.edges_inconsistent_before;
        sum.mesh.triangles += r.mesh.triangles;
        sum.mesh.patches += r.mesh.patches;
        sum.mesh.patches_inside_out += r.mesh.patches_inside_out;
        sum.mesh.edges_inconsistent += r.mesh.edges_inconsistent;
        sum.mesh.components_non_orientable += r.mesh.components_non_orientable;
        sum.mesh.area += r.mesh.area;
    }
    return sum;
}

} // namespace tool
