/* meshgen.h - procedural test meshes for the meshfix examples, tests and benchmark

   Every generator fills a mio_mesh (free it with mio_free) and winds its
   triangles counter-clockwise seen from the side they are meant to face:
   from outside for solids (a hollow faces into the hollow), from +z for
   sheets and terrains, as stated for the other open parts. The cuts and
   corruptions at the end keep a per-triangle truth of that facing
   (tests/scenes.h builds scenes from them).
   Include meshio.h first. Define MESHGEN_IMPLEMENTATION in one file. */
#ifndef MESHGEN_H
#define MESHGEN_H
#include <stddef.h>

/* UV sphere: 2 * segments * (rings - 1) triangles, closed, genus 0. */
int gen_sphere(mio_mesh *m, unsigned rings, unsigned segments, float cx, float cy, float cz, float radius);
/* Torus: 2 * n * k triangles, closed, genus 1 (Euler characteristic 0). */
int gen_torus(mio_mesh *m, unsigned n, unsigned k, float major, float minor);
/* Height field over [0,1]^2 with nx * ny quads: an open sheet facing +z. */
int gen_grid(mio_mesh *m, unsigned nx, unsigned ny);
/* Moebius strip of n quads around, 1 across: non-orientable. */
int gen_mobius(mio_mesh *m, unsigned n);
/* Appends src to dst (indices shifted). */
int gen_append(mio_mesh *dst, const mio_mesh *src);
/* A soup of src: every corner its own vertex, at its position. */
int gen_soup(mio_mesh *out, const mio_mesh *src);
/* Reverses each triangle with probability `fraction`; marks[t] = 1 for the
   reversed ones when marks is not NULL. Returns how many were reversed. */
size_t gen_flip_random(mio_mesh *m, double fraction, unsigned long long seed, unsigned char *marks);
/* Small deterministic generator (splitmix64). */
unsigned long long gen_random(unsigned long long *state);
double gen_uniform(unsigned long long *state);

/* ---- parts for scenes: solids face out, open parts as each one says ---- */

/* Axis-aligned box [lo, hi], every face cut into n x n quads: 12 n^2
   triangles, closed, facing out. */
int gen_box(mio_mesh *m, unsigned n, const float lo[3], const float hi[3]);
typedef struct gen_aabb {
    float lo[3], hi[3];
} gen_aabb;
/* The solid union of the `add` boxes less the union of the `cut` boxes,
   facing out of the material (so a hollow faces into the hollow). Every
   face lies on one grid through all box faces, refined so that no edge
   along an axis is longer than `step`: the surface is welded and closed.
   It is manifold unless two solid cells meet only along an edge. */
int gen_boxes(mio_mesh *m, const gen_aabb *add, size_t add_count, const gen_aabb *cut, size_t cut_count, float step);
/* Cylinder of `radius` around the z axis, z from 0 to `height`: `segments`
   around, `stacks` along, each cap `cap_rings` rings (1 = a fan). Closed,
   facing out; 2 segments stacks + 2 segments (2 cap_rings - 1) triangles. */
int gen_cylinder(mio_mesh *m, unsigned segments, unsigned stacks, unsigned cap_rings, float radius, float height);
/* The same tube without its caps: an open pipe facing away from its axis. */
int gen_pipe(mio_mesh *m, unsigned segments, unsigned stacks, float radius, float height);
/* Flat disc of `radius` around the origin at z = 0, facing +z: a fan of
   `segments` triangles for rings = 1, segments (2 rings - 1) in general. */
int gen_disc(mio_mesh *m, unsigned segments, unsigned rings, float radius);
/* Flat rectangle [0, sx] x [0, sy] at z = 0: nx * ny quads facing +z. */
int gen_plane(mio_mesh *m, unsigned nx, unsigned ny, float sx, float sy);
/* Height field over [0, size]^2, n * n quads, facing +z (up): hills of
   amplitude `hills`, and for canyon > 0 a V-shaped valley `canyon` deep
   and 0.12 size wide at the top, meandering along y. */
int gen_terrain(mio_mesh *m, unsigned n, float size, float hills, float canyon);
/* U-channel: an open sheet bent into a U, running along y from 0 to
   `length`: two walls `wall` high above a half circle of `radius` around
   the y axis, open towards +z. `around` segments across the profile,
   `along` along y. Faces away from the side the U encloses. */
int gen_channel(mio_mesh *m, unsigned around, unsigned along, float radius, float wall, float length);
/* L-bracket: a closed solid, a plate [0, width] x [0, length] x [0, thick]
   joined to an upright [0, thick] x [0, length] x [0, height]; facing out,
   edges at most `step` long. */
int gen_bracket(mio_mesh *m, float width, float height, float length, float thick, float step);
typedef enum gen_housing_kind {
    GEN_HOUSING_SEALED,  /* two closed surfaces: the outer box, and the hollow facing into itself */
    GEN_HOUSING_WINDOW,  /* a hole through the +x wall joins them: one closed surface (genus 0, like the cup) */
    GEN_HOUSING_OPEN_TOP /* no top wall: a thick-walled cup, one closed surface of genus 0 */
} gen_housing_kind;
/* Thick-walled housing [0, size[0]] x [0, size[1]] x [0, size[2]], walls
   `wall` thick, facing out of the material (gen_boxes). The window spans
   the middle 40% of the +x wall in y and z. */
int gen_housing(mio_mesh *m, const float size[3], float wall, gen_housing_kind kind, float step);
/* Moves every vertex p to rotation p + offset (rotation row-major). A
   mirroring rotation (negative determinant) also reverses every triangle,
   so the mesh still faces the way it was meant to. */
void gen_transform(mio_mesh *m, const float rotation[9], const float offset[3]);
/* Splits every triangle at its edge midpoints into four: triangle t
   becomes 4t .. 4t + 3, wound as t was. Returns 0 when out of memory
   (the mesh is then unchanged). */
int gen_subdivide(mio_mesh *m);

/* ---- cuts and corruptions that keep the truth ----
   truth (may be NULL): one flag per triangle, 1 when the triangle as it
   now stands faces the intended way. A generated mesh starts all 1. */

/* Splits the model into regions grown over shared edges from `patch_count`
   random seed triangles (a component that no seed reaches becomes one
   more region); every region gets its own copy of its vertices, moved
   `gap` of the way towards the region's centroid, so no index is shared
   across a seam and the seams open into small gaps. Triangles and their
   corners keep their order. patch_of (may be NULL) gets each triangle's
   region. Returns the number of regions; 0 when out of memory or the
   model has no triangle. */
size_t gen_cut(mio_mesh *out, unsigned int *patch_of, const mio_mesh *in, size_t patch_count, float gap,
               unsigned long long seed);
/* The same regions, with seams as real exports have them: every copy of a
   vertex that lies on a seam (its vertex is in two or more regions) moves
   by its own random offset, of length 0.5 to 1 times `jitter` times the
   model's box diagonal, in a uniformly random direction; the seams gap
   and overlap by turns. Other vertices stay. Returns the regions. */
size_t gen_cut_jittered(mio_mesh *out, unsigned int *patch_of, const mio_mesh *in, size_t patch_count, double jitter,
                        unsigned long long seed);
/* Shuffles the triangles and rotates each one's corners (which keeps its
   winding); truth moves with them. from (may be NULL) gets, for each new
   position, the triangle's old index. Returns 0 when out of memory. */
int gen_shuffle(mio_mesh *m, unsigned char *truth, unsigned int *from, unsigned long long seed);
/* Reverses every triangle: the mesh inside out. */
void gen_reverse_all(mio_mesh *m, unsigned char *truth);
/* Reverses each patch whole (patch_of[t] per triangle) with probability p.
   Returns the number of triangles reversed. */
size_t gen_reverse_patches(mio_mesh *m, unsigned char *truth, const unsigned int *patch_of, double p,
                           unsigned long long seed);
/* Reverses each triangle with probability p. Returns how many. */
size_t gen_reverse_random(mio_mesh *m, unsigned char *truth, double p, unsigned long long seed);
#endif

#ifdef MESHGEN_IMPLEMENTATION
#include <math.h>
#include <stdlib.h>
#include <string.h>

static int gen_alloc(mio_mesh *m, size_t vertices, size_t triangles)
{
    memset(m, 0, sizeof(*m));
    m->positions = (float *)malloc(3 * vertices * sizeof(float) + 1);
    m->indices = (unsigned int *)malloc(3 * triangles * sizeof(unsigned int) + 1);
    if (m->positions == NULL || m->indices == NULL) {
        mio_free(m);
        return 0;
    }
    m->vertex_count = vertices;
    m->index_count = 3 * triangles;
    return 1;
}

static void gen_set_vertex(mio_mesh *m, size_t v, float x, float y, float z)
{
    m->positions[3 * v] = x;
    m->positions[3 * v + 1] = y;
    m->positions[3 * v + 2] = z;
}

static void gen_set_triangle(mio_mesh *m, size_t t, unsigned a, unsigned b, unsigned c)
{
    m->indices[3 * t] = a;
    m->indices[3 * t + 1] = b;
    m->indices[3 * t + 2] = c;
}

int gen_sphere(mio_mesh *m, unsigned rings, unsigned segments, float cx, float cy, float cz, float radius)
{
    const double pi = 3.14159265358979323846;
    size_t t = 0;
    unsigned r, s, south;
    if (rings < 2 || segments < 3 || !gen_alloc(m, 2 + (size_t)(rings - 1) * segments, 2 * (size_t)segments * (rings - 1)))
        return 0;
    /* vertex 0 is the north pole, then rings - 1 rings, then the south pole */
    gen_set_vertex(m, 0, cx, cy, cz + radius);
    for (r = 1; r < rings; ++r) {
        double theta = pi * r / rings;
        for (s = 0; s < segments; ++s) {
            double phi = 2 * pi * s / segments;
            gen_set_vertex(m, 1 + (size_t)(r - 1) * segments + s, cx + (float)((double)radius * sin(theta) * cos(phi)),
                           cy + (float)((double)radius * sin(theta) * sin(phi)), cz + (float)((double)radius * cos(theta)));
        }
    }
    south = 1 + (rings - 1) * segments;
    gen_set_vertex(m, south, cx, cy, cz - radius);
    for (s = 0; s < segments; ++s) {
        unsigned s1 = (s + 1) % segments;
        gen_set_triangle(m, t++, 0, 1 + s, 1 + s1);
        for (r = 1; r + 1 < rings; ++r) {
            unsigned a = 1 + (r - 1) * segments + s, b = 1 + (r - 1) * segments + s1;
            unsigned c = a + segments, d = b + segments;
            gen_set_triangle(m, t++, a, c, d);
            gen_set_triangle(m, t++, a, d, b);
        }
        gen_set_triangle(m, t++, south, 1 + (rings - 2) * segments + s1, 1 + (rings - 2) * segments + s);
    }
    return 1;
}

int gen_torus(mio_mesh *m, unsigned n, unsigned k, float major, float minor)
{
    const double pi = 3.14159265358979323846;
    unsigned i, j;
    size_t t = 0;
    if (n < 3 || k < 3 || !gen_alloc(m, (size_t)n * k, 2 * (size_t)n * k))
        return 0;
    for (i = 0; i < n; ++i) {
        double u = 2 * pi * i / n;
        for (j = 0; j < k; ++j) {
            double v = 2 * pi * j / k;
            double ring = (double)major + (double)minor * cos(v);
            gen_set_vertex(m, (size_t)i * k + j, (float)(ring * cos(u)), (float)(ring * sin(u)), (float)((double)minor * sin(v)));
        }
    }
    for (i = 0; i < n; ++i) {
        for (j = 0; j < k; ++j) {
            unsigned a = i * k + j, b = ((i + 1) % n) * k + j;
            unsigned c = ((i + 1) % n) * k + (j + 1) % k, d = i * k + (j + 1) % k;
            gen_set_triangle(m, t++, a, b, c);
            gen_set_triangle(m, t++, a, c, d);
        }
    }
    return 1;
}

int gen_grid(mio_mesh *m, unsigned nx, unsigned ny)
{
    unsigned i, j;
    size_t t = 0;
    if (nx < 1 || ny < 1 || !gen_alloc(m, (size_t)(nx + 1) * (ny + 1), 2 * (size_t)nx * ny))
        return 0;
    for (j = 0; j <= ny; ++j)
        for (i = 0; i <= nx; ++i) {
            float x = (float)i / (float)nx, y = (float)j / (float)ny;
            gen_set_vertex(m, (size_t)j * (nx + 1) + i, x, y, 0.1f * (float)(sin(6.0 * (double)x) * cos(5.0 * (double)y)));
        }
    for (j = 0; j < ny; ++j)
        for (i = 0; i < nx; ++i) {
            unsigned a = j * (nx + 1) + i, b = a + 1, c = a + nx + 2, d = a + nx + 1;
            gen_set_triangle(m, t++, a, b, c);
            gen_set_triangle(m, t++, a, c, d);
        }
    return 1;
}

int gen_mobius(mio_mesh *m, unsigned n)
{
    const double pi = 3.14159265358979323846;
    unsigned i;
    size_t t = 0;
    if (n < 3 || !gen_alloc(m, 2 * (size_t)n, 2 * (size_t)n))
        return 0;
    for (i = 0; i < n; ++i) {
        double u = 2 * pi * i / n, half = u / 2;
        int side;
        for (side = 0; side < 2; ++side) {
            double w = side ? 0.3 : -0.3;
            gen_set_vertex(m, 2 * (size_t)i + (size_t)side, (float)((1 + w * cos(half)) * cos(u)),
                           (float)((1 + w * cos(half)) * sin(u)), (float)(w * sin(half)));
        }
    }
    for (i = 0; i < n; ++i) {
        unsigned a = 2 * i, b = 2 * i + 1, c, d;
        if (i + 1 < n) {
            c = 2 * (i + 1);
            d = 2 * (i + 1) + 1;
        } else { /* the half twist: the strip closes on its other side */
            c = 1;
            d = 0;
        }
        gen_set_triangle(m, t++, a, c, d);
        gen_set_triangle(m, t++, a, d, b);
    }
    return 1;
}

int gen_append(mio_mesh *dst, const mio_mesh *src)
{
    float *p = (float *)realloc(dst->positions, 3 * (dst->vertex_count + src->vertex_count) * sizeof(float) + 1);
    unsigned int *x;
    size_t i;
    if (p == NULL)
        return 0;
    dst->positions = p;
    x = (unsigned int *)realloc(dst->indices, (dst->index_count + src->index_count) * sizeof(unsigned int) + 1);
    if (x == NULL)
        return 0;
    dst->indices = x;
    memcpy(dst->positions + 3 * dst->vertex_count, src->positions, 3 * src->vertex_count * sizeof(float));
    for (i = 0; i < src->index_count; ++i)
        dst->indices[dst->index_count + i] = src->indices[i] + (unsigned int)dst->vertex_count;
    dst->vertex_count += src->vertex_count;
    dst->index_count += src->index_count;
    return 1;
}

int gen_soup(mio_mesh *out, const mio_mesh *src)
{
    size_t i;
    if (!gen_alloc(out, src->index_count, src->index_count / 3))
        return 0;
    for (i = 0; i < src->index_count; ++i) {
        out->indices[i] = (unsigned int)i;
        memcpy(out->positions + 3 * i, src->positions + 3 * (size_t)src->indices[i], 3 * sizeof(float));
    }
    return 1;
}

unsigned long long gen_random(unsigned long long *state)
{
    unsigned long long z = (*state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

double gen_uniform(unsigned long long *state)
{
    return (double)(gen_random(state) >> 11) * (1.0 / 9007199254740992.0);
}

size_t gen_flip_random(mio_mesh *m, double fraction, unsigned long long seed, unsigned char *marks)
{
    size_t t, count = 0;
    for (t = 0; t < m->index_count / 3; ++t) {
        int flip = gen_uniform(&seed) < fraction;
        if (flip) {
            unsigned int x = m->indices[3 * t + 1];
            m->indices[3 * t + 1] = m->indices[3 * t + 2];
            m->indices[3 * t + 2] = x;
            count++;
        }
        if (marks != NULL)
            marks[t] = (unsigned char)flip;
    }
    return count;
}

/* ---- shared helpers of the part generators ---- */

#define GEN_NONE 0xFFFFFFFFu

static void gen_reverse_triangle(mio_mesh *m, size_t t)
{
    unsigned int x = m->indices[3 * t + 1];
    m->indices[3 * t + 1] = m->indices[3 * t + 2];
    m->indices[3 * t + 2] = x;
}

/* Open-addressing map from 64-bit keys (never ~0) to vertex numbers. */
typedef struct gen_map {
    unsigned long long *keys;
    unsigned int *values;
    unsigned shift; /* 64 - log2(capacity) */
} gen_map;

static int gen_map_init(gen_map *map, size_t entries)
{
    size_t capacity = 16, i;
    map->shift = 60;
    while (capacity < 2 * entries + 1) {
        capacity *= 2;
        map->shift--;
    }
    map->keys = (unsigned long long *)malloc(capacity * sizeof(unsigned long long));
    map->values = (unsigned int *)malloc(capacity * sizeof(unsigned int));
    if (map->keys == NULL || map->values == NULL) {
        free(map->keys);
        free(map->values);
        return 0;
    }
    for (i = 0; i < capacity; ++i)
        map->keys[i] = ~0ull;
    return 1;
}

static void gen_map_free(gen_map *map)
{
    free(map->keys);
    free(map->values);
}

/* The value slot of `key`; a new key gets the value GEN_NONE. */
static unsigned int *gen_map_slot(gen_map *map, unsigned long long key)
{
    size_t mask = ((size_t)1 << (64 - map->shift)) - 1;
    size_t i = (size_t)((key * 0x9E3779B97F4A7C15ull) >> map->shift);
    while (map->keys[i] != key && map->keys[i] != ~0ull)
        i = (i + 1) & mask;
    if (map->keys[i] != key) {
        map->keys[i] = key;
        map->values[i] = GEN_NONE;
    }
    return &map->values[i];
}

static unsigned long long gen_edge_key(unsigned int a, unsigned int b)
{
    return a < b ? ((unsigned long long)a << 32) | b : ((unsigned long long)b << 32) | a;
}

/* ---- boxes: the faces of a solid made of grid cells ---- */

/* A rectilinear grid: corners axis[a][0 .. n[a]]; cell (i, j, k) is
   material when solid[i + n[0] (j + n[1] k)] != 0. */
typedef struct gen_lattice {
    float *axis[3];
    unsigned n[3];
    unsigned char *solid;
} gen_lattice;

static int gen_lattice_solid(const gen_lattice *g, const long c[3])
{
    int a;
    for (a = 0; a < 3; ++a)
        if (c[a] < 0 || c[a] >= (long)g->n[a])
            return 0;
    return g->solid[(size_t)c[0] + g->n[0] * ((size_t)c[1] + g->n[1] * (size_t)c[2])];
}

static size_t gen_lattice_corner(const gen_lattice *g, const long p[3])
{
    return (size_t)p[0] + (g->n[0] + 1) * ((size_t)p[1] + (g->n[1] + 1) * (size_t)p[2]);
}

/* Visits every face between material and non-material. With out == NULL
   it marks the faces' corners in vertex_of (0 = used); with out it writes
   the faces' triangles, vertex_of then holding vertex numbers. Returns the
   number of faces. */
static size_t gen_lattice_faces(const gen_lattice *g, unsigned int *vertex_of, mio_mesh *out)
{
    size_t faces = 0;
    long c[3];
    for (c[2] = 0; c[2] < (long)g->n[2]; ++c[2])
        for (c[1] = 0; c[1] < (long)g->n[1]; ++c[1])
            for (c[0] = 0; c[0] < (long)g->n[0]; ++c[0]) {
                int direction;
                if (!gen_lattice_solid(g, c))
                    continue;
                for (direction = 0; direction < 6; ++direction) {
                    /* normal +a (side 1) or -a (side 0); u x v = a, so corners
                       counter-clockwise in (u, v) face +a */
                    int a = direction / 2, side = direction % 2, u = (a + 1) % 3, v = (a + 2) % 3, k;
                    static const int du[4] = {0, 1, 1, 0}, dv[4] = {0, 0, 1, 1};
                    long next[3], p[3];
                    size_t corner[4];
                    memcpy(next, c, sizeof(next));
                    next[a] += side ? 1 : -1;
                    if (gen_lattice_solid(g, next))
                        continue;
                    for (k = 0; k < 4; ++k) {
                        int q = side ? k : 3 - k;
                        p[a] = c[a] + side;
                        p[u] = c[u] + du[q];
                        p[v] = c[v] + dv[q];
                        corner[k] = gen_lattice_corner(g, p);
                        if (out == NULL)
                            vertex_of[corner[k]] = 0;
                    }
                    if (out != NULL) {
                        gen_set_triangle(out, 2 * faces, vertex_of[corner[0]], vertex_of[corner[1]], vertex_of[corner[2]]);
                        gen_set_triangle(out, 2 * faces + 1, vertex_of[corner[0]], vertex_of[corner[2]], vertex_of[corner[3]]);
                    }
                    faces++;
                }
            }
    return faces;
}

/* The surface of the lattice's material, facing out of it. */
static int gen_lattice_surface(mio_mesh *m, const gen_lattice *g)
{
    size_t corners = (size_t)(g->n[0] + 1) * (g->n[1] + 1) * (g->n[2] + 1), i, faces, used = 0;
    unsigned int *vertex_of = (unsigned int *)malloc(corners * sizeof(unsigned int));
    memset(m, 0, sizeof(*m));
    if (vertex_of == NULL)
        return 0;
    for (i = 0; i < corners; ++i)
        vertex_of[i] = GEN_NONE;
    faces = gen_lattice_faces(g, vertex_of, NULL);
    for (i = 0; i < corners; ++i)
        if (vertex_of[i] != GEN_NONE)
            vertex_of[i] = (unsigned int)used++;
    if (!gen_alloc(m, used, 2 * faces)) {
        free(vertex_of);
        return 0;
    }
    for (i = 0; i < corners; ++i)
        if (vertex_of[i] != GEN_NONE) {
            size_t x = i % (g->n[0] + 1), y = i / (g->n[0] + 1) % (g->n[1] + 1), z = i / (g->n[0] + 1) / (g->n[1] + 1);
            gen_set_vertex(m, vertex_of[i], g->axis[0][x], g->axis[1][y], g->axis[2][z]);
        }
    gen_lattice_faces(g, vertex_of, m);
    free(vertex_of);
    return 1;
}

static int gen_compare_float(const void *a, const void *b)
{
    float x = *(const float *)a, y = *(const float *)b;
    return x < y ? -1 : x > y;
}

/* Grid corners along one axis through every value of `breaks` (sorted in
   place, duplicates dropped), each interval cut into `parts` equal parts,
   or when parts == 0 into as few as keep them at most `step` long. The
   break values themselves are kept exactly, so faces of different boxes
   on one plane share their corners. */
static size_t gen_axis_parts(float low, float high, float step, unsigned parts)
{
    return parts ? parts : (size_t)ceil(((double)high - (double)low) / (double)step);
}

static float *gen_axis(float *breaks, size_t count, float step, unsigned parts, unsigned *cells)
{
    size_t i, kept = 0, total = 0;
    float *axis;
    qsort(breaks, count, sizeof(float), gen_compare_float);
    for (i = 0; i < count; ++i)
        if (kept == 0 || breaks[i] > breaks[kept - 1])
            breaks[kept++] = breaks[i];
    for (i = 0; i + 1 < kept; ++i)
        total += gen_axis_parts(breaks[i], breaks[i + 1], step, parts);
    axis = (float *)malloc((total + 1) * sizeof(float));
    if (axis == NULL || kept < 2 || total > 0x7FFFFFFFu) {
        free(axis);
        return NULL;
    }
    total = 0;
    for (i = 0; i + 1 < kept; ++i) {
        double low = breaks[i], high = breaks[i + 1];
        size_t n = gen_axis_parts(breaks[i], breaks[i + 1], step, parts), k;
        for (k = 0; k < n; ++k)
            axis[total++] = (float)(low + (high - low) * (double)k / (double)n);
    }
    axis[total] = breaks[kept - 1];
    *cells = (unsigned)total;
    return axis;
}

static int gen_inside(const gen_aabb *boxes, size_t count, const double p[3])
{
    size_t b;
    int a;
    for (b = 0; b < count; ++b) {
        for (a = 0; a < 3; ++a)
            if (!(p[a] > (double)boxes[b].lo[a] && p[a] < (double)boxes[b].hi[a]))
                break;
        if (a == 3)
            return 1;
    }
    return 0;
}

/* gen_boxes with a given number of parts per interval (0: by step). */
static int gen_boxes_parts(mio_mesh *m, const gen_aabb *add, size_t add_count, const gen_aabb *cut, size_t cut_count,
                           float step, unsigned parts)
{
    gen_lattice g;
    size_t count = 2 * (add_count + cut_count), b, i, j, k, cells;
    float *breaks = (float *)malloc(count * sizeof(float) + 1);
    int a, ok = 0;
    memset(&g, 0, sizeof(g));
    memset(m, 0, sizeof(*m));
    if (breaks == NULL || add_count == 0 || (parts == 0 && !(step > 0)))
        goto done;
    for (a = 0; a < 3; ++a) {
        for (b = 0; b < add_count; ++b)
            breaks[2 * b] = add[b].lo[a], breaks[2 * b + 1] = add[b].hi[a];
        for (b = 0; b < cut_count; ++b)
            breaks[2 * (add_count + b)] = cut[b].lo[a], breaks[2 * (add_count + b) + 1] = cut[b].hi[a];
        if ((g.axis[a] = gen_axis(breaks, count, step, parts, &g.n[a])) == NULL)
            goto done;
    }
    cells = (size_t)g.n[0] * g.n[1] * g.n[2];
    if ((g.solid = (unsigned char *)malloc(cells)) == NULL)
        goto done;
    for (k = 0; k < g.n[2]; ++k)
        for (j = 0; j < g.n[1]; ++j)
            for (i = 0; i < g.n[0]; ++i) {
                double centre[3];
                centre[0] = 0.5 * ((double)g.axis[0][i] + (double)g.axis[0][i + 1]);
                centre[1] = 0.5 * ((double)g.axis[1][j] + (double)g.axis[1][j + 1]);
                centre[2] = 0.5 * ((double)g.axis[2][k] + (double)g.axis[2][k + 1]);
                g.solid[i + g.n[0] * (j + g.n[1] * k)] =
                    (unsigned char)(gen_inside(add, add_count, centre) && !gen_inside(cut, cut_count, centre));
            }
    ok = gen_lattice_surface(m, &g);
done:
    for (a = 0; a < 3; ++a)
        free(g.axis[a]);
    free(g.solid);
    free(breaks);
    return ok;
}

int gen_boxes(mio_mesh *m, const gen_aabb *add, size_t add_count, const gen_aabb *cut, size_t cut_count, float step)
{
    return gen_boxes_parts(m, add, add_count, cut, cut_count, step, 0);
}

int gen_box(mio_mesh *m, unsigned n, const float lo[3], const float hi[3])
{
    gen_aabb box;
    memcpy(box.lo, lo, sizeof(box.lo));
    memcpy(box.hi, hi, sizeof(box.hi));
    if (n < 1) {
        memset(m, 0, sizeof(*m));
        return 0;
    }
    return gen_boxes_parts(m, &box, 1, NULL, 0, 0, n);
}

static gen_aabb gen_make_aabb(float x0, float y0, float z0, float x1, float y1, float z1)
{
    gen_aabb b;
    b.lo[0] = x0, b.lo[1] = y0, b.lo[2] = z0;
    b.hi[0] = x1, b.hi[1] = y1, b.hi[2] = z1;
    return b;
}

int gen_bracket(mio_mesh *m, float width, float height, float length, float thick, float step)
{
    gen_aabb add[2];
    add[0] = gen_make_aabb(0, 0, 0, width, length, thick);
    add[1] = gen_make_aabb(0, 0, 0, thick, length, height);
    return gen_boxes(m, add, 2, NULL, 0, step);
}

int gen_housing(mio_mesh *m, const float size[3], float wall, gen_housing_kind kind, float step)
{
    gen_aabb outer = gen_make_aabb(0, 0, 0, size[0], size[1], size[2]), cut[2];
    size_t cuts = 1;
    /* OPEN_TOP: the hollow reaches the top face, which removes the top wall */
    cut[0] = gen_make_aabb(wall, wall, wall, size[0] - wall, size[1] - wall,
                           kind == GEN_HOUSING_OPEN_TOP ? size[2] : size[2] - wall);
    if (kind == GEN_HOUSING_WINDOW)
        cut[cuts++] = gen_make_aabb(size[0] - wall, 0.3f * size[1], 0.3f * size[2], size[0], 0.7f * size[1], 0.7f * size[2]);
    return gen_boxes(m, &outer, 1, cut, cuts, step);
}

/* ---- tubes and discs ---- */

/* The triangles of a disc facing +z (up) or -z: a fan from `centre` to
   the innermost ring, then bands between rings. Ring r (0 innermost,
   rings - 1 the rim) has `segments` vertices counter-clockwise from +z;
   the inner rings follow each other from inner_first, the rim starts at
   rim_first. Returns the next triangle. */
static size_t gen_disc_triangles(mio_mesh *m, size_t t, unsigned centre, unsigned inner_first, unsigned rim_first,
                                 unsigned rings, unsigned segments, int up)
{
    unsigned r, i;
    for (i = 0; i < segments; ++i) {
        unsigned first = rings > 1 ? inner_first : rim_first, a = first + i, b = first + (i + 1) % segments;
        if (up)
            gen_set_triangle(m, t++, centre, a, b);
        else
            gen_set_triangle(m, t++, centre, b, a);
    }
    for (r = 0; r + 1 < rings; ++r) {
        unsigned in = inner_first + r * segments, out = r + 2 < rings ? in + segments : rim_first;
        for (i = 0; i < segments; ++i) {
            unsigned a = in + i, b = in + (i + 1) % segments, c = out + (i + 1) % segments, d = out + i;
            if (up) {
                gen_set_triangle(m, t++, a, d, c);
                gen_set_triangle(m, t++, a, c, b);
            } else {
                gen_set_triangle(m, t++, a, c, d);
                gen_set_triangle(m, t++, a, b, c);
            }
        }
    }
    return t;
}

/* Ring of `segments` vertices from vertex v: radius r at height z. */
static void gen_ring(mio_mesh *m, size_t v, unsigned segments, double radius, float z)
{
    const double pi = 3.14159265358979323846;
    unsigned i;
    for (i = 0; i < segments; ++i) {
        double phi = 2 * pi * i / segments;
        gen_set_vertex(m, v + i, (float)(radius * cos(phi)), (float)(radius * sin(phi)), z);
    }
}

/* Cap `rings` of a tube end at height z: its centre at vertex `centre`,
   its inner rings after it; the rim is the tube's own ring. */
static void gen_cap_vertices(mio_mesh *m, size_t centre, unsigned segments, unsigned rings, double radius, float z)
{
    unsigned r;
    gen_set_vertex(m, centre, 0, 0, z);
    for (r = 1; r < rings; ++r)
        gen_ring(m, centre + 1 + (size_t)(r - 1) * segments, segments, radius * r / rings, z);
}

/* Cylinder side facing away from the axis, plus two caps unless cap_rings is 0. */
static int gen_tube(mio_mesh *m, unsigned segments, unsigned stacks, unsigned cap_rings, float radius, float height)
{
    size_t side = (size_t)(stacks + 1) * segments, cap = cap_rings ? 1 + (size_t)(cap_rings - 1) * segments : 0, t = 0;
    unsigned s, i;
    if (segments < 3 || stacks < 1 ||
        !gen_alloc(m, side + 2 * cap, 2 * (size_t)segments * stacks + (cap_rings ? 2 * (size_t)segments * (2 * cap_rings - 1) : 0)))
        return 0;
    for (s = 0; s <= stacks; ++s)
        gen_ring(m, (size_t)s * segments, segments, radius, (float)((double)height * s / stacks));
    for (s = 0; s < stacks; ++s)
        for (i = 0; i < segments; ++i) {
            /* a -> b runs counter-clockwise, b -> c up: the normal points away from the axis */
            unsigned a = s * segments + i, b = s * segments + (i + 1) % segments, c = b + segments, d = a + segments;
            gen_set_triangle(m, t++, a, b, c);
            gen_set_triangle(m, t++, a, c, d);
        }
    if (cap_rings) {
        gen_cap_vertices(m, side, segments, cap_rings, radius, 0);
        gen_cap_vertices(m, side + cap, segments, cap_rings, radius, height);
        t = gen_disc_triangles(m, t, (unsigned)side, (unsigned)side + 1, 0, cap_rings, segments, 0);
        gen_disc_triangles(m, t, (unsigned)(side + cap), (unsigned)(side + cap) + 1, stacks * segments, cap_rings, segments, 1);
    }
    return 1;
}

int gen_cylinder(mio_mesh *m, unsigned segments, unsigned stacks, unsigned cap_rings, float radius, float height)
{
    if (cap_rings < 1) {
        memset(m, 0, sizeof(*m));
        return 0;
    }
    return gen_tube(m, segments, stacks, cap_rings, radius, height);
}

int gen_pipe(mio_mesh *m, unsigned segments, unsigned stacks, float radius, float height)
{
    return gen_tube(m, segments, stacks, 0, radius, height);
}

int gen_disc(mio_mesh *m, unsigned segments, unsigned rings, float radius)
{
    if (segments < 3 || rings < 1 || !gen_alloc(m, 1 + (size_t)rings * segments, (size_t)segments * (2 * rings - 1)))
        return 0;
    gen_cap_vertices(m, 0, segments, rings, radius, 0);
    gen_ring(m, 1 + (size_t)(rings - 1) * segments, segments, radius, 0);
    gen_disc_triangles(m, 0, 0, 1, 1 + (rings - 1) * segments, rings, segments, 1);
    return 1;
}

/* ---- height fields ---- */

/* Height of the terrain at (x, y) in [0, size]^2. */
static double gen_relief(double x, double y, double size, double hills, double canyon)
{
    const double pi = 3.14159265358979323846;
    double u = x / size, w = y / size, z, middle, depth;
    z = hills * (0.6 * sin(2 * pi * 1.3 * u + 0.4) * cos(2 * pi * 0.9 * w) + 0.4 * sin(2 * pi * 2.7 * u) * sin(2 * pi * 2.1 * w + 1.1));
    if (canyon > 0) {
        middle = 0.5 + 0.08 * sin(2 * pi * w);         /* the valley's floor meanders */
        depth = 1 - fabs(u - middle) / 0.06;           /* 1 on the floor, 0 at the rims */
        z -= depth > 0 ? canyon * depth : 0;
    }
    return z;
}

/* nx * ny quads over [0, sx] x [0, sy], heights from gen_relief (flat when
   hills and canyon are 0), facing +z. */
static int gen_field(mio_mesh *m, unsigned nx, unsigned ny, float sx, float sy, float hills, float canyon)
{
    unsigned i, j;
    size_t t = 0;
    if (nx < 1 || ny < 1 || !gen_alloc(m, (size_t)(nx + 1) * (ny + 1), 2 * (size_t)nx * ny))
        return 0;
    for (j = 0; j <= ny; ++j)
        for (i = 0; i <= nx; ++i) {
            double x = (double)sx * i / nx, y = (double)sy * j / ny;
            gen_set_vertex(m, (size_t)j * (nx + 1) + i, (float)x, (float)y, (float)gen_relief(x, y, (double)sx, (double)hills, (double)canyon));
        }
    for (j = 0; j < ny; ++j)
        for (i = 0; i < nx; ++i) {
            unsigned a = j * (nx + 1) + i, b = a + 1, c = a + nx + 2, d = a + nx + 1;
            gen_set_triangle(m, t++, a, b, c);
            gen_set_triangle(m, t++, a, c, d);
        }
    return 1;
}

int gen_plane(mio_mesh *m, unsigned nx, unsigned ny, float sx, float sy)
{
    return gen_field(m, nx, ny, sx, sy, 0, 0);
}

int gen_terrain(mio_mesh *m, unsigned n, float size, float hills, float canyon)
{
    return gen_field(m, n, n, size, size, hills, canyon);
}

/* ---- the U-channel ---- */

/* Point s of `around` + 1 on the U's profile in the xz plane, from the top
   of the left wall (-radius, wall) down, round the bottom, up to the top
   of the right wall; `walls` segments on each wall. */
static void gen_profile(unsigned s, unsigned around, unsigned walls, double radius, double wall, double *x, double *z)
{
    const double pi = 3.14159265358979323846;
    unsigned arc = around - 2 * walls;
    if (s < walls) {
        *x = -radius, *z = wall * (walls - s) / walls;
    } else if (s <= walls + arc) {
        double angle = pi + pi * (s - walls) / arc;
        *x = radius * cos(angle), *z = radius * sin(angle);
    } else {
        *x = radius, *z = wall * (s - walls - arc) / walls;
    }
}

int gen_channel(mio_mesh *m, unsigned around, unsigned along, float radius, float wall, float length)
{
    const double pi = 3.14159265358979323846;
    double total = 2 * (double)wall + pi * (double)radius;
    unsigned walls = wall > 0 ? (unsigned)floor(around * (double)wall / total + 0.5) : 0, s, j;
    size_t t = 0;
    if (wall > 0 && walls < 1)
        walls = 1;
    if (around < 2 * walls + 2 || along < 1 || !gen_alloc(m, (size_t)(around + 1) * (along + 1), 2 * (size_t)around * along))
        return 0;
    for (j = 0; j <= along; ++j)
        for (s = 0; s <= around; ++s) {
            double x, z;
            gen_profile(s, around, walls, (double)radius, (double)wall, &x, &z);
            gen_set_vertex(m, (size_t)j * (around + 1) + s, (float)x, (float)((double)length * j / along), (float)z);
        }
    for (j = 0; j < along; ++j)
        for (s = 0; s < around; ++s) {
            /* a -> b runs along +y, a -> d along the profile: their cross
               product points away from the enclosed side */
            unsigned a = j * (around + 1) + s, b = a + around + 1, c = b + 1, d = a + 1;
            gen_set_triangle(m, t++, a, b, c);
            gen_set_triangle(m, t++, a, c, d);
        }
    return 1;
}

/* ---- placing and refining ---- */

void gen_transform(mio_mesh *m, const float rotation[9], const float offset[3])
{
    const float *r = rotation;
    double d[9], det;
    size_t v, t;
    int k;
    for (k = 0; k < 9; ++k)
        d[k] = (double)r[k];
    det = d[0] * (d[4] * d[8] - d[5] * d[7]) - d[1] * (d[3] * d[8] - d[5] * d[6]) + d[2] * (d[3] * d[7] - d[4] * d[6]);
    for (v = 0; v < m->vertex_count; ++v) {
        float *p = m->positions + 3 * v, q[3];
        for (k = 0; k < 3; ++k)
            q[k] = r[3 * k] * p[0] + r[3 * k + 1] * p[1] + r[3 * k + 2] * p[2] + offset[k];
        memcpy(p, q, sizeof(q));
    }
    if (det < 0)
        for (t = 0; t < m->index_count / 3; ++t)
            gen_reverse_triangle(m, t);
}

int gen_subdivide(mio_mesh *m)
{
    size_t triangles = m->index_count / 3, t, vertices = m->vertex_count;
    unsigned int *indices = (unsigned int *)malloc(4 * m->index_count * sizeof(unsigned int) + 1), mid[3];
    float *positions;
    gen_map edges;
    unsigned e;
    if (indices == NULL || !gen_map_init(&edges, m->index_count)) {
        free(indices);
        return 0;
    }
    for (t = 0; t < triangles; ++t) /* number the midpoints in order of first use */
        for (e = 0; e < 3; ++e) {
            unsigned int *slot = gen_map_slot(&edges, gen_edge_key(m->indices[3 * t + e], m->indices[3 * t + (e + 1) % 3]));
            if (*slot == GEN_NONE)
                *slot = (unsigned int)vertices++;
        }
    positions = (float *)realloc(m->positions, 3 * vertices * sizeof(float) + 1);
    if (positions == NULL) {
        free(indices);
        gen_map_free(&edges);
        return 0;
    }
    m->positions = positions;
    for (t = 0; t < triangles; ++t) {
        const unsigned int *v = m->indices + 3 * t;
        unsigned int *out = indices + 12 * t;
        for (e = 0; e < 3; ++e) {
            const float *a = positions + 3 * (size_t)v[e], *b = positions + 3 * (size_t)v[(e + 1) % 3];
            mid[e] = *gen_map_slot(&edges, gen_edge_key(v[e], v[(e + 1) % 3]));
            gen_set_vertex(m, mid[e], 0.5f * (a[0] + b[0]), 0.5f * (a[1] + b[1]), 0.5f * (a[2] + b[2]));
        }
        /* corners first, the middle last; each wound as the original */
        out[0] = v[0], out[1] = mid[0], out[2] = mid[2];
        out[3] = mid[0], out[4] = v[1], out[5] = mid[1];
        out[6] = mid[2], out[7] = mid[1], out[8] = v[2];
        out[9] = mid[0], out[10] = mid[1], out[11] = mid[2];
    }
    gen_map_free(&edges);
    free(m->indices);
    m->indices = indices;
    m->index_count *= 4;
    m->vertex_count = vertices;
    return 1;
}

/* ---- cutting into unwelded patches ---- */

/* Breadth-first growth from the triangles in queue[head .. tail): each
   takes its unclaimed neighbours (over any shared edge) into its region.
   edge_first maps an edge to its first corner slot (3 t + e), next_slot
   chains the other slots of the same edge. Returns the new tail. */
static size_t gen_grow(const mio_mesh *m, gen_map *edge_first, const unsigned int *next_slot, unsigned int *region,
                       unsigned int *queue, size_t head, size_t tail)
{
    while (head < tail) {
        unsigned int t = queue[head++], s;
        unsigned e;
        for (e = 0; e < 3; ++e) {
            unsigned long long key = gen_edge_key(m->indices[3 * (size_t)t + e], m->indices[3 * (size_t)t + (e + 1) % 3]);
            for (s = *gen_map_slot(edge_first, key); s != GEN_NONE; s = next_slot[s])
                if (region[s / 3] == GEN_NONE) {
                    region[s / 3] = region[t];
                    queue[tail++] = s / 3;
                }
        }
    }
    return tail;
}

/* Regions grown from `count` random seeds, then from each triangle no seed
   reached. Returns the number of regions, 0 when out of memory. */
static size_t gen_regions(const mio_mesh *m, size_t count, unsigned long long seed, unsigned int *region)
{
    size_t triangles = m->index_count / 3, t, i, tail = 0, head = 0, regions = 0;
    unsigned int *next_slot = (unsigned int *)malloc(m->index_count * sizeof(unsigned int) + 1);
    unsigned int *queue = (unsigned int *)malloc(triangles * sizeof(unsigned int) + 1);
    gen_map edge_first;
    if (triangles == 0 || next_slot == NULL || queue == NULL || !gen_map_init(&edge_first, m->index_count)) {
        free(next_slot);
        free(queue);
        return 0;
    }
    for (i = 0; i < m->index_count; ++i) {
        unsigned int *first = gen_map_slot(&edge_first, gen_edge_key(m->indices[i], m->indices[i - i % 3 + (i + 1) % 3]));
        next_slot[i] = *first;
        *first = (unsigned int)i;
    }
    for (t = 0; t < triangles; ++t)
        region[t] = GEN_NONE;
    for (i = 0; i < count && triangles > 0; ++i) {
        t = (size_t)(gen_random(&seed) % triangles);
        if (region[t] == GEN_NONE) {
            region[t] = (unsigned int)regions++;
            queue[tail++] = (unsigned int)t;
        }
    }
    tail = gen_grow(m, &edge_first, next_slot, region, queue, head, tail);
    for (t = 0; t < triangles; ++t)
        if (region[t] == GEN_NONE) {
            head = tail;
            region[t] = (unsigned int)regions++;
            queue[tail++] = (unsigned int)t;
            tail = gen_grow(m, &edge_first, next_slot, region, queue, head, tail);
        }
    gen_map_free(&edge_first);
    free(next_slot);
    free(queue);
    return regions;
}

static size_t gen_cut_regions(mio_mesh *out, unsigned int *patch_of, const mio_mesh *in, size_t patch_count, float gap,
                              double jitter, unsigned long long seed);

size_t gen_cut(mio_mesh *out, unsigned int *patch_of, const mio_mesh *in, size_t patch_count, float gap,
               unsigned long long seed)
{
    return gen_cut_regions(out, patch_of, in, patch_count, gap, 0.0, seed);
}

size_t gen_cut_jittered(mio_mesh *out, unsigned int *patch_of, const mio_mesh *in, size_t patch_count, double jitter,
                        unsigned long long seed)
{
    return gen_cut_regions(out, patch_of, in, patch_count, 0.0f, jitter, seed);
}

/* A point uniformly in a ball shell: direction uniform, length in [0.5, 1). */
static void gen_offset(unsigned long long *state, double length, double out[3])
{
    double z = 2.0 * gen_uniform(state) - 1.0, a = 2.0 * 3.14159265358979323846 * gen_uniform(state);
    double r = sqrt(1.0 - z * z), l = length * (0.5 + 0.5 * gen_uniform(state));
    out[0] = l * r * cos(a), out[1] = l * r * sin(a), out[2] = l * z;
}

static size_t gen_cut_regions(mio_mesh *out, unsigned int *patch_of, const mio_mesh *in, size_t patch_count, float gap,
                              double jitter, unsigned long long seed)
{
    size_t triangles = in->index_count / 3, regions = 0, i, used = 0;
    unsigned int *first_region = NULL;
    unsigned char *on_seam = NULL;
    double diagonal = 0.0, lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
    unsigned long long state = seed ^ 0x9E3779B97F4A7C15ull;
    unsigned int *region = (unsigned int *)malloc(triangles * sizeof(unsigned int) + 1);
    double *centroid = NULL;
    gen_map copies;
    size_t k;
    memset(out, 0, sizeof(*out));
    copies.keys = NULL, copies.values = NULL;
    if (region == NULL || (regions = gen_regions(in, patch_count, seed, region)) == 0 ||
        (centroid = (double *)calloc(4 * regions, sizeof(double))) == NULL || !gen_map_init(&copies, in->index_count) ||
        !gen_alloc(out, in->index_count, triangles)) {
        regions = 0;
        goto done;
    }
    /* centroid of a region: the mean of its triangles' corners */
    for (i = 0; i < in->index_count; ++i) {
        double *c = centroid + 4 * region[i / 3];
        for (k = 0; k < 3; ++k)
            c[k] += (double)in->positions[3 * (size_t)in->indices[i] + k];
        c[3] += 1;
    }
    if (jitter > 0) { /* which vertices are on a seam, and the model's size */
        first_region = (unsigned int *)malloc(in->vertex_count * sizeof(unsigned int) + 1);
        on_seam = (unsigned char *)calloc(in->vertex_count + 1, 1);
        if (first_region == NULL || on_seam == NULL) {
            regions = 0;
            goto done;
        }
        for (i = 0; i < in->vertex_count; ++i)
            first_region[i] = GEN_NONE;
        for (i = 0; i < in->index_count; ++i) {
            unsigned int v = in->indices[i];
            if (first_region[v] == GEN_NONE)
                first_region[v] = region[i / 3];
            else if (first_region[v] != region[i / 3])
                on_seam[v] = 1;
            for (k = 0; k < 3; ++k) {
                double p = (double)in->positions[3 * (size_t)v + k];
                lo[k] = p < lo[k] ? p : lo[k];
                hi[k] = p > hi[k] ? p : hi[k];
            }
        }
        for (k = 0; k < 3; ++k)
            diagonal += (hi[k] - lo[k]) * (hi[k] - lo[k]);
        diagonal = sqrt(diagonal);
    }
    for (i = 0; i < in->index_count; ++i) {
        unsigned int r = region[i / 3], v = in->indices[i];
        unsigned int *copy = gen_map_slot(&copies, ((unsigned long long)r << 32) | v);
        if (*copy == GEN_NONE) {
            const double *c = centroid + 4 * (size_t)r;
            double offset[3] = {0, 0, 0};
            if (on_seam != NULL && on_seam[v])
                gen_offset(&state, jitter * diagonal, offset);
            *copy = (unsigned int)used;
            for (k = 0; k < 3; ++k) {
                double p = (double)in->positions[3 * (size_t)v + k];
                out->positions[3 * used + k] = (float)(p + (c[k] / c[3] - p) * (double)gap + offset[k]);
            }
            used++;
        }
        out->indices[i] = *copy;
    }
    out->vertex_count = used;
    if (patch_of != NULL)
        memcpy(patch_of, region, triangles * sizeof(unsigned int));
done:
    if (regions == 0)
        mio_free(out);
    gen_map_free(&copies);
    free(centroid);
    free(region);
    free(first_region);
    free(on_seam);
    return regions;
}

/* ---- corruptions ---- */

int gen_shuffle(mio_mesh *m, unsigned char *truth, unsigned int *from, unsigned long long seed)
{
    size_t triangles = m->index_count / 3, t;
    unsigned int *order = from != NULL ? from : (unsigned int *)malloc(triangles * sizeof(unsigned int) + 1);
    unsigned int *old = (unsigned int *)malloc(m->index_count * sizeof(unsigned int) + 1);
    unsigned char *old_truth = (unsigned char *)malloc(triangles + 1);
    int ok = order != NULL && old != NULL && old_truth != NULL;
    if (ok) {
        for (t = 0; t < triangles; ++t)
            order[t] = (unsigned int)t;
        for (t = triangles; t > 1; --t) { /* Fisher-Yates */
            size_t j = (size_t)(gen_random(&seed) % t);
            unsigned int x = order[t - 1];
            order[t - 1] = order[j];
            order[j] = x;
        }
        memcpy(old, m->indices, m->index_count * sizeof(unsigned int));
        if (truth != NULL)
            memcpy(old_truth, truth, triangles);
        for (t = 0; t < triangles; ++t) {
            size_t o = order[t], turn = (size_t)(gen_random(&seed) % 3), k;
            for (k = 0; k < 3; ++k) /* a rotation of the corners keeps the winding */
                m->indices[3 * t + k] = old[3 * o + (k + turn) % 3];
            if (truth != NULL)
                truth[t] = old_truth[o];
        }
    }
    if (order != from)
        free(order);
    free(old);
    free(old_truth);
    return ok;
}

void gen_reverse_all(mio_mesh *m, unsigned char *truth)
{
    size_t t;
    for (t = 0; t < m->index_count / 3; ++t) {
        gen_reverse_triangle(m, t);
        if (truth != NULL)
            truth[t] ^= 1;
    }
}

size_t gen_reverse_patches(mio_mesh *m, unsigned char *truth, const unsigned int *patch_of, double p,
                           unsigned long long seed)
{
    size_t t, count = 0;
    for (t = 0; t < m->index_count / 3; ++t) {
        /* each patch draws from its own stream: the same coin for all its triangles */
        unsigned long long state = seed ^ ((unsigned long long)patch_of[t] * 0xD1B54A32D192ED03ull);
        if (gen_uniform(&state) < p) {
            gen_reverse_triangle(m, t);
            if (truth != NULL)
                truth[t] ^= 1;
            count++;
        }
    }
    return count;
}

size_t gen_reverse_random(mio_mesh *m, unsigned char *truth, double p, unsigned long long seed)
{
    size_t t, count = 0;
    for (t = 0; t < m->index_count / 3; ++t)
        if (gen_uniform(&seed) < p) {
            gen_reverse_triangle(m, t);
            if (truth != NULL)
                truth[t] ^= 1;
            count++;
        }
    return count;
}
#endif /* MESHGEN_IMPLEMENTATION */
