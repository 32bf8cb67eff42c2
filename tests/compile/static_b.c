#define MESHFIX_STATIC
#define MESHFIX_IMPLEMENTATION
#include "../../meshfix.h"

int static_b_call(void);

int static_b_call(void)
{
    static const unsigned int indices[] = {0, 1, 2};
    meshfix_report report;
    return (int)meshfix_inspect(indices, 3, 0, 3, 0, NULL, &report, NULL);
}
