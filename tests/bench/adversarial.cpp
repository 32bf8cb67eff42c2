// Part 4 of `make bench`: adversarial families at n and 4n triangles (or
// points). The ratio t(4n) / t(n) is about 4 where the cost is linear and
// about 16 where it is quadratic; "exponent" is log(time ratio) / log(size
// ratio): 1 linear, 2 quadratic. Each time is the best of several runs.
//
//   tetrahedra  closed tetrahedra on a 3D grid, each its own closed shell,
//               half of them reversed whole; meshfix_orient with options
//               NULL (the default policy: volume and nesting per shell);
//               the repair must make every one face out again;
//   weld        meshfix_weld of uniform random points in the unit cube, at
//               tolerance 0 and 1e-3;
//   hypergraph  every triangle of k vertices (the complete 3-uniform
//               hypergraph: C(k, 3) triangles, every edge in k - 2 of them,
//               so every triangle has three non-manifold edges, the case
//               the duplicate count hashes): meshfix_inspect (the report
//               counts duplicates) and the default orient; k = 40 and 64
//               (4.2x the triangles); also with every triangle given twice,
//               the second reversed (C(k, 3) duplicates);
//   fan         n thin triangles around one vertex (a disc): inspect and
//               the default orient;
//   one edge    n triangles sharing one edge (a ring of n at that edge):
//               inspect and the default orient.
#define MESHFIX_STATIC
#define MESHFIX_IMPLEMENTATION
#include "../../meshfix.h"
#include "../../examples/meshio.h"
#include "../../examples/meshgen.h"
#include "common.h"

#include <functional>

namespace bench {
namespace {

struct Soup {
    std::vector<float> positions;
    std::vector<unsigned int> indices;
    size_t triangles() const { return indices.size() / 3; }
    size_t vertices() const { return positions.size() / 3; }
    void vertex(double x, double y, double z)
    {
        positions.push_back(float(x));
        positions.push_back(float(y));
        positions.push_back(float(z));
    }
    void triangle(unsigned a, unsigned b, unsigned c)
    {
        indices.push_back(a);
        indices.push_back(b);
        indices.push_back(c);
    }
};

// nx * ny * nz tetrahedra, 4 triangles each, facing out.
static void tetrahedra(unsigned nx, unsigned ny, unsigned nz, Soup *s)
{
    const double h = 0.5;
    for (unsigned i = 0; i < nx; ++i)
        for (unsigned j = 0; j < ny; ++j)
            for (unsigned k = 0; k < nz; ++k) {
                unsigned v = unsigned(s->vertices());
                s->vertex(i, j, k);
                s->vertex(i + h, j, k);
                s->vertex(i, j + h, k);
                s->vertex(i, j, k + h);
                s->triangle(v, v + 2, v + 1);
                s->triangle(v, v + 1, v + 3);
                s->triangle(v, v + 3, v + 2);
                s->triangle(v + 1, v + 2, v + 3);
            }
}

// Every triangle of k points on a sphere; `twice`: each again, reversed.
static void hypergraph(unsigned k, bool twice, Soup *s)
{
    Random random(k);
    for (unsigned v = 0; v < k; ++v) {
        float d[3];
        random.direction(d);
        s->vertex(d[0], d[1], d[2]);
    }
    for (unsigned a = 0; a < k; ++a)
        for (unsigned b = a + 1; b < k; ++b)
            for (unsigned c = b + 1; c < k; ++c) {
                s->triangle(a, b, c);
                if (twice)
                    s->triangle(a, c, b);
            }
}

// n triangles around vertex 0: a disc of radius 1.
static void fan(unsigned n, Soup *s)
{
    s->vertex(0, 0, 0);
    for (unsigned i = 0; i < n; ++i) {
        double a = 6.283185307179586 * i / n;
        s->vertex(std::cos(a), std::sin(a), 0);
    }
    for (unsigned i = 0; i < n; ++i)
        s->triangle(0, 1 + i, 1 + (i + 1) % n);
}

// n triangles on the edge from (0,0,-1) to (0,0,1), apexes around it.
static void one_edge(unsigned n, Soup *s)
{
    s->vertex(0, 0, -1);
    s->vertex(0, 0, 1);
    for (unsigned i = 0; i < n; ++i) {
        double a = 6.283185307179586 * i / n;
        s->vertex(std::cos(a), std::sin(a), 0);
        s->triangle(0, 1, 2 + i);
    }
}

struct Result {
    double t_small = 0, t_large = 0, size_small = 0, size_large = 0;
    std::string note;
    bool failed = false;
};

// One size of a family (g: 0 the smaller, 1 the larger): its time and size.
static void record(Result *r, int g, const Timing &t, double size)
{
    (g ? r->t_large : r->t_small) = t.min;
    (g ? r->size_large : r->size_small) = size;
}

// At least `runs` runs, more while they add up to under half a second
// (small cases are over in a few ms, where one context switch shows).
template <class F> Timing time_enough(int runs, F f)
{
    Timing first = time_runs(1, f);
    int more = first.min > 0 ? int(0.5 / first.min) : runs;
    more = std::max(runs, std::min(more, 50)) - 1;
    if (more <= 0)
        return first;
    Timing rest = time_runs(more, f);
    rest.min = std::min(rest.min, first.min);
    rest.runs++;
    return rest;
}

static void print_row(const char *family, const char *operation, const Result &r, std::vector<std::string> *summary)
{
    double ratio_t = r.t_large / std::max(1e-12, r.t_small), ratio_n = r.size_large / r.size_small;
    double exponent = std::log(ratio_t) / std::log(ratio_n);
    std::printf("| %s | %s | %.0f | %.0f | %.2f | %.2f | %.3f / %.3f | %.2f | %.2f | %s |\n", family, operation,
                r.size_small, r.size_large, 1e3 * r.t_small, 1e3 * r.t_large, 1e6 * r.t_small / r.size_small,
                1e6 * r.t_large / r.size_large, ratio_t, exponent, r.note.c_str());
    std::fflush(stdout);
    if (exponent > 1.4) {
        char line[256];
        std::snprintf(line, sizeof(line), "adversarial: %s / %s grows like n^%.2f (t(4n)/t(n) = %.1f)", family,
                      operation, exponent, ratio_t);
        summary->push_back(line);
    }
}

static Timing time_orient(const Soup &s, int runs, std::vector<unsigned int> *out, bool *failed)
{
    out->resize(s.indices.size());
    return time_enough(runs, [&] {
        if (meshfix_orient(out->data(), s.indices.data(), s.indices.size(), s.positions.data(), s.vertices(), 12,
                           nullptr, nullptr, NULL) != MESHFIX_OK)
            *failed = true;
    });
}

static Timing time_inspect(const Soup &s, int runs, meshfix_report *report, bool *failed)
{
    return time_enough(runs, [&] {
        if (meshfix_inspect(s.indices.data(), s.indices.size(), s.positions.data(), s.vertices(), 12, NULL, report, NULL) !=
            MESHFIX_OK)
            *failed = true;
    });
}

// Inspect and the default policy on one size of a family, into their
// rows; inspect's report and the repaired indices stay for the notes.
static void inspect_and_orient(const Soup &soup, int g, int runs, Result *inspect, Result *orient,
                               meshfix_report *report, std::vector<unsigned int> *out)
{
    std::memset(report, 0, sizeof(*report));
    record(inspect, g, time_inspect(soup, runs, report, &inspect->failed), double(soup.triangles()));
    record(orient, g, time_orient(soup, runs, out, &orient->failed), double(soup.triangles()));
}

} // namespace

int part_adversarial(const Settings &s, std::vector<std::string> *summary)
{
    int runs = s.quick ? 2 : 3;
    std::printf("\n## Part 4. Adversarial families at n and 4n: growth of the time (t(4n)/t(n): ~4 linear, ~16 "
                "quadratic; exponent = log(time ratio) / log(size ratio): 1 linear, 2 quadratic)\n\n");
    std::printf("Sizes are triangles (points for weld); times in ms, best of at least %d runs (more for short ones, "
                "up to half a second in all).\n\n",
                runs);
    std::printf("| family | operation | n | 4n | t(n) ms | t(4n) ms | us per item n / 4n | t(4n)/t(n) | exponent | "
                "check |\n|---|---|---:|---:|---:|---:|---:|---:|---:|---|\n");
    int status = 0;

    // tetrahedra on a grid: 25^3 and 50 x 50 x 25 tetrahedra (62.5k, 250k triangles), then 1M
    {
        struct Grid {
            unsigned x, y, z;
        } grids[3] = {{25, 25, 25}, {50, 50, 25}, {50, 50, 100}};
        Timing t[3];
        size_t n[3] = {0, 0, 0};
        std::string notes;
        bool failed = false;
        int done = 0;
        for (int g = 0; g < (s.quick ? 2 : 3); ++g) {
            Soup clean;
            tetrahedra(grids[g].x, grids[g].y, grids[g].z, &clean);
            Soup input = clean;
            Random random(g + 1);
            for (size_t tet = 0; tet < clean.triangles() / 4; ++tet)
                if (random.uniform() < 0.5)
                    for (size_t f = 4 * tet; f < 4 * tet + 4; ++f)
                        std::swap(input.indices[3 * f + 1], input.indices[3 * f + 2]);
            std::vector<unsigned int> out;
            // the 1M size only when 250k took under 15 s (a minute for 1M if linear)
            if (g == 2 && t[1].min > 15.0)
                break;
            t[g] = time_orient(input, g == 2 ? 1 : runs, &out, &failed);
            n[g] = clean.triangles();
            size_t wrong = 0;
            for (size_t i = 0; i < out.size(); ++i)
                wrong += out[i] != clean.indices[i];
            char note[96];
            std::snprintf(note, sizeof(note), "%s%zu tri: %zu wrong", g ? "; " : "", n[g], wrong / 2);
            notes += note;
            if (wrong)
                failed = true;
            done = g + 1;
        }
        Result r;
        r.t_small = t[0].min, r.t_large = t[1].min, r.size_small = double(n[0]), r.size_large = double(n[1]);
        r.note = notes;
        print_row("tetrahedra on a grid, half reversed", "orient, default policy", r, summary);
        if (done == 3) {
            Result r2;
            r2.t_small = t[1].min, r2.t_large = t[2].min, r2.size_small = double(n[1]), r2.size_large = double(n[2]);
            r2.note = "one run at 1M";
            print_row("tetrahedra on a grid (4n -> 16n)", "orient, default policy", r2, summary);
        } else if (!s.quick) {
            std::printf("| tetrahedra 1M | | | | | | | | skipped: 250k took %.1f s |\n", t[1].min);
        }
        status |= failed;
    }

    // weld of random points
    for (float tolerance : {0.0f, 1e-3f}) {
        size_t sizes[2] = {200000, 800000};
        Result r;
        for (int g = 0; g < 2; ++g) {
            Random random(7 + g);
            std::vector<float> points(3 * sizes[g]);
            for (float &x : points)
                x = float(random.uniform());
            std::vector<unsigned int> remap(sizes[g]);
            size_t unique = 0;
            Timing t = time_enough(runs, [&] {
                if (meshfix_weld(remap.data(), points.data(), sizes[g], 12, tolerance, nullptr, &unique) != MESHFIX_OK)
                    r.failed = true;
            });
            record(&r, g, t, double(sizes[g]));
            char note[64];
            std::snprintf(note, sizeof(note), "%s%zu unique", g ? " / " : "", unique);
            r.note += note;
        }
        print_row("weld, random points in a cube",
                  tolerance == 0 ? "meshfix_weld, tolerance 0" : "meshfix_weld, tolerance 1e-3", r, summary);
        status |= r.failed;
    }

    // complete 3-uniform hypergraph, k = 40 and 64; once and twice
    for (bool twice : {false, true}) {
        Result inspect, orient;
        for (int g = 0; g < 2; ++g) {
            Soup soup;
            hypergraph(g ? 64 : 40, twice, &soup);
            meshfix_report report;
            std::vector<unsigned int> out;
            inspect_and_orient(soup, g, runs, &inspect, &orient, &report, &out);
            char note[128];
            std::snprintf(note, sizeof(note), "%sk=%d: %zu duplicates, %zu non-manifold edges", g ? "; " : "",
                          g ? 64 : 40, report.mesh.triangles_duplicate, report.mesh.edges_non_manifold);
            inspect.note += note;
        }
        print_row(twice ? "hypergraph k=40/64, each triangle twice" : "hypergraph k=40/64 (all triangles of k points)",
                  "inspect (duplicate count)", inspect, summary);
        print_row(twice ? "hypergraph k=40/64, each triangle twice" : "hypergraph k=40/64 (all triangles of k points)",
                  "orient, default policy", orient, summary);
        status |= inspect.failed | orient.failed;
    }

    // a fan around one vertex, triangles on one edge
    for (int family = 0; family < 2; ++family) {
        unsigned sizes[2] = {100000, 400000};
        Result inspect, orient;
        for (int g = 0; g < 2; ++g) {
            Soup soup;
            if (family == 0)
                fan(sizes[g], &soup);
            else
                one_edge(sizes[g], &soup);
            meshfix_report report;
            std::vector<unsigned int> out;
            inspect_and_orient(soup, g, runs, &inspect, &orient, &report, &out);
            size_t flips = 0;
            for (size_t i = 0; i < out.size(); i += 3)
                flips += out[i + 1] != soup.indices[i + 1];
            char note[128];
            std::snprintf(note, sizeof(note), "%s%u: %zu flipped", g ? "; " : "", sizes[g], flips);
            orient.note += note;
        }
        const char *name = family == 0 ? "fan of n triangles around one vertex" : "n triangles on one edge";
        print_row(name, "inspect", inspect, summary);
        print_row(name, "orient, default policy", orient, summary);
        status |= inspect.failed | orient.failed;
    }
    return status;
}

} // namespace bench
