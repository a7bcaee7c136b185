/*
 * An irregular lattice's explicit run is tested for stability on its mesh, which the first
 * steps build: hibi_mud_memory_size and hibi_mud_create_in (over memory filled with a byte
 * pattern) accept a short step the mesh refuses, and the hibi_mud_step that finds the failing
 * node returns HIBI_ERROR_MUD_SHORT_STEP_STABILITY, whose message names the field, writing no
 * progress; every later step returns it too, and the outputs stay those of an uncracked plate.
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hibi.h"

static int untouched(const void *bytes, size_t len, unsigned char fill) {
    const unsigned char *b = bytes;
    size_t i;
    for (i = 0; i < len; i++) {
        if (b[i] != fill) return 0;
    }
    return 1;
}

int main(void) {
    hibi_mud_params p = hibi_mud_params_default();
    hibi_mud *mud = NULL;
    hibi_mud_progress progress;
    hibi_status status;
    size_t size = 0, segments = 99, vertices = 99, edges = 99, points = 99;
    unsigned long calls = 0;
    void *memory;
    p.topology = HIBI_MUD_IRREGULAR;
    p.solver = HIBI_MUD_EXPLICIT;
    p.columns = 12;
    p.rows = 12;
    p.short_step = 1.0f;
    printf("memory_size: status %u\n", (unsigned)hibi_mud_memory_size(&p, &size));
    memory = malloc(size);
    if (memory == NULL) return 1;
    memset(memory, 0xa5, size);
    printf("create_in: status %u\n", (unsigned)hibi_mud_create_in(&p, memory, size, &mud));
    if (mud == NULL) return 1;
    do {
        memset(&progress, 0x5a, sizeof progress);
        status = hibi_mud_step(mud, 1, &progress);
        calls++;
    } while (status == HIBI_OK && !progress.finished);
    printf("step: status %u (%s), after more than 1000 calls: %s, progress untouched: %s [%s]\n",
           (unsigned)status, hibi_status_string(status), calls > 1000 ? "yes" : "no",
           untouched(&progress, sizeof progress, 0x5a) ? "yes" : "no", hibi_error_argument());
    status = hibi_mud_step(mud, UINT64_MAX, &progress);
    printf("step again: status %u, progress untouched: %s\n", (unsigned)status,
           untouched(&progress, sizeof progress, 0x5a) ? "yes" : "no");
    hibi_mud_segment_count(mud, &segments);
    hibi_mud_network_counts(mud, &vertices, &edges, &points);
    printf("uncracked: segments %lu, vertices %lu, edges %lu, points %lu\n", (unsigned long)segments,
           (unsigned long)vertices, (unsigned long)edges, (unsigned long)points);
    hibi_mud_destroy(mud);
    free(memory);
    return 0;
}
