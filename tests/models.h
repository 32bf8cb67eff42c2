/* Real files for the suites: a loader that counts a missing model as a
   failure (make test installs the packages: tests/install_deps.sh), and
   an OBJ loader that builds the vertex buffer a game engine would: one
   interleaved vertex (position, texture coordinate, normal; 32 bytes) per
   distinct v/vt/vn corner, so a vertex is split wherever a seam of UVs or
   normals runs.
   Include check.h and examples/meshio.h first. */
#ifndef MESHFIX_TESTS_MODELS_H
#define MESHFIX_TESTS_MODELS_H
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* a suite may use only some of these */
#if defined(__GNUC__) || defined(__clang__)
#define MODELS_MAYBE_UNUSED __attribute__((unused))
#else
#define MODELS_MAYBE_UNUSED
#endif

MODELS_MAYBE_UNUSED static int load_model(const char *path, mio_mesh *g)
{
    char error[256];
    if (mio_load(path, g, error, sizeof(error)))
        return 1;
    printf("    cannot load %s: %s (make test installs occt-misc and assimp-testmodels)\n", path, error);
    failures++;
    return 0;
}

/* An engine's mesh: `vertices` interleaved (8 floats each), `indices`
   into them, and the same triangles indexed by the file's positions
   (`by_position`, into `positions`). */
typedef struct engine_mesh {
    float *vertices;
    size_t vertex_count;
    unsigned int *indices;
    size_t index_count;
    float *positions;
    size_t position_count;
    unsigned int *by_position;
} engine_mesh;

#define ENGINE_STRIDE (8 * sizeof(float))

MODELS_MAYBE_UNUSED static void engine_free(engine_mesh *e)
{
    free(e->vertices);
    free(e->indices);
    free(e->positions);
    free(e->by_position);
    memset(e, 0, sizeof(*e));
}

/* A growing array of floats or corner keys. */
typedef struct engine_list {
    void *data;
    size_t count, capacity, size;
} engine_list;

static void *engine_push(engine_list *l)
{
    if (l->count == l->capacity) {
        size_t capacity = l->capacity != 0 ? 2 * l->capacity : 256;
        void *data = realloc(l->data, capacity * l->size);
        if (data == NULL)
            return NULL;
        l->data = data, l->capacity = capacity;
    }
    return (char *)l->data + l->size * l->count++;
}

/* v, vt and vn of one corner ("7/3/5", "7//5", "7/3" or "7"), 1-based,
   negative from the end; 0 when absent. Returns 0 when the corner is bad. */
static int engine_corner(const char *text, const size_t counts[3], long out[3])
{
    int k;
    for (k = 0; k < 3; ++k) {
        char *end;
        long x = 0;
        if (*text != '/' && *text != '\0')
            x = strtol(text, &end, 10), text = end;
        if (x < 0)
            x = (long)counts[k] + x + 1;
        if (x < 0 || (size_t)x > counts[k] || (k == 0 && x == 0))
            return 0;
        out[k] = x;
        if (*text == '/')
            ++text;
    }
    return 1;
}

/* Loads `path`; polygons become fans. Returns 0 (and says why) when the
   file is missing or malformed. */
MODELS_MAYBE_UNUSED static int engine_obj_load(const char *path, engine_mesh *e)
{
    FILE *f = fopen(path, "r");
    char line[4096];
    engine_list v = {NULL, 0, 0, 3 * sizeof(float)}, vt = {NULL, 0, 0, 2 * sizeof(float)};
    engine_list vn = {NULL, 0, 0, 3 * sizeof(float)}, keys = {NULL, 0, 0, 3 * sizeof(long)};
    engine_list corners = {NULL, 0, 0, sizeof(unsigned int)}, by_position = {NULL, 0, 0, sizeof(unsigned int)};
    int ok = f != NULL;
    size_t i;
    memset(e, 0, sizeof(*e));
    while (ok && fgets(line, sizeof(line), f) != NULL) {
        float *p;
        if (line[0] == 'v' && (line[1] == ' ' || line[1] == 't' || line[1] == 'n')) {
            engine_list *l = line[1] == ' ' ? &v : line[1] == 't' ? &vt : &vn;
            float x = 0, y = 0, z = 0;
            sscanf(line + 2, "%f %f %f", &x, &y, &z);
            if ((p = (float *)engine_push(l)) == NULL)
                ok = 0;
            else
                p[0] = x, p[1] = y, l == &vt ? (void)0 : (void)(p[2] = z);
        } else if (line[0] == 'f' && line[1] == ' ') {
            size_t counts[3], n = 0, first = corners.count;
            char *token = strtok(line + 2, " \t\r\n");
            counts[0] = v.count, counts[1] = vt.count, counts[2] = vn.count;
            for (; ok && token != NULL; token = strtok(NULL, " \t\r\n"), ++n) {
                long corner[3], *key;
                unsigned int *slot;
                if (!engine_corner(token, counts, corner))
                    ok = 0;
                /* a polygon's corners beyond the third start a new fan triangle */
                if (ok && n >= 3) {
                    unsigned int a = ((unsigned int *)corners.data)[first];
                    unsigned int b = ((unsigned int *)corners.data)[corners.count - 1];
                    unsigned int pa = ((unsigned int *)by_position.data)[first];
                    unsigned int pb = ((unsigned int *)by_position.data)[by_position.count - 1];
                    unsigned int *s1 = (unsigned int *)engine_push(&corners), *s2;
                    unsigned int *q1 = (unsigned int *)engine_push(&by_position), *q2;
                    if (s1 == NULL || q1 == NULL)
                        ok = 0;
                    else
                        *s1 = a, *q1 = pa;
                    s2 = (unsigned int *)engine_push(&corners), q2 = (unsigned int *)engine_push(&by_position);
                    if (s2 == NULL || q2 == NULL)
                        ok = 0;
                    else
                        *s2 = b, *q2 = pb;
                }
                if (!ok)
                    break;
                /* the vertex of this v/vt/vn: a linear search back would be
                   quadratic; keys are kept and matched at the end */
                if ((key = (long *)engine_push(&keys)) == NULL || (slot = (unsigned int *)engine_push(&corners)) == NULL ||
                    engine_push(&by_position) == NULL) {
                    ok = 0;
                    break;
                }
                key[0] = corner[0], key[1] = corner[1], key[2] = corner[2];
                *slot = (unsigned int)(keys.count - 1);
                ((unsigned int *)by_position.data)[by_position.count - 1] = (unsigned int)(corner[0] - 1);
            }
            if (n < 3)
                ok = 0;
        }
    }
    if (f != NULL)
        fclose(f);
    /* one vertex per distinct key: keys sorted by a counting pass over v */
    if (ok && keys.count != 0) {
        long *k = (long *)keys.data;
        unsigned int *vertex_of = (unsigned int *)malloc(keys.count * sizeof(unsigned int));
        size_t *head = (size_t *)malloc((v.count + 1) * sizeof(size_t)), *next = (size_t *)malloc(keys.count * sizeof(size_t));
        e->vertices = (float *)malloc(keys.count * ENGINE_STRIDE);
        ok = vertex_of != NULL && head != NULL && next != NULL && e->vertices != NULL;
        for (i = 0; ok && i <= v.count; ++i)
            head[i] = (size_t)-1;
        for (i = 0; ok && i < keys.count; ++i) {
            size_t j;
            for (j = head[k[3 * i]]; j != (size_t)-1; j = next[j])
                if (k[3 * j + 1] == k[3 * i + 1] && k[3 * j + 2] == k[3 * i + 2])
                    break;
            if (j != (size_t)-1) {
                vertex_of[i] = vertex_of[j];
                continue;
            }
            next[i] = head[k[3 * i]], head[k[3 * i]] = i;
            vertex_of[i] = (unsigned int)e->vertex_count;
            {
                float *out = e->vertices + 8 * e->vertex_count++;
                const float *p = (const float *)v.data + 3 * (k[3 * i] - 1);
                memset(out, 0, ENGINE_STRIDE);
                memcpy(out, p, 3 * sizeof(float));
                if (k[3 * i + 1] != 0)
                    memcpy(out + 3, (const float *)vt.data + 2 * (k[3 * i + 1] - 1), 2 * sizeof(float));
                if (k[3 * i + 2] != 0)
                    memcpy(out + 5, (const float *)vn.data + 3 * (k[3 * i + 2] - 1), 3 * sizeof(float));
            }
        }
        for (i = 0; ok && i < corners.count; ++i)
            ((unsigned int *)corners.data)[i] = vertex_of[((unsigned int *)corners.data)[i]];
        free(vertex_of);
        free(head);
        free(next);
    }
    if (ok) {
        e->indices = (unsigned int *)corners.data, corners.data = NULL;
        e->index_count = corners.count;
        e->by_position = (unsigned int *)by_position.data, by_position.data = NULL;
        e->positions = (float *)v.data, v.data = NULL;
        e->position_count = v.count;
    } else {
        printf("    cannot load %s as an engine would (make test installs assimp-testmodels)\n", path);
        failures++;
        engine_free(e);
    }
    free(v.data), free(vt.data), free(vn.data), free(keys.data), free(corners.data), free(by_position.data);
    return ok;
}
#endif
