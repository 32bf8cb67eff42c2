/* Included for declarations, then twice with the implementation: harmless. */
#include "../../meshfix.h"
#define MESHFIX_IMPLEMENTATION
#include "../../meshfix.h"
#include "../../meshfix.h"

int main(void)
{
    return meshfix_scratch_size(3, 3, 0) == 0;
}
