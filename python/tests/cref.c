/* The C side of the Python tests: runs one meshfix.h call on raw arrays
   that the test wrote, prints every report field as key=value lines and
   writes the output arrays, so test_meshfix.py compares the binding with
   the library itself on the same bytes. Built from the header by the test.

   cref MODE key=value...   MODE: orient, inspect, check, weld
     indices=FILE index_size=2|4 positions=FILE position_size=4|8
     vertex_count=N (with no positions file) policy=N topology=N
     weld_tolerance=X requirements=N tolerance=X (weld)
     triangle_normals=FILE vertex_normals=FILE (float32 x y z)
     out=FILE: orient: destination indices, flipped (a byte per triangle),
     patch ids (uint32); inspect: patch ids; weld: remap (uint32). */
#define MESHFIX_IMPLEMENTATION
#include "meshfix.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void *slurp(const char *path, size_t *size)
{
    FILE *f = fopen(path, "rb");
    void *data;
    long n;
    if (f == NULL || fseek(f, 0, SEEK_END) != 0 || (n = ftell(f)) < 0 || fseek(f, 0, SEEK_SET) != 0) {
        fprintf(stderr, "cref: cannot read %s\n", path);
        exit(2);
    }
    data = malloc((size_t)n + 1);
    if (data == NULL || fread(data, 1, (size_t)n, f) != (size_t)n) {
        fprintf(stderr, "cref: cannot read %s\n", path);
        exit(2);
    }
    fclose(f);
    *size = (size_t)n;
    return data;
}

static void spill(FILE *f, const void *data, size_t size)
{
    if (size != 0 && fwrite(data, 1, size, f) != size) {
        fprintf(stderr, "cref: cannot write\n");
        exit(2);
    }
}

#define SIZE(prefix, s, field) printf("%s%s=%lu\n", prefix, #field, (unsigned long)(s)->field);
#define REAL(prefix, s, field) printf("%s%s=%.17g\n", prefix, #field, (s)->field);

static void print_report(const meshfix_report *r)
{
    char line[512];
    const meshfix_mesh_facts *m = &r->mesh;
    const meshfix_evidence_counts *e = &r->evidence;
    meshfix_summary(r, line, sizeof(line));
    printf("verdict=%d\nsummary=%s\n", (int)r->verdict, line);
    SIZE("", r, triangles_flipped) SIZE("", r, patches_flipped) SIZE("", r, patches_doubtful)
    SIZE("", r, triangles_doubtful) REAL("", r, area_doubtful) SIZE("", r, edges_inconsistent_before)
    printf("verdict_before=%d\n", (int)r->verdict_before);
    SIZE("", r, patches_inside_out_before) REAL("", r, signed_volume_before)
    SIZE("mesh.", m, triangles) SIZE("mesh.", m, triangles_degenerate) SIZE("mesh.", m, triangles_zero_area)
    SIZE("mesh.", m, triangles_duplicate) SIZE("mesh.", m, vertices_used) SIZE("mesh.", m, vertices_joined)
    SIZE("mesh.", m, vertices_non_finite) SIZE("mesh.", m, vertices_non_manifold) SIZE("mesh.", m, edges)
    SIZE("mesh.", m, edges_boundary) SIZE("mesh.", m, edges_manifold) SIZE("mesh.", m, edges_non_manifold)
    SIZE("mesh.", m, edges_inconsistent) SIZE("mesh.", m, patches) SIZE("mesh.", m, patches_closed)
    SIZE("mesh.", m, patches_inside_out) SIZE("mesh.", m, components) SIZE("mesh.", m, components_closed)
    SIZE("mesh.", m, components_non_orientable)
    printf("mesh.euler_characteristic=%ld\n", m->euler_characteristic);
    REAL("mesh.", m, area) REAL("mesh.", m, signed_volume)
    SIZE("evidence.", e, patches_by_volume) SIZE("evidence.", e, patches_by_parity)
    SIZE("evidence.", e, patches_by_visibility) SIZE("evidence.", e, patches_by_normals)
    SIZE("evidence.", e, patches_kept) SIZE("evidence.", e, shells_inward) SIZE("evidence.", e, rays_cast)
    SIZE("evidence.", e, patch_pairs) SIZE("evidence.", e, patches_merged) SIZE("evidence.", e, pairs_conflicting)
    SIZE("evidence.", e, sdf_evaluations) SIZE("evidence.", e, triangles_sdf_disagree)
    SIZE("evidence.", e, triangles_against_normals)
}

int main(int argc, char **argv)
{
    const char *mode = argc > 1 ? argv[1] : "";
    const char *indices_path = NULL, *positions_path = NULL, *out_path = NULL;
    const char *triangle_normals_path = NULL, *vertex_normals_path = NULL;
    unsigned int requirements = 0;
    float tolerance = 0.0f;
    size_t vertex_count = 0, index_bytes = 0, position_bytes = 0, normal_bytes = 0, index_count, triangles;
    void *indices = NULL, *positions = NULL;
    meshfix_options o;
    meshfix_report report;
    meshfix_result r;
    FILE *out = NULL;
    int i;
    memset(&o, 0, sizeof(o));
    for (i = 2; i < argc; ++i) {
        char *value = strchr(argv[i], '=');
        if (value == NULL) {
            fprintf(stderr, "cref: %s is not key=value\n", argv[i]);
            return 2;
        }
        *value++ = '\0';
        if (strcmp(argv[i], "indices") == 0) indices_path = value;
        else if (strcmp(argv[i], "positions") == 0) positions_path = value;
        else if (strcmp(argv[i], "out") == 0) out_path = value;
        else if (strcmp(argv[i], "index_size") == 0) o.index_size = (unsigned int)atoi(value);
        else if (strcmp(argv[i], "position_size") == 0) o.position_size = (unsigned int)atoi(value);
        else if (strcmp(argv[i], "vertex_count") == 0) vertex_count = (size_t)strtoul(value, NULL, 10);
        else if (strcmp(argv[i], "policy") == 0) o.policy = (meshfix_policy)atoi(value);
        else if (strcmp(argv[i], "topology") == 0) o.topology = (meshfix_topology)atoi(value);
        else if (strcmp(argv[i], "weld_tolerance") == 0) o.weld_tolerance = (float)atof(value);
        else if (strcmp(argv[i], "requirements") == 0) requirements = (unsigned int)atoi(value);
        else if (strcmp(argv[i], "tolerance") == 0) tolerance = (float)atof(value);
        else if (strcmp(argv[i], "triangle_normals") == 0) triangle_normals_path = value;
        else if (strcmp(argv[i], "vertex_normals") == 0) vertex_normals_path = value;
        else {
            fprintf(stderr, "cref: unknown key %s\n", argv[i]);
            return 2;
        }
    }
    if (indices_path != NULL)
        indices = slurp(indices_path, &index_bytes);
    if (positions_path != NULL) {
        positions = slurp(positions_path, &position_bytes);
        vertex_count = position_bytes / (3 * (o.position_size == 8 ? 8 : 4));
    }
    if (triangle_normals_path != NULL)
        o.evidence.triangle_normals = (const float *)slurp(triangle_normals_path, &normal_bytes);
    if (vertex_normals_path != NULL)
        o.evidence.vertex_normals = (const float *)slurp(vertex_normals_path, &normal_bytes);
    index_count = index_bytes / (o.index_size == 2 ? 2 : 4);
    triangles = index_count / 3;
    if (out_path != NULL && (out = fopen(out_path, "wb")) == NULL) {
        fprintf(stderr, "cref: cannot write %s\n", out_path);
        return 2;
    }

    if (strcmp(mode, "orient") == 0 || strcmp(mode, "inspect") == 0) {
        void *destination = malloc(index_bytes + 1);
        unsigned char *flipped = (unsigned char *)malloc(triangles + 1);
        unsigned int *patch_ids = (unsigned int *)malloc(4 * triangles + 1);
        meshfix_outputs outputs;
        memset(&outputs, 0, sizeof(outputs));
        outputs.patch_ids = patch_ids;
        if (mode[0] == 'o') {
            outputs.flipped = flipped;
            r = meshfix_orient(destination, indices, index_count, positions, vertex_count, 0, &o, &report, &outputs);
        } else {
            r = meshfix_inspect(indices, index_count, positions, vertex_count, 0, &o, &report, &outputs);
        }
        printf("result=%d\n", (int)r);
        if (r != MESHFIX_OK)
            return 0;
        print_report(&report);
        if (out != NULL) {
            if (mode[0] == 'o') {
                spill(out, destination, index_bytes);
                spill(out, flipped, triangles);
            }
            spill(out, patch_ids, 4 * triangles);
        }
    } else if (strcmp(mode, "check") == 0) {
        meshfix_check_failure why;
        int ok = meshfix_check(indices, index_count, positions, vertex_count, 0, requirements, &o, &why);
        printf("ok=%d\nresult=%d\nrequirement=%u\ncount=%lu\ntriangle=%ld\nedge=%u %u\ntext=%s\n", ok,
               (int)why.result, why.requirement, (unsigned long)why.count,
               why.triangle == (size_t)-1 ? -1L : (long)why.triangle, why.edge[0], why.edge[1], why.text);
    } else if (strcmp(mode, "weld") == 0) {
        unsigned int *remap = (unsigned int *)malloc(4 * vertex_count + 1);
        size_t unique = 0;
        r = meshfix_weld(remap, positions, vertex_count, 0, tolerance, &o, &unique);
        printf("result=%d\nunique=%lu\n", (int)r, (unsigned long)unique);
        if (r == MESHFIX_OK && out != NULL)
            spill(out, remap, 4 * vertex_count);
    } else {
        fprintf(stderr, "cref: MODE is orient, inspect, check or weld\n");
        return 2;
    }
    if (out != NULL)
        fclose(out);
    return 0;
}
