// make bench: meshfix.h against OpenMesh on generated closed meshes.
//
// For each size, in one run on the same mesh:
//   orient   meshfix_orient (policy auto, positions given) on a copy with 30%
//            of its triangles reversed: the flood-fill repair;
//   inspect  meshfix_inspect on the same scrambled mesh;
//   openmesh OpenMesh building its half-edge structure for the clean mesh
//            (add_vertex + add_face), the baseline;
// each the fastest of several runs. All times are ns per triangle. "flood
// fill" is the topology-only repair (positions NULL, report NULL) with a
// fresh allocation per call; "reused scratch" is the same call with
// options.memory.scratch kept across calls, as an engine would: glibc hands a
// block this large back to the kernel on free, so each fresh call pays
// first-touch page faults, while OpenMesh's smaller vectors come back warm
// from the heap on its repeated runs. Peak scratch is counted through the
// allocator hooks. Ratios are what to compare across machines.
#define MESHFIX_IMPLEMENTATION
#include "../meshfix.h"
#define MESHIO_IMPLEMENTATION
#include "../examples/meshio.h"
#define MESHGEN_IMPLEMENTATION
#include "../examples/meshgen.h"
#define SDFMESH_IMPLEMENTATION
#include "../examples/sdfmesh.h"

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

#include <algorithm>
#include <map>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

typedef OpenMesh::TriMesh_ArrayKernelT<> OmMesh;

struct PeakAllocator {
    size_t current = 0, peak = 0, calls = 0;
};

static void *peak_alloc(size_t size, void *user)
{
    PeakAllocator *a = static_cast<PeakAllocator *>(user);
    size_t *block = static_cast<size_t *>(std::malloc(size + 16));
    if (!block)
        return nullptr;
    block[0] = size;
    a->current += size;
    a->peak = std::max(a->peak, a->current);
    a->calls++;
    return reinterpret_cast<char *>(block) + 16;
}

static void peak_free(void *p, void *user)
{
    PeakAllocator *a = static_cast<PeakAllocator *>(user);
    size_t *block = reinterpret_cast<size_t *>(static_cast<char *>(p) - 16);
    a->current -= block[0];
    std::free(block);
}

// Options that count every allocation of a call into `counter`.
static meshfix_options counting_options(PeakAllocator *counter)
{
    meshfix_options options;
    std::memset(&options, 0, sizeof(options));
    options.memory.alloc_func = peak_alloc;
    options.memory.free_func = peak_free;
    options.memory.user_data = counter;
    return options;
}

static double seconds_since(std::chrono::steady_clock::time_point start)
{
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

template <class F> static double fastest(int runs, F f)
{
    double best = 1e30;
    for (int i = 0; i < runs; ++i) {
        auto start = std::chrono::steady_clock::now();
        f();
        best = std::min(best, seconds_since(start));
    }
    return best;
}

static size_t openmesh_build(const mio_mesh &g)
{
    OmMesh om;
    om.reserve(g.vertex_count, 3 * g.index_count / 2, g.index_count / 3);
    std::vector<OmMesh::VertexHandle> v(g.vertex_count);
    for (size_t i = 0; i < g.vertex_count; ++i)
        v[i] = om.add_vertex(OmMesh::Point(g.positions[3 * i], g.positions[3 * i + 1], g.positions[3 * i + 2]));
    for (size_t t = 0; t < g.index_count / 3; ++t)
        om.add_face(v[g.indices[3 * t]], v[g.indices[3 * t + 1]], v[g.indices[3 * t + 2]]);
    return om.n_faces();
}

// The SDF policy on a smooth union of two spheres meshed to about a million
// triangles: SDF evaluations and time per triangle in both modes, as a
// ratio to the flood-fill repair of the same mesh.
static int bench_sdf(bool quick)
{
    const float cell = quick ? 0.03f : 0.0095f;
    int k = int(1.3f / cell) + 1;
    const float low[3] = {-k * cell + 0.0123f, -k * cell + 0.0171f, -k * cell};
    const unsigned n[3] = {unsigned(2 * k), unsigned(2 * k), unsigned(2 * k)};
    mio_mesh g;
    if (!sdfmesh_tetra(&g, sdf_smooth_union, nullptr, low, cell, n))
        return 1;
    size_t triangles = g.index_count / 3;
    std::vector<unsigned int> clean(g.indices, g.indices + g.index_count), out(g.index_count);
    gen_flip_random(&g, 0.3, 8, nullptr);
    std::vector<unsigned char> scratch(meshfix_scratch_size(g.vertex_count, g.index_count));
    meshfix_options options;
    std::memset(&options, 0, sizeof(options));
    options.memory.scratch = scratch.data();
    options.memory.scratch_size = scratch.size();
    int status = 0;
    meshfix_report report;
    auto run = [&](const float *positions, meshfix_policy policy, meshfix_sdf_mode mode) {
        options.policy = policy;
        options.sdf.distance = policy == MESHFIX_POLICY_SDF ? sdf_smooth_union : nullptr;
        options.sdf.mode = mode;
        double t = fastest(3, [&] {
            if (meshfix_orient(out.data(), g.indices, g.index_count, positions, g.vertex_count, 12, &options,
                               &report, NULL) != MESHFIX_OK)
                status = 1;
        });
        /* the plain per-triangle rule may leave triangles with no vote as
           they are (tests/test_sdf.c shows where); the others must restore */
        if (mode == MESHFIX_SDF_PER_PATCH && std::memcmp(out.data(), clean.data(), g.index_count * 4) != 0) {
            std::fprintf(stderr, "bench: SDF repair of %zu triangles is wrong\n", triangles);
            status = 1;
        }
        return t;
    };
    double flood = run(nullptr, MESHFIX_POLICY_MAJORITY, MESHFIX_SDF_PER_PATCH);
    double patch = run(g.positions, MESHFIX_POLICY_SDF, MESHFIX_SDF_PER_PATCH);
    double evaluations = double(report.evidence.sdf_evaluations) / triangles;
    double plain = run(g.positions, MESHFIX_POLICY_SDF, MESHFIX_SDF_PER_TRIANGLE);
    std::printf("\nSDF policy, smooth union of two spheres, %zu triangles, 30%% reversed, reused scratch, with report:\n\n",
                triangles);
    std::printf("| repair | SDF evaluations / triangle | ns / triangle | time / flood fill |\n|---|---:|---:|---:|\n");
    std::printf("| flood fill (topology only) | 0 | %.1f | 1.0x |\n", 1e9 * flood / triangles);
    std::printf("| SDF per patch | %.1f | %.1f | %.1fx |\n", evaluations, 1e9 * patch / triangles, patch / flood);
    std::printf("| SDF per triangle | %.1f | %.1f | %.1fx |\n", double(report.evidence.sdf_evaluations) / triangles,
                1e9 * plain / triangles, plain / flood);
    mio_free(&g);
    return status;
}


// A closed model cut into patches that share no vertices: triangles are
// grouped by the cell of a grid their centroid falls in, every group gets
// its own copy of its vertices, and half of the groups are reversed.
static void cut_by_grid(const mio_mesh &g, int cells, mio_mesh *out, size_t *groups)
{
    size_t triangles = g.index_count / 3;
    std::vector<unsigned long long> key(g.index_count);
    std::map<unsigned long long, unsigned int> copy;
    std::map<unsigned int, unsigned int> group_id;
    out->positions = (float *)std::malloc(3 * g.index_count * sizeof(float));
    out->indices = (unsigned int *)std::malloc(g.index_count * sizeof(unsigned int));
    out->index_count = g.index_count;
    out->vertex_count = 0;
    for (size_t t = 0; t < triangles; ++t) {
        float c[3] = {0, 0, 0};
        for (int k = 0; k < 3; ++k)
            for (int a = 0; a < 3; ++a)
                c[a] += g.positions[3 * g.indices[3 * t + k] + a] / 3.0f;
        unsigned int cell = 0;
        for (int a = 0; a < 3; ++a)
            cell = cell * unsigned(cells) + unsigned(std::min(cells - 1, std::max(0, int((c[a] + 1.0f) * 0.5f * cells))));
        unsigned int group = group_id.emplace(cell, unsigned(group_id.size())).first->second;
        for (int k = 0; k < 3; ++k) {
            unsigned long long id = (unsigned long long)group << 32 | g.indices[3 * t + k];
            auto it = copy.find(id);
            if (it == copy.end()) {
                it = copy.emplace(id, unsigned(out->vertex_count)).first;
                std::memcpy(out->positions + 3 * out->vertex_count, g.positions + 3 * g.indices[3 * t + k], 12);
                out->vertex_count++;
            }
            out->indices[3 * t + k] = it->second;
        }
        if (group % 2)
            std::swap(out->indices[3 * t + 1], out->indices[3 * t + 2]);
    }
    *groups = group_id.size();
}

// Incoherent rays: random origins in the bounding box, random directions.
static void bench_rays(const mio_mesh &g)
{
    meshfix__plan plan;
    meshfix__mesh m;
    meshfix__make_plan(&plan, g.vertex_count, g.index_count / 3);
    std::vector<unsigned char> block(plan.total + 16);
    unsigned char *aligned = block.data() + (16 - size_t(block.data()) % 16) % 16;
    meshfix__bind(&m, aligned, &plan, g.indices, g.index_count, g.positions, 12, g.vertex_count, nullptr, 0);
    meshfix__mark_degenerate(&m);
    meshfix_allocator allocator;
    std::memset(&allocator, 0, sizeof(allocator));
    meshfix__bvh bvh;
    auto start = std::chrono::steady_clock::now();
    meshfix__build_bvh(&bvh, &m, &allocator, meshfix__has_area);
    double build = seconds_since(start);
    const int rays = 1000000;
    std::vector<float> rays_data(6 * size_t(rays));
    unsigned int state = 1;
    for (int i = 0; i < rays; ++i) {
        for (int k = 0; k < 3; ++k)
            rays_data[6 * i + k] = bvh.low[k] + (bvh.high[k] - bvh.low[k]) * meshfix__random(&state);
        meshfix__random_direction(&state, &rays_data[6 * i + 3]);
    }
    unsigned int hits = 0;
    for (int mode = 0; mode < 2; ++mode) {
        double t = fastest(3, [&] {
            hits = 0;
            for (int i = 0; i < rays; ++i) {
                meshfix__ray ray;
                meshfix__query q;
                meshfix__setup_ray(&ray, &rays_data[6 * i], &rays_data[6 * i + 3], 0.0f, 1e30f);
                q.mode = mode == 0 ? MESHFIX__CLOSEST_HIT : MESHFIX__ANY_HIT;
                q.skip = MESHFIX__NONE;
                hits += (unsigned)meshfix__trace(&bvh, &ray, &q);
            }
        });
        std::printf("| %s | %zu | %.2f | %.1f%% | %.0f |\n", mode == 0 ? "closest hit" : "any hit", g.index_count / 3,
                    rays / t / 1e6, 100.0 * hits / rays, 1e3 * build);
    }
    meshfix__free_bvh(&bvh, &allocator);
}

static int bench_visibility(bool quick)
{
    mio_mesh g, cutm;
    if (!gen_sphere(&g, quick ? 101 : 501, quick ? 200 : 1000, 0, 0, 0, 1))
        return 1;
    std::printf("\nRay caster, one core, 1M incoherent rays (origins in the box, random directions), BVH over a sphere:\n\n");
    std::printf("| query | triangles | Mrays/s | rays that hit | BVH build ms |\n|---|---:|---:|---:|---:|\n");
    bench_rays(g);
    size_t groups = 0;
    cut_by_grid(g, quick ? 6 : 12, &cutm, &groups);
    size_t triangles = cutm.index_count / 3;
    std::vector<unsigned int> out(cutm.index_count);
    PeakAllocator counter;
    meshfix_options options = counting_options(&counter);
    meshfix_report report;
    int status = 0;
    options.policy = MESHFIX_POLICY_MAJORITY;
    double flood = fastest(3, [&] {
        status |= meshfix_orient(out.data(), cutm.indices, cutm.index_count, nullptr, cutm.vertex_count, 12, &options,
                                 nullptr, NULL) != MESHFIX_OK;
    });
    counter = PeakAllocator();
    options.policy = MESHFIX_POLICY_VISIBILITY;
    double visibility = fastest(3, [&] {
        status |= meshfix_orient(out.data(), cutm.indices, cutm.index_count, cutm.positions, cutm.vertex_count, 12,
                                 &options, &report, NULL) != MESHFIX_OK;
    });
    // every patch must face out again: compare with the uncut sphere's winding
    size_t outward = 0;
    for (size_t t = 0; t < triangles; ++t) {
        const float *a = cutm.positions + 3 * out[3 * t], *b = cutm.positions + 3 * out[3 * t + 1];
        const float *c = cutm.positions + 3 * out[3 * t + 2];
        float u[3], v[3], n[3];
        for (int k = 0; k < 3; ++k)
            u[k] = b[k] - a[k], v[k] = c[k] - a[k];
        n[0] = u[1] * v[2] - u[2] * v[1], n[1] = u[2] * v[0] - u[0] * v[2], n[2] = u[0] * v[1] - u[1] * v[0];
        outward += n[0] * (a[0] + b[0] + c[0]) + n[1] * (a[1] + b[1] + c[1]) + n[2] * (a[2] + b[2] + c[2]) > 0;
    }
    std::printf("\nVisibility policy on a sphere of %zu triangles cut into %zu unwelded patches, half reversed:\n\n",
                triangles, report.mesh.patches);
    std::printf("| repair | seconds | ns / triangle | time / flood fill | peak bytes / triangle | rays | outward |\n"
                "|---|---:|---:|---:|---:|---:|---:|\n");
    std::printf("| flood fill (topology only) | %.3f | %.1f | 1.0x | | | |\n", flood, 1e9 * flood / triangles);
    std::printf("| visibility + coherence | %.3f | %.1f | %.1fx | %.1f | %zu | %.2f%% |\n", visibility,
                1e9 * visibility / triangles, visibility / flood, double(counter.peak) / triangles, report.evidence.rays_cast,
                100.0 * outward / triangles);
    if (outward != triangles)
        status = 1;
    mio_free(&g);
    mio_free(&cutm);
    return status;
}

int main(int argc, char **argv)
{
    // rings x segments of a UV sphere: 2 * segments * (rings - 1) triangles
    struct Size {
        unsigned rings, segments;
    } sizes[] = {{51, 100}, {159, 316}, {501, 1000}, {1001, 2000}};
    size_t count = sizeof(sizes) / sizeof(sizes[0]);
    if (argc > 1 && std::strcmp(argv[1], "--quick") == 0)
        count = 2;

    std::printf("| triangles | flood fill | same, reused scratch | Mtri/s | auto (positions) | + report | inspect "
                "| OpenMesh build | OpenMesh / flood fill | OpenMesh / reused | scratch B/tri |\n");
    std::printf("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    int status = 0;
    for (size_t s = 0; s < count; ++s) {
        mio_mesh g;
        if (!gen_sphere(&g, sizes[s].rings, sizes[s].segments, 0, 0, 0, 1))
            return 1;
        size_t triangles = g.index_count / 3;
        int runs = triangles > 1000000 ? 3 : triangles > 100000 ? 5 : 20;

        std::vector<unsigned int> scrambled(g.indices, g.indices + g.index_count), out(g.index_count);
        mio_mesh sg = g;
        sg.indices = scrambled.data();
        gen_flip_random(&sg, 0.3, 5, nullptr);

        PeakAllocator counter;
        meshfix_options options = counting_options(&counter);
        meshfix_report report;

        auto repair = [&](const float *positions, meshfix_policy policy, meshfix_report *r) {
            options.policy = policy;
            return fastest(runs, [&] {
                if (meshfix_orient(out.data(), scrambled.data(), g.index_count, positions, g.vertex_count, 12,
                                   &options, r, NULL) != MESHFIX_OK)
                    status = 1;
            });
        };
        auto verify = [&](const char *what) {
            if (std::memcmp(out.data(), g.indices, g.index_count * 4) != 0) {
                std::fprintf(stderr, "bench: %s repair of %zu triangles is wrong\n", what, triangles);
                status = 1;
            }
        };
        double flood = repair(nullptr, MESHFIX_POLICY_MAJORITY, nullptr);
        verify("flood fill");
        std::vector<unsigned char> scratch(meshfix_scratch_size(g.vertex_count, g.index_count));
        options.memory.scratch = scratch.data();
        options.memory.scratch_size = scratch.size();
        double reused = repair(nullptr, MESHFIX_POLICY_MAJORITY, nullptr);
        verify("reused scratch");
        options.memory.scratch = nullptr;
        options.memory.scratch_size = 0;
        double automatic = repair(g.positions, MESHFIX_POLICY_AUTO, nullptr);
        verify("auto");
        double reported = repair(g.positions, MESHFIX_POLICY_AUTO, &report);
        verify("reported");
        if (report.mesh.edges_inconsistent != 0 || report.triangles_flipped == 0)
            status = 1;
        double inspect = fastest(runs, [&] {
            if (meshfix_inspect(scrambled.data(), g.index_count, g.positions, g.vertex_count, 12, &options,
                                   &report, NULL) != MESHFIX_OK)
                status = 1;
        });
        size_t faces = 0;
        double openmesh = fastest(runs > 5 ? 5 : runs, [&] { faces = openmesh_build(g); });
        if (faces != triangles)
            status = 1;

        double ns = 1e9 / triangles;
        std::printf("| %zu | %.1f | %.1f | %.1f | %.1f | %.1f | %.1f | %.1f | %.1fx | %.1fx | %.1f |\n", triangles,
                    flood * ns, reused * ns, triangles / reused / 1e6, automatic * ns, reported * ns, inspect * ns,
                    openmesh * ns, openmesh / flood, openmesh / reused, double(counter.peak) / triangles);
        std::fflush(stdout);
        mio_free(&g);
    }
    status |= bench_sdf(count == 2);
    return status | bench_visibility(count == 2);
}
