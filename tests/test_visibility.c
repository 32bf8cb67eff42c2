/* Tests of the Borodin-style policies (VISIBILITY, AUTO), nested shells,
   UP, the ray caster and the weld. Prints "N passed, N failed". */
#undef NDEBUG
#define MESHFIX_IMPLEMENTATION
#include "../meshfix.h"
#define MESHIO_IMPLEMENTATION
#include "../examples/meshio.h"
#define MESHGEN_IMPLEMENTATION
#include "../examples/meshgen.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int failures;

#define CHECK_EQ(a, b)                                                                                  \
    do {                                                                                                \
        unsigned long long va_ = (unsigned long long)(a), vb_ = (unsigned long long)(b);                \
        if (va_ != vb_) {                                                                               \
            printf("    %s:%d: %s == %llu, expected %s == %llu\n", __FILE__, __LINE__, #a, va_, #b, vb_); \
            failures++;                                                                                 \
        }                                                                                               \
    } while (0)
#define CHECK(cond)                                                                                     \
    do {                                                                                                \
        if (!(cond)) {                                                                                  \
            printf("    %s:%d: check failed: %s\n", __FILE__, __LINE__, #cond);                         \
            failures++;                                                                                 \
        }                                                                                               \
    } while (0)

static const char *models_dir(void)
{
    const char *dir = getenv("MESHFIX_MODELS");
    return dir != NULL ? dir : "/usr/share/assimp/models";
}

static void flip(unsigned int *indices, size_t t)
{
    unsigned int x = indices[3 * t + 1];
    indices[3 * t + 1] = indices[3 * t + 2];
    indices[3 * t + 2] = x;
}

static double triangle_area(const mio_mesh *g, size_t t)
{
    const float *a = g->positions + 3 * (size_t)g->indices[3 * t], *b = g->positions + 3 * (size_t)g->indices[3 * t + 1];
    const float *c = g->positions + 3 * (size_t)g->indices[3 * t + 2];
    double u[3], v[3], n[3];
    int k;
    for (k = 0; k < 3; ++k)
        u[k] = (double)b[k] - a[k], v[k] = (double)c[k] - a[k];
    n[0] = u[1] * v[2] - u[2] * v[1];
    n[1] = u[2] * v[0] - u[0] * v[2];
    n[2] = u[0] * v[1] - u[1] * v[0];
    return 0.5 * sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
}

/* ---- cutting a model into unwelded patches ---- */

/* Region growing from `count` seed triangles over shared edges (a
   breadth-first fill from all seeds at once); returns a cluster per
   triangle. Deterministic for a seed. */
static unsigned int *grow_clusters(const mio_mesh *g, size_t count, unsigned long long seed)
{
    size_t t, triangles = g->index_count / 3, head = 0, tail = 0, i, e;
    unsigned int *cluster = (unsigned int *)malloc(triangles * sizeof(unsigned int));
    unsigned int *queue = (unsigned int *)malloc(triangles * sizeof(unsigned int));
    /* edge -> triangles by a simple sorted list of (low, high, triangle) */
    unsigned long long *edges = (unsigned long long *)malloc(3 * triangles * sizeof(unsigned long long) * 2);
    size_t n = 0;
    for (t = 0; t < triangles; ++t)
        cluster[t] = 0xFFFFFFFFu;
    for (t = 0; t < triangles; ++t)
        for (e = 0; e < 3; ++e) {
            unsigned long long a = g->indices[3 * t + e], b = g->indices[3 * t + (e + 1) % 3];
            unsigned long long lo = a < b ? a : b, hi = a < b ? b : a;
            edges[2 * n] = (lo << 32) | hi;
            edges[2 * n + 1] = t;
            n++;
        }
    /* insertion-free sort: simple shell sort on pairs */
    {
        size_t gap, j;
        for (gap = n / 2; gap > 0; gap /= 2)
            for (i = gap; i < n; ++i) {
                unsigned long long k0 = edges[2 * i], k1 = edges[2 * i + 1];
                for (j = i; j >= gap && edges[2 * (j - gap)] > k0; j -= gap) {
                    edges[2 * j] = edges[2 * (j - gap)];
                    edges[2 * j + 1] = edges[2 * (j - gap) + 1];
                }
                edges[2 * j] = k0;
                edges[2 * j + 1] = k1;
            }
    }
    for (i = 0; i < count; ++i) {
        size_t s = (size_t)(gen_random(&seed) % triangles);
        if (cluster[s] == 0xFFFFFFFFu) {
            cluster[s] = (unsigned int)i;
            queue[tail++] = (unsigned int)s;
        }
    }
    while (head < tail) {
        unsigned int cur = queue[head++];
        for (e = 0; e < 3; ++e) {
            unsigned long long a = g->indices[3 * cur + e], b = g->indices[3 * cur + (e + 1) % 3];
            unsigned long long key = ((a < b ? a : b) << 32) | (a < b ? b : a);
            size_t lo = 0, hi = n;
            while (lo < hi) {
                size_t mid = (lo + hi) / 2;
                if (edges[2 * mid] < key)
                    lo = mid + 1;
                else
                    hi = mid;
            }
            for (; lo < n && edges[2 * lo] == key; ++lo) {
                unsigned int u = (unsigned int)edges[2 * lo + 1];
                if (cluster[u] == 0xFFFFFFFFu) {
                    cluster[u] = cluster[cur];
                    queue[tail++] = u;
                }
            }
        }
    }
    for (t = 0; t < triangles; ++t) /* anything unreached (another component) is its own cluster */
        if (cluster[t] == 0xFFFFFFFFu)
            cluster[t] = (unsigned int)(count + t);
    free(queue);
    free(edges);
    return cluster;
}

/* A cut model: every cluster has its own copy of its vertices (no index
   is shared across a seam), each copy moved `gap` of the way toward its
   cluster's centroid so the seams open. `second` records, per triangle,
   the corner that follows the first one in the reference winding (flips
   keep the first corner), so outward_share can score any result. */
typedef struct cut {
    mio_mesh mesh;
    unsigned int *second;
    unsigned int *cluster;
    size_t clusters;
} cut;

static void cut_model(const mio_mesh *g, size_t clusters, float gap, double inside, unsigned long long seed, cut *out)
{
    size_t t, c, k, triangles = g->index_count / 3, size = 1, mask, used = 0;
    unsigned long long *keys;
    unsigned int *values;
    double *centroid;
    size_t *count;
    out->cluster = grow_clusters(g, clusters, seed);
    out->clusters = 0;
    for (t = 0; t < triangles; ++t)
        out->clusters = out->cluster[t] + 1 > out->clusters ? out->cluster[t] + 1 : out->clusters;
    centroid = (double *)calloc(3 * out->clusters, sizeof(double));
    count = (size_t *)calloc(out->clusters, sizeof(size_t));
    for (t = 0; t < triangles; ++t)
        for (c = 0; c < 3; ++c) {
            for (k = 0; k < 3; ++k)
                centroid[3 * out->cluster[t] + k] += g->positions[3 * (size_t)g->indices[3 * t + c] + k];
            count[out->cluster[t]]++;
        }
    while (size < 4 * g->index_count)
        size *= 2;
    mask = size - 1;
    keys = (unsigned long long *)malloc(size * sizeof(unsigned long long));
    values = (unsigned int *)malloc(size * sizeof(unsigned int));
    for (k = 0; k < size; ++k)
        keys[k] = ~0ull;
    out->mesh.positions = (float *)malloc(3 * g->index_count * sizeof(float));
    out->mesh.indices = (unsigned int *)malloc(g->index_count * sizeof(unsigned int));
    out->mesh.index_count = g->index_count;
    for (t = 0; t < triangles; ++t)
        for (c = 0; c < 3; ++c) {
            unsigned int v = g->indices[3 * t + c], cl = out->cluster[t];
            unsigned long long key = ((unsigned long long)cl << 32) | v;
            size_t i = (size_t)((key * 0x9E3779B97F4A7C15ull) >> 17) & mask;
            while (keys[i] != ~0ull && keys[i] != key)
                i = (i + 1) & mask;
            if (keys[i] == ~0ull) {
                keys[i] = key;
                values[i] = (unsigned int)used;
                for (k = 0; k < 3; ++k) {
                    double p = g->positions[3 * (size_t)v + k], mid = centroid[3 * cl + k] / (double)count[cl];
                    out->mesh.positions[3 * used + k] = (float)(p + (mid - p) * gap);
                }
                used++;
            }
            out->mesh.indices[3 * t + c] = values[i];
        }
    out->mesh.vertex_count = used;
    out->second = (unsigned int *)malloc(triangles * sizeof(unsigned int));
    for (t = 0; t < triangles; ++t)
        out->second[t] = out->mesh.indices[3 * t + 1];
    /* half of the patches reversed, and `inside` of the triangles at random */
    for (t = 0; t < triangles; ++t) {
        unsigned long long h = ((unsigned long long)out->cluster[t] + 1) * 0x9E3779B97F4A7C15ull;
        int reverse_patch = (int)((h >> 45) & 1);
        if (reverse_patch ^ (gen_uniform(&seed) < inside))
            flip(out->mesh.indices, t);
    }
    free(keys);
    free(values);
    free(centroid);
    free(count);
}

static void free_cut(cut *c)
{
    mio_free(&c->mesh);
    free(c->second);
    free(c->cluster);
}

/* The share of area wound as the reference winds it. */
static double outward_share(const cut *c, const unsigned int *result)
{
    size_t t;
    double same = 0, total = 0;
    mio_mesh view = c->mesh;
    view.indices = (unsigned int *)result;
    for (t = 0; t < c->mesh.index_count / 3; ++t) {
        double a = triangle_area(&view, t);
        total += a;
        same += result[3 * t + 1] == c->second[t] ? a : 0;
    }
    return total > 0 ? same / total : 0;
}

/* ---- closed models cut into patches ---- */

/* Repairs a cut model with `policy`; returns the outward share of area. */
static double repair_cut(const cut *c, meshfix_policy policy, unsigned int flags, meshfix_report *r)
{
    meshfix_options o;
    unsigned int *out = (unsigned int *)malloc(c->mesh.index_count * sizeof(unsigned int));
    double share;
    memset(&o, 0, sizeof(o));
    o.policy = policy;
    o.visibility_flags = flags;
    CHECK_EQ(meshfix_orient(out, c->mesh.indices, c->mesh.index_count, c->mesh.positions, c->mesh.vertex_count, 12,
                            &o, r),
             MESHFIX_OK);
    share = outward_share(c, out);
    free(out);
    return share;
}

/* The closed parts of a real model, wound outward by meshfix itself (the
   files are not all consistent), as the reference. */
static int load_closed_reference(const char *file, mio_mesh *g)
{
    char path[512], error[256];
    meshfix_report r;
    snprintf(path, sizeof(path), "%s/%s", models_dir(), file);
    if (!mio_load(path, g, error, sizeof(error))) {
        printf("    cannot load %s: %s (install Debian's assimp-testmodels)\n", path, error);
        return 0;
    }
    return meshfix_orient(g->indices, g->indices, g->index_count, g->positions, g->vertex_count, 12, NULL, &r) ==
           MESHFIX_OK;
}

static void check_cut(const char *name, const mio_mesh *g, size_t clusters)
{
    cut c;
    meshfix_report r;
    double share;
    cut_model(g, clusters, 0.002f, 0.2, 77, &c);
    CHECK_EQ(meshfix_inspect(c.mesh.indices, c.mesh.index_count, c.mesh.positions, c.mesh.vertex_count, 12, &r),
             MESHFIX_OK);
    share = repair_cut(&c, MESHFIX_POLICY_VISIBILITY, 0, &r);
    printf("    %s in %lu patches (%lu triangles): %.4f%% of the area outward; %lu rays, %lu pairs, %lu merges\n",
           name, (unsigned long)r.patches, (unsigned long)r.triangles, 100 * share, (unsigned long)r.rays_cast,
           (unsigned long)r.patch_pairs, (unsigned long)r.patches_merged);
    CHECK(r.patches >= clusters / 2);
    CHECK(share >= 0.999);
    CHECK_EQ(r.edges_inconsistent, 0);
    share = repair_cut(&c, MESHFIX_POLICY_AUTO, 0, &r);
    CHECK(share >= 0.999);
    free_cut(&c);
}

static void test_cut_generated(void)
{
    mio_mesh g, t;
    CHECK(gen_sphere(&g, 40, 60, 0, 0, 0, 1));
    check_cut("sphere", &g, 60);
    mio_free(&g);
    CHECK(gen_torus(&g, 80, 30, 2, 0.6f));
    check_cut("torus", &g, 120);
    mio_free(&g);
    CHECK(gen_sphere(&g, 30, 40, 0, 0, 0, 1));
    CHECK(gen_torus(&t, 60, 20, 3.5f, 0.5f));
    CHECK(gen_append(&g, &t));
    check_cut("sphere and torus", &g, 300);
    mio_free(&g);
    mio_free(&t);
}

static void test_cut_real(void)
{
    static const char *files[] = {"OBJ/spider.obj", "OBJ/empty_mat.obj", "STL/Spider_binary.stl"};
    size_t f;
    for (f = 0; f < sizeof(files) / sizeof(files[0]); ++f) {
        mio_mesh g;
        if (!load_closed_reference(files[f], &g)) {
            failures++;
            continue;
        }
        check_cut(files[f], &g, f == 1 ? 20 : 150);
        mio_free(&g);
    }
}

typedef struct test_case {
    const char *name;
    void (*run)(void);
} test_case;

static const test_case tests[] = {
    {"generated closed models cut into unwelded patches with gaps", test_cut_generated},
    {"real closed models cut into unwelded patches with gaps", test_cut_real},
};

int main(int argc, char **argv)
{
    size_t i, passed = 0, failed = 0;
    for (i = 0; i < sizeof(tests) / sizeof(tests[0]); ++i) {
        int before = failures;
        if (argc > 1 && strstr(tests[i].name, argv[1]) == NULL)
            continue;
        tests[i].run();
        if (failures == before) {
            passed++;
            printf("ok   %s\n", tests[i].name);
        } else {
            failed++;
            printf("FAIL %s\n", tests[i].name);
        }
    }
    printf("%lu passed, %lu failed\n", (unsigned long)passed, (unsigned long)failed);
    return failed != 0;
}
