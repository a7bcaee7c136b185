/*
 * mud.c: model A (drying mud, Hirota et al.) from C99. Runs a simulation in library memory,
 * step by step as an engine would spread it over frames, fetches its crack network (a plane
 * graph) and its cells (polygons), writes the crack mask as a PGM, and runs it again in
 * caller memory to show the two give the same bytes.
 *
 *   cc -std=c99 -Wall -Wextra -Wpedantic -Werror -Iinclude c_examples/mud.c \
 *      target/release/libhibi.a -lpthread -ldl -lm -o mud && ./mud mud.pgm
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hibi.h"

#define SIZE 96u
#define PIXELS (4u * SIZE)
#define UNTOUCHED ((size_t)12345)

static int fail(const char *what, hibi_status status) {
    fprintf(stderr, "%s: %s (status %u)\n", what, hibi_status_string(status), (unsigned)status);
    return 1;
}

/* Fetches the crack network into buffers of the size hibi_mud_network_counts asks for;
 * returns 0 on success. */
static int network(const hibi_mud *mud) {
    size_t counts[3] = {0, 0, 0}, written[3] = {0, 0, 0};
    hibi_mud_network_vertex *vertices;
    hibi_mud_network_edge *edges;
    hibi_mud_network_point *points;
    hibi_status status = hibi_mud_network_counts(mud, &counts[0], &counts[1], &counts[2]);
    if (status != HIBI_OK) return fail("hibi_mud_network_counts", status);
    /* One more than needed, so that no count asks malloc for 0 bytes. */
    vertices = malloc((counts[0] + 1) * sizeof *vertices);
    edges = malloc((counts[1] + 1) * sizeof *edges);
    points = malloc((counts[2] + 1) * sizeof *points);
    status = HIBI_OK;
    if (vertices != NULL && edges != NULL && points != NULL) {
        status = hibi_mud_network(mud, vertices, counts[0], edges, counts[1], points, counts[2], &written[0],
                                  &written[1], &written[2]);
        if (status == HIBI_OK) {
            printf("network: %lu vertices, %lu edges, %lu points\n", (unsigned long)written[0],
                   (unsigned long)written[1], (unsigned long)written[2]);
        }
    }
    free(vertices);
    free(edges);
    free(points);
    if (vertices == NULL || edges == NULL || points == NULL) return 1;
    return status == HIBI_OK ? 0 : fail("hibi_mud_network", status);
}

/* Fetches the cells, first into a ring buffer one too short (an error that writes nothing);
 * returns 0 on success. */
static int cells(const hibi_mud *mud) {
    size_t ring_count = 0, point_count = 0, wrapping = 0, i;
    size_t rings_written = UNTOUCHED, points_written = UNTOUCHED;
    int untouched = 1;
    double area = 0.0;
    hibi_ring *rings;
    hibi_vec2 *points;
    hibi_status status = hibi_mud_cell_counts(mud, &ring_count, &point_count, &wrapping);
    if (status != HIBI_OK) return fail("hibi_mud_cell_counts", status);
    rings = calloc(ring_count + 1, sizeof *rings); /* zeroed: point_count 0 in every ring */
    points = calloc(point_count + 1, sizeof *points);
    if (rings == NULL || points == NULL) {
        free(rings);
        free(points);
        return 1;
    }
    if (ring_count > 0) {
        status = hibi_mud_cells(mud, rings, ring_count - 1, points, point_count, &rings_written, &points_written);
        for (i = 0; i < ring_count; i++) untouched &= rings[i].point_count == 0;
        untouched &= rings_written == UNTOUCHED && points_written == UNTOUCHED;
        printf("cells into a short buffer: status %u, %s; nothing written: %s\n", (unsigned)status,
               hibi_status_string(status), untouched ? "yes" : "no");
    }
    status = hibi_mud_cells(mud, rings, ring_count, points, point_count, &rings_written, &points_written);
    if (status == HIBI_OK) {
        for (i = 0; i < rings_written; i++) area += rings[i].area;
        printf("cells: %lu rings, %lu points, area %.1f\n", (unsigned long)rings_written,
               (unsigned long)points_written, area);
    }
    free(rings);
    free(points);
    return status == HIBI_OK ? 0 : fail("hibi_mud_cells", status);
}

/* Runs to the end, a budget of work per call; returns the final progress. */
static hibi_status run(hibi_mud *mud, hibi_mud_progress *progress) {
    unsigned calls = 0;
    hibi_status status;
    do {
        status = hibi_mud_step(mud, 200000u, progress);
        calls++;
    } while (status == HIBI_OK && !progress->finished);
    printf("steps: %u calls\n", calls);
    return status;
}

int main(int argc, char **argv) {
    const char *path = argc > 1 ? argv[1] : "mud.pgm";
    hibi_mud_params params = hibi_mud_params_default();
    hibi_mud_params bad;
    hibi_mud_render_params render = hibi_mud_render_params_default();
    hibi_mud_progress progress;
    hibi_mud_crack_statistics statistics;
    hibi_mud *mud = NULL, *placed = NULL;
    hibi_status status;
    size_t segments = 0, bytes = 0, i;
    unsigned char *mask, *again;
    void *memory;
    FILE *file;

    params.columns = SIZE;
    params.rows = SIZE;
    params.seed = 7;

    /* Bad input is a status naming the field; nothing is created. */
    bad = params;
    bad.young_modulus = -1.0f;
    status = hibi_mud_create(&bad, &mud);
    printf("negative young_modulus: status %u, %s\n", (unsigned)status, hibi_status_string(status));
    memset(&bad, 0, sizeof bad);
    status = hibi_mud_create(&bad, &mud);
    printf("params not from the default: status %u, %s\n", (unsigned)status, hibi_status_string(status));

    status = hibi_mud_create(&params, &mud);
    if (status != HIBI_OK) return fail("hibi_mud_create", status);
    status = run(mud, &progress);
    if (status != HIBI_OK) return fail("hibi_mud_step", status);
    printf("finished: shrink %.4f, time %.1f long steps, %u springs broken\n", progress.shrink, progress.time,
           (unsigned)progress.broken_springs);
    status = hibi_mud_segment_count(mud, &segments);
    if (status != HIBI_OK) return fail("hibi_mud_segment_count", status);
    printf("segments: %lu\n", (unsigned long)segments);
    status = hibi_mud_statistics(mud, &statistics);
    if (status != HIBI_OK) return fail("hibi_mud_statistics", status);
    printf("cells: %u, mean cell area %.1f cm^2, crack density %.3f /cm\n", (unsigned)statistics.cells,
           statistics.mean_cell_area, statistics.crack_density);
    if (network(mud) != 0 || cells(mud) != 0) return 1;

    render.width = PIXELS;
    render.height = PIXELS;
    mask = malloc(PIXELS * PIXELS);
    again = malloc(PIXELS * PIXELS);
    if (mask == NULL || again == NULL) return 1;
    status = hibi_mud_render(mud, &render, HIBI_MUD_LAYER_MASK, mask, PIXELS * PIXELS - 1);
    printf("short pixel buffer: status %u, %s\n", (unsigned)status, hibi_status_string(status));
    status = hibi_mud_render(mud, &render, HIBI_MUD_LAYER_MASK, mask, PIXELS * PIXELS);
    if (status != HIBI_OK) return fail("hibi_mud_render", status);

    file = fopen(path, "wb");
    if (file == NULL) {
        perror(path);
        return 1;
    }
    fprintf(file, "P5\n%u %u\n255\n", PIXELS, PIXELS);
    for (i = 0; i < (size_t)PIXELS * PIXELS; i++) fputc(255 - mask[i], file); /* dark cracks on light mud */
    fclose(file);
    printf("wrote %s\n", path);
    hibi_mud_destroy(mud);

    /* The same run in caller memory. */
    status = hibi_mud_memory_size(&params, &bytes);
    if (status != HIBI_OK) return fail("hibi_mud_memory_size", status);
    memory = malloc(bytes); /* malloc's alignment covers hibi_mud_memory_align() */
    if (memory == NULL) return 1;
    status = hibi_mud_create_in(&params, memory, bytes, &placed);
    if (status != HIBI_OK) return fail("hibi_mud_create_in", status);
    status = run(placed, &progress);
    if (status != HIBI_OK) return fail("hibi_mud_step", status);
    status = hibi_mud_render(placed, &render, HIBI_MUD_LAYER_MASK, again, PIXELS * PIXELS);
    if (status != HIBI_OK) return fail("hibi_mud_render", status);
    printf("caller memory, same bytes: %s\n", memcmp(mask, again, PIXELS * PIXELS) == 0 ? "yes" : "no");
    hibi_mud_destroy(placed);
    free(memory);
    free(mask);
    free(again);
    return 0;
}
