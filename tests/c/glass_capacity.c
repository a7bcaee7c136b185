/*
 * After hibi_glass_step reports HIBI_ERROR_GLASS_CAPACITY, the plate stays usable: fragments,
 * cracks, points and the render all work (no HIBI_ERROR_PANIC), and nothing is printed on
 * stderr (the test checks).
 */
#include <stdio.h>
#include <stdlib.h>

#include "hibi.h"

static void plate(unsigned max_vertices, unsigned max_cracks, unsigned long seed) {
    hibi_glass_params params = hibi_glass_params_default();
    hibi_glass_render_params render = hibi_glass_render_params_default();
    hibi_glass *glass = NULL;
    hibi_glass_progress progress;
    hibi_status status = HIBI_OK, first = HIBI_OK;
    size_t rings = 0, points = 0, rings_written = 0, points_written = 0, cracks = 0, i, scratch_size = 0;
    void *scratch = NULL;
    hibi_ring *ring_buffer;
    hibi_vec2 *point_buffer;
    unsigned char *mask;
    double area = 0.0;
    int steps = 0;
    params.max_vertices = max_vertices;
    params.max_cracks = max_cracks;
    params.seed = seed;
    if (hibi_glass_create(&params, &glass) != HIBI_OK) {
        printf("create failed\n");
        return;
    }
    do {
        status = hibi_glass_step(glass, 50, &progress);
    } while (status == HIBI_OK && !progress.finished && ++steps < 100000);
    /* Stepping on after the capacity ran out keeps saying so. */
    first = status;
    status = hibi_glass_step(glass, 50, NULL);
    printf("max_vertices %u, max_cracks %u, seed %lu: step %u then %u", max_vertices, max_cracks, seed,
           (unsigned)first, (unsigned)status);
    if (hibi_glass_scratch_size(glass, &scratch_size) != HIBI_OK || (scratch = malloc(scratch_size)) == NULL) abort();
    status = hibi_glass_fragment_counts(glass, scratch, scratch_size, &rings, &points);
    printf(", fragment_counts %u", (unsigned)status);
    ring_buffer = malloc((rings + 1) * sizeof *ring_buffer);
    point_buffer = malloc((points + 1) * sizeof *point_buffer);
    mask = malloc((size_t)render.width * render.height);
    if (ring_buffer == NULL || point_buffer == NULL || mask == NULL) abort();
    status = hibi_glass_fragments(glass, scratch, scratch_size, ring_buffer, rings, point_buffer, points,
                                  &rings_written, &points_written);
    for (i = 0; i < rings_written; i++) area += ring_buffer[i].area;
    printf(", fragments %u covering %.1f", (unsigned)status, area);
    status = hibi_glass_crack_count(glass, &cracks);
    for (i = 0; status == HIBI_OK && i < cracks; i++) {
        hibi_glass_crack crack;
        hibi_glass_point point_list[64];
        size_t written = 0;
        status = hibi_glass_crack_info(glass, i, &crack);
        if (status == HIBI_OK && crack.points <= 64) {
            status = hibi_glass_points(glass, i, point_list, 64, &written);
        }
    }
    printf(", cracks %u", (unsigned)status);
    status = hibi_glass_render(glass, &render, HIBI_GLASS_LAYER_MASK, mask, (size_t)render.width * render.height);
    printf(", render %u\n", (unsigned)status);
    free(scratch);
    free(ring_buffer);
    free(point_buffer);
    free(mask);
    hibi_glass_destroy(glass);
}

int main(void) {
    unsigned long seed;
    for (seed = 1; seed <= 4; seed++) {
        plate(2, 512, seed);
        plate(3, 2, seed);
        plate(40, 7, seed);
    }
    return 0;
}
