/* Finding 2 (fuzz_stress, UBSan): the strides of
   options.evidence.triangle_normals and vertex_normals were not
   validated. With stride 13 the normals were read as misaligned floats
   (undefined behaviour; UBSan: "load of misaligned address" in
   meshfix__is_finite_point called from meshfix__authored_normal) and the
   call succeeded, where a positions stride that is not a multiple of 4
   (or below 12) is refused with MESHFIX_ERROR_INVALID_ARGUMENT. Also
   checked: stride 0, documented as 12 bytes, behaves as 12 (an earlier
   state of the rewrite used it as 0, giving every triangle the first
   triangle's normal). Two separate triangles wound +z; the caller's
   normals say +z for the first and -z for the second, so
   MESHFIX_POLICY_NORMALS flips the second. Fixed in 0.2:
   meshfix__options_valid refuses a normals stride that is not 0 or a
   multiple of 4 of at least 12.

       cc -std=c99 -g -fsanitize=undefined -o build/normals_stride tests/fuzz/crashes/normals_stride.c -lm
       build/normals_stride        (exits 0; UBSan reports and it exits 1 while stride 13 is accepted) */
#define MESHFIX_IMPLEMENTATION
#include "../../../meshfix.h"

#include <stdio.h>
#include <string.h>

static int flipped_second(const float *normals, size_t stride, meshfix_result *result)
{
    static const unsigned int indices[6] = {0, 1, 2, 3, 4, 5};
    static const float positions[18] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 5, 0, 0, 6, 0, 0, 5, 1, 0};
    unsigned int out[6];
    meshfix_options o;
    meshfix_report r;
    memset(&o, 0, sizeof(o));
    o.policy = MESHFIX_POLICY_NORMALS;
    o.evidence.triangle_normals = normals;
    o.evidence.triangle_normals_stride = stride;
    *result = meshfix_orient(out, indices, 6, positions, 6, 12, &o, &r, NULL);
    return *result == MESHFIX_OK && out[4] == 5;
}

int main(void)
{
    static const float packed[6] = {0, 0, 1, 0, 0, -1};
    unsigned char bytes[32];
    meshfix_result r12, r0, r13;
    int with_12 = flipped_second(packed, 12, &r12), with_0 = flipped_second(packed, 0, &r0);
    /* the same two normals 13 bytes apart */
    memset(bytes, 0, sizeof(bytes));
    memcpy(bytes + 1, packed, 12);
    memcpy(bytes + 14, packed + 3, 12);
    flipped_second((const float *)(const void *)(bytes + 1), 13, &r13);
    printf("stride 12: second triangle %s\n", with_12 ? "flipped" : "kept");
    printf("stride 0 (documented as 12): second triangle %s\n", with_0 ? "flipped" : "kept");
    printf("stride 13: result %d (%s)\n", (int)r13, meshfix_result_string(r13));
    return with_12 != with_0 || r13 == MESHFIX_OK;
}
