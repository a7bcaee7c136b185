/*
 * A case the property tests found: on a periodic lattice whose only crack is one closed
 * loop, the region around the island wraps around the torus and has no outline. Its boundary
 * (the island's, walked from outside) must be a hole in a wrapping cell
 * (HIBI_MUD_IN_WRAPPING_CELL), not a ring with a negative area and hole_of =
 * HIBI_RING_NOT_A_HOLE, the mark of an outer ring; and the statistics must count two cells,
 * not one of mean area zero less its island.
 */
#include <stdio.h>

#include "hibi.h"

int main(void) {
    hibi_mud_params params = hibi_mud_params_default();
    hibi_mud *mud = NULL;
    hibi_mud_progress progress;
    hibi_ring rings[8];
    hibi_vec2 points[256];
    hibi_mud_crack_statistics stats;
    size_t ring_count = 0, point_count = 0, wrapping = 0, rings_written = 0, points_written = 0, i;
    params.topology = HIBI_MUD_SQUARE;
    params.boundary = HIBI_MUD_PERIODIC;
    params.solver = HIBI_MUD_QUASI_STATIC;
    params.columns = 12;
    params.rows = 12;
    params.seed = 3;
    params.layer_thickness = 0.5f;
    params.element_size = 0.5168934f;
    params.shrink_ratio = 0.99f;
    params.young_modulus = 1193037.8f;
    params.shear_modulus = 369243.03f;
    params.density = 1.0f;
    params.break_stretch_mean = 1.102564f;
    params.break_stretch_spread = 0.029327579f;
    params.break_stretch_size_exponent = 0.8583656f;
    params.anisotropy_direction = -2.7145653f;
    params.anisotropy_ratio = 1.1981164f;
    params.target_shrink = 0.10066851f;
    if (hibi_mud_create(&params, &mud) != HIBI_OK) {
        printf("create failed\n");
        return 1;
    }
    do {
        if (hibi_mud_step(mud, 100000, &progress) != HIBI_OK) {
            printf("step failed\n");
            return 1;
        }
    } while (!progress.finished);
    if (hibi_mud_cell_counts(mud, &ring_count, &point_count, &wrapping) != HIBI_OK || ring_count > 8 ||
        point_count > 256 ||
        hibi_mud_cells(mud, rings, 8, points, 256, &rings_written, &points_written) != HIBI_OK ||
        hibi_mud_statistics(mud, &stats) != HIBI_OK) {
        printf("outputs failed\n");
        return 1;
    }
    printf("rings %u, wrapping %u\n", (unsigned)rings_written, (unsigned)wrapping);
    for (i = 0; i < rings_written; i++) {
        const char *kind = rings[i].hole_of == HIBI_RING_NOT_A_HOLE      ? "outer"
                           : rings[i].hole_of == HIBI_MUD_IN_WRAPPING_CELL ? "hole in a wrapping cell"
                                                                           : "hole in a ring";
        printf("ring %u: %s, area %s\n", (unsigned)i, kind, rings[i].area > 0.0 ? "positive" : "negative");
    }
    printf("cells %u, mean area %s\n", (unsigned)stats.cells, stats.mean_cell_area > 0.0f ? "positive" : "not positive");
    hibi_mud_destroy(mud);
    return 0;
}
