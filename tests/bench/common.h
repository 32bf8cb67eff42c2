// Shared helpers of `make bench` (tests/bench.cpp and tests/bench/*.cpp).
//
// Every part of the bench times its candidates and their baselines in the
// same process, on the same data, several times each, and prints the
// fastest (min) and the middle (median) run. Ratios are taken between
// mins: on a shared, noisy machine the fastest run is the one least
// disturbed by others; the median says how noisy it was.
//
// Each translation unit that looks inside meshfix.h includes it with
// MESHFIX_STATIC and MESHFIX_IMPLEMENTATION before this file, so the
// internals (meshfix__trace, whole_tree...) are its own.
#ifndef MESHFIX_BENCH_COMMON_H
#define MESHFIX_BENCH_COMMON_H

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "../../examples/meshio.h"
#include "../../meshfix.h" /* the declarations, for counting_options */

namespace bench {

// What every part is told by main.
struct Settings {
    bool quick = false;
    std::string head_stl = "/usr/share/opencascade/data/stl/head.stl";
    std::string corpus = "build/corpus";
    std::string build_dir = "build";
};

inline double seconds_since(std::chrono::steady_clock::time_point start)
{
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The fastest and the median of several runs, in seconds.
struct Timing {
    double min = 0, median = 0;
    int runs = 0;
};

template <class F> Timing time_runs(int runs, F f)
{
    std::vector<double> t;
    for (int i = 0; i < runs; ++i) {
        auto start = std::chrono::steady_clock::now();
        f();
        t.push_back(seconds_since(start));
    }
    std::sort(t.begin(), t.end());
    Timing r;
    r.runs = runs;
    r.min = t.front();
    r.median = runs % 2 ? t[runs / 2] : 0.5 * (t[runs / 2 - 1] + t[runs / 2]);
    return r;
}

// "min / median" of a timing scaled by `factor` (e.g. 1e3 for ms).
inline std::string min_med(const Timing &t, double factor, int decimals = 1)
{
    char s[64];
    std::snprintf(s, sizeof(s), "%.*f / %.*f", decimals, t.min * factor, decimals, t.median * factor);
    return s;
}

// A rate (count / seconds) from the fastest and the median run, "best / median".
inline std::string rate(double count, const Timing &t, double unit, int decimals = 2)
{
    char s[64];
    std::snprintf(s, sizeof(s), "%.*f / %.*f", decimals, count / t.min / unit, decimals, count / t.median / unit);
    return s;
}

inline std::string ratio(double a, double b, int decimals = 2)
{
    char s[32];
    if (!(b > 0))
        return "-";
    std::snprintf(s, sizeof(s), "%.*fx", decimals, a / b);
    return s;
}

// An allocator that counts calls and the peak of live bytes.
struct CountingAllocator {
    size_t current = 0, peak = 0, calls = 0;
};

inline void *counting_alloc(size_t size, void *user)
{
    CountingAllocator *a = static_cast<CountingAllocator *>(user);
    size_t *block = static_cast<size_t *>(std::malloc(size + 16));
    if (!block)
        return nullptr;
    block[0] = size;
    a->current += size;
    a->peak = std::max(a->peak, a->current);
    a->calls++;
    return reinterpret_cast<char *>(block) + 16;
}

inline void counting_free(void *p, void *user)
{
    if (!p)
        return;
    CountingAllocator *a = static_cast<CountingAllocator *>(user);
    size_t *block = reinterpret_cast<size_t *>(static_cast<char *>(p) - 16);
    a->current -= block[0];
    std::free(block);
}

// Options that count every allocation of a call into `counter`.
inline meshfix_options counting_options(CountingAllocator *counter)
{
    meshfix_options options;
    std::memset(&options, 0, sizeof(options));
    options.memory.alloc_func = counting_alloc;
    options.memory.free_func = counting_free;
    options.memory.user_data = counter;
    return options;
}

// OpenMesh building its half-edge structure of g (add_vertex + add_face):
// the baseline of parts 0 and 2 (tests/bench/cut.cpp). Returns the faces it
// refused as complex.
size_t openmesh_build(const mio_mesh &g);

// Small deterministic generator (xorshift64*), independent of meshfix's.
struct Random {
    unsigned long long s;
    explicit Random(unsigned long long seed) : s(seed * 0x9E3779B97F4A7C15ull + 1) {}
    unsigned long long next()
    {
        s ^= s >> 12;
        s ^= s << 25;
        s ^= s >> 27;
        return s * 0x2545F4914F6CDD1Dull;
    }
    // uniform in [0, 1)
    double uniform() { return double(next() >> 11) * (1.0 / 9007199254740992.0); }
    // a uniformly distributed unit vector
    void direction(float d[3])
    {
        double z = 1.0 - 2.0 * uniform(), phi = 6.283185307179586 * uniform(), r = std::sqrt(std::max(0.0, 1 - z * z));
        d[0] = float(r * std::cos(phi));
        d[1] = float(r * std::sin(phi));
        d[2] = float(z);
    }
};

// A model of the bench, owned (mio_free on destruction).
struct Mesh {
    mio_mesh m;
    Mesh() { std::memset(&m, 0, sizeof(m)); }
    ~Mesh() { mio_free(&m); }
    Mesh(const Mesh &) = delete;
    Mesh &operator=(const Mesh &) = delete;
    size_t triangles() const { return m.index_count / 3; }
};

inline bool load_mesh(const std::string &path, Mesh *out)
{
    char error[256];
    if (!mio_load(path.c_str(), &out->m, error, sizeof(error))) {
        std::printf("(cannot load %s: %s)\n", path.c_str(), error);
        return false;
    }
    return true;
}

// The parts, each printing its own table(s); they return 0 when every
// check passed. Each appends lines for the closing summary.
int part_rays(const Settings &s, std::vector<std::string> *summary);
int part_cut(const Settings &s, std::vector<std::string> *summary);
int part_quality(const Settings &s, std::vector<std::string> *summary);
int part_adversarial(const Settings &s, std::vector<std::string> *summary);

} // namespace bench

#endif
