/* Finding 4 (fuzz_stress): options.evidence.sigma and min_confidence
   were not validated. sigma = +Infinity was accepted (it passes the `> 0`
   test that picks the default for 0, NaN and negative values), and a
   patch decided without evidence then got patch_confidence NaN, where the
   header promises 0 .. 1: meshfix__weigh computed
   u->weight * sigma * u->error = 0 * Inf = NaN for both bounds, and
   meshfix__verdict_from_weights passed the NaN through maxd / mind.
   A tetrahedron under MAJORITY is enough. Fixed in 0.2:
   meshfix__options_valid refuses a sigma outside 0 .. 1e6 and a
   min_confidence outside 0 .. 1 (MESHFIX_ERROR_INVALID_ARGUMENT).

       cc -std=c99 -g -o build/evidence_sigma tests/fuzz/crashes/evidence_sigma_infinite.c -lm
       build/evidence_sigma        (exits 0; 1 while the bug is there) */
#define MESHFIX_IMPLEMENTATION
#include "../../../meshfix.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

int main(void)
{
    static const unsigned int indices[12] = {0, 1, 2, 0, 3, 1, 0, 2, 3, 1, 3, 2};
    static const float positions[12] = {1, 1, 1, 1, -1, -1, -1, 1, -1, -1, -1, 1};
    unsigned int out[12];
    float confidence[1] = {-1.0f};
    meshfix_options o;
    meshfix_outputs outputs;
    meshfix_report r;
    meshfix_result result;
    memset(&o, 0, sizeof(o));
    memset(&outputs, 0, sizeof(outputs));
    o.policy = MESHFIX_POLICY_MAJORITY;
    o.evidence.sigma = INFINITY;
    outputs.patch_confidence = confidence;
    outputs.patch_confidence_capacity = 1;
    result = meshfix_orient(out, indices, 12, positions, 4, 12, &o, &r, &outputs);
    printf("evidence.sigma = inf: result %d (%s), patch_confidence[0] = %g\n", (int)result,
           meshfix_result_string(result), (double)confidence[0]);
    /* either refused, or a confidence within 0 .. 1 */
    return result == MESHFIX_OK && !(confidence[0] >= 0.0f && confidence[0] <= 1.0f);
}
