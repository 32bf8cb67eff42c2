/* meshgen.h - procedural test meshes for the meshfix examples, tests and benchmark

   Every generator fills a mio_mesh (free it with mio_free) and winds its
   triangles counter-clockwise seen from outside (or from +z for sheets).
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
/* Reverses each triangle with probability `fraction`; marks[t] = 1 for the
   reversed ones when marks is not NULL. Returns how many were reversed. */
size_t gen_flip_random(mio_mesh *m, double fraction, unsigned long long seed, unsigned char *marks);
/* Small deterministic generator (splitmix64). */
unsigned long long gen_random(unsigned long long *state);
double gen_uniform(unsigned long long *state);
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
#endif /* MESHGEN_IMPLEMENTATION */
