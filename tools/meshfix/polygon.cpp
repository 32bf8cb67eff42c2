/* meshfix command-line tool: triangles of a polygon, for the decision only
   (the file keeps its polygons).

   A fan around the first corner is right for convex polygons, but in a
   concave one some fan triangles face backwards and overlap the others,
   so their areas, normals and edges would mislead the library. Ear
   clipping in the plane of the polygon's (Newell) normal gives triangles
   that all face the polygon's way. */
#include "meshfile.h"

#include <algorithm>
#include <cmath>

namespace tool {
namespace {

/* Twice the signed area of (a, b, c) in the plane. */
double cross2(const double *a, const double *b, const double *c)
{
    return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}

bool same_point(const double *p, const double *q) { return p[0] == q[0] && p[1] == q[1]; }

/* Whether p lies in the triangle or on its edges. A corner repeated
   elsewhere in the polygon (the bridge of a polygon with a hole) does not
   block the ear. */
bool inside(const double *p, const double *a, const double *b, const double *c)
{
    if (same_point(p, a) || same_point(p, b) || same_point(p, c))
        return false;
    return cross2(a, b, p) >= 0 && cross2(b, c, p) >= 0 && cross2(c, a, p) >= 0;
}

/* The corners projected on the plane of the Newell normal, wound
   counter-clockwise; false when the polygon has no area. */
bool project(const std::vector<double> &positions, const uint32_t *corners, size_t n, std::vector<double> &flat)
{
    double normal[3] = {0, 0, 0};
    for (size_t i = 0; i < n; ++i) {
        const double *p = &positions[3 * (size_t)corners[i]], *q = &positions[3 * (size_t)corners[(i + 1) % n]];
        normal[0] += (p[1] - q[1]) * (p[2] + q[2]);
        normal[1] += (p[2] - q[2]) * (p[0] + q[0]);
        normal[2] += (p[0] - q[0]) * (p[1] + q[1]);
    }
    int axis = 0;
    for (int k = 1; k < 3; ++k)
        if (std::fabs(normal[k]) > std::fabs(normal[axis]))
            axis = k;
    if (!(std::fabs(normal[axis]) > 0.0))
        return false;
    /* drop the dominant axis; swap the other two when the normal points
       down it, so the projection winds counter-clockwise */
    int u = (axis + 1) % 3, v = (axis + 2) % 3;
    if (normal[axis] < 0)
        std::swap(u, v);
    flat.resize(2 * n);
    for (size_t i = 0; i < n; ++i) {
        flat[2 * i] = positions[3 * (size_t)corners[i] + (size_t)u];
        flat[2 * i + 1] = positions[3 * (size_t)corners[i] + (size_t)v];
    }
    return true;
}

/* Ear clipping; false when no ear is found (a self-intersecting polygon). */
bool clip_ears(const std::vector<double> &flat, size_t n, std::vector<uint32_t> &out)
{
    std::vector<size_t> ring(n);
    for (size_t i = 0; i < n; ++i)
        ring[i] = i;
    std::vector<uint32_t> result;
    while (ring.size() > 3) {
        size_t m = ring.size(), ear = m;
        for (size_t i = 0; i < m && ear == m; ++i) {
            const double *a = &flat[2 * ring[(i + m - 1) % m]], *b = &flat[2 * ring[i]], *c = &flat[2 * ring[(i + 1) % m]];
            if (!(cross2(a, b, c) > 0))
                continue;
            bool empty = true;
            for (size_t j = 0; j < m && empty; ++j) {
                size_t k = ring[j];
                if (j != i && j != (i + m - 1) % m && j != (i + 1) % m && inside(&flat[2 * k], a, b, c))
                    empty = false;
            }
            if (empty)
                ear = i;
        }
        if (ear == m)
            return false;
        result.insert(result.end(), {(uint32_t)ring[(ear + m - 1) % m], (uint32_t)ring[ear], (uint32_t)ring[(ear + 1) % m]});
        ring.erase(ring.begin() + (long)ear);
    }
    result.insert(result.end(), {(uint32_t)ring[0], (uint32_t)ring[1], (uint32_t)ring[2]});
    out.insert(out.end(), result.begin(), result.end());
    return true;
}

} // namespace

void triangulate(const std::vector<double> &positions, const uint32_t *corners, size_t n, std::vector<uint32_t> &out)
{
    std::vector<double> flat;
    /* quadratic in the corners: beyond a few hundred, the fan */
    if (n > 3 && n <= 256 && project(positions, corners, n, flat) && clip_ears(flat, n, out))
        return;
    for (size_t i = 2; i < n; ++i)
        out.insert(out.end(), {0u, (uint32_t)(i - 1), (uint32_t)i});
}

} // namespace tool

namespace tool {

void add_face(Unit &u, const uint32_t *vertices, size_t n, uint32_t face)
{
    std::vector<uint32_t> corners;
    triangulate(u.positions, vertices, n, corners);
    for (size_t i = 0; i < corners.size(); i += 3) {
        u.indices.insert(u.indices.end(), {vertices[corners[i]], vertices[corners[i + 1]], vertices[corners[i + 2]]});
        u.triangle_face.push_back(face);
    }
}

} // namespace tool

namespace tool {

std::vector<double> face_normals(const Unit &u)
{
    std::vector<double> n(3 * u.face_count, 0.0);
    for (size_t t = 0; t < u.triangle_face.size(); ++t) {
        const double *a = &u.positions[3 * (size_t)u.indices[3 * t]];
        const double *b = &u.positions[3 * (size_t)u.indices[3 * t + 1]];
        const double *c = &u.positions[3 * (size_t)u.indices[3 * t + 2]];
        double e[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, g[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
        double *f = &n[3 * (size_t)u.triangle_face[t]];
        f[0] += e[1] * g[2] - e[2] * g[1];
        f[1] += e[2] * g[0] - e[0] * g[2];
        f[2] += e[0] * g[1] - e[1] * g[0];
    }
    return n;
}

void find_flat_normals(Unit &u)
{
    std::vector<double> faces = face_normals(u);
    std::sort(u.slot_faces.begin(), u.slot_faces.end());
    for (size_t i = 0; i < u.slot_faces.size();) {
        uint32_t slot = u.slot_faces[i].first, first = u.slot_faces[i].second;
        const double *a = &faces[3 * (size_t)first];
        double la = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
        bool flat = la > 0.0;
        for (; i < u.slot_faces.size() && u.slot_faces[i].first == slot; ++i) {
            const double *b = &faces[3 * (size_t)u.slot_faces[i].second];
            double lb = std::sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
            flat = flat && std::fabs(a[0] * b[0] + a[1] * b[1] + a[2] * b[2]) >= 0.99996 * la * lb;
        }
        const float *n = &u.slot_normals[3 * (size_t)slot];
        if (flat)
            u.flat_normals.push_back({first, {n[0], n[1], n[2]}, slot});
    }
    u.slot_faces.clear();
    u.slot_faces.shrink_to_fit();
}

} // namespace tool
