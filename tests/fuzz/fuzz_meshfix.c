/* libFuzzer target for every public entry point of meshfix.h.

   Byte 0 picks the call: inspect, orient under each policy (SDF with a
   cheap function), weld, check. Byte 1 picks how many vertices (1..64)
   and whether positions come from a small integer grid (mostly
   non-manifold, degenerate and coincident meshes) or straight from the
   input as raw floats (NaN, Inf, huge, denormal). The rest are indices:
   one byte each modulo the vertex count, or, with bit 7 of byte 1, raw
   32-bit values (out of range, 0xFFFFFFFF). Every call must return a
   status without crashing, reading or writing out of bounds, or leaking. */
#define MESHFIX_IMPLEMENTATION
#include "../../meshfix.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

static float cheap_sdf(const float p[3], void *user)
{
    (void)user;
    return sqrtf(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]) - 2.0f;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    float positions[64 * 3];
    unsigned int indices[600], out[600];
    unsigned char flipped[200];
    unsigned int patch_ids[200], remap[64];
    float confidence[200];
    meshfix_component components[4];
    meshfix_options o;
    meshfix_outputs outputs;
    meshfix_report r;
    size_t vertices, count = 0, i;
    int call, raw_floats, raw_indices;
    if (size < 2)
        return 0;
    call = data[0] % 10;
    vertices = 1 + (data[1] & 63);
    raw_floats = (data[1] & 64) != 0;
    raw_indices = (data[1] & 128) != 0;
    data += 2, size -= 2;
    for (i = 0; i < 3 * vertices; ++i) {
        if (raw_floats && size >= 4) {
            memcpy(&positions[i], data, 4);
            data += 4, size -= 4;
        } else {
            positions[i] = (float)((i * 7 + (i / 3) * 13) % 5);
        }
    }
    while (count < 600 && size > 0) {
        if (raw_indices && size >= 4) {
            memcpy(&indices[count++], data, 4);
            data += 4, size -= 4;
        } else {
            indices[count++] = data[0] % (unsigned)vertices;
            data += 1, size -= 1;
        }
    }
    memset(&o, 0, sizeof(o));
    memset(&outputs, 0, sizeof(outputs));
    o.sdf.distance = cheap_sdf;
    o.visibility.rays = 256;
    outputs.flipped = flipped;
    outputs.patch_ids = patch_ids;
    outputs.patch_confidence = confidence;
    outputs.patch_confidence_capacity = 200;
    outputs.components = components;
    outputs.components_capacity = 4;
    switch (call) {
    case 0:
        meshfix_inspect(indices, count, positions, vertices, 12, &o, &r, &outputs);
        break;
    case 7:
        meshfix_weld(remap, positions, vertices, 12, raw_floats ? 0.5f : 0.0f, NULL, &i);
        break;
    case 8:
        meshfix_check(indices, count, positions, vertices, 12, MESHFIX_REQUIRE_SOLID, NULL, NULL);
        break;
    case 9: /* without positions */
        meshfix_orient(out, indices, count, NULL, vertices, 0, &o, &r, &outputs);
        break;
    default: {
        static const meshfix_policy policies[6] = {MESHFIX_POLICY_AUTO, MESHFIX_POLICY_OUTWARD,
                                                   MESHFIX_POLICY_VISIBILITY, MESHFIX_POLICY_SDF,
                                                   MESHFIX_POLICY_UP, MESHFIX_POLICY_MAJORITY};
        o.policy = policies[call - 1];
        if (meshfix_orient(out, indices, count, positions, vertices, 12, &o, &r, &outputs) == MESHFIX_OK && count % 3 == 0) {
            /* the output is a reordering of each input triangle's corners */
            for (i = 0; i < count; i += 3)
                if (out[i] != indices[i])
                    abort();
        }
    }
    }
    return 0;
}
