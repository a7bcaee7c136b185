/*
 * rng.c: the hibi frame from C99, end to end. Draws from hibi's deterministic random source
 * in library memory and in caller memory, and shows how every error comes back as a status.
 *
 *   cc -std=c99 -Wall -Wextra -Wpedantic -Werror -Iinclude c_examples/rng.c \
 *      target/release/libhibi.a -lpthread -ldl -lm -o rng && ./rng
 */
#include <stdio.h>
#include <stdlib.h>

#include "hibi.h"

static int fail(const char *what, hibi_status status) {
    fprintf(stderr, "%s: %s (status %u)\n", what, hibi_status_string(status), (unsigned)status);
    return 1;
}

int main(void) {
    hibi_rng *rng = NULL;
    hibi_status status;
    uint32_t bits[4];
    float uniform[3];
    uint32_t count = 12345;
    float speed = 0.0f;
    void *memory;
    hibi_rng *placed = NULL;
    uint32_t placed_first = 0;
    size_t i;

    printf("hibi %s\n", hibi_version());

    /* Library memory: create, draw, destroy. */
    status = hibi_rng_create(42, 7, &rng);
    if (status != HIBI_OK) return fail("hibi_rng_create", status);
    for (i = 0; i < 4; i++) {
        status = hibi_rng_next_u32(rng, &bits[i]);
        if (status != HIBI_OK) return fail("hibi_rng_next_u32", status);
    }
    printf("next_u32: %lu %lu %lu %lu\n", (unsigned long)bits[0], (unsigned long)bits[1],
           (unsigned long)bits[2], (unsigned long)bits[3]);
    status = hibi_rng_uniform(rng, uniform, 3);
    if (status != HIBI_OK) return fail("hibi_rng_uniform", status);
    printf("uniform: %.9g %.9g %.9g\n", uniform[0], uniform[1], uniform[2]);
    status = hibi_rng_poisson(rng, 100.0, &count);
    if (status != HIBI_OK) return fail("hibi_rng_poisson", status);
    printf("poisson(100): %lu\n", (unsigned long)count);
    status = hibi_rng_rand(rng, 40.0f, 0.3f, HIBI_SPREAD_NORMAL, &speed);
    if (status != HIBI_OK) return fail("hibi_rng_rand", status);
    printf("rand(40, 0.3, normal) within [28, 52]: %s\n", speed >= 28.0f && speed <= 52.0f ? "yes" : "no");

    /* Errors are statuses; outputs are untouched on failure. */
    status = hibi_rng_poisson(rng, -1.0, &count);
    printf("poisson(-1): status %u, %s; output untouched: %s\n", (unsigned)status,
           hibi_status_string(status), count != 12345 ? "yes" : "no");
    status = hibi_rng_rand(rng, 40.0f, 0.3f, 9u, &speed);
    printf("spread 9: status %u, %s\n", (unsigned)status, hibi_status_string(status));
    status = hibi_rng_next_u32(NULL, &bits[0]);
    printf("NULL rng: status %u, %s\n", (unsigned)status, hibi_status_string(status));
    hibi_rng_destroy(rng);

    /* Caller memory: the engine's allocator owns the bytes. */
    memory = malloc(hibi_rng_memory_size() + 1);
    if (memory == NULL) return 1;
    status = hibi_rng_create_in(42, 7, memory, hibi_rng_memory_size() - 1, &placed);
    printf("short memory: status %u, %s\n", (unsigned)status, hibi_status_string(status));
    status = hibi_rng_create_in(42, 7, (char *)memory + 1, hibi_rng_memory_size(), &placed);
    printf("misaligned memory: status %u, %s\n", (unsigned)status, hibi_status_string(status));
    status = hibi_rng_create_in(42, 7, memory, hibi_rng_memory_size(), &placed);
    if (status != HIBI_OK) return fail("hibi_rng_create_in", status);
    status = hibi_rng_next_u32(placed, &placed_first);
    if (status != HIBI_OK) return fail("hibi_rng_next_u32", status);
    printf("caller memory, same seed, same first draw: %s\n", placed_first == bits[0] ? "yes" : "no");
    hibi_rng_destroy(placed); /* optional for caller memory: frees nothing */
    free(memory);
    return 0;
}
