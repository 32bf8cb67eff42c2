/* The one file that holds the implementation. */
#define MESHFIX_IMPLEMENTATION
#include "meshfix.h"
