/* The header and implementation as strict C89: -std=c89 -pedantic -Werror. */
#define MESHFIX_IMPLEMENTATION
#include "../../meshfix.h"

int main(void)
{
    static const unsigned int indices[] = {0, 1, 2};
    meshfix_report report;
    return meshfix_inspect(indices, 3, 0, 3, 0, NULL, &report, NULL) != MESHFIX_OK || report.mesh.edges_boundary != 3;
}
