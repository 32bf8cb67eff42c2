/* sdf_demo - meshes an SDF scene, scrambles its winding, repairs it with
   meshfix's SDF policy, and prints the reports before and after.

   usage: sdf_demo [OUTPUT.obj]

   The scene: a sphere smoothly blended into a box, and above them a thin
   plate 0.02 thick, meshed by marching tetrahedra (examples/sdfmesh.h)
   with cells of 0.1, five times thicker than the plate. */
#define MESHFIX_IMPLEMENTATION
#include "../meshfix.h"
#define MESHIO_IMPLEMENTATION
#include "meshio.h"
#define MESHGEN_IMPLEMENTATION
#include "meshgen.h"
#define SDFMESH_IMPLEMENTATION
#include "sdfmesh.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static float scene(const float p[3], void *user)
{
    float sphere, box, plate, q[3], h, k = 0.25f;
    (void)user;
    sphere = sqrtf((p[0] + 0.5f) * (p[0] + 0.5f) + p[1] * p[1] + p[2] * p[2]) - 0.7f;
    q[0] = p[0] - 0.45f, q[1] = p[1], q[2] = p[2];
    box = sdf_box(q, NULL);
    h = fmaxf(k - fabsf(sphere - box), 0.0f) / k;
    q[0] = p[0], q[1] = p[1], q[2] = p[2] - 1.1f; /* z = 1.1 is a grid plane: inside the plate */
    plate = sdf_thin_box(q, NULL);
    return fminf(fminf(sphere, box) - h * h * k * 0.25f, plate);
}

static void print_report(const char *title, const meshfix_report *r)
{
    printf("%s\n", title);
    printf("  triangles %lu, components %lu, Euler characteristic %ld\n", (unsigned long)r->mesh.triangles,
           (unsigned long)r->mesh.components, r->mesh.euler_characteristic);
    printf("  edges %lu: manifold %lu, boundary %lu, inconsistent %lu\n", (unsigned long)r->mesh.edges,
           (unsigned long)r->mesh.edges_manifold, (unsigned long)r->mesh.edges_boundary, (unsigned long)r->mesh.edges_inconsistent);
    printf("  closed patches %lu, inside-out %lu, signed volume %.4f\n", (unsigned long)r->mesh.patches_closed,
           (unsigned long)r->mesh.patches_inside_out, r->mesh.signed_volume);
}

int main(int argc, char **argv)
{
    const float cell = 0.1f, low[3] = {-1.4f + 0.0123f, -1.4f + 0.0171f, -1.4f};
    const unsigned n[3] = {28, 28, 28};
    mio_mesh mesh;
    meshfix_options options;
    meshfix_report before, after;
    meshfix_result r;
    size_t scrambled;
    char error[256];

    if (!sdfmesh_tetra(&mesh, scene, NULL, low, cell, n)) {
        fprintf(stderr, "sdf_demo: out of memory\n");
        return 1;
    }
    scrambled = gen_flip_random(&mesh, 0.4, 2026, NULL);
    printf("meshed the scene with marching tetrahedra (cells %.2f) and reversed %lu of %lu triangles\n\n", cell,
           (unsigned long)scrambled, (unsigned long)(mesh.index_count / 3));
    meshfix_inspect(mesh.indices, mesh.index_count, mesh.positions, mesh.vertex_count, 12, NULL, &before, NULL);
    print_report("before", &before);

    memset(&options, 0, sizeof(options));
    options.policy = MESHFIX_POLICY_SDF;
    options.sdf.distance = scene; /* the gradient comes from central differences */
    r = meshfix_orient(mesh.indices, mesh.indices, mesh.index_count, mesh.positions, mesh.vertex_count, 12,
                       &options, &after, NULL);
    if (r != MESHFIX_OK) {
        fprintf(stderr, "sdf_demo: %s\n", meshfix_result_string(r));
        return 2;
    }
    printf("\nrepair (policy sdf, per patch): flipped %lu triangles with %lu SDF evaluations; "
           "%lu triangles' own gradient vote disagreed with their patch\n\n",
           (unsigned long)after.triangles_flipped, (unsigned long)after.evidence.sdf_evaluations,
           (unsigned long)after.evidence.triangles_sdf_disagree);
    print_report("after", &after);
    if (argc > 1 && !mio_save(argv[1], &mesh, NULL, error, sizeof(error))) {
        fprintf(stderr, "sdf_demo: %s\n", error);
        return 1;
    }
    mio_free(&mesh);
    return after.mesh.edges_inconsistent == 0 && after.mesh.patches_inside_out == 0 ? 0 : 3;
}
