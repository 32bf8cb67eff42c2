// The header and implementation as C++ (built as C++98 and C++17).
#define MESHFIX_IMPLEMENTATION
#include "../../meshfix.h"

int main()
{
    unsigned int indices[] = {0, 1, 2, 0, 1, 3};
    meshfix_report report;
    meshfix_result r = meshfix_orient(indices, indices, 6, 0, 4, 0, 0, &report, NULL);
    return r != MESHFIX_OK || report.triangles_flipped != 1;
}
