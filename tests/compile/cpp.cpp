// The header and implementation as C++ (built as C++98, C++11 and C++17,
// with g++ and clang++): options zero-initialised both ways a C++ user
// writes it. `= {0}` draws -Wmissing-field-initializers under -Wextra in
// C++ (the caller's business, as the README says); the build passes
// -Wno-missing-field-initializers for that one line's sake only.
#define MESHFIX_IMPLEMENTATION
#include "../../meshfix.h"

int main()
{
    unsigned int indices[] = {0, 1, 2, 0, 1, 3};
    meshfix_options empty = {};
    meshfix_options zero = {0};
    meshfix_report report;
    meshfix_result r = meshfix_orient(indices, indices, 6, 0, 4, 0, &empty, &report, NULL);
    if (r != MESHFIX_OK || report.triangles_flipped != 1)
        return 1;
    r = meshfix_orient(indices, indices, 6, 0, 4, 0, &zero, &report, NULL);
    return r != MESHFIX_OK || report.triangles_flipped != 0;
}
