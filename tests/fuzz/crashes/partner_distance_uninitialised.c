/* Finding 5 (fuzz_stress, MSan): the coherence stage read the distance
   of a boundary segment whose own partner search was skipped.
   meshfix__edge_segment sets a segment's partner (NONE) and matched, not
   its distance; meshfix__find_partners skipped a segment whose search box
   (its cells widened by `reach`) fails meshfix__cells_usable (more than
   16 cells along an axis) before it wrote the distance; the segment is
   still in the grid (meshfix__grid_pass files it at its ends and middle),
   so a neighbour can choose it, and meshfix__pair_partners then read
   f->distance. Here the model is 1 long and the cell is reach = 0.02 (the
   tiny triangles keep the average edge below it); the long edge of the
   first triangle spans 17 cells with the margin, and the short edge just
   below its middle picks it. Fixed in 0.2: meshfix__find_partners sets
   the distance to `reach` before it decides to skip the search.

   The call is made with an allocator that fills every fresh block with
   one byte, then another: a read of the unwritten distance gives
   different pairs (report.evidence.patch_pairs) and flips.

       cc -std=c99 -g -o build/partner_distance tests/fuzz/crashes/partner_distance_uninitialised.c -lm
       build/partner_distance      (exits 0; prints DIFFERENT and exits 1 while the bug is there)
       clang -std=c99 -g -fsanitize=memory -fsanitize-memory-track-origins=2 \
           -o build/partner_distance tests/fuzz/crashes/partner_distance_uninitialised.c -lm
       build/partner_distance      (MSan: use-of-uninitialized-value in meshfix__pair_partners
                                    while the bug is there) */
#define MESHFIX_IMPLEMENTATION
#include "../../../meshfix.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define TINY 60

static int garbage;

static void *filling_alloc(size_t size, void *user)
{
    void *p = malloc(size);
    (void)user;
    if (p != NULL)
        memset(p, garbage, size);
    return p;
}

static void filling_free(void *p, void *user)
{
    (void)user;
    free(p);
}

static float p[3 * (6 + 3 * TINY)];
static unsigned int idx[3 * (2 + TINY)];

/* garbage < 0: the default allocator (what MSan watches) */
static size_t orient(unsigned int *out, size_t n, size_t v, int fill, size_t *pairs)
{
    meshfix_options o = {0};
    meshfix_report r;
    meshfix_result result;
    o.policy = MESHFIX_POLICY_VISIBILITY;
    o.visibility.rays = 2000;
    if (fill >= 0) {
        o.memory.alloc_func = filling_alloc;
        o.memory.free_func = filling_free;
        garbage = fill;
    }
    result = meshfix_orient(out, idx, n, p, v, 12, &o, &r, NULL);
    if (result != MESHFIX_OK) {
        printf("orient failed: %s\n", meshfix_result_string(result));
        exit(2);
    }
    *pairs = r.evidence.patch_pairs;
    return r.triangles_flipped;
}

int main(void)
{
    static unsigned int a[3 * (2 + TINY)], b[3 * (2 + TINY)], c[3 * (2 + TINY)];
    unsigned int v = 0, n = 0, i;
    size_t pairs[3], flips[3];
    int different = 0, fill;
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
    /* distances from garbage: 0x00 bytes read as 0.0, 0x7F as about 1e304,
       0xFF as NaN; the default allocator last (for MSan) */
    flips[0] = orient(a, n, v, 0x00, &pairs[0]);
    for (fill = 0x7F; fill <= 0xFF; fill += 0x80) {
        flips[1] = orient(b, n, v, fill, &pairs[1]);
        different |= pairs[1] != pairs[0] || memcmp(a, b, sizeof(a)) != 0;
    }
    flips[2] = orient(c, n, v, -1, &pairs[2]);
    different |= pairs[2] != pairs[0] || memcmp(a, c, sizeof(a)) != 0;
    printf("patch pairs %lu / %lu / %lu, flips %lu / %lu / %lu: %s\n", (unsigned long)pairs[0],
           (unsigned long)pairs[1], (unsigned long)pairs[2], (unsigned long)flips[0], (unsigned long)flips[1],
           (unsigned long)flips[2], different ? "DIFFERENT" : "same");
    return different;
}
