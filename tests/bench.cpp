// make bench: meshfix.h measured against baselines run in the same process,
// on the same data, so that the ratios carry over between machines.
//
//   Part 0  the flood fill against OpenMesh building its half-edge
//           structure, on closed spheres (this file), and the SDF policy;
//   Part 1  rays: meshfix's BVH against Embree 3, one thread each
//           (tests/bench/rays.cpp; `build/bench --only rays` re-runs it alone);
//   Part 2  the whole default policy on models cut into unwelded patches
//           with gaps, next to the flood fill and OpenMesh (tests/bench/cut.cpp);
//   Part 3  quality: the STL stored-normal truth over the corpus and the
//           generated scenes (tests/bench/quality.cpp runs tests/eval/*);
//   Part 4  adversarial families at n and 4n (tests/bench/adversarial.cpp).
//
// Usage: bench [--quick] [--only PARTS] [--head FILE] [--corpus DIR] [--build DIR]
//        PARTS: comma-separated of flood, sdf, rays, cut, quality, adversarial.
// Every time is the best and the median of several runs (a shared, noisy
// machine); ratios are between the best runs.
//
// Part 0, for each size, in one run on the same mesh:
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
// allocator hooks.
#define MESHFIX_STATIC
#define MESHFIX_IMPLEMENTATION
#include "../meshfix.h"
#include "bench/common.h" // before the implementations below: it includes meshio.h
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

using bench::CountingAllocator;
using bench::counting_options;
using bench::openmesh_build;

template <class F> static double fastest(int runs, F f)
{
    return bench::time_runs(runs, f).min;
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
    meshfix_options options;
    std::memset(&options, 0, sizeof(options));
    options.policy = MESHFIX_POLICY_SDF; // and MAJORITY: neither casts rays, the same scratch
    // the mesher puts several vertices at one point where the surface meets a
    // grid corner: joined by position those triangles repeat a vertex and are
    // left alone (tests/test_sdf.c); the mesher's own vertices are its topology
    options.topology = MESHFIX_TOPOLOGY_INDICES;
    std::vector<unsigned char> scratch(meshfix_scratch_size(g.index_count, g.vertex_count, &options));
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
    std::printf("\n## Part 0b. SDF policy against the flood fill, smooth union of two spheres, %zu triangles, 30%% reversed, reused scratch, with report (time / flood fill: how many times longer)\n\n",
                triangles);
    std::printf("| repair | SDF evaluations / triangle | ns / triangle | time / flood fill |\n|---|---:|---:|---:|\n");
    std::printf("| flood fill (topology only) | 0 | %.1f | 1.0x |\n", 1e9 * flood / triangles);
    std::printf("| SDF per patch | %.1f | %.1f | %.1fx |\n", evaluations, 1e9 * patch / triangles, patch / flood);
    std::printf("| SDF per triangle | %.1f | %.1f | %.1fx |\n", double(report.evidence.sdf_evaluations) / triangles,
                1e9 * plain / triangles, plain / flood);
    mio_free(&g);
    return status;
}


static int bench_flood(bool quick, std::vector<std::string> *summary)
{
    // rings x segments of a UV sphere: 2 * segments * (rings - 1) triangles
    struct Size {
        unsigned rings, segments;
    } sizes[] = {{51, 100}, {159, 316}, {501, 1000}, {1001, 2000}};
    size_t count = sizeof(sizes) / sizeof(sizes[0]);
    if (quick)
        count = 2;
    std::printf("\n## Part 0. Flood fill against OpenMesh's half-edge build, closed spheres, 30%% of triangles reversed\n\n"
                "ns per triangle, best of several runs; \"OpenMesh / x\" is how many times longer OpenMesh takes to\n"
                "build its half-edge structure of the clean sphere than meshfix takes to repair the scrambled one.\n\n");
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

        CountingAllocator counter;
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
        std::vector<unsigned char> scratch(meshfix_scratch_size(g.index_count, g.vertex_count, &options));
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
        size_t refused = 0;
        double openmesh = fastest(runs > 5 ? 5 : runs, [&] { refused = openmesh_build(g); });
        if (refused != 0)
            status = 1;

        double ns = 1e9 / triangles;
        std::printf("| %zu | %.1f | %.1f | %.1f | %.1f | %.1f | %.1f | %.1f | %.1fx | %.1fx | %.1f |\n", triangles,
                    flood * ns, reused * ns, triangles / reused / 1e6, automatic * ns, reported * ns, inspect * ns,
                    openmesh * ns, openmesh / flood, openmesh / reused, double(counter.peak) / triangles);
        std::fflush(stdout);
        if (s + 1 == count) {
            char line[256];
            std::snprintf(line, sizeof(line),
                          "flood fill, %zu-triangle sphere: OpenMesh's half-edge build takes %.1fx the time of the "
                          "repair (%.1fx with reused scratch); the default policy with positions %.1f ns/triangle",
                          triangles, openmesh / flood, openmesh / reused, automatic * ns);
            summary->push_back(line);
        }
        mio_free(&g);
    }
    return status;
}

int main(int argc, char **argv)
{
    bench::Settings settings;
    std::string only;
    for (int i = 1; i < argc; ++i) {
        std::string a = argv[i];
        if (a == "--quick")
            settings.quick = true;
        else if (a == "--only" && i + 1 < argc)
            only = std::string(",") + argv[++i] + ",";
        else if (a == "--head" && i + 1 < argc)
            settings.head_stl = argv[++i];
        else if (a == "--corpus" && i + 1 < argc)
            settings.corpus = argv[++i];
        else if (a == "--build" && i + 1 < argc)
            settings.build_dir = argv[++i];
        else {
            std::fprintf(stderr, "usage: bench [--quick] [--only flood,sdf,rays,cut,quality,adversarial] [--head FILE] "
                                 "[--corpus DIR] [--build DIR]\n");
            return 2;
        }
    }
    auto wanted = [&](const char *part) { return only.empty() || only.find(std::string(",") + part + ",") != std::string::npos; };
    auto load = [] {
        char text[64] = "?";
        if (FILE *f = std::fopen("/proc/loadavg", "r")) {
            if (!std::fgets(text, sizeof(text), f))
                text[0] = 0;
            std::fclose(f);
        }
        std::string s(text);
        return s.substr(0, s.find(' ', s.find(' ', s.find(' ') + 1) + 1));
    };
    std::printf("# meshfix.h bench%s: every number is measured in this run against a baseline run alongside it\n",
                settings.quick ? " (--quick)" : "");
    std::printf("(load average at the start: %s; other processes on this machine make the medians noisier than the "
                "bests)\n",
                load().c_str());
    auto start = std::chrono::steady_clock::now();
    std::vector<std::string> summary;
    int status = 0;
    auto part = [&](const char *name, int result) {
        if (result) {
            std::printf("\n(part %s: a check FAILED)\n", name);
            summary.push_back(std::string("FAILED: a check of part ") + name);
        }
        status |= result;
        std::fflush(stdout);
    };
    if (wanted("flood"))
        part("flood", bench_flood(settings.quick, &summary));
    if (wanted("sdf"))
        part("sdf", bench_sdf(settings.quick));
    if (wanted("rays"))
        part("rays", bench::part_rays(settings, &summary));
    if (wanted("cut"))
        part("cut", bench::part_cut(settings, &summary));
    if (wanted("quality"))
        part("quality", bench::part_quality(settings, &summary));
    if (wanted("adversarial"))
        part("adversarial", bench::part_adversarial(settings, &summary));
    std::printf("\n## Summary (%.0f s; load average at the end: %s)\n\n", bench::seconds_since(start), load().c_str());
    for (const std::string &line : summary)
        std::printf("- %s\n", line.c_str());
    return status;
}
