/* Finding 1 (fuzz_stress): patches land in the wrong component.
   Two separate fans, three triangles on one edge each: six patches (no
   manifold edge), two components of three triangles, Euler
   characteristic 1 each (discs). With the bug, meshfix reported
   components of 5 and 1 triangles and a total Euler characteristic of 4.
   Fixed in 0.2 (meshfix__join_components renumbers in two passes).

       cc -std=c99 -g -o build/two_fans tests/fuzz/crashes/components_two_fans.c -lm
       build/two_fans              (exits 0; 1 while the bug is there) */
#define MESHFIX_IMPLEMENTATION
#include "../../../meshfix.h"

#include <stdio.h>

int main(void)
{
    static const unsigned int indices[18] = {0, 1, 2, 0, 1, 3, 0, 1, 4, 5, 6, 7, 5, 6, 8, 5, 6, 9};
    meshfix_component c[4];
    meshfix_outputs out = {0};
    meshfix_report r;
    size_t i;
    int wrong;
    out.components = c, out.components_capacity = 4;
    if (meshfix_inspect(indices, 18, NULL, 10, 0, NULL, &r, &out) != MESHFIX_OK)
        return 2;
    printf("patches %lu, components %lu, Euler characteristic %ld (expected 6, 2, 2)\n", (unsigned long)r.mesh.patches,
           (unsigned long)r.mesh.components, r.mesh.euler_characteristic);
    for (i = 0; i < r.mesh.components && i < 4; ++i)
        printf("  component %lu: first triangle %lu, %lu triangles, %lu patches, %lu vertices (expected 3 and 5)\n",
               (unsigned long)i, (unsigned long)c[i].first_triangle, (unsigned long)c[i].triangles,
               (unsigned long)c[i].patches, (unsigned long)c[i].vertices);
    wrong = r.mesh.components != 2 || r.mesh.euler_characteristic != 2 || c[0].triangles != 3 || c[1].triangles != 3;
    printf("%s\n", wrong ? "WRONG" : "ok");
    return wrong;
}
