/*
 * glass.c: model B (a glass plate hit by a ball, Agui et al.) from C99. Grows the cracks of
 * one impact on the paper's 640 x 640 plate, prints what the impact drew, writes the crack
 * mask as a PGM, takes the fragments as polygons (what a physics engine needs), and grows the
 * same plate in caller memory to show the same bytes come out.
 *
 *   cc -std=c99 -Wall -Wextra -Wpedantic -Werror -Iinclude c_examples/glass.c \
 *      target/release/libhibi.a -lpthread -ldl -lm -o glass && ./glass glass.pgm
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hibi.h"

static int fail(const char *what, hibi_status status) {
    fprintf(stderr, "%s: %s (status %u)\n", what, hibi_status_string(status), (unsigned)status);
    return 1;
}

static hibi_status grow(hibi_glass *glass, hibi_glass_progress *progress) {
    hibi_status status;
    do {
        status = hibi_glass_step(glass, 100u, progress);
    } while (status == HIBI_OK && !progress->finished);
    return status;
}

int main(int argc, char **argv) {
    const char *path = argc > 1 ? argv[1] : "glass.pgm";
    hibi_glass_params params = hibi_glass_params_default();
    hibi_glass_render_params render = hibi_glass_render_params_default();
    hibi_glass_progress progress;
    hibi_glass_counts counts;
    hibi_glass_crack crack;
    hibi_glass *glass = NULL, *placed = NULL;
    hibi_status status;
    size_t cracks = 0, bytes = 0, i, large_at_edge = 0, large = 0;
    size_t pixels = (size_t)render.width * render.height;
    size_t ring_count = 0, point_count = 0, holes = 0, scratch_size = 0;
    void *scratch;
    hibi_ring *rings;
    hibi_vec2 *points;
    double area = 0.0;
    unsigned char *mask, *again;
    void *memory;
    FILE *file;

    params.seed = 7;
    params.impact[0] = 700.0f; /* outside the 640-pixel plate */
    status = hibi_glass_create(&params, &glass);
    printf("impact outside the plate: status %u, %s\n", (unsigned)status, hibi_status_string(status));
    params.impact[0] = 320.0f;

    status = hibi_glass_create(&params, &glass);
    if (status != HIBI_OK) return fail("hibi_glass_create", status);
    status = grow(glass, &progress);
    if (status != HIBI_OK) return fail("hibi_glass_step", status);
    status = hibi_glass_crack_count(glass, &cracks);
    if (status != HIBI_OK) return fail("hibi_glass_crack_count", status);
    for (i = 0; i < cracks; i++) {
        status = hibi_glass_crack_info(glass, i, &crack);
        if (status != HIBI_OK) return fail("hibi_glass_crack_info", status);
        if (crack.kind == HIBI_GLASS_KIND_LARGE) {
            large++;
            if (crack.end == HIBI_GLASS_END_EDGE) large_at_edge++;
        }
    }
    printf("finished after %u steps: %lu cracks, %lu large, %lu of them at the edge\n", (unsigned)progress.time,
           (unsigned long)cracks, (unsigned long)large, (unsigned long)large_at_edge);
    status = hibi_glass_crack_info(glass, cracks, &crack);
    printf("crack index past the end: status %u, %s\n", (unsigned)status, hibi_status_string(status));

    mask = malloc(pixels);
    again = malloc(pixels);
    if (mask == NULL || again == NULL) return 1;
    status = hibi_glass_render(glass, &render, HIBI_GLASS_LAYER_MASK, mask, pixels);
    if (status != HIBI_OK) return fail("hibi_glass_render", status);
    file = fopen(path, "wb");
    if (file == NULL) {
        perror(path);
        return 1;
    }
    fprintf(file, "P5\n%u %u\n255\n", (unsigned)render.width, (unsigned)render.height);
    for (i = 0; i < pixels; i++) fputc(255 - mask[i], file);
    fclose(file);
    printf("wrote %s\n", path);

    /* The fragments: ask for the counts, then hand buffers that fit. The queries only read the
       plate; they work in scratch memory of the caller's. */
    status = hibi_glass_scratch_size(glass, &scratch_size);
    if (status != HIBI_OK) return fail("hibi_glass_scratch_size", status);
    scratch = malloc(scratch_size); /* malloc's alignment suffices (hibi_glass_memory_align(): 8) */
    if (scratch == NULL) return 1;
    status = hibi_glass_fragment_counts(glass, scratch, scratch_size, &ring_count, &point_count);
    if (status != HIBI_OK) return fail("hibi_glass_fragment_counts", status);
    rings = malloc(ring_count * sizeof *rings);
    points = malloc(point_count * sizeof *points);
    if (rings == NULL || points == NULL) return 1;
    status = hibi_glass_fragments(glass, scratch, scratch_size, rings, ring_count, points, point_count - 1,
                                  &ring_count, &point_count);
    printf("fragments into a short buffer: status %u, %s\n", (unsigned)status, hibi_status_string(status));
    status = hibi_glass_fragments(glass, scratch, scratch_size, rings, ring_count, points, point_count,
                                  &ring_count, &point_count);
    if (status != HIBI_OK) return fail("hibi_glass_fragments", status);
    for (i = 0; i < ring_count; i++) {
        area += rings[i].area; /* holes count negative */
        if (rings[i].hole_of != HIBI_RING_NOT_A_HOLE) holes++;
    }
    printf("fragments: %lu, holes: %lu, points: %lu, covering %.1f of %.1f square pixels\n",
           (unsigned long)(ring_count - holes), (unsigned long)holes, (unsigned long)point_count, area,
           (double)params.width * params.height);
    free(scratch);
    free(rings);
    free(points);

    /* A second impact: its cracks stop where they meet the first's. */
    status = hibi_glass_impact(glass, 160.0f, 480.0f, &counts);
    if (status != HIBI_OK) return fail("hibi_glass_impact", status);
    status = grow(glass, &progress);
    if (status != HIBI_OK) return fail("hibi_glass_step", status);
    printf("second impact drew M %u, N %u, R %u\n", (unsigned)counts.radial, (unsigned)counts.large,
           (unsigned)counts.rings);
    hibi_glass_destroy(glass);

    /* The same plate in caller memory. */
    status = hibi_glass_memory_size(&params, &bytes);
    if (status != HIBI_OK) return fail("hibi_glass_memory_size", status);
    memory = malloc(bytes);
    if (memory == NULL) return 1;
    status = hibi_glass_create_in(&params, memory, bytes, &placed);
    if (status != HIBI_OK) return fail("hibi_glass_create_in", status);
    status = grow(placed, &progress);
    if (status != HIBI_OK) return fail("hibi_glass_step", status);
    status = hibi_glass_render(placed, &render, HIBI_GLASS_LAYER_MASK, again, pixels);
    if (status != HIBI_OK) return fail("hibi_glass_render", status);
    printf("caller memory, same bytes: %s\n", memcmp(mask, again, pixels) == 0 ? "yes" : "no");
    hibi_glass_destroy(placed);
    free(memory);
    free(mask);
    free(again);
    return 0;
}
