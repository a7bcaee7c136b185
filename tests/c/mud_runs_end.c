/*
 * Explicit runs whose f32 lattice cannot bring every force below the tolerance end: open
 * plates grown by the explicit solver to the end (a hundredfold), where the surface is pulled
 * so far from its deep nodes that a short step's move is below f32's step at their
 * displacements, reach finished within 1e8 units of work, at a growth of 100 or more.
 */
#include <stdio.h>

#include "hibi.h"

static void run(const char *name, uint32_t topology, uint32_t size, float break_stretch_mean, float shrink_ratio) {
    hibi_mud_params params = hibi_mud_params_default();
    hibi_mud *mud = NULL;
    hibi_mud_progress progress;
    hibi_status status;
    int calls = 0;
    params.solver = HIBI_MUD_EXPLICIT;
    params.boundary = HIBI_MUD_OPEN;
    params.drive = HIBI_MUD_GROWTH;
    params.topology = topology;
    params.columns = size;
    params.rows = size;
    params.break_stretch_mean = break_stretch_mean;
    params.shrink_ratio = shrink_ratio;
    params.target_shrink = 0.0f; /* to the largest growth the model follows */
    status = hibi_mud_create(&params, &mud);
    if (status != HIBI_OK) {
        printf("%s: create %u, %s\n", name, (unsigned)status, hibi_status_string(status));
        return;
    }
    /* At most 100 calls of 1e6 units: 1e8 units, and the loop ends whatever the run does. */
    do {
        status = hibi_mud_step(mud, 1000000, &progress);
    } while (status == HIBI_OK && !progress.finished && ++calls < 100);
    printf("%s: status %u, finished %u, growth 100 or more: %s, broken %u\n", name, (unsigned)status,
           (unsigned)progress.finished, progress.shrink >= 100.0f ? "yes" : "no", (unsigned)progress.broken_springs);
    hibi_mud_destroy(mud);
}

int main(void) {
    run("hexagonal 3x3, unbreakable, gamma 0.5", HIBI_MUD_HEXAGONAL, 3, 1e30f, 0.5f);
    run("square 3x3, unbreakable, gamma 0.5", HIBI_MUD_SQUARE, 3, 1e30f, 0.5f);
    run("hexagonal 4x4, break stretch 3, gamma 0.99", HIBI_MUD_HEXAGONAL, 4, 3.0f, 0.99f);
    return 0;
}
