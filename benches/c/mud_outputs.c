/*
 * mud_outputs.c: what a C engine waits for once the default 128² mud run is done, timed from
 * C through the static library: each output with the counts call that sizes its buffers
 * (hibi_mud_network_counts + hibi_mud_network, hibi_mud_cell_counts + hibi_mud_cells), and a
 * 512-pixel-wide height render (hibi_mud_render_params_fit + hibi_mud_render). Prints each
 * pair's median over RUNS calls as a Markdown table, beside the run's own time (create and
 * hibi_mud_step calls of 200 000 units until finished). Built and run by
 * `cargo bench --bench mud_c` (benches/mud_c.rs).
 */
#define _POSIX_C_SOURCE 199309L
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "hibi.h"

#define RUNS 21

static int fail(const char *what, hibi_status status) {
    fprintf(stderr, "%s: %s (status %u)\n", what, hibi_status_string(status), (unsigned)status);
    return 1;
}

static double now_ms(void) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec * 1e3 + (double)t.tv_nsec * 1e-6;
}

static int by_value(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double median(double *times) {
    qsort(times, RUNS, sizeof *times, by_value);
    return times[RUNS / 2];
}

int main(void) {
    hibi_mud_params params = hibi_mud_params_default();
    hibi_mud_progress progress;
    hibi_mud_render_params render;
    hibi_mud *mud = NULL;
    hibi_status status;
    size_t network[3] = {0, 0, 0}, cells[3] = {0, 0, 0}, written[3], i;
    hibi_mud_network_vertex *vertices;
    hibi_mud_network_edge *edges;
    hibi_mud_network_point *points;
    hibi_ring *rings;
    hibi_vec2 *ring_points;
    float *height;
    double start, run_ms, times[3][RUNS], ms[3];

    start = now_ms();
    status = hibi_mud_create(&params, &mud);
    if (status != HIBI_OK) return fail("hibi_mud_create", status);
    do {
        status = hibi_mud_step(mud, 200000u, &progress);
    } while (status == HIBI_OK && !progress.finished);
    if (status != HIBI_OK) return fail("hibi_mud_step", status);
    run_ms = now_ms() - start;

    /* Buffers of the sizes the counts ask for (one more, so that none asks malloc for 0). */
    status = hibi_mud_network_counts(mud, &network[0], &network[1], &network[2]);
    if (status != HIBI_OK) return fail("hibi_mud_network_counts", status);
    status = hibi_mud_cell_counts(mud, &cells[0], &cells[1], &cells[2]);
    if (status != HIBI_OK) return fail("hibi_mud_cell_counts", status);
    status = hibi_mud_render_params_fit(mud, 512u, &render);
    if (status != HIBI_OK) return fail("hibi_mud_render_params_fit", status);
    vertices = malloc((network[0] + 1) * sizeof *vertices);
    edges = malloc((network[1] + 1) * sizeof *edges);
    points = malloc((network[2] + 1) * sizeof *points);
    rings = malloc((cells[0] + 1) * sizeof *rings);
    ring_points = malloc((cells[1] + 1) * sizeof *ring_points);
    height = malloc((size_t)render.width * render.height * sizeof *height);
    if (!vertices || !edges || !points || !rings || !ring_points || !height) return 1;

    for (i = 0; i < RUNS; i++) {
        size_t n[3], c[3];
        hibi_mud_render_params fitted;
        start = now_ms();
        status = hibi_mud_network_counts(mud, &n[0], &n[1], &n[2]);
        if (status == HIBI_OK)
            status = hibi_mud_network(mud, vertices, n[0], edges, n[1], points, n[2], &written[0], &written[1],
                                      &written[2]);
        times[0][i] = now_ms() - start;
        if (status != HIBI_OK) return fail("hibi_mud_network", status);
        start = now_ms();
        status = hibi_mud_cell_counts(mud, &c[0], &c[1], &c[2]);
        if (status == HIBI_OK) status = hibi_mud_cells(mud, rings, c[0], ring_points, c[1], &written[0], &written[1]);
        times[1][i] = now_ms() - start;
        if (status != HIBI_OK) return fail("hibi_mud_cells", status);
        start = now_ms();
        status = hibi_mud_render_params_fit(mud, 512u, &fitted);
        if (status == HIBI_OK)
            status = hibi_mud_render(mud, &fitted, HIBI_MUD_LAYER_HEIGHT, height,
                                     (size_t)fitted.width * fitted.height);
        times[2][i] = now_ms() - start;
        if (status != HIBI_OK) return fail("hibi_mud_render", status);
    }
    for (i = 0; i < 3; i++) ms[i] = median(times[i]);

    printf("| 128² default run, from C (median of %d calls) | time | ÷ the run |\n", RUNS);
    printf("|---|---|---|\n");
    printf("| the run: `hibi_mud_create`, `hibi_mud_step` (200 000 units a call) to the end | %.1f ms | 1× |\n",
           run_ms);
    printf("| `hibi_mud_network_counts` + `hibi_mud_network` (%lu vertices, %lu edges, %lu points) | %.2f ms | "
           "%.3f× |\n",
           (unsigned long)network[0], (unsigned long)network[1], (unsigned long)network[2], ms[0], ms[0] / run_ms);
    printf("| `hibi_mud_cell_counts` + `hibi_mud_cells` (%lu rings, %lu points) | %.2f ms | %.3f× |\n",
           (unsigned long)cells[0], (unsigned long)cells[1], ms[1], ms[1] / run_ms);
    printf("| `hibi_mud_render_params_fit` + `hibi_mud_render`, height %lu × %lu | %.2f ms | %.3f× |\n",
           (unsigned long)render.width, (unsigned long)render.height, ms[2], ms[2] / run_ms);

    free(vertices);
    free(edges);
    free(points);
    free(rings);
    free(ring_points);
    free(height);
    hibi_mud_destroy(mud);
    return 0;
}
