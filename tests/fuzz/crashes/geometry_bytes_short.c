/* Finding 6 (fuzz_stress): the geometry arena was sized too small for
   MESHFIX_POLICY_VISIBILITY, so a plain quad failed.
   meshfix__geometry_bytes counts the merge's visibility arrays as one
   array of 3 * patches doubles (`meshfix__add_size(&total, vis, 3 *
   sizeof(double), &at)`), but meshfix__alloc_merge takes front, back and
   area as three arrays, each aligned to 16 bytes: for an odd patch count
   that is 16 bytes more than counted. The last take of the stage (the
   coherence grid's items in meshfix__index_segments) then does not fit:
   with assertions (MESHFIX_DEBUG, on unless NDEBUG) "Assertion `fits'
   failed" in meshfix__take; with -DNDEBUG the take returns NULL and the
   call returns MESHFIX_ERROR_OUT_OF_MEMORY although no allocation failed.

       cc -std=c99 -g -o build/geometry_bytes tests/fuzz/crashes/geometry_bytes_short.c -lm
       build/geometry_bytes        (exits 0; aborts while the bug is there)
       cc -std=c99 -g -DNDEBUG -o build/geometry_bytes tests/fuzz/crashes/geometry_bytes_short.c -lm
       build/geometry_bytes        (exits 0; prints "out of memory" and exits 1 while the bug is there)
   Fixed in 0.2: the arena has MESHFIX__ARENA_SLACK (64 bytes) and its
   count lists the arrays as the stage takes them. The merge's three
   visibility arrays are still counted as one array of 3 * patches
   doubles (16 bytes short for an odd patch count), which the slack
   covers. */
#define MESHFIX_IMPLEMENTATION
#include "../../../meshfix.h"

#include <stdio.h>

static int run(const char *what, meshfix_policy policy, const unsigned int *indices, size_t index_count,
               const float *positions, size_t vertex_count)
{
    unsigned int out[6];
    meshfix_options o = {0};
    meshfix_report r;
    meshfix_result result;
    o.policy = policy;
    o.visibility.rays = 2000;
    result = meshfix_orient(out, indices, index_count, positions, vertex_count, 12, &o, &r, NULL);
    printf("%s: %s\n", what, meshfix_result_string(result));
    return result != MESHFIX_OK;
}

int main(void)
{
    /* one quad: two triangles, one patch, four boundary edges (from
       fuzz_stress; aborted with the header of 08:17, sha256 452ebb24...) */
    static const unsigned int quad[6] = {0, 3, 1, 0, 3, 2};
    static const float quad_positions[12] = {0, 0, 0x1.ff911cp+127f, 1, 0, 0x1.ff07f8p+127f,
                                             0, 1, -0x1.fface4p+127f, 1, 1, 0x1.ff3ad2p+127f};
    /* one triangle under AUTO (from fuzz_meshfix's corpus; aborted in
       meshfix__decide_by_shells with the header of 08:26, sha256 c3396123...) */
    static const unsigned int triangle[3] = {0, 1, 2};
    static const float triangle_positions[9] = {0, 2, 4, 4, 1, 3, 3, 0, 2};
    int failed = run("VISIBILITY on a quad near FLT_MAX", MESHFIX_POLICY_VISIBILITY, quad, 6, quad_positions, 4);
    failed |= run("AUTO on one triangle", MESHFIX_POLICY_AUTO, triangle, 3, triangle_positions, 3);
    return failed;
}
