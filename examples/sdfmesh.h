/* sdfmesh.h - a small marching-tetrahedra mesher and six signed distance
   functions, for the meshfix SDF example, tests and benchmark.

   sdfmesh_tetra() samples f on a grid of cubes, splits every cube into six
   tetrahedra around its main diagonal (the same split in every cube, so
   neighbours share faces exactly), and puts a vertex where f changes sign
   along a tetrahedron edge. Vertices are shared through the grid edge
   they lie on, so a closed zero set gives a closed manifold mesh with no
   duplicate vertices. Each triangle is wound to face from the inside
   corners of its tetrahedron to the outside ones: outward, consistently.
   f < 0 is inside; f == 0 counts as outside. The grid is processed one
   layer of cubes at a time, so memory is two layers of samples and edge
   vertices plus the mesh.

   Include meshio.h first. Define SDFMESH_IMPLEMENTATION in one file. */
#ifndef SDFMESH_H
#define SDFMESH_H
#include <stddef.h>

typedef float (*sdfmesh_fn)(const float p[3], void *user);

/* Meshes the zero set of f on cells of size `cell`, n[0] x n[1] x n[2] of
   them from corner `low`. Returns 1, or 0 when out of memory. */
int sdfmesh_tetra(mio_mesh *out, sdfmesh_fn f, void *user, const float low[3], float cell, const unsigned n[3]);

/* The six shapes of the SDF tests. `user` is unused. */
float sdf_sphere(const float p[3], void *user);        /* radius 1 */
float sdf_box(const float p[3], void *user);           /* half extents 0.77, 0.61, 0.47 (off the test grids) */
float sdf_cylinder(const float p[3], void *user);      /* radius 0.6, half height 0.77, along z */
float sdf_union(const float p[3], void *user);         /* spheres of radius 0.7 at x = -0.45 and 0.45 */
float sdf_smooth_union(const float p[3], void *user);  /* the same, blended over k = 0.3 */
float sdf_thin_box(const float p[3], void *user);      /* half extents 1, 1, 0.01 */
#endif

#ifdef SDFMESH_IMPLEMENTATION
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define SDFMESH_NONE 0xFFFFFFFFu

typedef struct sdfmesh_state {
    mio_mesh *mesh;
    size_t vertex_capacity, index_capacity;
    unsigned nx, ny;           /* points per layer: (nx + 1) * (ny + 1) */
    float *values[2];          /* samples of layers k and k + 1 */
    unsigned int *edges[2];    /* vertex on the edge leaving a point of layer k (k + 1), 7 directions */
    float low[3], cell;
} sdfmesh_state;

static int sdfmesh_grow(void **p, size_t *capacity, size_t needed, size_t size)
{
    size_t n = *capacity ? *capacity : 1024;
    void *q;
    if (needed <= *capacity)
        return 1;
    while (n < needed)
        n *= 2;
    q = realloc(*p, n * size);
    if (q == NULL)
        return 0;
    *p = q;
    *capacity = n;
    return 1;
}

static void sdfmesh_point(const sdfmesh_state *s, unsigned i, unsigned j, unsigned k, float p[3])
{
    p[0] = s->low[0] + s->cell * (float)i;
    p[1] = s->low[1] + s->cell * (float)j;
    p[2] = s->low[2] + s->cell * (float)k;
}

static void sdfmesh_sample_layer(sdfmesh_state *s, sdfmesh_fn f, void *user, unsigned k, float *values)
{
    unsigned i, j;
    for (j = 0; j <= s->ny; ++j)
        for (i = 0; i <= s->nx; ++i) {
            float p[3];
            sdfmesh_point(s, i, j, k, p);
            values[(size_t)j * (s->nx + 1) + i] = f(p, user);
        }
}

/* The vertex on the tetrahedron edge from corner a to corner b of cube
   (i, j, k) (corner bits: x 1, y 2, z 4; b's bits contain a's), made on
   first use. */
static unsigned int sdfmesh_edge_vertex(sdfmesh_state *s, unsigned i, unsigned j, unsigned k, unsigned a, unsigned b)
{
    unsigned layer = (a >> 2) & 1, ai = i + (a & 1), aj = j + ((a >> 1) & 1);
    unsigned bi = i + (b & 1), bj = j + ((b >> 1) & 1), blayer = (b >> 2) & 1;
    size_t slot = ((size_t)aj * (s->nx + 1) + ai) * 7 + ((a ^ b) - 1);
    unsigned int *entry = &s->edges[layer][slot];
    if (*entry == SDFMESH_NONE) {
        float va = s->values[layer][(size_t)aj * (s->nx + 1) + ai];
        float vb = s->values[blayer][(size_t)bj * (s->nx + 1) + bi];
        float pa[3], pb[3], t = va / (va - vb);
        mio_mesh *m = s->mesh;
        int c;
        sdfmesh_point(s, ai, aj, k + layer, pa);
        sdfmesh_point(s, bi, bj, k + blayer, pb);
        if (!sdfmesh_grow((void **)&m->positions, &s->vertex_capacity, 3 * (m->vertex_count + 1), sizeof(float)))
            return SDFMESH_NONE;
        for (c = 0; c < 3; ++c)
            m->positions[3 * m->vertex_count + c] = pa[c] + t * (pb[c] - pa[c]);
        *entry = (unsigned int)m->vertex_count++;
    }
    return *entry;
}

/* Adds triangle (x, y, z) facing along `out`. Its facing is decided on
   the triangle through the midpoints of the tetrahedron edges its vertices
   lie on (edge ab is ab[0], ab[1]): the real vertices can meet where the
   function is exactly zero at a corner, and a triangle with no area has no
   facing of its own. Moving a vertex along its edge never turns the
   triangle over, so both agree wherever the real one has an area. */
static int sdfmesh_triangle(sdfmesh_state *s, const unsigned vertex[3], const unsigned edge[3][2], const float out[3])
{
    mio_mesh *m = s->mesh;
    float mid[3][3], u[3], v[3], n[3];
    int k, q;
    if (vertex[0] == SDFMESH_NONE || vertex[1] == SDFMESH_NONE || vertex[2] == SDFMESH_NONE ||
        !sdfmesh_grow((void **)&m->indices, &s->index_capacity, m->index_count + 3, sizeof(unsigned int)))
        return 0;
    for (q = 0; q < 3; ++q)
        for (k = 0; k < 3; ++k)
            mid[q][k] = 0.5f * (float)(((edge[q][0] >> k) & 1) + ((edge[q][1] >> k) & 1));
    for (k = 0; k < 3; ++k) {
        u[k] = mid[1][k] - mid[0][k];
        v[k] = mid[2][k] - mid[0][k];
    }
    n[0] = u[1] * v[2] - u[2] * v[1];
    n[1] = u[2] * v[0] - u[0] * v[2];
    n[2] = u[0] * v[1] - u[1] * v[0];
    m->indices[m->index_count++] = vertex[0];
    if (n[0] * out[0] + n[1] * out[1] + n[2] * out[2] < 0) {
        m->indices[m->index_count++] = vertex[2];
        m->indices[m->index_count++] = vertex[1];
    } else {
        m->indices[m->index_count++] = vertex[1];
        m->indices[m->index_count++] = vertex[2];
    }
    return 1;
}

/* Adds the triangle across the tetrahedron edges a, b, c (pairs of corners). */
static int sdfmesh_cut(sdfmesh_state *s, unsigned i, unsigned j, unsigned k, const unsigned a[2], const unsigned b[2],
                       const unsigned c[2], const float out[3])
{
    const unsigned *ends[3];
    unsigned edge[3][2], vertex[3], q;
    ends[0] = a, ends[1] = b, ends[2] = c;
    for (q = 0; q < 3; ++q) {
        edge[q][0] = ends[q][0] < ends[q][1] ? ends[q][0] : ends[q][1];
        edge[q][1] = ends[q][0] < ends[q][1] ? ends[q][1] : ends[q][0];
        vertex[q] = sdfmesh_edge_vertex(s, i, j, k, edge[q][0], edge[q][1]);
    }
    return sdfmesh_triangle(s, vertex, (const unsigned(*)[2])edge, out);
}

static int sdfmesh_tetrahedron(sdfmesh_state *s, unsigned i, unsigned j, unsigned k, const unsigned corner[4])
{
    unsigned inside[4], outside[4], ni = 0, no = 0, q, axis;
    float out[3] = {0, 0, 0};
    for (q = 0; q < 4; ++q) {
        unsigned c = corner[q], layer = (c >> 2) & 1;
        float v = s->values[layer][(size_t)(j + ((c >> 1) & 1)) * (s->nx + 1) + i + (c & 1)];
        if (v < 0)
            inside[ni++] = c;
        else
            outside[no++] = c;
    }
    if (ni == 0 || no == 0)
        return 1;
    /* out: from the centroid of the inside corners to that of the outside ones */
    for (axis = 0; axis < 3; ++axis) {
        for (q = 0; q < no; ++q)
            out[axis] += (float)((outside[q] >> axis) & 1) / (float)no;
        for (q = 0; q < ni; ++q)
            out[axis] -= (float)((inside[q] >> axis) & 1) / (float)ni;
    }
    if (ni == 1 || no == 1) {
        const unsigned *lone = ni == 1 ? inside : outside, *rest = ni == 1 ? outside : inside;
        unsigned e0[2], e1[2], e2[2];
        e0[0] = e1[0] = e2[0] = lone[0];
        e0[1] = rest[0], e1[1] = rest[1], e2[1] = rest[2];
        return sdfmesh_cut(s, i, j, k, e0, e1, e2, out);
    }
    {
        unsigned a[2], b[2], c[2], d[2];
        a[0] = inside[0], a[1] = outside[0];
        b[0] = inside[0], b[1] = outside[1];
        c[0] = inside[1], c[1] = outside[1];
        d[0] = inside[1], d[1] = outside[0];
        return sdfmesh_cut(s, i, j, k, a, b, c, out) && sdfmesh_cut(s, i, j, k, a, c, d, out);
    }
}

int sdfmesh_tetra(mio_mesh *out, sdfmesh_fn f, void *user, const float low[3], float cell, const unsigned n[3])
{
    /* the six tetrahedra of a cube: 0 -> one axis -> two axes -> 7 */
    static const unsigned tets[6][4] = {{0, 1, 3, 7}, {0, 1, 5, 7}, {0, 2, 3, 7},
                                        {0, 2, 6, 7}, {0, 4, 5, 7}, {0, 4, 6, 7}};
    sdfmesh_state s;
    size_t layer_points = (size_t)(n[0] + 1) * (n[1] + 1);
    unsigned i, j, k, t;
    int ok = 1;
    memset(&s, 0, sizeof(s));
    memset(out, 0, sizeof(*out));
    s.mesh = out;
    s.nx = n[0];
    s.ny = n[1];
    s.low[0] = low[0], s.low[1] = low[1], s.low[2] = low[2];
    s.cell = cell;
    for (t = 0; t < 2; ++t) {
        s.values[t] = (float *)malloc(layer_points * sizeof(float));
        s.edges[t] = (unsigned int *)malloc(layer_points * 7 * sizeof(unsigned int));
        ok &= s.values[t] != NULL && s.edges[t] != NULL;
    }
    if (ok) {
        sdfmesh_sample_layer(&s, f, user, 0, s.values[0]);
        memset(s.edges[0], 0xFF, layer_points * 7 * sizeof(unsigned int));
    }
    for (k = 0; k < n[2] && ok; ++k) {
        sdfmesh_sample_layer(&s, f, user, k + 1, s.values[1]);
        memset(s.edges[1], 0xFF, layer_points * 7 * sizeof(unsigned int));
        for (j = 0; j < n[1] && ok; ++j)
            for (i = 0; i < n[0] && ok; ++i)
                for (t = 0; t < 6 && ok; ++t)
                    ok = sdfmesh_tetrahedron(&s, i, j, k, tets[t]);
        /* layer k + 1 becomes layer k */
        {
            float *v = s.values[0];
            unsigned int *e = s.edges[0];
            s.values[0] = s.values[1], s.values[1] = v;
            s.edges[0] = s.edges[1], s.edges[1] = e;
        }
    }
    for (t = 0; t < 2; ++t) {
        free(s.values[t]);
        free(s.edges[t]);
    }
    if (!ok)
        mio_free(out);
    return ok;
}

/* ---- the six shapes ---- */

static float sdf_length3(float x, float y, float z)
{
    return sqrtf(x * x + y * y + z * z);
}

static float sdf_box_with(const float p[3], float bx, float by, float bz)
{
    float q[3], outside;
    q[0] = fabsf(p[0]) - bx, q[1] = fabsf(p[1]) - by, q[2] = fabsf(p[2]) - bz;
    outside = sdf_length3(q[0] > 0 ? q[0] : 0, q[1] > 0 ? q[1] : 0, q[2] > 0 ? q[2] : 0);
    return outside + fminf(fmaxf(q[0], fmaxf(q[1], q[2])), 0.0f);
}

float sdf_sphere(const float p[3], void *user)
{
    (void)user;
    return sdf_length3(p[0], p[1], p[2]) - 1.0f;
}

float sdf_box(const float p[3], void *user)
{
    (void)user;
    return sdf_box_with(p, 0.77f, 0.61f, 0.47f);
}

float sdf_cylinder(const float p[3], void *user)
{
    float radial = sqrtf(p[0] * p[0] + p[1] * p[1]) - 0.6f, axial = fabsf(p[2]) - 0.77f;
    float ox = radial > 0 ? radial : 0, oy = axial > 0 ? axial : 0;
    (void)user;
    return fminf(fmaxf(radial, axial), 0.0f) + sqrtf(ox * ox + oy * oy);
}

static float sdf_two_spheres(const float p[3], float *a, float *b)
{
    *a = sdf_length3(p[0] + 0.45f, p[1], p[2]) - 0.7f;
    *b = sdf_length3(p[0] - 0.45f, p[1], p[2]) - 0.7f;
    return 0;
}

float sdf_union(const float p[3], void *user)
{
    float a, b;
    (void)user;
    sdf_two_spheres(p, &a, &b);
    return fminf(a, b);
}

float sdf_smooth_union(const float p[3], void *user)
{
    const float k = 0.3f;
    float a, b, h;
    (void)user;
    sdf_two_spheres(p, &a, &b);
    h = fmaxf(k - fabsf(a - b), 0.0f) / k;
    return fminf(a, b) - h * h * k * 0.25f;
}

float sdf_thin_box(const float p[3], void *user)
{
    (void)user;
    return sdf_box_with(p, 1.0f, 1.0f, 0.01f);
}
#endif /* SDFMESH_IMPLEMENTATION */
