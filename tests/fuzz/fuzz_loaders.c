/* libFuzzer target for the example file loaders (examples/meshio.h).
   Byte 0 picks the format (OBJ, OFF, STL, PLY); the rest is the file. A
   file that loads is then repaired, so whatever a loader lets through
   meets the library too. */
#define MESHFIX_IMPLEMENTATION
#include "../../meshfix.h"
#define MESHIO_IMPLEMENTATION
#include "../../examples/meshio.h"

#include <stdint.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static const char *formats[4] = {"obj", "off", "stl", "ply"};
    char error[256];
    mio_mesh mesh;
    meshfix_report report;
    if (size < 1)
        return 0;
    if (mio_parse((const char *)data + 1, size - 1, formats[data[0] % 4], &mesh, error, sizeof(error))) {
        meshfix_orient(mesh.indices, mesh.indices, mesh.index_count, mesh.positions, mesh.vertex_count, 12, NULL,
                       &report, NULL);
        mio_free(&mesh);
    }
    return 0;
}
