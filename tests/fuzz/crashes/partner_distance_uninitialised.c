/* Finding 5 (fuzz_stress, MSan): the coherence stage reads the distance
   of a boundary segment whose own partner search was skipped.
   meshfix__edge_segment sets a segment's partner (NONE) and matched, not
   its distance; meshfix__find_partners skips a segment whose search box
   (its cells widened by `reach`) fails meshfix__cells_usable (more than
   16 cells along an axis) before it writes the distance; the segment is
   still in the grid (meshfix__grid_pass files it at its ends and middle),
   so a neighbour can choose it, and meshfix__pair_partners then reads
   f->distance. Here the model is 1 long and the cell is reach = 0.02 (the
   tiny triangles keep the average edge below it); the long edge of the
   first triangle spans 17 cells with the margin, and the short edge just
   below its middle picks it.

       clang -std=c99 -g -fsanitize=memory -fsanitize-memory-track-origins=2 \
           -o build/partner_distance tests/fuzz/crashes/partner_distance_uninitialised.c -lm
       build/partner_distance      (MSan: use-of-uninitialized-value in meshfix__pair_partners) */
#define MESHFIX_IMPLEMENTATION
#include "../../../meshfix.h"

#include <stdio.h>

#define TINY 60

int main(void)
{
    static float p[3 * (6 + 3 * TINY)];
    static unsigned int idx[3 * (2 + TINY)];
    unsigned int v = 0, n = 0, i;
    meshfix_options o = {0};
    meshfix_report r;
    meshfix_result result;
    /* a long thin triangle: its edge along x covers cells 0 .. 15 */
    static const float tri[18] = {0, 0, 0, 0.31f, 0, 0, 0.155f, 0.05f, 0,
                                  /* a short one just below its middle: another patch, within reach */
                                  0.145f, -0.005f, 0, 0.155f, -0.01f, 0, 0.165f, -0.005f, 0};
    for (i = 0; i < 18; ++i)
        p[i] = tri[i];
    for (i = 0; i < 6; ++i)
        idx[n++] = v++;
    for (i = 0; i < TINY; ++i) { /* tiny triangles up to x = 1: the box, and a small average edge */
        float x = 0.4f + 0.6f * (float)i / (TINY - 1);
        float q[9] = {x, 0.5f, 0, x + 0.001f, 0.5f, 0, x, 0.501f, 0};
        unsigned int k;
        for (k = 0; k < 9; ++k)
            p[3 * v + k] = q[k];
        idx[n++] = v, idx[n++] = v + 1, idx[n++] = v + 2;
        v += 3;
    }
    o.policy = MESHFIX_POLICY_VISIBILITY;
    o.visibility_rays = 2000;
    result = meshfix_orient(idx, idx, n, p, v, 12, &o, &r);
    printf("result %d, %lu patch pairs\n", (int)result, (unsigned long)r.patch_pairs);
    return 0;
}
