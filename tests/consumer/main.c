/*
 * A C99 consumer of hibi, beside main.cpp: built by tests/subproject.rs (hibi as a CMake
 * subproject) and tests/release.rs (the release archive, through pkg-config). The version
 * macros against hibi_version(), hibi's first draw for seed 42 and stream 7, and an error's
 * status.
 */
#include <stdio.h>
#include <string.h>

#include <hibi.h>

int main(void) {
    char macros[32];
    hibi_rng *rng = NULL;
    uint32_t draw = 0;
    hibi_status status;

    snprintf(macros, sizeof macros, "%d.%d.%d", HIBI_VERSION_MAJOR, HIBI_VERSION_MINOR, HIBI_VERSION_PATCH);
    printf("hibi_version() %s, macros %s, equal: %s\n", hibi_version(), macros,
           strcmp(macros, hibi_version()) == 0 ? "yes" : "no");
    status = hibi_rng_create(42, 7, &rng);
    if (status != HIBI_OK) {
        fprintf(stderr, "hibi_rng_create: %s\n", hibi_status_string(status));
        return 1;
    }
    status = hibi_rng_next_u32(rng, &draw);
    hibi_rng_destroy(rng);
    if (status != HIBI_OK) {
        fprintf(stderr, "hibi_rng_next_u32: %s\n", hibi_status_string(status));
        return 1;
    }
    printf("draw: %lu\n", (unsigned long)draw);
    printf("NULL rng: status %u\n", (unsigned)hibi_rng_next_u32(NULL, &draw));
    return 0;
}
