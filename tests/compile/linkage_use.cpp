// ... and used from C++ through the header alone: the extern "C" block works.
#include "../../meshfix.h"

int main()
{
    unsigned int indices[] = {0, 1, 2};
    return meshfix_check(indices, 3, 0, 3, 0, MESHFIX_REQUIRE_CONSISTENT, NULL, NULL) != 1;
}
