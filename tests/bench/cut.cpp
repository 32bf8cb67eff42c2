// Part 2 of `make bench`: the whole default policy, per triangle, on models
// cut into unwelded patches with gaps, next to the flood fill and OpenMesh.
//
// Models (examples/meshgen.h gen_cut: regions grown over shared edges from
// random seeds, each with its own copy of its vertices, pulled 1% of the
// way toward the region's centroid, so that every seam opens into a small
// gap and no index is shared across it):
//   a 1M-triangle sphere in 1024 patches, a 1M-triangle torus in 1024
//   patches, head.stl (117k triangles) in 500 patches;
// each as cut (correct), with half of the patches reversed
// (gen_reverse_patches, p = 0.5) and with 30% of the triangles reversed
// (gen_reverse_random). Timed on each, best and median of several runs:
//   default     meshfix_orient(out, ..., positions, ..., NULL, NULL);
//   visibility  the same with options.policy = MESHFIX_POLICY_VISIBILITY;
//   flood fill  options.policy = MESHFIX_POLICY_SEED, positions NULL;
//   OpenMesh    building its half-edge structure of the same mesh
//               (add_vertex + add_face; faces it refuses as complex are
//               counted, its error stream is silenced).
// Then, once each: the share of triangles facing their intended way after
// the default and the visibility repair, and the allocations each makes
// when handed caller scratch (options.memory.scratch of meshfix_scratch_size()
// bytes for that policy, counted through options.allocator).
#define MESHFIX_STATIC
#define MESHFIX_IMPLEMENTATION
#include "../../meshfix.h"
#include "../../examples/meshio.h"
#include "../../examples/meshgen.h"
#include "common.h"

#include <thread>

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/System/omstream.hh>

namespace bench {

typedef OpenMesh::TriMesh_ArrayKernelT<> OmMesh;

size_t openmesh_build(const mio_mesh &g)
{
    OmMesh om;
    om.reserve(g.vertex_count, 3 * g.index_count / 2, g.index_count / 3);
    std::vector<OmMesh::VertexHandle> v(g.vertex_count);
    for (size_t i = 0; i < g.vertex_count; ++i)
        v[i] = om.add_vertex(OmMesh::Point(g.positions[3 * i], g.positions[3 * i + 1], g.positions[3 * i + 2]));
    size_t refused = 0;
    for (size_t t = 0; t < g.index_count / 3; ++t)
        refused += !om.add_face(v[g.indices[3 * t]], v[g.indices[3 * t + 1]], v[g.indices[3 * t + 2]]).is_valid();
    return refused;
}

namespace {

// parallel_for with `*user` std::threads, thread t taking tasks t, t + n, ...
static void thread_parallel_for(void (*task)(void *, size_t), void *context, size_t count, void *user)
{
    size_t n = *static_cast<const size_t *>(user);
    std::vector<std::thread> pool;
    for (size_t t = 1; t < n; ++t)
        pool.emplace_back([=] {
            for (size_t i = t; i < count; i += n)
                task(context, i);
        });
    for (size_t i = 0; i < count; i += n)
        task(context, i);
    for (std::thread &thread : pool)
        thread.join();
}

struct Row {
    std::string model, variant;
    size_t triangles = 0, patches = 0;
    Timing preset, threads2, visibility, flood, openmesh;
    size_t refused = 0;
    double right_input = 0, right_default = 0, right_visibility = 0;
    size_t flips_default = 0, flips_visibility = 0;
    size_t allocs_default = 0, allocs_visibility = 0, allocs_flood = 0;
    size_t peak_default = 0, peak_visibility = 0;
    double scratch_default = 0, scratch_visibility = 0; // bytes per triangle asked for
    size_t peak_free_default = 0;                        // bytes live at once without scratch
    bool failed = false;
};

// Share of triangles facing the intended way after a repair `out` of `in`.
static double right_after(const std::vector<unsigned int> &in, const std::vector<unsigned int> &out,
                          const std::vector<unsigned char> &truth, size_t *flips)
{
    size_t right = 0, flipped = 0, n = truth.size();
    for (size_t t = 0; t < n; ++t) {
        bool f = out[3 * t + 1] != in[3 * t + 1];
        flipped += f;
        right += (truth[t] != 0) != f;
    }
    *flips = flipped;
    return 100.0 * right / std::max<size_t>(1, n);
}

static void run_variant(const mio_mesh &cut, const std::vector<unsigned int> &patch_of, size_t patches, int variant,
                        int runs, Row *row)
{
    static const char *names[3] = {"correct", "half the patches reversed", "30% of triangles reversed"};
    Mesh m;
    m.m = cut;
    m.m.positions = static_cast<float *>(std::malloc(cut.vertex_count * 12 + 1));
    m.m.indices = static_cast<unsigned int *>(std::malloc(cut.index_count * 4 + 1));
    std::memcpy(m.m.positions, cut.positions, cut.vertex_count * 12);
    std::memcpy(m.m.indices, cut.indices, cut.index_count * 4);
    size_t n = cut.index_count / 3;
    std::vector<unsigned char> truth(n, 1);
    if (variant == 1)
        gen_reverse_patches(&m.m, truth.data(), patch_of.data(), 0.5, 77);
    else if (variant == 2)
        gen_reverse_random(&m.m, truth.data(), 0.3, 78);
    row->variant = names[variant];
    row->triangles = n;
    row->patches = patches;
    size_t right = 0;
    for (unsigned char x : truth)
        right += x;
    row->right_input = 100.0 * right / n;

    const mio_mesh &g = m.m;
    std::vector<unsigned int> in(g.indices, g.indices + g.index_count), out(g.index_count);
    auto orient = [&](const float *positions, const meshfix_options *o) {
        if (meshfix_orient(out.data(), g.indices, g.index_count, positions, g.vertex_count, 12, o, nullptr, NULL) != MESHFIX_OK)
            row->failed = true;
    };
    meshfix_options vis;
    std::memset(&vis, 0, sizeof(vis));
    vis.policy = MESHFIX_POLICY_VISIBILITY;
    meshfix_options seed;
    std::memset(&seed, 0, sizeof(seed));
    seed.policy = MESHFIX_POLICY_SEED;

    // quality first (one call each), then the timings
    orient(g.positions, nullptr);
    row->right_default = right_after(in, out, truth, &row->flips_default);
    orient(g.positions, &vis);
    row->right_visibility = right_after(in, out, truth, &row->flips_visibility);

    row->preset = time_runs(runs, [&] { orient(g.positions, nullptr); });
    {
        // the same with a parallel_for of two std::threads
        meshfix_options two;
        std::memset(&two, 0, sizeof(two));
        size_t threads = 2;
        two.parallel_for = thread_parallel_for;
        two.parallel_user = &threads;
        row->threads2 = time_runs(runs, [&] { orient(g.positions, &two); });
    }
    row->visibility = time_runs(runs, [&] { orient(g.positions, &vis); });
    row->flood = time_runs(runs, [&] { orient(nullptr, &seed); });
    row->openmesh = time_runs(runs, [&] { row->refused = openmesh_build(g); });

    // allocations with caller scratch of the size meshfix_scratch_size asks for that policy
    auto count_allocations = [&](meshfix_policy policy, const float *positions, size_t *calls, size_t *peak,
                                 double *scratch_per_triangle) {
        CountingAllocator counter;
        meshfix_options o = counting_options(&counter);
        o.policy = policy;
        size_t bytes = meshfix_scratch_size(g.index_count, g.vertex_count, &o);
        std::vector<unsigned char> scratch(bytes + 1);
        o.memory.scratch = scratch.data();
        o.memory.scratch_size = bytes;
        orient(positions, &o);
        *calls = counter.calls;
        if (peak)
            *peak = counter.peak;
        if (scratch_per_triangle)
            *scratch_per_triangle = double(bytes) / n;
    };
    count_allocations(MESHFIX_POLICY_AUTO, g.positions, &row->allocs_default, &row->peak_default, &row->scratch_default);
    count_allocations(MESHFIX_POLICY_VISIBILITY, g.positions, &row->allocs_visibility, &row->peak_visibility,
                      &row->scratch_visibility);
    count_allocations(MESHFIX_POLICY_SEED, nullptr, &row->allocs_flood, nullptr, nullptr);
    {
        // what the default policy really holds at once when it allocates for itself
        CountingAllocator counter;
        meshfix_options o = counting_options(&counter);
        orient(g.positions, &o);
        row->peak_free_default = counter.peak;
    }
}

} // namespace

int part_cut(const Settings &s, std::vector<std::string> *summary)
{
    omerr().disable(); // "complex edge" for every face it refuses
    int runs = s.quick ? 3 : 5;
    std::printf("\n## Part 2. The default policy per triangle on models cut into unwelded patches with gaps, "
                "against the flood fill and OpenMesh's half-edge build\n\n");
    std::printf("ms per 100k triangles, best / median of %d runs. default = meshfix_orient with options NULL (policy auto),\n"
                "visibility = MESHFIX_POLICY_VISIBILITY, flood fill = MESHFIX_POLICY_SEED with positions NULL, OpenMesh =\n"
                "add_vertex + add_face of the same mesh. \"x / OpenMesh\" = how many times longer than OpenMesh's build\n"
                "(1.0x = as fast). gen_cut gap 0.01; reversed patches p = 0.5, reversed triangles 30%%.\n\n",
                runs);
    struct Model {
        const char *name;
        size_t patches;
    } models[3] = {{"sphere 1M", 1024}, {"torus 1M", 1024}, {"head.stl", 500}};
    std::vector<Row> rows;
    int status = 0;
    std::printf("| model | input | triangles | default | default, 2 threads | visibility | flood fill | OpenMesh | "
                "default / OpenMesh | visibility / OpenMesh | default / flood fill |\n"
                "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    for (const Model &model : models) {
        Mesh whole;
        bool ok;
        if (model.name[0] == 's')
            ok = s.quick ? gen_sphere(&whole.m, 159, 316, 0, 0, 0, 1) : gen_sphere(&whole.m, 501, 1000, 0, 0, 0, 1);
        else if (model.name[0] == 't')
            ok = s.quick ? gen_torus(&whole.m, 316, 158, 1.0f, 0.35f) : gen_torus(&whole.m, 1000, 500, 1.0f, 0.35f);
        else
            ok = load_mesh(s.head_stl, &whole);
        if (!ok)
            continue;
        size_t patch_count = s.quick && model.patches == 1024 ? 256 : model.patches;
        Mesh cut;
        std::vector<unsigned int> patch_of(whole.triangles() + 1);
        size_t patches = gen_cut(&cut.m, patch_of.data(), &whole.m, patch_count, 0.01f, 5);
        if (patches == 0) {
            status = 1;
            continue;
        }
        char name[64];
        std::snprintf(name, sizeof(name), "%s%s / %zu patches", model.name,
                      s.quick && model.name[0] != 'h' ? " (quick: 100k)" : "", patches);
        for (int variant = 0; variant < 3; ++variant) {
            Row row;
            row.model = name;
            run_variant(cut.m, patch_of, patches, variant, runs, &row);
            status |= row.failed;
            double per = 1e3 * 1e5 / row.triangles;
            std::printf("| %s | %s | %zu | %s | %s | %s | %s | %s | %s | %s | %s |\n", row.model.c_str(),
                        row.variant.c_str(), row.triangles, min_med(row.preset, per).c_str(),
                        min_med(row.threads2, per).c_str(), min_med(row.visibility, per).c_str(),
                        min_med(row.flood, per, 2).c_str(), min_med(row.openmesh, per).c_str(),
                        ratio(row.preset.min, row.openmesh.min).c_str(),
                        ratio(row.visibility.min, row.openmesh.min).c_str(),
                        ratio(row.preset.min, row.flood.min, 0).c_str());
            std::fflush(stdout);
            rows.push_back(row);
        }
    }
    std::printf("\nThe same runs: triangles facing their intended way (before -> after), triangles flipped, and "
                "allocations made when the call is given caller scratch of meshfix_scratch_size(index_count, "
                "vertex_count, &options) bytes (the target is 0; peak = bytes live at once through the allocator), next "
                "to what the default policy holds at once when it allocates for itself.\n\n");
    std::printf("| model | input | right before | right after default | after visibility | flips default / visibility | "
                "OpenMesh refused faces | scratch asked, B/tri default / visibility | default without scratch: peak B/tri | "
                "allocations with scratch: default (peak MB) | visibility (peak MB) | flood fill |\n"
                "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    double worst_ratio = 0, worst_vis = 0, sum_log = 0;
    size_t most_allocs = 0;
    for (const Row &r : rows) {
        std::printf("| %s | %s | %.2f%% | %.3f%% | %.3f%% | %zu / %zu | %zu | %.0f / %.0f | %.0f | %zu (%.1f) | %zu (%.1f) | "
                    "%zu |\n",
                    r.model.c_str(), r.variant.c_str(), r.right_input, r.right_default, r.right_visibility,
                    r.flips_default, r.flips_visibility, r.refused, r.scratch_default, r.scratch_visibility,
                    double(r.peak_free_default) / r.triangles, r.allocs_default, r.peak_default / 1e6, r.allocs_visibility, r.peak_visibility / 1e6,
                    r.allocs_flood);
        worst_ratio = std::max(worst_ratio, r.preset.min / r.openmesh.min);
        worst_vis = std::max(worst_vis, r.visibility.min / r.openmesh.min);
        sum_log += std::log(r.preset.min / r.openmesh.min);
        most_allocs = std::max(most_allocs, std::max(r.allocs_default, r.allocs_visibility));
    }
    if (!rows.empty()) {
        char line[256];
        std::snprintf(line, sizeof(line),
                      "cut models: default policy / OpenMesh build geometric mean %.2fx, worst %.2fx; visibility / "
                      "OpenMesh worst %.2fx; allocations with caller scratch: at most %zu per call (target 0)",
                      std::exp(sum_log / rows.size()), worst_ratio, worst_vis, most_allocs);
        summary->push_back(line);
        double worst_right = 100;
        for (const Row &r : rows)
            worst_right = std::min(worst_right, r.right_default);
        std::snprintf(line, sizeof(line), "cut models: default policy leaves at worst %.3f%% of triangles facing right",
                      worst_right);
        summary->push_back(line);
        double asked = 0, used = 0;
        for (const Row &r : rows) {
            asked = std::max(asked, r.scratch_default);
            used = std::max(used, double(r.peak_free_default) / r.triangles);
        }
        std::snprintf(line, sizeof(line),
                      "cut models: meshfix_scratch_size asks up to %.0f B/triangle for the default policy; it holds at "
                      "most %.0f B/triangle at once when it allocates for itself",
                      asked, used);
        summary->push_back(line);
    }
    return status;
}

} // namespace bench
