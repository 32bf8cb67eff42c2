// Part 1 of `make bench`: meshfix's ray tree against Embree 3, one thread each.
//
// Kept in a file of its own so that the comparison can be re-run exactly
// when the tree changes (`build/bench --only rays`). It uses meshfix's
// internals the way tests/internals.h does, by their meaning only:
//   whole_tree(&bvh, &mesh, &arena, units)       the tree over every
//       triangle with an area, as one unit (frame fit + slots + the library's builder for its size);
//   meshfix__frame_float(&bvh, p, out)           a model point into the
//       tree's frame (a translation and a power-of-two scale);
//   meshfix__setup_ray / meshfix__trace          with query.mode
//       MESHFIX__ANY_HIT, MESHFIX__CLOSEST_HIT or MESHFIX__COUNT_HITS
//       (every crossing along the ray, each counted once) and skip NONE.
// Embree gets the very same triangles: the tree's frame-space vertex
// positions (so both trace identical floats) and only the triangles meshfix
// keeps (those with an area). Embree runs on a device made with
// "threads=1"; the scene is built with RTC_BUILD_QUALITY_MEDIUM (binned SAH,
// like meshfix's builder) and, for the build time only, HIGH (spatial
// splits) as well. The fair baseline is Embree's single-ray API
// (rtcIntersect1 / rtcOccluded1); packets of 8 (rtcIntersect8 /
// rtcOccluded8) are printed too, labelled. "all crossings" in Embree is
// rtcIntersect1 with an intersect filter that counts each hit and rejects
// it, so the traversal goes on to the end of the ray; hits of one ray at
// the same distance on triangles sharing a vertex (a shared edge or vertex,
// reported by each triangle around it) are merged, as meshfix's count does.
// Embree runs in its default mode (no RTC_SCENE_FLAG_ROBUST): the timings
// are of its fast path. In that mode it can miss a crossing at an edge
// (seen: 1 ray in 250k on the 40k sphere, where meshfix counts the 2 a
// closed surface needs); the other count differences seen were pairs of
// hits at one distance on vertex-sharing triangles of head.stl that the
// merge above takes as one crossing and meshfix counts as two.
//
// Each mesh also gets a table of the trees' build time and bytes per
// triangle (tree_bytes; Embree's through rtcSetDeviceMemoryMonitorFunction).
//
// Build without Embree: leave MESHFIX_BENCH_EMBREE undefined (the Makefile
// defines it when /usr/include/embree3/rtcore.h exists); meshfix's own
// numbers are then printed alone.
#define MESHFIX_STATIC
#define MESHFIX_IMPLEMENTATION
#include "../../meshfix.h"
#include "../../examples/meshio.h"
#include "../../examples/meshgen.h"
#include "../internals.h"
#include "common.h"

#ifdef MESHFIX_BENCH_EMBREE
#include <embree3/rtcore.h>
#include <sys/resource.h>
#endif

#include <cmath>
#include <limits>

namespace bench {
namespace {

// Rays in the tree's frame: origin, direction.
struct RaySet {
    const char *name;
    bool coherent;
    std::vector<float> data; // 6 floats per ray
    size_t count() const { return data.size() / 6; }
};

// Origins uniform in the tree's box, directions uniform on the sphere.
static void incoherent_rays(const meshfix__bvh &bvh, size_t n, RaySet *out)
{
    Random random(12345);
    out->name = "incoherent";
    out->coherent = false;
    out->data.resize(6 * n);
    for (size_t i = 0; i < n; ++i) {
        float *r = &out->data[6 * i];
        for (int k = 0; k < 3; ++k)
            r[k] = bvh.low[k] + float((bvh.high[k] - bvh.low[k]) * random.uniform());
        random.direction(r + 3);
    }
}

// A pinhole camera outside the box looking at its centre: side x side rays
// in scanline order, the image just covering the box.
static void camera_rays(const meshfix__bvh &bvh, size_t side, RaySet *out)
{
    out->name = "coherent (camera)";
    out->coherent = true;
    out->data.resize(6 * side * side);
    double centre[3], radius = 0;
    for (int k = 0; k < 3; ++k) {
        centre[k] = 0.5 * (bvh.low[k] + bvh.high[k]);
        radius += 0.25 * (bvh.high[k] - bvh.low[k]) * (bvh.high[k] - bvh.low[k]);
    }
    radius = std::sqrt(radius);
    // looking from a direction off every axis, 3 radii away
    double view[3] = {0.45, -0.8, 0.4}, up[3] = {0, 0, 1}, right[3], true_up[3], len = 0;
    for (double x : view)
        len += x * x;
    for (double &x : view)
        x /= std::sqrt(len);
    double eye[3];
    for (int k = 0; k < 3; ++k)
        eye[k] = centre[k] - 3.0 * radius * view[k];
    right[0] = view[1] * up[2] - view[2] * up[1];
    right[1] = view[2] * up[0] - view[0] * up[2];
    right[2] = view[0] * up[1] - view[1] * up[0];
    len = std::sqrt(right[0] * right[0] + right[1] * right[1] + right[2] * right[2]);
    for (double &x : right)
        x /= len;
    true_up[0] = right[1] * view[2] - right[2] * view[1];
    true_up[1] = right[2] * view[0] - right[0] * view[2];
    true_up[2] = right[0] * view[1] - right[1] * view[0];
    // the box's bounding sphere seen from 3 radii: half angle asin(1/3), tan 1/sqrt(8)
    double half = 1.05 / std::sqrt(8.0);
    for (size_t y = 0; y < side; ++y)
        for (size_t x = 0; x < side; ++x) {
            float *r = &out->data[6 * (y * side + x)];
            double u = (2.0 * (x + 0.5) / side - 1.0) * half;
            double v = (2.0 * (y + 0.5) / side - 1.0) * half;
            double d[3], n = 0;
            for (int k = 0; k < 3; ++k) {
                d[k] = view[k] + u * right[k] + v * true_up[k];
                n += d[k] * d[k];
            }
            for (int k = 0; k < 3; ++k) {
                r[k] = float(eye[k]);
                r[3 + k] = float(d[k] / std::sqrt(n));
            }
        }
}

// What one engine answered for each ray of a set, to compare.
struct Answers {
    std::vector<unsigned char> hit;  // any / closest: 1 when something was hit
    std::vector<float> t;            // closest: the distance
    std::vector<unsigned int> count; // all crossings
};

// meshfix's tree over one mesh, built by tests/internals.h's whole_tree
// (which takes an arena block of its own: freed on release).
struct MeshfixTree {
    meshfix__mesh mesh;
    meshfix__bvh bvh;
    meshfix__arena arena;
    unsigned char *block = nullptr;
    std::vector<unsigned int> units;
    unsigned int root = MESHFIX__NONE;

    explicit MeshfixTree(const mio_mesh &g)
    {
        meshfix_options o;
        std::memset(&o, 0, sizeof(o));
        std::memset(&arena, 0, sizeof(arena));
        std::memset(&bvh, 0, sizeof(bvh));
        block = bind_mesh(&mesh, &o, g.indices, g.index_count, g.positions, g.vertex_count);
        units.resize(g.index_count / 3 + 1);
    }
    // MESHFIX__BUILD_AUTO: as the library builds it; MESHFIX__BUILD_SAH or _MORTON: that builder whatever the size
    int builder = MESHFIX__BUILD_AUTO;
    void build()
    {
        root = builder == MESHFIX__BUILD_AUTO ? whole_tree(&bvh, &mesh, &arena, units.data())
                                              : whole_tree_built(&bvh, &mesh, &arena, units.data(), builder);
    }
    void release()
    {
        free_arena(&arena);
        std::memset(&arena, 0, sizeof(arena));
        root = MESHFIX__NONE;
    }
    ~MeshfixTree()
    {
        release();
        std::free(block);
    }
};

// The bytes of meshfix's tree a ray reads: the nodes reachable from the
// root (256 bytes each) and the leaf blocks of its slots; and the bytes the
// library's scratch reserves for the trees (nodes and blocks at their
// bound, the slots' triangles, corners and Morton sort keys).
struct TreeBytes {
    size_t nodes = 0, used = 0, reserved = 0;
};

static TreeBytes tree_bytes(const MeshfixTree &tree)
{
    TreeBytes r;
    std::vector<unsigned int> stack(1, tree.root);
    while (!stack.empty()) {
        const meshfix__wide &n = tree.bvh.nodes[stack.back()];
        stack.pop_back();
        r.nodes++;
        for (int c = 0; c < MESHFIX__WIDE; ++c)
            if (n.inner & (1u << c))
                stack.push_back(n.child[c]);
    }
    const meshfix__geometry_plan &p = tree.arena.plan;
    r.used = r.nodes * sizeof(meshfix__wide) + (tree.bvh.count + MESHFIX__WIDE - 1) / MESHFIX__WIDE * sizeof(meshfix__leaf_block);
    r.reserved = p.nodes.count * sizeof(meshfix__wide) + p.blocks.count * sizeof(meshfix__leaf_block) +
                 p.order.count * sizeof(unsigned int) + p.corners.count * sizeof(float) +
                 p.morton_sort.count * sizeof(unsigned int);
    return r;
}

static unsigned long long meshfix_trace_all(const MeshfixTree &tree, const RaySet &rays, int mode, Answers *answers)
{
    size_t n = rays.count();
    unsigned long long total = 0;
    if (answers) {
        answers->hit.assign(n, 0);
        answers->t.assign(n, 0);
        answers->count.assign(n, 0);
    }
    for (size_t i = 0; i < n; ++i) {
        meshfix__ray ray;
        meshfix__query q;
        meshfix__setup_ray(&ray, &rays.data[6 * i], &rays.data[6 * i + 3], 0.0f, 1e30f);
        q.mode = mode;
        q.skip = MESHFIX__NONE;
        int hit = meshfix__trace(&tree.bvh, tree.root, &ray, &q);
        total += mode == MESHFIX__COUNT_HITS ? q.hits : unsigned(hit);
        if (answers) {
            answers->hit[i] = (unsigned char)hit;
            answers->t[i] = hit && mode == MESHFIX__CLOSEST_HIT ? q.t : 0.0f;
            answers->count[i] = q.hits;
        }
    }
    return total;
}

#ifdef MESHFIX_BENCH_EMBREE

static double cpu_seconds()
{
    struct rusage u;
    getrusage(RUSAGE_SELF, &u);
    return u.ru_utime.tv_sec + u.ru_stime.tv_sec + 1e-6 * (u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

// Context of an "all crossings" query: the hits so far (distance, triangle).
struct CountContext {
    RTCIntersectContext context; // first: Embree hands back its address
    unsigned int hits;
    unsigned int distinct;
    float t[64];
    unsigned int prim[64];
};

static bool share_vertex(const unsigned int *indices, unsigned int a, unsigned int b)
{
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            if (indices[3 * a + i] == indices[3 * b + j])
                return true;
    return false;
}

// Counts every hit and rejects it, so the traversal goes on. A hit at the
// distance of an earlier one on a triangle sharing a vertex with it is the
// same crossing seen by two triangles (a shared edge or vertex): counted once.
static void count_filter(const RTCFilterFunctionNArguments *args)
{
    CountContext *c = reinterpret_cast<CountContext *>(args->context);
    const unsigned int *indices = static_cast<const unsigned int *>(args->geometryUserPtr);
    for (unsigned int i = 0; i < args->N; ++i) {
        if (args->valid[i] == 0)
            continue;
        float t = RTCRayN_tfar(args->ray, args->N, i);
        unsigned int prim = RTCHitN_primID(args->hit, args->N, i);
        c->hits++;
        unsigned int k = 0, known = c->distinct < 64 ? c->distinct : 64;
        for (; k < known; ++k)
            if (std::fabs(c->t[k] - t) <= 1e-6f * t && share_vertex(indices, c->prim[k], prim))
                break;
        if (k == known) {
            if (c->distinct < 64) {
                c->t[c->distinct] = t;
                c->prim[c->distinct] = prim;
            }
            c->distinct++;
        }
        args->valid[i] = 0;
    }
}

// Embree's bytes in use, through the device's memory monitor.
static bool count_memory(void *user, ssize_t bytes, bool)
{
    *static_cast<long long *>(user) += bytes;
    return true;
}

struct EmbreeScene {
    RTCDevice device = nullptr;
    long long bytes = 0;       // in use by the device now (count_memory)
    long long scene_bytes = 0; // of the last scene built: its buffers (a copy of the mesh) and its tree
    RTCScene scene = nullptr;
    std::vector<float> vertices;       // frame space, 4 floats each (Embree reads 16 bytes)
    std::vector<unsigned int> indices; // triangles with an area
    bool filter = false;

    void build(RTCBuildQuality quality, bool with_filter)
    {
        release();
        long long before = bytes;
        scene = rtcNewScene(device);
        rtcSetSceneBuildQuality(scene, quality);
        RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
        rtcSetGeometryBuildQuality(geometry, quality);
        size_t nv = vertices.size() / 4, nt = indices.size() / 3;
        float *v = static_cast<float *>(
            rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 16, nv));
        std::memcpy(v, vertices.data(), nv * 16);
        unsigned int *t = static_cast<unsigned int *>(
            rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 12, nt));
        std::memcpy(t, indices.data(), nt * 12);
        if (with_filter) {
            rtcSetGeometryIntersectFilterFunction(geometry, count_filter);
            rtcSetGeometryUserData(geometry, indices.data());
        }
        filter = with_filter;
        rtcCommitGeometry(geometry);
        rtcAttachGeometry(scene, geometry);
        rtcReleaseGeometry(geometry);
        rtcCommitScene(scene);
        scene_bytes = bytes - before;
    }
    void release()
    {
        if (scene)
            rtcReleaseScene(scene);
        scene = nullptr;
    }
    ~EmbreeScene()
    {
        release();
        if (device)
            rtcReleaseDevice(device);
    }
};

static void setup_rayhit(RTCRayHit *rh, const float *r)
{
    rh->ray.org_x = r[0], rh->ray.org_y = r[1], rh->ray.org_z = r[2];
    rh->ray.dir_x = r[3], rh->ray.dir_y = r[4], rh->ray.dir_z = r[5];
    rh->ray.tnear = 0.0f;
    rh->ray.tfar = std::numeric_limits<float>::infinity();
    rh->ray.time = 0.0f;
    rh->ray.mask = 0xFFFFFFFFu;
    rh->ray.id = 0;
    rh->ray.flags = 0;
    rh->hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh->hit.primID = RTC_INVALID_GEOMETRY_ID;
    rh->hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
}

// mode: 0 any (rtcOccluded1), 1 closest (rtcIntersect1), 2 all crossings
// (rtcIntersect1 + counting filter).
static unsigned long long embree_trace_all(const EmbreeScene &e, const RaySet &rays, int mode, Answers *answers)
{
    size_t n = rays.count();
    unsigned long long total = 0;
    if (answers) {
        answers->hit.assign(n, 0);
        answers->t.assign(n, 0);
        answers->count.assign(n, 0);
    }
    CountContext c;
    rtcInitIntersectContext(&c.context);
    c.context.flags = rays.coherent ? RTC_INTERSECT_CONTEXT_FLAG_COHERENT : RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
    for (size_t i = 0; i < n; ++i) {
        RTCRayHit rh;
        setup_rayhit(&rh, &rays.data[6 * i]);
        int hit;
        float t = 0;
        unsigned int count = 0;
        if (mode == 0) {
            rtcOccluded1(e.scene, &c.context, &rh.ray);
            hit = rh.ray.tfar < 0; // -inf when occluded
        } else {
            c.hits = c.distinct = 0;
            rtcIntersect1(e.scene, &c.context, &rh);
            hit = rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
            t = rh.ray.tfar;
            if (mode == 2) {
                count = c.distinct;
                hit = count > 0;
            }
        }
        total += mode == 2 ? count : unsigned(hit);
        if (answers) {
            answers->hit[i] = (unsigned char)hit;
            answers->t[i] = hit && mode == 1 ? t : 0.0f;
            answers->count[i] = count;
        }
    }
    return total;
}

// Packets of 8 consecutive rays of the set (any or closest).
static unsigned long long embree_trace_packets(const EmbreeScene &e, const RaySet &rays, int mode)
{
    size_t n = rays.count();
    unsigned long long total = 0;
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    context.flags = rays.coherent ? RTC_INTERSECT_CONTEXT_FLAG_COHERENT : RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
    alignas(32) RTCRayHit8 rh;
    alignas(32) int valid[8];
    for (size_t i = 0; i < n; i += 8) {
        for (int j = 0; j < 8; ++j) {
            size_t r = i + j < n ? i + j : i;
            const float *d = &rays.data[6 * r];
            valid[j] = i + j < n ? -1 : 0;
            rh.ray.org_x[j] = d[0], rh.ray.org_y[j] = d[1], rh.ray.org_z[j] = d[2];
            rh.ray.dir_x[j] = d[3], rh.ray.dir_y[j] = d[4], rh.ray.dir_z[j] = d[5];
            rh.ray.tnear[j] = 0.0f;
            rh.ray.tfar[j] = std::numeric_limits<float>::infinity();
            rh.ray.time[j] = 0.0f;
            rh.ray.mask[j] = 0xFFFFFFFFu;
            rh.ray.id[j] = 0;
            rh.ray.flags[j] = 0;
            rh.hit.geomID[j] = RTC_INVALID_GEOMETRY_ID;
            rh.hit.instID[0][j] = RTC_INVALID_GEOMETRY_ID;
        }
        if (mode == 0) {
            rtcOccluded8(valid, e.scene, &context, &rh.ray);
            for (int j = 0; j < 8; ++j)
                total += valid[j] && rh.ray.tfar[j] < 0;
        } else {
            rtcIntersect8(valid, e.scene, &context, &rh);
            for (int j = 0; j < 8; ++j)
                total += valid[j] && rh.hit.geomID[j] != RTC_INVALID_GEOMETRY_ID;
        }
    }
    return total;
}
#endif

struct Agreement {
    size_t hit_rays = 0, hit_differs = 0, closest_rays = 0, t_differs = 0;
    size_t count_rays = 0, count_differs = 0, parity_differs = 0;
};

static const char *QUERY_NAMES[3] = {"any hit", "closest hit", "all crossings"};

// One mesh: build times, then every ray set and query.
static int bench_mesh(const char *name, const mio_mesh &g, const Settings &s, int runs,
                      std::vector<std::string> *summary, Agreement *agreement)
{
    MeshfixTree tree(g);
    Timing build = time_runs(runs, [&] {
        tree.release();
        tree.build();
    });
    if (tree.root == MESHFIX__NONE) {
        std::printf("| %s | (no tree) |\n", name);
        return 1;
    }
    size_t triangles = tree.bvh.count;
    size_t ray_count = s.quick ? 250000 : 1000000;
    size_t side = size_t(std::sqrt(double(ray_count)) + 0.5);
    RaySet sets[2];
    incoherent_rays(tree.bvh, ray_count, &sets[0]);
    camera_rays(tree.bvh, side, &sets[1]);

#ifdef MESHFIX_BENCH_EMBREE
    EmbreeScene e;
    e.device = rtcNewDevice("threads=1,set_affinity=0");
    if (!e.device) {
        std::printf("(Embree: rtcNewDevice failed, error %d)\n", int(rtcGetDeviceError(nullptr)));
        return 1;
    }
    rtcSetDeviceMemoryMonitorFunction(e.device, count_memory, &e.bytes);
    // the very triangles meshfix traces: its frame's vertices, its slots
    e.vertices.resize(4 * g.vertex_count);
    for (size_t v = 0; v < g.vertex_count; ++v) {
        meshfix__frame_float(&tree.bvh, g.positions + 3 * v, &e.vertices[4 * v]);
        e.vertices[4 * v + 3] = 0;
    }
    for (unsigned int t = 0; t < g.index_count / 3; ++t)
        if (tree.units[t] != MESHFIX__NONE)
            for (int k = 0; k < 3; ++k)
                e.indices.push_back(g.indices[3 * t + k]);
    // cpu / wall over the MEDIUM builds: about 1 when Embree keeps to one thread
    double cpu_before = cpu_seconds();
    auto wall_before = std::chrono::steady_clock::now();
    Timing medium = time_runs(runs, [&] { e.build(RTC_BUILD_QUALITY_MEDIUM, false); });
    double cpu_per_wall = (cpu_seconds() - cpu_before) / std::max(1e-9, seconds_since(wall_before));
    long long medium_bytes = e.scene_bytes;
    Timing high = time_runs(runs, [&] { e.build(RTC_BUILD_QUALITY_HIGH, false); });
    long long high_bytes = e.scene_bytes;
    e.build(RTC_BUILD_QUALITY_MEDIUM, false);
    std::printf("\n%s: %zu triangles. Build ms (min / median of %d): meshfix whole_tree %s | Embree MEDIUM %s "
                "(cpu/wall %.2f) | Embree HIGH %s | meshfix / Embree MEDIUM %s\n\n",
                name, triangles, runs, min_med(build, 1e3).c_str(), min_med(medium, 1e3).c_str(),
                cpu_per_wall, min_med(high, 1e3).c_str(),
                ratio(build.min, medium.min).c_str());
    char line[256];
    std::snprintf(line, sizeof(line), "rays, %s (%zu tri): BVH build meshfix / Embree MEDIUM %s", name, triangles,
                  ratio(build.min, medium.min).c_str());
    summary->push_back(line);
#else
    (void)summary;
    (void)agreement;
    std::printf("\n%s: %zu triangles. Build ms (min / median of %d): meshfix whole_tree %s (Embree not built in)\n\n",
                name, triangles, runs, min_med(build, 1e3).c_str());
#endif
    {
        // the other builder on the same triangles: what the library's choice at this size trades
        bool morton = triangles >= MESHFIX__MORTON_MIN;
        const char *library = morton ? "Morton clusters" : "binned SAH", *other = morton ? "binned SAH" : "Morton clusters";
        MeshfixTree sah(g);
        sah.builder = morton ? MESHFIX__BUILD_SAH : MESHFIX__BUILD_MORTON;
        Timing sah_build = time_runs(runs, [&] {
            sah.release();
            sah.build();
        });
        Timing sah_rays = time_runs(runs, [&] { meshfix_trace_all(sah, sets[0], MESHFIX__CLOSEST_HIT, nullptr); });
        Timing lib_rays = time_runs(runs, [&] { meshfix_trace_all(tree, sets[0], MESHFIX__CLOSEST_HIT, nullptr); });
        std::printf("The library's tree (%s) against %s over the same triangles: build %s ms vs %s ms; "
                    "incoherent closest hit %s vs %s Mrays/s\n\n",
                    library, other, min_med(build, 1e3).c_str(),
                    min_med(sah_build, 1e3).c_str(), rate(double(sets[0].count()), lib_rays, 1e6).c_str(),
                    rate(double(sets[0].count()), sah_rays, 1e6).c_str());
        char text[256];
        std::snprintf(text, sizeof(text),
                      "rays, %s: the library's tree (%s) builds in %s the time of %s and traces incoherent "
                      "closest hits at %s its rate",
                      name, library, ratio(build.min, sah_build.min).c_str(), other,
                      ratio(sah_rays.min, lib_rays.min).c_str());
        summary->push_back(text);
        // build time and memory per triangle of each tree
        TreeBytes lib = tree_bytes(tree), binned = tree_bytes(sah);
        double per = 1e9 / double(triangles);
        std::printf("| tree | build ms | build ns / triangle | nodes | bytes / triangle (what rays read) | "
                    "bytes / triangle (reserved) |\n|---|---:|---:|---:|---:|---:|\n");
        std::printf("| meshfix (%s) | %s | %.0f | %zu | %.1f | %.1f |\n", library, min_med(build, 1e3).c_str(),
                    build.min * per, lib.nodes, double(lib.used) / triangles, double(lib.reserved) / triangles);
        std::printf("| meshfix %s | %s | %.0f | %zu | %.1f | %.1f |\n", other, min_med(sah_build, 1e3).c_str(),
                    sah_build.min * per, binned.nodes, double(binned.used) / triangles,
                    double(binned.reserved) / triangles);
#ifdef MESHFIX_BENCH_EMBREE
        std::printf("| Embree MEDIUM | %s | %.0f | - | %.1f (with its copy of the mesh) | - |\n",
                    min_med(medium, 1e3).c_str(), medium.min * per, double(medium_bytes) / triangles);
        std::printf("| Embree HIGH | %s | %.0f | - | %.1f (with its copy of the mesh) | - |\n",
                    min_med(high, 1e3).c_str(), high.min * per, double(high_bytes) / triangles);
#endif
        std::printf("\n");
        std::snprintf(text, sizeof(text), "rays, %s: meshfix's tree %.0f ns and %.0f bytes per triangle (%.0f reserved)",
                      name, build.min * per, double(lib.used) / triangles, double(lib.reserved) / triangles);
        summary->push_back(text);
    }
    std::printf("| rays | query | meshfix Mrays/s | Embree 1-ray Mrays/s | Embree / meshfix | Embree 8-packets Mrays/s | "
                "hit rate (avg crossings) | disagree |\n|---|---|---:|---:|---:|---:|---:|---|\n");
    int status = 0;
    for (const RaySet &rays : sets) {
        size_t n = rays.count();
        for (int mode = 0; mode < 3; ++mode) {
            int mf_mode = mode == 0 ? MESHFIX__ANY_HIT : mode == 1 ? MESHFIX__CLOSEST_HIT : MESHFIX__COUNT_HITS;
            Answers mine, theirs;
            unsigned long long total = meshfix_trace_all(tree, rays, mf_mode, &mine);
            Timing tm = time_runs(runs, [&] { meshfix_trace_all(tree, rays, mf_mode, nullptr); });
            std::string embree1 = "-", packets = "-", speedup = "-", disagree = "-";
#ifdef MESHFIX_BENCH_EMBREE
            if (mode == 2)
                e.build(RTC_BUILD_QUALITY_MEDIUM, true);
            embree_trace_all(e, rays, mode, &theirs);
            Timing te = time_runs(runs, [&] { embree_trace_all(e, rays, mode, nullptr); });
            embree1 = rate(double(n), te, 1e6);
            speedup = ratio(tm.min, te.min);
            if (mode < 2) {
                Timing tp = time_runs(runs, [&] { embree_trace_packets(e, rays, mode); });
                packets = rate(double(n), tp, 1e6);
            } else {
                e.build(RTC_BUILD_QUALITY_MEDIUM, false);
            }
            size_t differs = 0, t_differs = 0, parity = 0, more = 0;
            for (size_t i = 0; i < n; ++i) {
                if (mode < 2) {
                    differs += mine.hit[i] != theirs.hit[i];
                    if (mode == 1 && mine.hit[i] && theirs.hit[i])
                        t_differs += std::fabs(mine.t[i] - theirs.t[i]) > 1e-4f * std::max(1.0f, theirs.t[i]);
                } else {
                    differs += mine.count[i] != theirs.count[i];
                    more += mine.count[i] > theirs.count[i];
                    parity += (mine.count[i] ^ theirs.count[i]) & 1u;
                }
            }
            char text[160];
            if (mode == 0)
                std::snprintf(text, sizeof(text), "hit/miss %.4f%%", 100.0 * differs / n);
            else if (mode == 1)
                std::snprintf(text, sizeof(text), "hit/miss %.4f%%, distance %.4f%%", 100.0 * differs / n,
                              100.0 * t_differs / n);
            else
                std::snprintf(text, sizeof(text), "count %.4f%% (meshfix more %zu, fewer %zu), parity %.4f%%",
                              100.0 * differs / n, more, differs - more, 100.0 * parity / n);
            disagree = text;
            if (mode < 2) {
                agreement->hit_rays += n;
                agreement->hit_differs += differs;
            } else {
                agreement->count_rays += n;
                agreement->count_differs += differs;
                agreement->parity_differs += parity;
            }
            if (mode == 1) {
                agreement->closest_rays += n;
                agreement->t_differs += t_differs;
            }
            if (mode == 1) {
                std::snprintf(line, sizeof(line), "rays, %s, %s, closest hit: Embree 1-ray / meshfix speed %s",
                              name, rays.name, ratio(tm.min, te.min).c_str());
                summary->push_back(line);
            }
#endif
            char rate_text[64];
            if (mode == 2)
                std::snprintf(rate_text, sizeof(rate_text), "%.3f", double(total) / n);
            else
                std::snprintf(rate_text, sizeof(rate_text), "%.1f%%", 100.0 * double(total) / n);
            std::printf("| %s | %s | %s | %s | %s | %s | %s | %s |\n", rays.name, QUERY_NAMES[mode],
                        rate(double(n), tm, 1e6).c_str(), embree1.c_str(), speedup.c_str(), packets.c_str(), rate_text,
                        disagree.c_str());
            std::fflush(stdout);
        }
    }
    return status;
}

} // namespace

int part_rays(const Settings &s, std::vector<std::string> *summary)
{
    int runs = s.quick ? 3 : 5;
    std::printf("\n## Part 1. Rays: meshfix's BVH against Embree %s, one thread each\n\n",
#ifdef MESHFIX_BENCH_EMBREE
                RTC_VERSION_STRING
#else
                "(not built in: -DMESHFIX_BENCH_EMBREE)"
#endif
    );
    std::printf("Same triangles in the same float frame; %s rays per set; rates are Mrays/s as best / median of %d runs;\n"
                "\"Embree / meshfix\" is meshfix's best time over Embree's best time (how many times faster Embree's\n"
                "1-ray API is). Embree: device \"threads=1\", scene built with RTC_BUILD_QUALITY_MEDIUM; any hit =\n"
                "rtcOccluded1, closest hit = rtcIntersect1, all crossings = rtcIntersect1 with a filter that counts\n"
                "and rejects every hit (hits at one distance on triangles sharing a vertex merged); 8-packets =\n"
                "rtcOccluded8 / rtcIntersect8 on consecutive rays. Disagree: share of rays where the two differ (hit\n"
                "or miss; closest distance beyond 1e-4 relative; crossing count and its parity). Per mesh, the\n"
                "trees' build time and bytes per triangle: meshfix's nodes reachable from the root and its leaf\n"
                "blocks (what rays read), and the room its scratch reserves for the trees; Embree's bytes as its\n"
                "device's memory monitor counts them for the scene (its copy of the mesh included).\n",
                s.quick ? "250k" : "1M", runs);
    int status = 0;
    Agreement agreement;
    {
        Mesh g;
        if (gen_sphere(&g.m, 101, 200, 0, 0, 0, 1))
            status |= bench_mesh("sphere 40k", g.m, s, runs, summary, &agreement);
    }
    if (!s.quick) {
        Mesh g;
        if (gen_sphere(&g.m, 501, 1000, 0, 0, 0, 1))
            status |= bench_mesh("sphere 1M", g.m, s, runs, summary, &agreement);
    }
    {
        Mesh g;
        if (load_mesh(s.head_stl, &g))
            status |= bench_mesh("head.stl", g.m, s, runs, summary, &agreement);
    }
#ifdef MESHFIX_BENCH_EMBREE
    char line[256];
    std::snprintf(line, sizeof(line),
                  "rays: meshfix and Embree disagree on hit/miss for %.4f%% of %zu any/closest rays (closest distance: "
                  "%.4f%%), on the crossing count for %.4f%% (parity %.4f%%) of %zu counted rays",
                  100.0 * agreement.hit_differs / std::max<size_t>(1, agreement.hit_rays), agreement.hit_rays,
                  100.0 * agreement.t_differs / std::max<size_t>(1, agreement.closest_rays),
                  100.0 * agreement.count_differs / std::max<size_t>(1, agreement.count_rays),
                  100.0 * agreement.parity_differs / std::max<size_t>(1, agreement.count_rays), agreement.count_rays);
    summary->push_back(line);
    std::printf("\n%s\n", line);
#endif
    return status;
}

} // namespace bench
