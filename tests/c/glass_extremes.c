/*
 * Model B at the ends of its parameters' ranges, one line per case:
 * - a plate wider than 65536 px (width 1e15, 1e20) is refused by name, HIBI_ERROR_GLASS_SIZE,
 *   and nothing is created; the fragments of the widest valid plate cover it;
 * - radial cracks of 1e8 to 1e30 px a step (seeds 1 to 10): the fragments' signed areas
 *   (outer rings positive, holes negative) add up to the plate's, relative error at most 1e-4;
 * - large cracks of 1e-30 to 1e-5 px a step: generation finishes within 1e9 units of work, at
 *   the time limit (32768 steps), and the fragments cover the plate.
 * Each run is stepped with a budget and given up past 1e9 units, so a run that would not end
 * prints "finished 0".
 */
#include <stdio.h>
#include <stdlib.h>

#include "hibi.h"

#define MOST_WORK 1000000000ull

/* Runs the plate to the end of generation (or past MOST_WORK units) and prints the status of
 * the last call, whether it finished, and, when `timed`, its time steps and whether its work
 * stayed within MOST_WORK; then whether the fragments' areas add up to width * height. */
static void run(const char *what, const hibi_glass_params *params, int timed) {
    hibi_glass *glass = NULL;
    hibi_glass_progress progress = {0};
    hibi_status status = hibi_glass_create(params, &glass);
    size_t scratch_size = 0, rings = 0, points = 0, rings_written = 0, points_written = 0, i;
    void *scratch = NULL;
    hibi_ring *ring_buffer = NULL;
    hibi_vec2 *point_buffer = NULL;
    double area = 0.0, plate = (double)params->width * (double)params->height, error;
    int covered = 0;
    while (status == HIBI_OK && !progress.finished && progress.work <= MOST_WORK) {
        status = hibi_glass_step(glass, 1000000, &progress);
    }
    printf("%s: status %u, finished %u", what, (unsigned)status, (unsigned)progress.finished);
    if (timed) {
        printf(", time %u, work within 1e9: %s", (unsigned)progress.time, progress.work <= MOST_WORK ? "yes" : "no");
    }
    if (status == HIBI_OK && hibi_glass_scratch_size(glass, &scratch_size) == HIBI_OK &&
        (scratch = malloc(scratch_size)) != NULL &&
        hibi_glass_fragment_counts(glass, scratch, scratch_size, &rings, &points) == HIBI_OK &&
        (ring_buffer = malloc((rings + 1) * sizeof *ring_buffer)) != NULL &&
        (point_buffer = malloc((points + 1) * sizeof *point_buffer)) != NULL &&
        hibi_glass_fragments(glass, scratch, scratch_size, ring_buffer, rings, point_buffer, points, &rings_written,
                             &points_written) == HIBI_OK) {
        for (i = 0; i < rings_written; i++) area += ring_buffer[i].area;
        error = area > plate ? area - plate : plate - area;
        covered = error <= 1e-4 * plate;
    }
    printf(", areas sum to the plate: %s\n", covered ? "yes" : "no");
    free(scratch);
    free(ring_buffer);
    free(point_buffer);
    hibi_glass_destroy(glass);
}

/* A plate `width` wide: refused with its status and nothing created, or run. */
static void width(float value, float impact_x) {
    hibi_glass_params params = hibi_glass_params_default();
    hibi_glass *glass = NULL;
    size_t size = 777;
    hibi_status sized, created;
    char what[64];
    params.width = value;
    params.impact[0] = impact_x;
    sized = hibi_glass_memory_size(&params, &size);
    created = hibi_glass_create(&params, &glass);
    snprintf(what, sizeof what, "width %g", (double)value);
    if (created != HIBI_OK) {
        printf("%s: status %u and %u, %s, nothing created: %s\n", what, (unsigned)sized, (unsigned)created,
               hibi_status_string(created), size == 777 && glass == NULL ? "yes" : "no");
        return;
    }
    hibi_glass_destroy(glass);
    run(what, &params, 0);
}

int main(void) {
    static const float radial_speeds[] = {1e8f, 1e10f, 1e20f, 1e30f};
    static const float large_speeds[] = {1e-30f, 1e-20f, 1e-6f, 1e-5f};
    char what[64];
    size_t k;
    unsigned long seed;
    width(1e15f, 320.0f);
    width(1e20f, 320.0f);
    width(65536.0f, 65536.0f - 320.0f);
    for (k = 0; k < sizeof radial_speeds / sizeof radial_speeds[0]; k++) {
        for (seed = 1; seed <= 10; seed++) {
            hibi_glass_params params = hibi_glass_params_default();
            params.radial_speed = radial_speeds[k];
            params.seed = seed;
            snprintf(what, sizeof what, "radial_speed %g seed %lu", (double)radial_speeds[k], seed);
            run(what, &params, 0);
        }
    }
    for (k = 0; k < sizeof large_speeds / sizeof large_speeds[0]; k++) {
        hibi_glass_params params = hibi_glass_params_default();
        params.large_speed = large_speeds[k];
        snprintf(what, sizeof what, "large_speed %g", (double)large_speeds[k]);
        run(what, &params, 1);
    }
    return 0;
}
