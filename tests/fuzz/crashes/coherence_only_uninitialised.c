/* Finding 3 (fuzz_stress, MSan): MESHFIX_POLICY_VISIBILITY with
   MESHFIX_VISIBILITY_COHERENCE_ONLY decided patches from memory nobody
   wrote (fixed during the session that found it: the merge's front, back
   and area are set before the verdicts read them). The same call is made
   twice with an allocator that fills fresh blocks with one pattern, then
   with another (each block its own byte, so two arrays never hold the
   same garbage); a correct library gives the same flips both times.

       cc -std=c99 -g -o build/coherence_only tests/fuzz/crashes/coherence_only_uninitialised.c -lm
       build/coherence_only        (exits 0; prints DIFFERENT and exits 1 while the bug is there)

   Built with clang -fsanitize=memory -fsanitize-memory-track-origins=2, the
   third call (default allocator, memory MSan knows is unwritten) reported
   the read in meshfix__visibility_verdicts of a block from
   meshfix__alloc_merge. */
#define MESHFIX_IMPLEMENTATION
#include "../../../meshfix.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static unsigned int fill;

static void *filling_alloc(size_t size, void *user)
{
    void *p = malloc(size);
    (void)user;
    fill = fill * 37u + 11u; /* the next block gets another byte */
    if (p != NULL)
        memset(p, (int)(fill & 0xFFu), size);
    return p;
}

static void filling_free(void *p, void *user)
{
    (void)user;
    free(p);
}

#define N 8 /* an N x N grid of squares, every other row of triangles reversed: open patches */

/* pattern 0: the default allocator (malloc) */
static size_t orient(unsigned int *out, const unsigned int *indices, size_t index_count, const float *positions,
                     size_t vertex_count, unsigned int pattern)
{
    meshfix_options o;
    meshfix_report r;
    memset(&o, 0, sizeof(o));
    o.policy = MESHFIX_POLICY_VISIBILITY;
    o.visibility.flags = MESHFIX_VISIBILITY_COHERENCE_ONLY;
    if (pattern != 0) {
        o.memory.alloc_func = filling_alloc;
        o.memory.free_func = filling_free;
    }
    fill = pattern;
    if (meshfix_orient(out, indices, index_count, positions, vertex_count, 12, &o, &r, NULL) != MESHFIX_OK) {
        printf("orient failed\n");
        exit(2);
    }
    return r.triangles_flipped;
}

int main(void)
{
    static float positions[3 * (N + 1) * (N + 1)];
    static unsigned int indices[6 * N * N], a[6 * N * N], b[6 * N * N], c[6 * N * N];
    size_t x, y, n = 0, fa, fb;
    for (y = 0; y <= N; ++y)
        for (x = 0; x <= N; ++x) {
            float *p = &positions[3 * (y * (N + 1) + x)];
            p[0] = (float)x, p[1] = (float)y, p[2] = 0.1f * (float)((x * 7 + y * 3) % 5);
        }
    for (y = 0; y < N; ++y)
        for (x = 0; x < N; ++x) {
            unsigned int v = (unsigned int)(y * (N + 1) + x), w = v + N + 1;
            int flip = (y % 2) == 1;
            indices[n++] = v, indices[n++] = flip ? w + 1 : v + 1, indices[n++] = flip ? v + 1 : w + 1;
            indices[n++] = v, indices[n++] = flip ? w : w + 1, indices[n++] = flip ? w + 1 : w;
        }
    fa = orient(a, indices, n, positions, (N + 1) * (N + 1), 1);
    fb = orient(b, indices, n, positions, (N + 1) * (N + 1), 2);
    printf("flipped %lu with one garbage pattern, %lu with another: %s\n", (unsigned long)fa, (unsigned long)fb,
           memcmp(a, b, sizeof(a)) == 0 ? "same" : "DIFFERENT");
    orient(c, indices, n, positions, (N + 1) * (N + 1), 0);
    return memcmp(a, b, sizeof(a)) != 0;
}
