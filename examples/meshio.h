/* meshio.h - small triangle-mesh file reader and writer for the meshfix examples and tests

   Reads OBJ, OFF, STL (ASCII and binary) and PLY (ASCII, binary little and
   big endian); writes OBJ, OFF, STL (binary) and PLY (binary little endian,
   with optional per-face colours). The format comes from the file
   extension. Polygons are split into triangle fans. STL stores every
   triangle with its own corners, so the reader merges corners with
   bit-identical positions (-0 taken as 0) into shared vertices, numbered
   in the order of their first corner, with meshfix_weld (so the program
   links meshfix.h's implementation somewhere).

   mio_load reads regular files only: a directory, FIFO or device is
   refused before anything is read from it (POSIX; on Windows it is simply
   opened).

   Hostile files are expected: every count is checked against the bytes
   left, indices against the vertex count, sizes against overflow, and every
   failure returns 0 with a one-line message. NaN and Inf coordinates are
   kept: judging them is meshfix's job.

   Include it with MESHIO_IMPLEMENTATION defined in one file. */
#ifndef MESHIO_H
#define MESHIO_H
#include <stddef.h>
#include <stdio.h>

typedef struct mio_mesh {
    float *positions;      /* 3 floats per vertex */
    size_t vertex_count;
    unsigned int *indices; /* 3 per triangle */
    size_t index_count;
} mio_mesh;

/* Returns 1 on success; on failure 0 and a message in error. */
int mio_load(const char *path, mio_mesh *mesh, char *error, size_t error_size);
/* face_rgb: NULL, or 3 bytes per triangle (PLY only). Returns 1 on success. */
int mio_save(const char *path, const mio_mesh *mesh, const unsigned char *face_rgb, char *error, size_t error_size);
void mio_free(mio_mesh *mesh);
/* Loads from memory; `format` is "obj", "off", "stl" or "ply". */
int mio_parse(const char *data, size_t size, const char *format, mio_mesh *mesh, char *error, size_t error_size);
/* The format a path's extension names ("obj", "off", "stl" or "ply", any
   case), or NULL for any other extension. */
const char *mio_format(const char *path);
/* Writes the mesh to an open stream in `format` (as mio_format returns) and
   flushes it; does not close it. Returns 1 when every write succeeded;
   `name` only goes into the message. */
int mio_write(FILE *f, const char *format, const mio_mesh *mesh, const unsigned char *face_rgb, const char *name,
              char *error, size_t error_size);

#endif

#ifdef MESHIO_IMPLEMENTATION
#include "../meshfix.h" /* meshfix_weld (include-guarded) */
#include <ctype.h>
#include <errno.h>
#include <limits.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#ifndef _WIN32
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#endif

#define MIO_MAX_VERTICES 0xFFFFFFFEu

typedef struct mio_reader {
    const char *data, *end, *at;
    mio_mesh *mesh;
    size_t vertex_capacity, index_capacity;
    char *error;
    size_t error_size;
    int failed;
} mio_reader;

static int mio_fail(mio_reader *r, const char *format, ...)
{
    va_list args;
    if (!r->failed && r->error != NULL && r->error_size > 0) {
        va_start(args, format);
        vsnprintf(r->error, r->error_size, format, args);
        va_end(args);
    }
    r->failed = 1;
    return 0;
}

static int mio_grow(void **array, size_t *capacity, size_t needed, size_t element_size)
{
    size_t n = *capacity ? *capacity : 64;
    void *p;
    if (needed <= *capacity)
        return 1;
    while (n < needed) {
        if (n > ((size_t)-1) / 2)
            return 0;
        n *= 2;
    }
    if (n > ((size_t)-1) / element_size)
        return 0;
    p = realloc(*array, n * element_size);
    if (p == NULL)
        return 0;
    *array = p;
    *capacity = n;
    return 1;
}

static int mio_add_vertex(mio_reader *r, const float v[3])
{
    mio_mesh *m = r->mesh;
    /* the second bound keeps 3 * (vertex_count + 1) floats within size_t (32-bit) */
    if (m->vertex_count >= MIO_MAX_VERTICES || m->vertex_count >= ((size_t)-1) / (3 * sizeof(float)) - 1)
        return mio_fail(r, "too many vertices");
    if (!mio_grow((void **)&m->positions, &r->vertex_capacity, 3 * (m->vertex_count + 1), sizeof(float)))
        return mio_fail(r, "out of memory for %lu vertices", (unsigned long)m->vertex_count);
    memcpy(m->positions + 3 * m->vertex_count, v, 3 * sizeof(float));
    m->vertex_count++;
    return 1;
}

static int mio_add_triangle(mio_reader *r, unsigned int a, unsigned int b, unsigned int c)
{
    mio_mesh *m = r->mesh;
    if (m->index_count > ((size_t)0x7FFFFFFF) - 3)
        return mio_fail(r, "too many triangles");
    if (!mio_grow((void **)&m->indices, &r->index_capacity, m->index_count + 3, sizeof(unsigned int)))
        return mio_fail(r, "out of memory for %lu triangles", (unsigned long)(m->index_count / 3));
    m->indices[m->index_count++] = a;
    m->indices[m->index_count++] = b;
    m->indices[m->index_count++] = c;
    return 1;
}

/* Adds a polygon as a fan around its first corner. */
static int mio_add_polygon(mio_reader *r, const unsigned int *corners, size_t count)
{
    size_t i;
    for (i = 0; i < count; ++i)
        if (corners[i] >= r->mesh->vertex_count)
            return mio_fail(r, "face index %u out of range (%lu vertices)", corners[i],
                            (unsigned long)r->mesh->vertex_count);
    for (i = 2; i < count; ++i)
        if (!mio_add_triangle(r, corners[0], corners[i - 1], corners[i]))
            return 0;
    return 1;
}

/* ---- text tokens ---- */

static void mio_skip_space(mio_reader *r)
{
    while (r->at < r->end && (*r->at == ' ' || *r->at == '\t' || *r->at == '\r'))
        r->at++;
}

static void mio_skip_line(mio_reader *r)
{
    while (r->at < r->end && *r->at != '\n')
        r->at++;
    if (r->at < r->end)
        r->at++;
}

/* Copies the next whitespace-delimited token on this line; 0 at line end.
   A token with a NUL byte in it, or too long for `out`, is copied as ""
   (it is there, but no keyword or number): reading a prefix of it would
   make "endloop\0x" an endloop, or a long number another number. */
static int mio_token(mio_reader *r, char *out, size_t out_size)
{
    size_t n = 0;
    int usable = 1;
    mio_skip_space(r);
    while (r->at < r->end && !isspace((unsigned char)*r->at)) {
        if (n + 1 < out_size && *r->at != 0)
            out[n] = *r->at;
        else
            usable = 0;
        n++;
        r->at++;
    }
    out[usable ? n : 0] = 0;
    return n > 0;
}

/* Like mio_token, but crosses line breaks and skips '#' comments (OFF). */
static int mio_word(mio_reader *r, char *out, size_t out_size)
{
    for (;;) {
        while (r->at < r->end && isspace((unsigned char)*r->at))
            r->at++;
        if (r->at < r->end && *r->at == '#') {
            mio_skip_line(r);
            continue;
        }
        return mio_token(r, out, out_size);
    }
}

static int mio_parse_float(const char *s, float *out)
{
    char *end;
    errno = 0;
    *out = strtof(s, &end);
    return end != s && *end == 0;
}

static int mio_parse_count(const char *s, unsigned long long limit, unsigned long long *out)
{
    char *end;
    if (*s == '-' || *s == '+')
        return 0;
    errno = 0;
    *out = strtoull(s, &end, 10);
    return end != s && *end == 0 && errno == 0 && *out <= limit;
}

/* ---- OBJ ---- */

/* "7", "7/1", "7//3", "-1/2/3": the vertex index, 1-based or negative. */
static int mio_obj_corner(mio_reader *r, const char *token, unsigned int *out)
{
    char *end;
    long long value;
    errno = 0;
    value = strtoll(token, &end, 10);
    if (end == token || (*end != 0 && *end != '/') || errno != 0)
        return mio_fail(r, "bad face corner '%s'", token);
    if (value < 0)
        value += (long long)r->mesh->vertex_count + 1;
    if (value < 1 || (unsigned long long)value > r->mesh->vertex_count)
        return mio_fail(r, "face index '%s' out of range (%lu vertices)", token,
                        (unsigned long)r->mesh->vertex_count);
    *out = (unsigned int)(value - 1);
    return 1;
}

static int mio_parse_obj(mio_reader *r)
{
    char token[256];
    unsigned int *corners = NULL;
    size_t corner_capacity = 0, line = 0;
    while (r->at < r->end && !r->failed) {
        line++;
        if (!mio_token(r, token, sizeof(token))) {
            mio_skip_line(r);
            continue;
        }
        if (strcmp(token, "v") == 0) {
            float v[3];
            int k;
            for (k = 0; k < 3; ++k)
                if (!mio_token(r, token, sizeof(token)) || !mio_parse_float(token, &v[k]))
                    mio_fail(r, "line %lu: bad vertex", (unsigned long)line);
            if (!r->failed)
                mio_add_vertex(r, v);
        } else if (strcmp(token, "f") == 0) {
            size_t n = 0;
            while (!r->failed && mio_token(r, token, sizeof(token))) {
                if (!mio_grow((void **)&corners, &corner_capacity, n + 1, sizeof(unsigned int)))
                    mio_fail(r, "out of memory");
                else
                    mio_obj_corner(r, token, &corners[n++]);
            }
            if (!r->failed && n < 3)
                mio_fail(r, "line %lu: face with fewer than 3 corners", (unsigned long)line);
            if (!r->failed)
                mio_add_polygon(r, corners, n);
        }
        mio_skip_line(r);
    }
    free(corners);
    return !r->failed;
}

/* ---- OFF ---- */

static int mio_parse_off(mio_reader *r)
{
    char word[256];
    unsigned long long nv, nf, ne, i, k, n;
    unsigned int corners[256];
    if (!mio_word(r, word, sizeof(word)) || strstr(word, "OFF") == NULL)
        return mio_fail(r, "missing OFF header");
    if (!mio_word(r, word, sizeof(word)) || !mio_parse_count(word, MIO_MAX_VERTICES, &nv) ||
        !mio_word(r, word, sizeof(word)) || !mio_parse_count(word, 0x7FFFFFFF, &nf) ||
        !mio_word(r, word, sizeof(word)) || !mio_parse_count(word, ULLONG_MAX, &ne))
        return mio_fail(r, "bad OFF counts");
    /* every vertex needs at least 6 bytes of text, every face 8 */
    if (nv > (unsigned long long)(r->end - r->at) / 6 || nf > (unsigned long long)(r->end - r->at) / 8)
        return mio_fail(r, "OFF counts (%llu vertices, %llu faces) exceed the file size", nv, nf);
    for (i = 0; i < nv && !r->failed; ++i) {
        float v[3];
        for (k = 0; k < 3; ++k)
            if (!mio_word(r, word, sizeof(word)) || !mio_parse_float(word, &v[k]))
                return mio_fail(r, "bad or missing vertex %llu", i);
        mio_skip_line(r);
        mio_add_vertex(r, v);
    }
    for (i = 0; i < nf && !r->failed; ++i) {
        if (!mio_word(r, word, sizeof(word)) || !mio_parse_count(word, 256, &n) || n < 3)
            return mio_fail(r, "bad or missing face %llu", i);
        for (k = 0; k < n; ++k) {
            unsigned long long index;
            if (!mio_word(r, word, sizeof(word)) || !mio_parse_count(word, 0xFFFFFFFFu, &index))
                return mio_fail(r, "bad index in face %llu", i);
            corners[k] = (unsigned int)index;
        }
        mio_skip_line(r);
        mio_add_polygon(r, corners, (size_t)n);
    }
    return !r->failed;
}

/* ---- STL ---- */

/* STL stores every triangle with its own three corners. The readers add
   each corner as a vertex of its own (-0 stored as +0) and triangle t as
   corners 3t, 3t+1, 3t+2; mio_stl_weld then merges corners with
   bit-identical positions through meshfix_weld (tolerance 0), keeping the
   first corner of each position, in file order. */
static int mio_add_stl_triangle(mio_reader *r, const float corners[9])
{
    unsigned int first = (unsigned int)r->mesh->vertex_count;
    float p[3];
    int k, j;
    for (k = 0; k < 3; ++k) {
        for (j = 0; j < 3; ++j)
            p[j] = corners[3 * k + j] == 0.0f ? 0.0f : corners[3 * k + j];
        if (!mio_add_vertex(r, p))
            return 0;
    }
    return mio_add_triangle(r, first, first + 1, first + 2);
}

static int mio_is_finite3(const float *p)
{
    int k;
    for (k = 0; k < 3; ++k) {
        unsigned int bits;
        memcpy(&bits, p + k, 4);
        if (((bits >> 23) & 0xFFu) == 0xFFu)
            return 0;
    }
    return 1;
}

static int mio_weld_failed(mio_reader *r, meshfix_result result)
{
    if (result == MESHFIX_ERROR_OUT_OF_MEMORY)
        return mio_fail(r, "out of memory merging %lu STL corners", (unsigned long)r->mesh->vertex_count);
    return mio_fail(r, "cannot merge STL corners: %s", meshfix_result_string(result));
}

/* remap[v] becomes the lowest corner with v's position. meshfix_weld refuses
   NaN and Inf, so when the file has such corners only the finite ones are
   welded and the others stay vertices of their own: judging them is
   meshfix's job, not the loader's. */
static int mio_stl_remap(mio_reader *r, unsigned int *remap)
{
    const float *positions = r->mesh->positions;
    size_t n = r->mesh->vertex_count, finite = 0, i, j, unique;
    unsigned int *origin, *packed_remap;
    float *packed;
    meshfix_result result;
    for (i = 0; i < n; ++i)
        finite += (size_t)mio_is_finite3(positions + 3 * i);
    if (finite == n) {
        result = meshfix_weld(remap, positions, n, 3 * sizeof(float), 0.0f, NULL, &unique);
        return result == MESHFIX_OK ? 1 : mio_weld_failed(r, result);
    }
    /* finite <= n, and n * 3 floats are allocated already: no overflow */
    packed = (float *)malloc(3 * sizeof(float) * finite + 1);
    origin = (unsigned int *)malloc(sizeof(unsigned int) * finite + 1);
    packed_remap = (unsigned int *)malloc(sizeof(unsigned int) * finite + 1);
    if (packed == NULL || origin == NULL || packed_remap == NULL) {
        result = MESHFIX_ERROR_OUT_OF_MEMORY;
    } else {
        for (i = 0, j = 0; i < n; ++i) {
            remap[i] = (unsigned int)i;
            if (mio_is_finite3(positions + 3 * i)) {
                memcpy(packed + 3 * j, positions + 3 * i, 3 * sizeof(float));
                origin[j++] = (unsigned int)i;
            }
        }
        result = meshfix_weld(packed_remap, packed, finite, 3 * sizeof(float), 0.0f, NULL, &unique);
        if (result == MESHFIX_OK)
            for (j = 0; j < finite; ++j)
                remap[origin[j]] = origin[packed_remap[j]];
    }
    free(packed);
    free(origin);
    free(packed_remap);
    return result == MESHFIX_OK ? 1 : mio_weld_failed(r, result);
}

static int mio_stl_weld(mio_reader *r)
{
    mio_mesh *m = r->mesh;
    size_t n = m->vertex_count, i, unique = 0;
    unsigned int *remap;
    if (n == 0)
        return 1;
    /* n * 3 floats are allocated already, so n * sizeof(unsigned int) fits */
    remap = (unsigned int *)malloc(sizeof(unsigned int) * n);
    if (remap == NULL)
        return mio_fail(r, "out of memory merging %lu STL corners", (unsigned long)n);
    if (!mio_stl_remap(r, remap)) {
        free(remap);
        return 0;
    }
    /* keep the first corner of each position, in order; remap[v] < v is
       already rewritten to its new index when v is reached */
    for (i = 0; i < n; ++i) {
        if (remap[i] > i) {
            free(remap);
            return mio_fail(r, "meshfix_weld returned a bad remap");
        }
        if (remap[i] == i) {
            if (unique != i)
                memcpy(m->positions + 3 * unique, m->positions + 3 * i, 3 * sizeof(float));
            remap[i] = (unsigned int)unique++;
        } else {
            remap[i] = remap[remap[i]];
        }
    }
    for (i = 0; i < m->index_count; ++i)
        m->indices[i] = remap[m->indices[i]];
    free(remap);
    m->vertex_count = unique;
    if (unique < n) {
        float *smaller = (float *)realloc(m->positions, 3 * sizeof(float) * unique);
        if (smaller != NULL) {
            m->positions = smaller;
            r->vertex_capacity = 3 * unique;
        }
    }
    return 1;
}

static float mio_read_f32le(const unsigned char *p)
{
    unsigned int bits = (unsigned int)p[0] | (unsigned int)p[1] << 8 | (unsigned int)p[2] << 16 |
                        (unsigned int)p[3] << 24;
    float f;
    memcpy(&f, &bits, 4);
    return f;
}

/* The caller checked that the file is exactly 84 + 50 * n bytes. */
static int mio_parse_stl_binary(mio_reader *r, size_t n)
{
    const unsigned char *p = (const unsigned char *)r->data;
    size_t i;
    /* n <= size / 50, so 9 * n and 3 * n cannot overflow */
    if (!mio_grow((void **)&r->mesh->positions, &r->vertex_capacity, 9 * n, sizeof(float)) ||
        !mio_grow((void **)&r->mesh->indices, &r->index_capacity, 3 * n, sizeof(unsigned int)))
        return mio_fail(r, "out of memory for %lu triangles", (unsigned long)n);
    for (i = 0; i < n && !r->failed; ++i) {
        const unsigned char *facet = p + 84 + 50 * i + 12;
        float corners[9];
        int k;
        for (k = 0; k < 9; ++k)
            corners[k] = mio_read_f32le(facet + 4 * k);
        mio_add_stl_triangle(r, corners);
    }
    return !r->failed;
}

static int mio_parse_stl_ascii(mio_reader *r)
{
    char word[256];
    float corners[9];
    int count = 0;
    while (!r->failed && mio_word(r, word, sizeof(word))) {
        if (strcmp(word, "vertex") == 0) {
            int k;
            if (count == 3)
                return mio_fail(r, "facet with more than 3 vertices");
            for (k = 0; k < 3; ++k)
                if (!mio_word(r, word, sizeof(word)) || !mio_parse_float(word, &corners[3 * count + k]))
                    return mio_fail(r, "bad STL vertex");
            count++;
        } else if (strcmp(word, "endloop") == 0) {
            if (count != 3)
                return mio_fail(r, "facet with %d vertices", count);
            mio_add_stl_triangle(r, corners);
            count = 0;
        }
    }
    if (!r->failed && r->mesh->index_count == 0 && r->end - r->data >= 5 && memcmp(r->data, "solid", 5) != 0)
        return mio_fail(r, "not an STL file");
    return !r->failed;
}

static int mio_parse_stl(mio_reader *r)
{
    size_t size = (size_t)(r->end - r->data);
    unsigned long long n = 0;
    int binary = 0;
    if (size >= 84) {
        const unsigned char *p = (const unsigned char *)r->data;
        n = (unsigned long long)p[80] | (unsigned long long)p[81] << 8 | (unsigned long long)p[82] << 16 |
            (unsigned long long)p[83] << 24;
        binary = 84 + 50 * n == (unsigned long long)size;
        if (!binary && memcmp(r->data, "solid", 5) != 0)
            return mio_fail(r, "binary STL of %lu bytes cannot hold the %llu triangles it declares",
                            (unsigned long)size, n);
    }
    /* binary: n < size / 50 fits in size_t */
    if (!(binary ? mio_parse_stl_binary(r, (size_t)n) : mio_parse_stl_ascii(r)))
        return 0;
    return mio_stl_weld(r);
}

/* ---- PLY ---- */

enum { MIO_PLY_MAX_PROPERTIES = 64, MIO_PLY_MAX_ELEMENTS = 16 };
typedef struct mio_ply_property {
    char name[64];
    int type;       /* byte size and kind, see mio_ply_type */
    int count_type; /* 0 for a scalar, else the type of a list's length */
} mio_ply_property;

typedef struct mio_ply_element {
    char name[64];
    unsigned long long count;
    mio_ply_property properties[MIO_PLY_MAX_PROPERTIES];
    int property_count;
} mio_ply_element;

/* Types are encoded as size * 4 + kind (0 unsigned, 1 signed, 2 float). */
static int mio_ply_type(const char *name)
{
    static const struct { const char *name; int code; } types[] = {
        {"char", 5}, {"int8", 5}, {"uchar", 4}, {"uint8", 4}, {"short", 9}, {"int16", 9},
        {"ushort", 8}, {"uint16", 8}, {"int", 17}, {"int32", 17}, {"uint", 16}, {"uint32", 16},
        {"float", 18}, {"float32", 18}, {"double", 34}, {"float64", 34}};
    size_t i;
    for (i = 0; i < sizeof(types) / sizeof(types[0]); ++i)
        if (strcmp(name, types[i].name) == 0)
            return types[i].code;
    return 0;
}

typedef struct mio_ply_reader {
    mio_reader *r;
    int format; /* 0 ascii, 1 little endian, 2 big endian */
} mio_ply_reader;

/* Reads one value of `type` as a double; 0 at the end of the data. */
static int mio_ply_value(mio_ply_reader *p, int type, double *out)
{
    mio_reader *r = p->r;
    if (p->format == 0) {
        char word[128], *end;
        if (!mio_word(r, word, sizeof(word)))
            return mio_fail(r, "PLY data ends early");
        *out = strtod(word, &end);
        if (*end != 0)
            return mio_fail(r, "bad PLY value '%s'", word);
        return 1;
    } else {
        int size = type / 4, kind = type % 4, i;
        unsigned char b[8];
        unsigned long long bits = 0;
        if (r->end - r->at < size)
            return mio_fail(r, "PLY data ends early");
        for (i = 0; i < size; ++i)
            b[i] = (unsigned char)r->at[p->format == 1 ? i : size - 1 - i];
        r->at += size;
        for (i = size - 1; i >= 0; --i)
            bits = bits << 8 | b[i];
        if (kind == 2 && size == 4) {
            unsigned int u = (unsigned int)bits;
            float f;
            memcpy(&f, &u, 4);
            *out = (double)f;
        } else if (kind == 2) {
            double d;
            memcpy(&d, &bits, 8);
            *out = d;
        } else if (kind == 1) {
            unsigned long long sign = 1ull << (8 * size - 1);
            *out = (double)(long long)((bits ^ sign) - sign);
        } else {
            *out = (double)bits;
        }
        return 1;
    }
}

static int mio_ply_header(mio_reader *r, mio_ply_element *elements, int *element_count, int *format)
{
    char word[128];
    mio_ply_element *current = NULL;
    if (!mio_token(r, word, sizeof(word)) || strcmp(word, "ply") != 0)
        return mio_fail(r, "missing 'ply' magic");
    mio_skip_line(r);
    *element_count = 0;
    *format = -1;
    while (r->at < r->end) {
        if (!mio_token(r, word, sizeof(word))) {
            mio_skip_line(r);
            continue;
        }
        if (strcmp(word, "end_header") == 0) {
            mio_skip_line(r);
            if (*format < 0)
                return mio_fail(r, "PLY header without format");
            return 1;
        } else if (strcmp(word, "format") == 0) {
            mio_token(r, word, sizeof(word));
            *format = strcmp(word, "ascii") == 0 ? 0 : strcmp(word, "binary_little_endian") == 0 ? 1
                    : strcmp(word, "binary_big_endian") == 0 ? 2 : -1;
            if (*format < 0)
                return mio_fail(r, "unknown PLY format '%s'", word);
        } else if (strcmp(word, "element") == 0) {
            if (*element_count == MIO_PLY_MAX_ELEMENTS)
                return mio_fail(r, "too many PLY elements");
            current = &elements[(*element_count)++];
            memset(current, 0, sizeof(*current));
            mio_token(r, current->name, sizeof(current->name));
            if (!mio_token(r, word, sizeof(word)) || !mio_parse_count(word, 0xFFFFFFFFull, &current->count))
                return mio_fail(r, "bad PLY element count");
        } else if (strcmp(word, "property") == 0) {
            mio_ply_property *prop;
            if (current == NULL || current->property_count == MIO_PLY_MAX_PROPERTIES)
                return mio_fail(r, "PLY property outside an element or too many");
            prop = &current->properties[current->property_count++];
            mio_token(r, word, sizeof(word));
            if (strcmp(word, "list") == 0) {
                mio_token(r, word, sizeof(word));
                prop->count_type = mio_ply_type(word);
                mio_token(r, word, sizeof(word));
                prop->type = mio_ply_type(word);
                if (prop->count_type == 0 || prop->count_type % 4 == 2)
                    return mio_fail(r, "bad PLY list count type");
            } else {
                prop->type = mio_ply_type(word);
            }
            if (prop->type == 0)
                return mio_fail(r, "unknown PLY type '%s'", word);
            mio_token(r, prop->name, sizeof(prop->name));
        }
        mio_skip_line(r);
    }
    return mio_fail(r, "PLY header without end_header");
}

static int mio_ply_element_data(mio_ply_reader *p, const mio_ply_element *e, int is_vertex, int is_face)
{
    mio_reader *r = p->r;
    unsigned long long i;
    unsigned int corners[256];
    /* even ASCII needs 2 bytes per value: refuse counts the file cannot hold */
    if (e->count > (unsigned long long)(r->end - r->at) / 2 + 1)
        return mio_fail(r, "PLY element '%s' count %llu exceeds the file size", e->name, e->count);
    for (i = 0; i < e->count && !r->failed; ++i) {
        float v[3] = {0, 0, 0};
        int j, have = 0;
        for (j = 0; j < e->property_count && !r->failed; ++j) {
            const mio_ply_property *prop = &e->properties[j];
            double value, n;
            unsigned long long k;
            if (prop->count_type == 0) {
                if (!mio_ply_value(p, prop->type, &value))
                    return 0;
                if (is_vertex && prop->name[0] >= 'x' && prop->name[0] <= 'z' && prop->name[1] == 0) {
                    v[prop->name[0] - 'x'] = (float)value;
                    have |= 1 << (prop->name[0] - 'x');
                }
                continue;
            }
            if (!mio_ply_value(p, prop->count_type, &n))
                return 0;
            if (!(n >= 0 && n <= 1e9))
                return mio_fail(r, "bad PLY list length");
            if (is_face && (strcmp(prop->name, "vertex_indices") == 0 || strcmp(prop->name, "vertex_index") == 0)) {
                if (n < 3 || n > 256)
                    return mio_fail(r, "PLY face %llu has %g corners", i, n);
                for (k = 0; k < (unsigned long long)n; ++k) {
                    if (!mio_ply_value(p, prop->type, &value))
                        return 0;
                    if (!(value >= 0 && value < 4294967295.0))
                        return mio_fail(r, "bad PLY vertex index %g", value);
                    corners[k] = (unsigned int)value;
                }
                mio_add_polygon(r, corners, (size_t)n);
            } else {
                for (k = 0; k < (unsigned long long)n; ++k)
                    if (!mio_ply_value(p, prop->type, &value))
                        return 0;
            }
        }
        if (is_vertex && !r->failed) {
            if (have != 7)
                return mio_fail(r, "PLY vertex without x, y and z");
            mio_add_vertex(r, v);
        }
    }
    return !r->failed;
}

static int mio_parse_ply(mio_reader *r)
{
    mio_ply_element elements[MIO_PLY_MAX_ELEMENTS];
    mio_ply_reader p;
    int count = 0, i, seen_vertices = 0;
    p.r = r;
    p.format = 0;
    if (!mio_ply_header(r, elements, &count, &p.format))
        return 0;
    for (i = 0; i < count && !r->failed; ++i) {
        int is_vertex = strcmp(elements[i].name, "vertex") == 0;
        int is_face = strcmp(elements[i].name, "face") == 0;
        if (is_face && !seen_vertices)
            return mio_fail(r, "PLY faces before vertices");
        seen_vertices |= is_vertex;
        mio_ply_element_data(&p, &elements[i], is_vertex, is_face);
    }
    return !r->failed;
}

/* ---- entry points ---- */

int mio_parse(const char *data, size_t size, const char *format, mio_mesh *mesh, char *error, size_t error_size)
{
    mio_reader r;
    int ok;
    memset(&r, 0, sizeof(r));
    memset(mesh, 0, sizeof(*mesh));
    r.data = r.at = data;
    r.end = data + size;
    r.mesh = mesh;
    r.error = error;
    r.error_size = error_size;
    if (strcmp(format, "obj") == 0)
        ok = mio_parse_obj(&r);
    else if (strcmp(format, "off") == 0)
        ok = mio_parse_off(&r);
    else if (strcmp(format, "stl") == 0)
        ok = mio_parse_stl(&r);
    else if (strcmp(format, "ply") == 0)
        ok = mio_parse_ply(&r);
    else
        ok = mio_fail(&r, "unknown format '%s' (use .obj, .off, .stl or .ply)", format);
    if (ok && mesh->index_count == 0)
        ok = mio_fail(&r, "no triangles");
    if (!ok)
        mio_free(mesh);
    return ok;
}

static const char *mio_extension(const char *path, char *out, size_t out_size)
{
    const char *dot = strrchr(path, '.');
    size_t i = 0;
    if (dot != NULL)
        for (dot++; *dot && i + 1 < out_size; ++dot)
            out[i++] = (char)tolower((unsigned char)*dot);
    out[i] = 0;
    return out;
}

/* Reads a whole regular file into a new 0-terminated buffer. */
static int mio_read_file(const char *path, char **data_out, size_t *size_out, char *error, size_t error_size)
{
    char *data;
    size_t size;
#ifndef _WIN32
    struct stat st;
    size_t got = 0;
    int fd;
    /* O_NONBLOCK: opening a FIFO does not wait for a writer (it is refused
       below), and nothing is read before the file is known to be regular */
    do
        fd = open(path, O_RDONLY | O_NONBLOCK);
    while (fd < 0 && errno == EINTR);
    if (fd < 0) {
        snprintf(error, error_size, "cannot open '%s': %s", path, strerror(errno));
        return 0;
    }
    if (fstat(fd, &st) != 0) {
        snprintf(error, error_size, "cannot read '%s': %s", path, strerror(errno));
        close(fd);
        return 0;
    }
    if (!S_ISREG(st.st_mode)) {
        if (S_ISDIR(st.st_mode))
            snprintf(error, error_size, "'%s' is a directory, not a mesh file", path);
        else
            snprintf(error, error_size, "'%s' is not a regular file (a FIFO, socket or device)", path);
        close(fd);
        return 0;
    }
    if (st.st_size < 0 || (unsigned long long)st.st_size >= (unsigned long long)((size_t)-1)) {
        snprintf(error, error_size, "'%s' is too large to load", path);
        close(fd);
        return 0;
    }
    size = (size_t)st.st_size;
    if ((data = (char *)malloc(size + 1)) == NULL) {
        snprintf(error, error_size, "out of memory reading '%s' (%lu bytes)", path, (unsigned long)size);
        close(fd);
        return 0;
    }
    while (got < size) {
        size_t chunk = size - got < ((size_t)1 << 30) ? size - got : ((size_t)1 << 30);
        ssize_t n = read(fd, data + got, chunk);
        if (n < 0 && errno == EINTR)
            continue;
        if (n <= 0)
            break;
        got += (size_t)n;
    }
    close(fd);
    if (got != size) {
        snprintf(error, error_size, "cannot read '%s'", path);
        free(data);
        return 0;
    }
#else
    FILE *f = fopen(path, "rb");
    long length;
    if (f == NULL) {
        snprintf(error, error_size, "cannot open '%s'", path);
        return 0;
    }
    data = NULL;
    if (fseek(f, 0, SEEK_END) != 0 || (length = ftell(f)) < 0 || fseek(f, 0, SEEK_SET) != 0) {
        snprintf(error, error_size, "cannot read '%s'", path);
    } else if ((unsigned long)length >= (unsigned long)((size_t)-1) ||
               (data = (char *)malloc((size_t)length + 1)) == NULL) {
        snprintf(error, error_size, "out of memory reading '%s'", path);
    } else if (fread(data, 1, (size_t)length, f) != (size_t)length) {
        snprintf(error, error_size, "cannot read '%s'", path);
        free(data);
        data = NULL;
    }
    fclose(f);
    if (data == NULL)
        return 0;
    size = (size_t)length;
#endif
    data[size] = 0;
    *data_out = data;
    *size_out = size;
    return 1;
}

int mio_load(const char *path, mio_mesh *mesh, char *error, size_t error_size)
{
    char *data, ext[16];
    size_t size;
    int ok;
    memset(mesh, 0, sizeof(*mesh));
    if (!mio_read_file(path, &data, &size, error, error_size))
        return 0;
    ok = mio_parse(data, size, mio_extension(path, ext, sizeof(ext)), mesh, error, error_size);
    free(data);
    return ok;
}

void mio_free(mio_mesh *mesh)
{
    free(mesh->positions);
    free(mesh->indices);
    memset(mesh, 0, sizeof(*mesh));
}

/* ---- writers ---- */

static void mio_put_u32le(FILE *f, unsigned int x)
{
    unsigned char b[4];
    b[0] = (unsigned char)x;
    b[1] = (unsigned char)(x >> 8);
    b[2] = (unsigned char)(x >> 16);
    b[3] = (unsigned char)(x >> 24);
    fwrite(b, 1, 4, f);
}

static void mio_put_f32le(FILE *f, float x)
{
    unsigned int bits;
    memcpy(&bits, &x, 4);
    mio_put_u32le(f, bits);
}

static void mio_write_stl(FILE *f, const mio_mesh *m)
{
    char header[80];
    size_t t;
    memset(header, 0, sizeof(header));
    snprintf(header, sizeof(header), "binary STL written by meshfix");
    fwrite(header, 1, 80, f);
    mio_put_u32le(f, (unsigned int)(m->index_count / 3));
    for (t = 0; t < m->index_count / 3; ++t) {
        const float *a = m->positions + 3 * (size_t)m->indices[3 * t];
        const float *b = m->positions + 3 * (size_t)m->indices[3 * t + 1];
        const float *c = m->positions + 3 * (size_t)m->indices[3 * t + 2];
        float n[3];
        int k;
        n[0] = (b[1] - a[1]) * (c[2] - a[2]) - (b[2] - a[2]) * (c[1] - a[1]);
        n[1] = (b[2] - a[2]) * (c[0] - a[0]) - (b[0] - a[0]) * (c[2] - a[2]);
        n[2] = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
        for (k = 0; k < 3; ++k)
            mio_put_f32le(f, n[k]);
        for (k = 0; k < 3; ++k)
            mio_put_f32le(f, a[k]);
        for (k = 0; k < 3; ++k)
            mio_put_f32le(f, b[k]);
        for (k = 0; k < 3; ++k)
            mio_put_f32le(f, c[k]);
        fputc(0, f);
        fputc(0, f);
    }
}

static void mio_write_ply(FILE *f, const mio_mesh *m, const unsigned char *rgb)
{
    size_t i;
    fprintf(f, "ply\nformat binary_little_endian 1.0\ncomment written by meshfix\n");
    fprintf(f, "element vertex %lu\nproperty float x\nproperty float y\nproperty float z\n",
            (unsigned long)m->vertex_count);
    fprintf(f, "element face %lu\nproperty list uchar uint vertex_indices\n", (unsigned long)(m->index_count / 3));
    if (rgb != NULL)
        fprintf(f, "property uchar red\nproperty uchar green\nproperty uchar blue\n");
    fprintf(f, "end_header\n");
    for (i = 0; i < 3 * m->vertex_count; ++i)
        mio_put_f32le(f, m->positions[i]);
    for (i = 0; i < m->index_count / 3; ++i) {
        fputc(3, f);
        mio_put_u32le(f, m->indices[3 * i]);
        mio_put_u32le(f, m->indices[3 * i + 1]);
        mio_put_u32le(f, m->indices[3 * i + 2]);
        if (rgb != NULL)
            fwrite(rgb + 3 * i, 1, 3, f);
    }
}

const char *mio_format(const char *path)
{
    static const char *const formats[] = {"obj", "off", "stl", "ply"};
    char ext[16];
    size_t i;
    mio_extension(path, ext, sizeof(ext));
    for (i = 0; i < sizeof(formats) / sizeof(formats[0]); ++i)
        if (strcmp(ext, formats[i]) == 0)
            return formats[i];
    return NULL;
}

int mio_write(FILE *f, const char *format, const mio_mesh *m, const unsigned char *face_rgb, const char *name,
              char *error, size_t error_size)
{
    size_t i;
    if (format == NULL || (strcmp(format, "obj") != 0 && strcmp(format, "off") != 0 && strcmp(format, "stl") != 0 &&
                           strcmp(format, "ply") != 0)) {
        snprintf(error, error_size, "unknown output format for '%s' (use .obj, .off, .stl or .ply)", name);
        return 0;
    }
    if (strcmp(format, "obj") == 0) {
        for (i = 0; i < m->vertex_count; ++i)
            fprintf(f, "v %.9g %.9g %.9g\n", (double)m->positions[3 * i], (double)m->positions[3 * i + 1],
                    (double)m->positions[3 * i + 2]);
        for (i = 0; i < m->index_count; i += 3)
            fprintf(f, "f %u %u %u\n", m->indices[i] + 1, m->indices[i + 1] + 1, m->indices[i + 2] + 1);
    } else if (strcmp(format, "off") == 0) {
        fprintf(f, "OFF\n%lu %lu 0\n", (unsigned long)m->vertex_count, (unsigned long)(m->index_count / 3));
        for (i = 0; i < m->vertex_count; ++i)
            fprintf(f, "%.9g %.9g %.9g\n", (double)m->positions[3 * i], (double)m->positions[3 * i + 1],
                    (double)m->positions[3 * i + 2]);
        for (i = 0; i < m->index_count; i += 3)
            fprintf(f, "3 %u %u %u\n", m->indices[i], m->indices[i + 1], m->indices[i + 2]);
    } else if (strcmp(format, "stl") == 0) {
        mio_write_stl(f, m);
    } else {
        mio_write_ply(f, m, face_rgb);
    }
    if (fflush(f) != 0 || ferror(f)) {
        snprintf(error, error_size, "error writing '%s'", name);
        return 0;
    }
    return 1;
}

int mio_save(const char *path, const mio_mesh *m, const unsigned char *face_rgb, char *error, size_t error_size)
{
    const char *format = mio_format(path);
    FILE *f;
    int ok;
    if (format == NULL) {
        snprintf(error, error_size, "unknown output format '%s' (use .obj, .off, .stl or .ply)", path);
        return 0;
    }
    if ((f = fopen(path, "wb")) == NULL) {
        snprintf(error, error_size, "cannot write '%s': %s", path, strerror(errno));
        return 0;
    }
    ok = mio_write(f, format, m, face_rgb, path, error, error_size);
    if (fclose(f) != 0 && ok) {
        snprintf(error, error_size, "error writing '%s'", path);
        ok = 0;
    }
    return ok;
}

#endif /* MESHIO_IMPLEMENTATION */
