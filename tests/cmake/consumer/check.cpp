// A C++ unit calling the C implementation (extern "C" linkage).
#include "meshfix.h"

extern "C" int consumer_is_consistent(const unsigned int *indices, size_t index_count, const float *positions,
                                      size_t vertex_count)
{
    meshfix_check_failure why;
    return meshfix_check(indices, index_count, positions, vertex_count, 0, MESHFIX_REQUIRE_SOLID, nullptr, &why);
}
