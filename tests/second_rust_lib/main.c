/*
 * One C program, two Rust static libraries: libhibi.a and tests/second_rust_lib's
 * libsecond.a, each with its own copy of Rust's std. Built by tests/package.rs.
 */
#include <stdint.h>
#include <stdio.h>

#include "hibi.h"

uint64_t second_work(uint32_t n);

int main(void) {
    hibi_rng *rng = NULL;
    uint32_t draw = 0;
    hibi_status status = hibi_rng_create(42, 7, &rng);
    if (status == HIBI_OK) status = hibi_rng_next_u32(rng, &draw);
    hibi_rng_destroy(rng);
    if (status != HIBI_OK) {
        fprintf(stderr, "hibi: %s\n", hibi_status_string(status));
        return 1;
    }
    printf("second_work(100): %llu\n", (unsigned long long)second_work(100));
    printf("second_work(0): %llu\n", (unsigned long long)second_work(0));
    printf("hibi draw: %lu\n", (unsigned long)draw);
    return 0;
}
