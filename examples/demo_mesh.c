/* Writes the demo input: a sphere with 70% of its triangles reversed (its
   first triangle among them, as the plain flood fill's seed) and a torus
   beside it turned completely inside-out, as one OBJ file.
   usage: demo_mesh OUTPUT.obj */
#define MESHFIX_IMPLEMENTATION
#include "../meshfix.h"
#define MESHIO_IMPLEMENTATION
#include "meshio.h"
#define MESHGEN_IMPLEMENTATION
#include "meshgen.h"

#include <stdio.h>

int main(int argc, char **argv)
{
    mio_mesh sphere, torus;
    char error[256];
    size_t t, v, sphere_flipped;
    if (argc != 2) {
        fprintf(stderr, "usage: demo_mesh OUTPUT.obj\n");
        return 1;
    }
    if (!gen_sphere(&sphere, 40, 64, 0, 0, 0, 1) || !gen_torus(&torus, 64, 24, 1.2f, 0.35f))
        return 1;
    sphere_flipped = gen_flip_random(&sphere, 0.7, 2026, NULL);
    if (sphere.indices[1] == 1) { /* triangle 0 is (0, 1, 2): make it one of the reversed */
        sphere.indices[1] = sphere.indices[2];
        sphere.indices[2] = 1;
        sphere_flipped++;
    }
    for (v = 0; v < torus.vertex_count; ++v)
        torus.positions[3 * v] += 3.0f;
    for (t = 0; t < torus.index_count / 3; ++t) {
        unsigned int x = torus.indices[3 * t + 1];
        torus.indices[3 * t + 1] = torus.indices[3 * t + 2];
        torus.indices[3 * t + 2] = x;
    }
    if (!gen_append(&sphere, &torus) || !mio_save(argv[1], &sphere, NULL, error, sizeof(error))) {
        fprintf(stderr, "demo_mesh: %s\n", error);
        return 1;
    }
    printf("wrote %s: a sphere (%lu triangles, %lu of them reversed) and an inside-out torus (%lu triangles)\n",
           argv[1], (unsigned long)(sphere.index_count / 3 - torus.index_count / 3), (unsigned long)sphere_flipped,
           (unsigned long)(torus.index_count / 3));
    mio_free(&sphere);
    mio_free(&torus);
    return 0;
}
