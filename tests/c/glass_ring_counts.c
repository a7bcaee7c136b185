/*
 * hibi_glass_create must not run for minutes when the ring count formula
 * R = floor(ring_slope * M + ring_offset) is huge. Creation looks at no more than
 * max_cracks ring start points; a larger R counts as running out of capacity.
 */
#include <stdio.h>
#include <time.h>

#include "hibi.h"

static void create(const char *field, float value) {
    hibi_glass_params params = hibi_glass_params_default();
    hibi_glass *glass = NULL;
    hibi_glass_progress progress;
    size_t cracks = 0;
    clock_t start = clock();
    hibi_status created, stepped, counted;
    double seconds;
    if (field[5] == 's') {
        params.ring_slope = value;
    } else {
        params.ring_offset = value;
    }
    created = hibi_glass_create(&params, &glass);
    seconds = (double)(clock() - start) / CLOCKS_PER_SEC;
    stepped = hibi_glass_step(glass, 1000, &progress);
    counted = hibi_glass_crack_count(glass, &cracks);
    /* The old loop took 2.2 s for 1e5 and minutes for 1e30; the bounded one, microseconds. */
    printf("%s %g: create %u, under a second: %s, step %u, crack count %u, cracks within max_cracks: %s\n", field,
           (double)value, (unsigned)created, seconds < 1.0 ? "yes" : "no", (unsigned)stepped, (unsigned)counted,
           cracks <= params.max_cracks ? "yes" : "no");
    hibi_glass_destroy(glass);
}

int main(void) {
    create("ring_slope", 1e5f);
    create("ring_slope", 1e7f);
    create("ring_slope", 1e30f);
    create("ring_offset", 1e30f);
    return 0;
}
