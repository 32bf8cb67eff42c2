/* assets_eval.cpp - scores the command-line tool's repair against the normals
   the authors of real assets stored (tests/corpus/fetch_assets.sh).

   Each file of DIR/manifest.tsv is read with the tool's own loaders
   (tool::load_file: OBJ vn, PLY nx ny nz, glTF NORMAL, STL facet
   normals). Per unit, per triangle, the truth is the sign of
   dot(n, g), g the geometric normal (b - a) x (c - a) of the triangle as
   wound in the file and n the sum of the unit normals at its corners (STL:
   the facet's normal). A triangle has no truth when
     - its area is about 0 (|g| < 1e-6 of the sum of its squared edges),
     - a corner has no normal (zero or not finite),
     - its corner normals disagree in sign with each other about the face,
     - or |cos(n, g)| < 0.3.
   It is correct as shipped when the sign is positive.

   The repair is the CLI's: tool::repair_unit with default Settings
   (policy auto), the faces turned whole as the CLI writes them, in two
   modes:
     normals    the file's normals passed as evidence (what the CLI does);
     geometry   a copy of the unit with its normals withheld;
   each on (a) the file as shipped and (b) a copy with a seeded random half
   of the faces reversed (exactly half, Fisher-Yates on splitmix64, the
   generator restarted per unit; normals left as authored).

   Per file (percentages of the triangles with truth):
     ship%     correct as shipped;
     fix%      correct after the repair of (a);
     damaged   correct as shipped and turned by the repair of (a); "mixed"
               of it in patches whose other correct triangles were kept
               (the shipped winding, normals with it, disagrees with itself
               inside one orientable patch: no consistent repair keeps
               both), the rest "whole" (a correct patch turned whole: the
               repair chose the wrong side);
     half%     correct after the repair of (b);
     ms        load, repair of (a) per mode, and all of it (one thread).
   --tsv writes that table with counts; the summary gives totals (weighted
   by triangles with truth) per split and family, the worst files by
   damage, and the files whose normals disagree with their winding
   wholesale (ship% < 10).

   --explain prints, for each file the repair damaged, the damaged patches
   of the shipped repair: triangles, damaged, share correct as shipped,
   closed or open (boundary, non-manifold and inconsistent seam edges),
   signed volume as shipped, the evidence that decided the unit, a closed
   patch whose box holds its box (a shell inside another), its box and
   mean normal, and the patches whose boundary vertices come within 1e-4
   of the unit's diagonal of its own (touching parts).

   Build:  make build/assets_eval
   Usage:  assets_eval [--split tune|heldout|all] [--family NAME] [--match TEXT]
                       [--seed N] [--worst N] [--tsv FILE] [--summary FILE] [--explain] [--rows FILE] [DIR]
           --rows: a line per patch for tests/eval/fit.c; the output ends
           with the reliability of the reported confidence per mode
           (tests/eval/calibration.h).
           DIR defaults to build/assets; --split defaults to tune: the
           held-out half is scored only when asked by name.
   Exit:   0; 1 for bad usage or an unreadable manifest. */
#include "tool.h"
extern "C" {
#include "calibration.h"
}

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

namespace {

double now_ms()
{
    using namespace std::chrono;
    return duration<double, std::milli>(steady_clock::now().time_since_epoch()).count();
}

/* splitmix64, as tests/eval/stl_truth.c */
uint64_t next_random(uint64_t &state)
{
    uint64_t z = (state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

uint64_t fnv1a(const std::string &s)
{
    uint64_t h = 1469598103934665603ull;
    for (unsigned char c : s)
        h = (h ^ c) * 1099511628211ull;
    return h;
}

struct Entry {
    std::string sha, package, version, family, split, stored, original, note;
};

/* What one mode did to one file, summed over its units. */
struct ModeScore {
    size_t agree_fix = 0, damaged = 0, damaged_mixed = 0, agree_half = 0;
    double repair_ms = 0.0;
    size_t refused = 0; /* units the library refused */
    meshfix_evidence_counts evidence{};
};

struct FileScore {
    Entry entry;
    bool loaded = false;
    std::string error;
    size_t units = 0, triangles = 0, truth = 0, agree_ship = 0;
    size_t no_truth_area = 0, no_truth_normal = 0, no_truth_split = 0, no_truth_oblique = 0;
    size_t patches = 0, patches_closed = 0, edges_boundary = 0, edges_non_manifold = 0;
    ModeScore mode[2]; /* 0: normals as evidence, 1: geometry only */
    double load_ms = 0.0, total_ms = 0.0;
};

const char *const MODE_NAMES[2] = {"normals", "geometry"};

double pct(size_t part, size_t whole) { return whole == 0 ? 0.0 : 100.0 * (double)part / (double)whole; }

std::string fmt(const char *format, ...) __attribute__((format(printf, 1, 2)));
std::string fmt(const char *format, ...)
{
    char buffer[1024];
    va_list args;
    va_start(args, format);
    std::vsnprintf(buffer, sizeof(buffer), format, args);
    va_end(args);
    return buffer;
}

/* +1, -1, or 0 (no truth) per triangle of the unit; counts the reasons. */
std::vector<signed char> judge(const tool::Unit &u, FileScore &s)
{
    size_t n = u.indices.size() / 3;
    std::vector<signed char> truth(n, 0);
    for (size_t t = 0; t < n; ++t) {
        const double *p[3];
        for (int k = 0; k < 3; ++k)
            p[k] = &u.positions[3 * (size_t)u.indices[3 * t + (size_t)k]];
        double e1[3], e2[3], e3[3], g[3];
        for (int i = 0; i < 3; ++i) {
            e1[i] = p[1][i] - p[0][i];
            e2[i] = p[2][i] - p[0][i];
            e3[i] = p[2][i] - p[1][i];
        }
        g[0] = e1[1] * e2[2] - e1[2] * e2[1];
        g[1] = e1[2] * e2[0] - e1[0] * e2[2];
        g[2] = e1[0] * e2[1] - e1[1] * e2[0];
        double gl = std::sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
        double edges = 0.0;
        for (int i = 0; i < 3; ++i)
            edges += e1[i] * e1[i] + e2[i] * e2[i] + e3[i] * e3[i];
        if (!std::isfinite(gl) || !std::isfinite(edges) || !(gl >= 1e-6 * edges) || gl == 0.0) {
            s.no_truth_area++;
            continue;
        }
        double sum[3] = {0, 0, 0};
        bool missing = false;
        int positive = 0, negative = 0;
        int corners = u.triangle_normals.empty() ? 3 : 1;
        for (int k = 0; k < corners && !missing; ++k) {
            const float *f = u.triangle_normals.empty() ? &u.vertex_normals[3 * (size_t)u.indices[3 * t + (size_t)k]]
                                                        : &u.triangle_normals[3 * t];
            double m[3] = {f[0], f[1], f[2]};
            double ml = std::sqrt(m[0] * m[0] + m[1] * m[1] + m[2] * m[2]);
            if (!std::isfinite(ml) || !(ml > 1e-12)) {
                missing = true;
                break;
            }
            double d = (m[0] * g[0] + m[1] * g[1] + m[2] * g[2]) / ml;
            positive += d > 0.0;
            negative += d < 0.0;
            for (int i = 0; i < 3; ++i)
                sum[i] += m[i] / ml;
        }
        if (missing) {
            s.no_truth_normal++;
            continue;
        }
        if (positive != corners && negative != corners) {
            s.no_truth_split++;
            continue;
        }
        double sl = std::sqrt(sum[0] * sum[0] + sum[1] * sum[1] + sum[2] * sum[2]);
        double c = sl > 0.0 ? (sum[0] * g[0] + sum[1] * g[1] + sum[2] * g[2]) / (sl * gl) : 0.0;
        if (!(std::fabs(c) >= 0.3)) {
            s.no_truth_oblique++;
            continue;
        }
        truth[t] = c > 0.0 ? 1 : -1;
    }
    return truth;
}

/* Per triangle: whether the repair turns it (its face turned whole, as the
   CLI writes it). Nothing turns when the library refused the unit. */
std::vector<unsigned char> turned(const tool::Unit &u, const tool::UnitResult &r)
{
    std::vector<unsigned char> out(u.triangle_face.size(), 0);
    if (r.status != MESHFIX_OK)
        return out;
    for (size_t t = 0; t < out.size(); ++t)
        out[t] = r.changes.face_flipped[u.triangle_face[t]];
    return out;
}

void add_evidence(meshfix_evidence_counts &to, const meshfix_evidence_counts &e)
{
    to.patches_by_volume += e.patches_by_volume;
    to.patches_by_parity += e.patches_by_parity;
    to.patches_by_visibility += e.patches_by_visibility;
    to.patches_by_normals += e.patches_by_normals;
    to.patches_kept += e.patches_kept;
    to.shells_inward += e.shells_inward;
}

bool explain = false;

/* The damaged patches of one repair (--explain), as lines on stderr. */
void explain_damage(const tool::Unit &u, const tool::UnitResult &r, const std::vector<signed char> &truth,
                    const std::vector<unsigned char> &flip, const char *mode, const std::string &file)
{
    size_t n = truth.size();
    std::map<unsigned, size_t> damaged;
    for (size_t t = 0; t < n; ++t)
        if (truth[t] > 0 && flip[t])
            damaged[r.patch_ids[t]]++;
    if (damaged.empty())
        return;
    /* vertices joined by position, as the library's default topology */
    std::map<std::array<double, 3>, uint32_t> ids;
    std::vector<uint32_t> vid(u.positions.size() / 3);
    for (size_t v = 0; v < vid.size(); ++v)
        vid[v] = ids.emplace(std::array<double, 3>{u.positions[3 * v], u.positions[3 * v + 1], u.positions[3 * v + 2]},
                             (uint32_t)ids.size())
                     .first->second;
    std::map<std::pair<uint32_t, uint32_t>, std::vector<size_t>> edges;
    for (size_t t = 0; t < n; ++t)
        for (int k = 0; k < 3; ++k) {
            uint32_t a = vid[u.indices[3 * t + (size_t)k]], b = vid[u.indices[3 * t + (size_t)((k + 1) % 3)]];
            if (a != b)
                edges[{std::min(a, b), std::max(a, b)}].push_back(t);
        }
    struct Facts {
        size_t triangles = 0, truth = 0, right = 0, boundary = 0, non_manifold = 0, seams = 0;
        double volume = 0.0, area = 0.0, lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
        double normal[3] = {0, 0, 0}; /* area-weighted, as shipped */
        std::vector<uint32_t> boundary_vertices;
    };
    std::map<unsigned, Facts> facts;
    for (size_t t = 0; t < n; ++t) {
        Facts &f = facts[r.patch_ids[t]];
        f.triangles++;
        f.truth += truth[t] != 0;
        f.right += truth[t] > 0;
        const double *a = &u.positions[3 * (size_t)u.indices[3 * t]], *b = &u.positions[3 * (size_t)u.indices[3 * t + 1]],
                     *c = &u.positions[3 * (size_t)u.indices[3 * t + 2]];
        f.volume += (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
                     a[2] * (b[0] * c[1] - b[1] * c[0])) / 6.0;
        double e[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, g[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
        double x[3] = {e[1] * g[2] - e[2] * g[1], e[2] * g[0] - e[0] * g[2], e[0] * g[1] - e[1] * g[0]};
        f.area += 0.5 * std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
        for (int i = 0; i < 3; ++i)
            f.normal[i] += 0.5 * x[i];
        for (const double *p : {a, b, c})
            for (int i = 0; i < 3; ++i) {
                f.lo[i] = std::min(f.lo[i], p[i]);
                f.hi[i] = std::max(f.hi[i], p[i]);
            }
    }
    for (const auto &e : edges) {
        const std::vector<size_t> &ts = e.second;
        for (size_t t : ts) {
            Facts &f = facts[r.patch_ids[t]];
            if (ts.size() == 1) {
                f.boundary++;
                f.boundary_vertices.push_back(e.first.first);
                f.boundary_vertices.push_back(e.first.second);
            }
            else if (ts.size() > 2)
                f.non_manifold++;
            else if (r.patch_ids[ts[0]] != r.patch_ids[ts[1]])
                f.seams++;
        }
    }
    std::fprintf(stderr, "  %s [%s]%s%s: %zu patches; evidence volume %zu, parity %zu, visibility %zu, normals %zu, kept %zu,"
                         " shells inward %zu\n",
                 file.c_str(), mode, u.name.empty() ? "" : " unit ", u.name.c_str(), facts.size(),
                 r.after.evidence.patches_by_volume, r.after.evidence.patches_by_parity,
                 r.after.evidence.patches_by_visibility, r.after.evidence.patches_by_normals,
                 r.after.evidence.patches_kept, r.after.evidence.shells_inward);
    /* the joined vertices' positions, and the boundary vertices of every
       patch in a grid of cells of 1e-4 of the unit's diagonal */
    std::vector<const double *> where(ids.size());
    for (const auto &p : ids)
        where[p.second] = p.first.data();
    double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
    for (const auto &f : facts)
        for (int i = 0; i < 3; ++i) {
            lo[i] = std::min(lo[i], f.second.lo[i]);
            hi[i] = std::max(hi[i], f.second.hi[i]);
        }
    double diagonal = std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                                (hi[2] - lo[2]) * (hi[2] - lo[2]));
    double cell = std::max(diagonal * 1e-4, 1e-300);
    auto key = [&](const double *p, int dx, int dy, int dz) {
        return std::array<long long, 3>{(long long)std::floor(p[0] / cell) + dx, (long long)std::floor(p[1] / cell) + dy,
                                        (long long)std::floor(p[2] / cell) + dz};
    };
    std::map<std::array<long long, 3>, std::vector<std::pair<uint32_t, unsigned>>> grid;
    for (const auto &f : facts)
        for (uint32_t v : f.second.boundary_vertices)
            grid[key(where[v], 0, 0, 0)].push_back({v, f.first});
    for (const auto &d : damaged) {
        const Facts &f = facts[d.first];
        /* other patches with a boundary vertex within a cell of one of its own */
        std::map<unsigned, size_t> touching;
        for (uint32_t v : f.boundary_vertices) {
            std::map<unsigned, bool> seen;
            for (int dx = -1; dx <= 1; ++dx)
                for (int dy = -1; dy <= 1; ++dy)
                    for (int dz = -1; dz <= 1; ++dz) {
                        auto it = grid.find(key(where[v], dx, dy, dz));
                        if (it == grid.end())
                            continue;
                        for (const auto &w : it->second) {
                            const double *p = where[v], *q = where[w.first];
                            double dd = std::sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
                                                  (p[2] - q[2]) * (p[2] - q[2]));
                            if (w.second != d.first && dd <= cell && !seen[w.second]) {
                                seen[w.second] = true;
                                touching[w.second]++;
                            }
                        }
                    }
        }
        std::string near;
        for (const auto &t : touching) {
            const Facts &g = facts[t.first];
            near += fmt("%s%u (%zu triangles, %.0f%% correct, %zu boundary vertices near)", near.empty() ? "" : ", ",
                        t.first, g.triangles, pct(g.right, g.truth), t.second);
        }
        bool closed = f.boundary == 0 && f.non_manifold == 0 && f.seams == 0;
        std::string inside;
        for (const auto &o : facts) {
            const Facts &g = o.second;
            if (o.first == d.first || g.boundary != 0 || g.non_manifold != 0 || g.seams != 0)
                continue;
            bool in = true;
            for (int i = 0; i < 3; ++i)
                in = in && g.lo[i] <= f.lo[i] && f.hi[i] <= g.hi[i];
            if (in && g.area > f.area) {
                inside = fmt(", inside closed patch %u (%zu triangles)", o.first, g.triangles);
                break;
            }
        }
        std::fprintf(stderr,
                     "    patch %u: %zu triangles, %zu damaged, %.1f%% of %zu correct as shipped, %s (boundary %zu,"
                     " non-manifold %zu, seam %zu edge-uses), signed volume %.4g, area %.4g, confidence %.2f%s\n",
                     d.first, f.triangles, d.second, pct(f.right, f.truth), f.truth, closed ? "closed" : "open",
                     f.boundary, f.non_manifold, f.seams, f.volume, f.area,
                     d.first < r.patch_confidence.size() ? r.patch_confidence[d.first] : -1.0f, inside.c_str());
        double nl = std::sqrt(f.normal[0] * f.normal[0] + f.normal[1] * f.normal[1] + f.normal[2] * f.normal[2]);
        std::fprintf(stderr, "      box %.4g %.4g %.4g .. %.4g %.4g %.4g, mean normal %.2f %.2f %.2f (%.2f of its area)%s%s\n",
                     f.lo[0], f.lo[1], f.lo[2], f.hi[0], f.hi[1], f.hi[2], nl > 0 ? f.normal[0] / nl : 0.0,
                     nl > 0 ? f.normal[1] / nl : 0.0, nl > 0 ? f.normal[2] / nl : 0.0, f.area > 0 ? nl / f.area : 0.0,
                     near.empty() ? "" : "; boundary touches patches ", near.c_str());
    }
}

/* The reliability of the reported confidence, per mode, over both inputs
   of every unit (the library's own flips, before faces are turned whole). */
calib_table reliability[2];

void score_confidence(const tool::UnitResult &r, const std::vector<signed char> &truth, const tool::Unit &unit,
                      const std::vector<unsigned char> *reversed_face, calib_table &table)
{
    if (r.status != MESHFIX_OK)
        return;
    std::vector<unsigned char> right_as_given(truth.size());
    for (size_t t = 0; t < truth.size(); ++t) {
        bool reversed = reversed_face != nullptr && (*reversed_face)[unit.triangle_face[t]] != 0;
        right_as_given[t] = truth[t] == 0 ? 2 : (truth[t] > 0) != reversed;
    }
    calib_score(&table, truth.size(), right_as_given.data(), r.triangle_flipped.data(), r.patch_ids.data(),
                r.patch_confidence.data(), r.after.mesh.patches);
}

void score_unit(const tool::Unit &shipped, size_t unit_index, unsigned seed, FileScore &s)
{
    std::vector<signed char> truth = judge(shipped, s);
    size_t n = truth.size();
    for (signed char v : truth) {
        s.truth += v != 0;
        s.agree_ship += v > 0;
    }
    s.triangles += n;

    /* the faces reversed in (b): exactly half, the same in both modes */
    std::vector<unsigned char> reversed_face(shipped.face_count, 0);
    for (size_t f = 0; f < shipped.face_count / 2; ++f)
        reversed_face[f] = 1;
    uint64_t state = (uint64_t)seed ^ fnv1a(s.entry.stored) ^ (0x632BE59BD9B4E019ull * (uint64_t)(unit_index + 1));
    for (size_t f = shipped.face_count; f > 1; --f) {
        size_t j = (size_t)(next_random(state) % f);
        std::swap(reversed_face[f - 1], reversed_face[j]);
    }

    tool::Settings settings; /* the CLI's defaults: policy auto */
    for (int m = 0; m < 2; ++m) {
        ModeScore &ms = s.mode[m];
        tool::Unit unit = shipped;
        if (m == 1) {
            unit.triangle_normals.clear();
            unit.vertex_normals.clear();
        }
        double t0 = now_ms();
        calib_begin();
        tool::UnitResult r = tool::repair_unit(unit, settings);
        ms.repair_ms += now_ms() - t0;
        score_confidence(r, truth, unit, nullptr, reliability[m]);
        if (r.status != MESHFIX_OK) {
            ms.refused++;
        } else {
            add_evidence(ms.evidence, r.after.evidence);
            if (m == 0) {
                s.patches += r.before.mesh.patches;
                s.patches_closed += r.before.mesh.patches_closed;
                s.edges_boundary += r.before.mesh.edges_boundary;
                s.edges_non_manifold += r.before.mesh.edges_non_manifold;
            }
        }
        std::vector<unsigned char> flip = turned(unit, r);
        for (size_t t = 0; t < n; ++t) {
            if (truth[t] == 0)
                continue;
            bool right = (truth[t] > 0) != (flip[t] != 0);
            ms.agree_fix += right;
            ms.damaged += truth[t] > 0 && flip[t];
        }
        if (r.status == MESHFIX_OK) {
            /* per patch: correct triangles turned and kept */
            std::map<unsigned, std::pair<size_t, size_t>> correct;
            for (size_t t = 0; t < n; ++t)
                if (truth[t] > 0)
                    (flip[t] ? correct[r.patch_ids[t]].first : correct[r.patch_ids[t]].second)++;
            for (const auto &c : correct)
                if (c.second.first != 0 && c.second.second != 0)
                    ms.damaged_mixed += c.second.first;
        }
        if (explain && r.status == MESHFIX_OK)
            explain_damage(unit, r, truth, flip, MODE_NAMES[m], s.entry.stored);

        for (size_t t = 0; t < n; ++t)
            if (reversed_face[unit.triangle_face[t]])
                std::swap(unit.indices[3 * t + 1], unit.indices[3 * t + 2]);
        calib_begin();
        tool::UnitResult h = tool::repair_unit(unit, settings);
        if (h.status != MESHFIX_OK)
            ms.refused++;
        score_confidence(h, truth, unit, &reversed_face, reliability[m]);
        std::vector<unsigned char> hflip = turned(unit, h);
        for (size_t t = 0; t < n; ++t) {
            if (truth[t] == 0)
                continue;
            bool against = (reversed_face[unit.triangle_face[t]] != 0) != (hflip[t] != 0);
            ms.agree_half += (truth[t] > 0) != against;
        }
    }
}

FileScore score_file(const Entry &e, const std::string &dir, unsigned seed)
{
    FileScore s;
    s.entry = e;
    double start = now_ms();
    std::string error;
    std::unique_ptr<tool::MeshFile> file = tool::load_file(dir + "/" + e.stored, error);
    s.load_ms = now_ms() - start;
    if (!file) {
        s.error = error.empty() ? "not loaded" : error;
        s.total_ms = now_ms() - start;
        return s;
    }
    s.loaded = true;
    s.units = file->units.size();
    for (size_t i = 0; i < file->units.size(); ++i)
        score_unit(file->units[i], i, seed, s);
    s.total_ms = now_ms() - start;
    return s;
}

/* ---- output ---- */

std::string tsv_clean(std::string text)
{
    for (char &c : text)
        if (c == '\t' || c == '\n' || c == '\r')
            c = ' ';
    return text;
}

void write_tsv(const std::string &path, const std::vector<FileScore> &files)
{
    std::ofstream out(path);
    out << "file\tfamily\tsplit\tpackage\tunits\ttriangles\ttruth\tship_pct\t"
           "fix_pct_normals\tdamaged_normals\thalf_pct_normals\t"
           "fix_pct_geometry\tdamaged_geometry\thalf_pct_geometry\t"
           "damaged_mixed_normals\tdamaged_mixed_geometry\t"
           "agree_ship\tagree_fix_normals\tagree_half_normals\tagree_fix_geometry\tagree_half_geometry\t"
           "no_truth_area\tno_truth_normal\tno_truth_split\tno_truth_oblique\t"
           "patches\tpatches_closed\tedges_boundary\tedges_non_manifold\t"
           "evidence_normals(volume/parity/visibility/normals/kept/inward)\tevidence_geometry\t"
           "load_ms\trepair_ms_normals\trepair_ms_geometry\ttotal_ms\tnote\n";
    for (const FileScore &s : files) {
        auto ev = [](const meshfix_evidence_counts &e) {
            return fmt("%zu/%zu/%zu/%zu/%zu/%zu", e.patches_by_volume, e.patches_by_parity, e.patches_by_visibility,
                       e.patches_by_normals, e.patches_kept, e.shells_inward);
        };
        std::string note = s.loaded ? (s.truth == 0 ? "no truth" : "") : "load failed: " + s.error;
        for (int m = 0; m < 2; ++m)
            if (s.mode[m].refused != 0)
                note += (note.empty() ? "" : "; ") + fmt("%s: %zu repairs refused", MODE_NAMES[m], s.mode[m].refused);
        if (s.entry.note != "-")
            note += (note.empty() ? "" : "; ") + s.entry.note;
        out << s.entry.stored << '\t' << s.entry.family << '\t' << s.entry.split << '\t' << s.entry.package << '\t'
            << s.units << '\t' << s.triangles << '\t' << s.truth << '\t' << fmt("%.2f", pct(s.agree_ship, s.truth)) << '\t'
            << fmt("%.2f", pct(s.mode[0].agree_fix, s.truth)) << '\t' << s.mode[0].damaged << '\t'
            << fmt("%.2f", pct(s.mode[0].agree_half, s.truth)) << '\t' << fmt("%.2f", pct(s.mode[1].agree_fix, s.truth))
            << '\t' << s.mode[1].damaged << '\t' << fmt("%.2f", pct(s.mode[1].agree_half, s.truth)) << '\t'
            << s.mode[0].damaged_mixed << '\t' << s.mode[1].damaged_mixed << '\t'
            << s.agree_ship << '\t' << s.mode[0].agree_fix << '\t' << s.mode[0].agree_half << '\t' << s.mode[1].agree_fix
            << '\t' << s.mode[1].agree_half << '\t' << s.no_truth_area << '\t' << s.no_truth_normal << '\t'
            << s.no_truth_split << '\t' << s.no_truth_oblique << '\t' << s.patches << '\t' << s.patches_closed << '\t'
            << s.edges_boundary << '\t' << s.edges_non_manifold << '\t' << ev(s.mode[0].evidence) << '\t'
            << ev(s.mode[1].evidence) << '\t' << fmt("%.2f", s.load_ms) << '\t' << fmt("%.2f", s.mode[0].repair_ms) << '\t'
            << fmt("%.2f", s.mode[1].repair_ms) << '\t' << fmt("%.2f", s.total_ms) << '\t' << tsv_clean(note) << '\n';
    }
}

struct Total {
    size_t files = 0, scored = 0, failed = 0, no_truth = 0, truth = 0, agree_ship = 0;
    size_t agree_fix[2] = {0, 0}, damaged[2] = {0, 0}, mixed[2] = {0, 0}, damaged_files[2] = {0, 0}, agree_half[2] = {0, 0};
    double ms = 0.0, max_ms = 0.0;

    void add(const FileScore &s)
    {
        files++;
        ms += s.total_ms;
        max_ms = std::max(max_ms, s.total_ms);
        if (!s.loaded) {
            failed++;
            return;
        }
        if (s.truth == 0) {
            no_truth++;
            return;
        }
        scored++;
        truth += s.truth;
        agree_ship += s.agree_ship;
        for (int m = 0; m < 2; ++m) {
            agree_fix[m] += s.mode[m].agree_fix;
            damaged[m] += s.mode[m].damaged;
            mixed[m] += s.mode[m].damaged_mixed;
            damaged_files[m] += s.mode[m].damaged != 0;
            agree_half[m] += s.mode[m].agree_half;
        }
    }
};

std::string total_header()
{
    return "                         files  scored   truth-tris   ship%  |  normals: fix%  damaged (files)   mixed   half%"
           "  | geometry: fix%  damaged (files)   mixed   half%  | s total  max ms\n";
}

std::string total_row(const std::string &name, const Total &t)
{
    std::string row = fmt("%-24s %5zu  %6zu  %11zu  %6.2f  |", name.c_str(), t.files, t.scored, t.truth,
                          pct(t.agree_ship, t.truth));
    for (int m = 0; m < 2; ++m)
        row += fmt("  %13.2f  %7zu %5.2f%% (%3zu) %6zu  %6.2f  |", pct(t.agree_fix[m], t.truth), t.damaged[m],
                   pct(t.damaged[m], t.truth), t.damaged_files[m], t.mixed[m], pct(t.agree_half[m], t.truth));
    row += fmt(" %7.1f  %6.0f\n", t.ms / 1000.0, t.max_ms);
    return row;
}

/* The one-line totals of a split. */
std::string one_line(const std::string &split, const Total &t)
{
    return fmt("%s: %zu files (%zu scored, %zu without truth, %zu not loaded), %zu triangles with truth, ship %.2f%%; "
               "normals: fix %.2f%%, damaged %zu (%.3f%%, %zu files, %zu mixed), half %.2f%%; "
               "geometry: fix %.2f%%, damaged %zu (%.3f%%, %zu files, %zu mixed), half %.2f%%; %.1f s\n",
               split.c_str(), t.files, t.scored, t.no_truth, t.failed, t.truth, pct(t.agree_ship, t.truth),
               pct(t.agree_fix[0], t.truth), t.damaged[0], pct(t.damaged[0], t.truth), t.damaged_files[0], t.mixed[0],
               pct(t.agree_half[0], t.truth), pct(t.agree_fix[1], t.truth), t.damaged[1], pct(t.damaged[1], t.truth),
               t.damaged_files[1], t.mixed[1], pct(t.agree_half[1], t.truth), t.ms / 1000.0);
}

std::string summary(const std::vector<FileScore> &files, unsigned seed, size_t worst, const std::string &split)
{
    std::string out = fmt("assets_eval: %zu files, split %s, seed %u, policy auto (the CLI's defaults)\n\n", files.size(),
                          split.c_str(), seed);
    std::map<std::string, Total> splits;
    std::map<std::pair<std::string, std::string>, Total> families;
    for (const FileScore &s : files) {
        splits[s.entry.split].add(s);
        families[{s.entry.split, s.entry.family}].add(s);
    }
    out += "totals (percentages of triangles with truth; damaged: correct as shipped, turned by the repair;\n"
           "mixed: of it, in patches whose other correct triangles were kept)\n";
    out += total_header();
    for (const auto &sp : splits) {
        out += total_row(sp.first, sp.second);
        for (const auto &f : families)
            if (f.first.first == sp.first)
                out += total_row("  " + f.first.second, f.second);
    }
    out += "\n";
    for (const auto &sp : splits)
        out += one_line(sp.first, sp.second);

    for (int m = 0; m < 2; ++m) {
        std::vector<const FileScore *> order;
        for (const FileScore &s : files)
            if (s.loaded && s.mode[m].damaged != 0)
                order.push_back(&s);
        std::sort(order.begin(), order.end(), [m](const FileScore *a, const FileScore *b) {
            if (a->mode[m].damaged != b->mode[m].damaged)
                return a->mode[m].damaged > b->mode[m].damaged;
            return a->entry.stored < b->entry.stored;
        });
        out += fmt("\nworst %zu files by damage, %s mode (%zu files damaged)\n", std::min(worst, order.size()),
                   m == 0 ? "normals as evidence" : "geometry only", order.size());
        out += "  damaged  (mixed)  of truth  ship%  fix%   half%  family     file\n";
        for (size_t i = 0; i < order.size() && i < worst; ++i) {
            const FileScore &s = *order[i];
            out += fmt("  %7zu  %7zu  %8zu  %5.1f  %5.1f  %5.1f  %-9s  %s\n", s.mode[m].damaged, s.mode[m].damaged_mixed, s.truth,
                       pct(s.agree_ship, s.truth), pct(s.mode[m].agree_fix, s.truth), pct(s.mode[m].agree_half, s.truth),
                       s.entry.family.c_str(), s.entry.stored.c_str());
        }
    }

    std::string against, failed, none;
    size_t n_against = 0, n_failed = 0, n_none = 0;
    for (const FileScore &s : files) {
        if (!s.loaded) {
            n_failed++;
            failed += fmt("  %s: %s\n", s.entry.stored.c_str(), s.error.c_str());
        } else if (s.truth == 0) {
            n_none++;
            none += fmt("  %s (%zu triangles: %zu about zero area, %zu without normals, %zu split, %zu oblique)\n",
                        s.entry.stored.c_str(), s.triangles, s.no_truth_area, s.no_truth_normal, s.no_truth_split,
                        s.no_truth_oblique);
        } else if (pct(s.agree_ship, s.truth) < 10.0) {
            n_against++;
            against += fmt("  %5.1f%% of %zu  %s\n", pct(s.agree_ship, s.truth), s.truth, s.entry.stored.c_str());
        }
    }
    out += fmt("\nfiles whose normals disagree with their own winding wholesale (ship%% < 10): %zu\n", n_against) + against;
    out += fmt("files without truth: %zu\n", n_none) + none;
    out += fmt("files not loaded: %zu\n", n_failed) + failed;
    return out;
}

bool read_manifest(const std::string &path, std::vector<Entry> &out)
{
    std::ifstream in(path);
    if (!in)
        return false;
    std::string line;
    while (std::getline(in, line)) {
        if (line.empty() || line[0] == '#')
            continue;
        std::vector<std::string> f;
        std::stringstream ss(line);
        std::string field;
        while (std::getline(ss, field, '\t'))
            f.push_back(field);
        if (f.size() < 9)
            continue;
        out.push_back({f[0], f[2], f[3], f[4], f[5], f[6], f[7], f[8]});
    }
    return true;
}

int usage()
{
    std::fprintf(stderr, "usage: assets_eval [--split tune|heldout|all] [--family NAME] [--match TEXT] [--seed N]\n"
                         "                   [--worst N] [--tsv FILE] [--summary FILE] [--explain] [--rows FILE] [DIR]\n");
    return 1;
}

} // namespace

int main(int argc, char **argv)
{
    std::string dir = "build/assets", split = "tune", family, match, tsv, summary_path;
    unsigned seed = 1;
    size_t worst = 15;
    for (int i = 1; i < argc; ++i) {
        std::string a = argv[i];
        auto value = [&](std::string &to) {
            if (i + 1 >= argc)
                return false;
            to = argv[++i];
            return true;
        };
        std::string v;
        if (a == "--split") {
            if (!value(split) || (split != "tune" && split != "heldout" && split != "all"))
                return usage();
        } else if (a == "--family") {
            if (!value(family))
                return usage();
        } else if (a == "--match") {
            if (!value(match))
                return usage();
        } else if (a == "--seed") {
            if (!value(v))
                return usage();
            seed = (unsigned)std::strtoul(v.c_str(), nullptr, 10);
        } else if (a == "--worst") {
            if (!value(v))
                return usage();
            worst = (size_t)std::strtoul(v.c_str(), nullptr, 10);
        } else if (a == "--tsv") {
            if (!value(tsv))
                return usage();
        } else if (a == "--explain") {
            explain = true;
        } else if (a == "--rows") {
            if (!value(v) || !calib_open_rows(v.c_str()))
                return usage();
        } else if (a == "--summary") {
            if (!value(summary_path))
                return usage();
        } else if (!a.empty() && a[0] == '-') {
            return usage();
        } else {
            dir = a;
        }
    }
    std::vector<Entry> entries;
    if (!read_manifest(dir + "/manifest.tsv", entries)) {
        std::fprintf(stderr, "assets_eval: cannot read %s/manifest.tsv (run tests/corpus/fetch_assets.sh)\n", dir.c_str());
        return 1;
    }
    std::vector<FileScore> files;
    double start = now_ms();
    for (const Entry &e : entries) {
        if (split != "all" && e.split != split)
            continue;
        if (!family.empty() && e.family != family)
            continue;
        if (!match.empty() && e.stored.find(match) == std::string::npos)
            continue;
        files.push_back(score_file(e, dir, seed));
        const FileScore &s = files.back();
        std::fprintf(stderr, "[%zu] %s: %s\n", files.size(), e.stored.c_str(),
                     !s.loaded ? ("load failed: " + s.error).c_str()
                               : fmt("%zu/%zu truth, ship %.1f%%, damaged %zu/%zu, %.0f ms", s.truth, s.triangles,
                                     pct(s.agree_ship, s.truth), s.mode[0].damaged, s.mode[1].damaged, s.total_ms)
                                     .c_str());
    }
    if (!tsv.empty())
        write_tsv(tsv, files);
    std::string text = summary(files, seed, worst, split);
    text += fmt("\nwall time %.1f s (one thread)\n", (now_ms() - start) / 1000.0);
    std::fputs(text.c_str(), stdout);
    for (int m = 0; m < 2; ++m) {
        std::printf("\nreliability of the reported confidence, %s (as shipped and half reversed):\n", MODE_NAMES[m]);
        calib_print(&reliability[m], stdout);
    }
    calib_close_rows();
    if (!summary_path.empty()) {
        std::ofstream out(summary_path);
        out << text;
    }
    return 0;
}
