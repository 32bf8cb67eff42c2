/* meshfix command-line tool: the implementations of meshfix.h and of the
   examples' loaders (STL corners, the --mark and conversion writers),
   compiled as C99. */
#define _POSIX_C_SOURCE 200809L
#define _FILE_OFFSET_BITS 64 /* stat and read files over 2 GiB on 32-bit systems */
#define MESHFIX_IMPLEMENTATION
#include "../../meshfix.h"
#define MESHIO_IMPLEMENTATION
#include "../../examples/meshio.h"
