/* Helpers for the tests that look inside the implementation (include
   after meshfix.h with MESHFIX_IMPLEMENTATION). */
#ifndef MESHFIX_TESTS_INTERNALS_H
#define MESHFIX_TESTS_INTERNALS_H
#include <stdlib.h>
#include <string.h>

/* A mesh bound to scratch of its own (free `block` after), set up as a
   call sets it up (meshfix__call_setup: the options resolved, the input
   described), its input read (the options' topology) and degenerate and
   non-finite triangles marked. */
static unsigned char *bind_mesh(meshfix__mesh *m, const meshfix_options *o, const unsigned int *indices,
                                size_t index_count, const float *positions, size_t vertex_count)
{
    static meshfix_outputs no_outputs;
    meshfix__plan plan;
    meshfix__call call, *kept;
    unsigned char *block, *aligned;
    size_t head = (sizeof(meshfix__call) + 15) / 16 * 16;
    meshfix__call_setup(&call, NULL, indices, index_count, positions, vertex_count, 12, o, -1, NULL, NULL);
    meshfix__make_plan(&plan, vertex_count, index_count / 3, &call.input);
    block = (unsigned char *)malloc(head + plan.total + 16);
    kept = (meshfix__call *)(void *)block; /* m->input and m->options point into it: it lives as long as the block */
    *kept = call;
    aligned = block + head + (16 - (size_t)(block + head) % 16) % 16;
    meshfix__bind(m, aligned, &plan, &kept->input, vertex_count, &kept->options, &no_outputs, 0);
    meshfix__read_input(m, &kept->input, &plan, aligned, 0);
    meshfix__mark_degenerate(m);
    return block;
}

/* An arena of its own for the trees of a mesh of `triangles` in one
   unit, laid out as the library lays out its own, its base on a cache
   line as the library's is (malloc's 16 bytes put every node across five
   lines); free it with free_arena. */
static void make_arena(meshfix__arena *arena, size_t triangles)
{
    meshfix__geometry_counts counts;
    unsigned char *raw;
    size_t skip;
    memset(&counts, 0, sizeof(counts));
    counts.triangles = triangles;
    counts.patches = 1;
    meshfix__plan_geometry(&counts, MESHFIX_POLICY_AUTO, &arena->plan);
    raw = (unsigned char *)malloc(arena->plan.total + MESHFIX__ARENA_ALIGN + sizeof(void *));
    arena->base = NULL;
    if (raw == NULL)
        return;
    skip = sizeof(void *) + (MESHFIX__ARENA_ALIGN - (size_t)(raw + sizeof(void *)) % MESHFIX__ARENA_ALIGN) %
                                MESHFIX__ARENA_ALIGN;
    arena->base = raw + skip;
    memcpy(arena->base - sizeof(void *), &raw, sizeof(void *)); /* where the block starts, for free_arena */
}

/* Frees an arena of make_arena (NULL base: nothing). */
static void free_arena(meshfix__arena *arena)
{
    unsigned char *raw;
    if (arena->base == NULL)
        return;
    memcpy(&raw, arena->base - sizeof(void *), sizeof(void *));
    free(raw);
    arena->base = NULL;
}

/* The slots of every triangle with an area, as one unit, in an arena of
   its own (free_arena(bvh_arena) after); `units` holds a word per
   triangle. Returns 0 when out of memory. */
static int whole_unit(meshfix__bvh *bvh, const meshfix__mesh *m, meshfix__arena *bvh_arena, unsigned int *units)
{
    unsigned int t;
    for (t = 0; t < m->triangle_count; ++t)
        units[t] = meshfix__has_area(m, t) ? 0 : MESHFIX__NONE;
    memset(bvh, 0, sizeof(*bvh));
    make_arena(bvh_arena, m->triangle_count);
    meshfix__fit_frame(bvh, m);
    return meshfix__prepare_bvh(bvh, m, bvh_arena, units, 1);
}

/* The ray tree over that unit, as the library builds it (builder
   MESHFIX__BUILD_AUTO), or by binned SAH (MESHFIX__BUILD_SAH: the
   library's below MESHFIX__MORTON_MIN triangles) or Morton clusters
   (MESHFIX__BUILD_MORTON) whatever its size; returns its root. */
static unsigned int whole_tree_built(meshfix__bvh *bvh, const meshfix__mesh *m, meshfix__arena *bvh_arena,
                                     unsigned int *units, int builder)
{
    if (!whole_unit(bvh, m, bvh_arena, units) || bvh->count == 0)
        return MESHFIX__NONE;
    return meshfix__build_unit_by(bvh, m, 0, NULL, builder);
}

static unsigned int whole_tree(meshfix__bvh *bvh, const meshfix__mesh *m, meshfix__arena *bvh_arena,
                               unsigned int *units)
{
    return whole_tree_built(bvh, m, bvh_arena, units, MESHFIX__BUILD_AUTO);
}
#endif
