/* Repairs a tetrahedron with one face turned inside out: exactly one flip
   (triangle 3 becomes 1 2 3), after which the mesh is solid. Prints the
   summary line and the header's version; exit status 0 when all holds. */
#include <stdio.h>
#include "meshfix.h"

int consumer_is_consistent(const unsigned int *indices, size_t index_count, const float *positions,
                           size_t vertex_count);

int main(void)
{
    float positions[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
    unsigned int indices[] = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 3, 2};
    unsigned int fixed[12];
    meshfix_report report;
    char line[160];
    meshfix_result r;
    if (consumer_is_consistent(indices, 12, positions, 4)) {
        printf("the turned tetrahedron passed meshfix_check\n");
        return 1;
    }
    r = meshfix_orient(fixed, indices, 12, positions, 4, 0, NULL, &report, NULL);
    if (r != MESHFIX_OK) {
        printf("meshfix_orient: %s\n", meshfix_result_string(r));
        return 1;
    }
    meshfix_summary(&report, line, sizeof(line));
    printf("meshfix %d.%d.%d: %s\n", MESHFIX_VERSION_MAJOR, MESHFIX_VERSION_MINOR, MESHFIX_VERSION_PATCH, line);
    if (report.triangles_flipped != 1 || report.verdict != MESHFIX_VERDICT_REPAIRED || fixed[9] != 1 ||
        fixed[10] != 2 || fixed[11] != 3) {
        printf("expected one flip, triangle 3 = 1 2 3; got %u flips, triangle 3 = %u %u %u\n",
               (unsigned int)report.triangles_flipped, fixed[9], fixed[10], fixed[11]);
        return 1;
    }
    if (!consumer_is_consistent(fixed, 12, positions, 4)) {
        printf("the repaired tetrahedron fails meshfix_check\n");
        return 1;
    }
    return 0;
}
