/* The implementation compiled as C ... */
#define MESHFIX_IMPLEMENTATION
#include "../../meshfix.h"
