/* Finding 7 (fuzz_stress, session 3): the report counts a triangle as
   without an area that meshfix_check cannot find. A small triangle in
   the patch of a huge one: the report's sums took each corner relative
   to the patch's first vertex, 10^30 away, where the small triangle's
   x coordinates round together and its area to 0; meshfix_check looks
   for a triangle without an area from the positions as given, finds
   none, and its failure names no triangle. Fixed: meshfix__load_triangle
   takes the normal from the positions as given, in the operations of
   meshfix__spans_area.

       cc -std=c99 -g -o build/zero_area_far_origin tests/fuzz/crashes/zero_area_far_origin.c -lm
       build/zero_area_far_origin  (exits 0; 1 while the bug is there) */
#define MESHFIX_IMPLEMENTATION
#include "../../../meshfix.h"

#include <stdio.h>

int main(void)
{
    static const float positions[12] = {1e30f, 0, 0, 0, 0, 0, 0, 1e-3f, 0, 1e-3f, 0, 0};
    static const unsigned int indices[6] = {0, 1, 2, 1, 3, 2};
    meshfix_report r;
    meshfix_check_failure why;
    int passes;
    if (meshfix_inspect(indices, 6, positions, 4, 12, NULL, &r, NULL) != MESHFIX_OK)
        return 2;
    passes = meshfix_check(indices, 6, positions, 4, 12, MESHFIX_REQUIRE_NO_DEGENERATE, NULL, &why);
    printf("report: %lu triangles without an area; check: %s, triangle named %ld (expected 0, passes, -1)\n",
           (unsigned long)r.mesh.triangles_zero_area, passes ? "passes" : "fails", (long)why.triangle);
    return r.mesh.triangles_zero_area == 0 && passes && why.triangle == (size_t)-1 ? 0 : 1;
}
