/* native_orient.c - meshfix.h built natively, as the reference for the
   JavaScript tests: the same meshes, the same options, and the flips and
   report must come out the same as from the WebAssembly build.

       native_orient IN OUT

   IN holds meshes one after another, little-endian:
       u32 index_count, u32 vertex_count, u32 policy_length, u32 has_normals,
       the policy's name (policy_length bytes, as meshfix_policy_from_string
       takes it), u32 indices[index_count], f32 positions[3 * vertex_count],
       f32 normals[3 * vertex_count] when has_normals (vertex normals, as evidence).
   OUT gets, per mesh:
       i32 status, f64 values[REPORT_VALUES] (the fields named below),
       u32 summary_length, summary bytes, u8 flipped[index_count / 3]. */
#define MESHFIX_IMPLEMENTATION
#include "meshfix.h"

#include <stdio.h>
#include <stdlib.h>

#define REPORT_VALUES 14
/* verdict, trianglesFlipped, patchesFlipped, patchesDoubtful, trianglesDoubtful,
   edgesInconsistentBefore, mesh.patches, mesh.edgesInconsistent, mesh.components,
   evidence.patchesByVolume, evidence.patchesByNormals, evidence.patchesKept,
   verdictBefore, patchesInsideOutBefore */

static int read_u32(FILE *f, unsigned int *v)
{
    unsigned char b[4];
    if (fread(b, 1, 4, f) != 4)
        return 0;
    *v = (unsigned int)b[0] | (unsigned int)b[1] << 8 | (unsigned int)b[2] << 16 | (unsigned int)b[3] << 24;
    return 1;
}

int main(int argc, char **argv)
{
    FILE *in, *out;
    unsigned int index_count, vertex_count, policy_length, has_normals;
    int meshes = 0;
    if (argc != 3) {
        fprintf(stderr, "usage: native_orient IN OUT\n");
        return 2;
    }
    in = fopen(argv[1], "rb");
    out = fopen(argv[2], "wb");
    if (in == NULL || out == NULL) {
        fprintf(stderr, "native_orient: cannot open %s or %s\n", argv[1], argv[2]);
        return 2;
    }
    while (read_u32(in, &index_count)) {
        unsigned int *indices;
        float *positions, *normals = NULL;
        unsigned char *flipped;
        meshfix_options options = {0};
        meshfix_outputs outputs = {0};
        meshfix_report report;
        char summary[512], policy[32];
        double values[REPORT_VALUES] = {0};
        unsigned int length;
        int status;
        size_t triangles;
        if (!read_u32(in, &vertex_count) || !read_u32(in, &policy_length) || !read_u32(in, &has_normals) ||
            policy_length >= sizeof(policy) || fread(policy, 1, policy_length, in) != policy_length)
            return 3;
        policy[policy_length] = 0;
        options.policy = meshfix_policy_from_string(policy);
        if (options.policy == MESHFIX_POLICY_COUNT) {
            fprintf(stderr, "native_orient: no policy \"%s\"\n", policy);
            return 3;
        }
        triangles = index_count / 3;
        indices = (unsigned int *)malloc((size_t)index_count * 4 + 4);
        positions = (float *)malloc((size_t)vertex_count * 12 + 12);
        flipped = (unsigned char *)calloc(triangles + 1, 1);
        if (has_normals)
            normals = (float *)malloc((size_t)vertex_count * 12 + 12);
        if (indices == NULL || positions == NULL || flipped == NULL || (has_normals && normals == NULL))
            return 4;
        /* the test machine is little-endian, as WebAssembly is */
        if (fread(indices, 4, index_count, in) != index_count ||
            fread(positions, 12, vertex_count, in) != vertex_count ||
            (has_normals && fread(normals, 12, vertex_count, in) != vertex_count))
            return 3;
        options.evidence.vertex_normals = normals;
        outputs.flipped = flipped;
        status = (int)meshfix_orient(indices, indices, index_count, positions, vertex_count, 0, &options, &report,
                                     &outputs);
        summary[0] = 0;
        if (status == MESHFIX_OK) {
            values[0] = (double)report.verdict;
            values[1] = (double)report.triangles_flipped;
            values[2] = (double)report.patches_flipped;
            values[3] = (double)report.patches_doubtful;
            values[4] = (double)report.triangles_doubtful;
            values[5] = (double)report.edges_inconsistent_before;
            values[6] = (double)report.mesh.patches;
            values[7] = (double)report.mesh.edges_inconsistent;
            values[8] = (double)report.mesh.components;
            values[9] = (double)report.evidence.patches_by_volume;
            values[10] = (double)report.evidence.patches_by_normals;
            values[11] = (double)report.evidence.patches_kept;
            values[12] = (double)report.verdict_before;
            values[13] = (double)report.patches_inside_out_before;
            meshfix_summary(&report, summary, sizeof(summary));
        }
        length = (unsigned int)strlen(summary);
        fwrite(&status, 4, 1, out);
        fwrite(values, 8, REPORT_VALUES, out);
        fwrite(&length, 4, 1, out);
        fwrite(summary, 1, length, out);
        fwrite(flipped, 1, triangles, out);
        free(indices);
        free(positions);
        free(normals);
        free(flipped);
        ++meshes;
    }
    fclose(in);
    return fclose(out) == 0 && meshes >= 0 ? 0 : 5;
}
