/*
 * shrink_ratio = 1 (nothing ever shrinks) is refused by name, and a break_stretch_mean no
 * spring reaches ends both solvers the same way: at the target shrink, uncracked, at a
 * positive time.
 */
#include <stdio.h>

#include "hibi.h"

static void run(const char *name, uint32_t solver) {
    hibi_mud_params params = hibi_mud_params_default();
    hibi_mud *mud = NULL;
    hibi_mud_progress progress;
    hibi_status status;
    int calls = 0;
    params.columns = 8;
    params.rows = 8;
    params.solver = solver;
    params.break_stretch_mean = 1e30f;
    status = hibi_mud_create(&params, &mud);
    if (status != HIBI_OK) {
        printf("%s: create %u, %s\n", name, (unsigned)status, hibi_status_string(status));
        return;
    }
    do {
        status = hibi_mud_step(mud, 1000000, &progress);
    } while (status == HIBI_OK && !progress.finished && ++calls < 100000);
    printf("%s: status %u, finished %u, shrink %.3f, broken %u, positive time: %s\n", name, (unsigned)status,
           (unsigned)progress.finished, (double)progress.shrink, (unsigned)progress.broken_springs,
           progress.time > 0.0f ? "yes" : "no");
    hibi_mud_destroy(mud);
}

int main(void) {
    hibi_mud_params params = hibi_mud_params_default();
    hibi_mud *mud = NULL;
    size_t size = 12345;
    hibi_status status;
    params.shrink_ratio = 1.0f;
    status = hibi_mud_create(&params, &mud);
    printf("shrink_ratio 1: status %u, %s; nothing created: %s\n", (unsigned)status, hibi_status_string(status),
           mud == NULL ? "yes" : "no");
    status = hibi_mud_memory_size(&params, &size);
    printf("shrink_ratio 1, memory size: status %u, size untouched: %s\n", (unsigned)status,
           size == 12345 ? "yes" : "no");
    params.shrink_ratio = 0.99999994f; /* the largest float below 1 */
    status = hibi_mud_memory_size(&params, &size);
    printf("shrink_ratio just below 1: status %u\n", (unsigned)status);
    run("explicit, break_stretch_mean 1e30", HIBI_MUD_EXPLICIT);
    run("quasi-static, break_stretch_mean 1e30", HIBI_MUD_QUASI_STATIC);
    return 0;
}
