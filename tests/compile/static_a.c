/* MESHFIX_STATIC in two translation units linked together: no clashes. */
#define MESHFIX_STATIC
#define MESHFIX_IMPLEMENTATION
#include "../../meshfix.h"

int static_b_call(void);

int main(void)
{
    return meshfix_scratch_size(3, 3, 0) == 0 || static_b_call() != 0;
}
