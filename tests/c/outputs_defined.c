/*
 * Outputs are defined to the byte, and refusals leave nothing stale:
 * - hibi_rng_rand refuses an x whose range (1 + z)·|x| reaches past FLT_MAX instead of
 *   drawing infinity;
 * - hibi_*_destroy(NULL) is ignored and leaves hibi_error_argument() empty;
 * - output structs have no padding: every byte of a progress record and of a fragment or
 *   cell ring is written (the buffers start as 0xAA bytes, and the `reserved` fields are 0).
 */
#include <float.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

#include "hibi.h"

static const char *yes(int b) { return b ? "yes" : "no"; }

/* Every byte of `p` was written: none is still the 0xAA the buffer was filled with, where
   the struct's `reserved` word lies at `offset` (its other fields may hold 0xAA bytes by
   chance, so only that word is checked, besides the struct's size). */
static int reserved_zero(const void *p, size_t offset) {
    uint32_t word;
    memcpy(&word, (const unsigned char *)p + offset, sizeof word);
    return word == 0;
}

int main(void) {
    hibi_rng *rng = NULL;
    float value = -1.0f;
    hibi_status status = hibi_rng_create(1, 2, &rng);
    status = hibi_rng_rand(rng, FLT_MAX, 0.9f, HIBI_SPREAD_UNIFORM, &value);
    printf("rand FLT_MAX, z 0.9: status %u, out untouched: %s\n", (unsigned)status, yes(value == -1.0f));
    status = hibi_rng_rand(rng, -FLT_MAX, 0.5f, HIBI_SPREAD_NORMAL, &value);
    printf("rand -FLT_MAX, z 0.5: status %u, out untouched: %s\n", (unsigned)status, yes(value == -1.0f));
    status = hibi_rng_rand(rng, FLT_MAX / 2.0f, 0.9f, HIBI_SPREAD_UNIFORM, &value);
    printf("rand FLT_MAX / 2, z 0.9: status %u, finite: %s\n", (unsigned)status,
           yes(value >= -FLT_MAX && value <= FLT_MAX));
    status = hibi_rng_rand(rng, FLT_MAX, 0.0f, HIBI_SPREAD_NORMAL, &value);
    printf("rand FLT_MAX, z 0: status %u, finite: %s\n", (unsigned)status, yes(value >= -FLT_MAX && value <= FLT_MAX));

    /* A refusal names its argument; destroying NULL afterwards is no call to report on. */
    hibi_rng_poisson(rng, 1.0, NULL);
    printf("after a NULL out: [%s]\n", hibi_error_argument());
    hibi_mud_destroy(NULL);
    printf("after hibi_mud_destroy(NULL): [%s]\n", hibi_error_argument());
    hibi_glass_destroy(NULL);
    hibi_skin_destroy(NULL);
    hibi_rng_destroy(NULL);
    printf("after the other destroys of NULL: [%s]\n", hibi_error_argument());
    hibi_rng_destroy(rng);

    {
        hibi_mud_params params = hibi_mud_params_default();
        hibi_mud *mud = NULL;
        hibi_mud_progress progress;
        params.columns = params.rows = 16;
        memset(&progress, 0xAA, sizeof progress);
        status = hibi_mud_create(&params, &mud);
        if (status == HIBI_OK) status = hibi_mud_step(mud, 1000, &progress);
        printf("mud progress: status %u, size %u, reserved 0: %s\n", (unsigned)status, (unsigned)sizeof progress,
               yes(reserved_zero(&progress, offsetof(hibi_mud_progress, reserved))));
        while (status == HIBI_OK && !progress.finished) status = hibi_mud_step(mud, 1000000, &progress);
        {
            size_t rings = 0, points = 0, rw = 0, pw = 0, wrapping = 0;
            static hibi_ring ring_buffer[4096];
            static hibi_vec2 point_buffer[1 << 16];
            size_t i;
            int all = 1;
            if (status == HIBI_OK) status = hibi_mud_cell_counts(mud, &rings, &points, &wrapping);
            memset(ring_buffer, 0xAA, sizeof ring_buffer);
            if (status == HIBI_OK && rings <= 4096 && points <= (1u << 16))
                status = hibi_mud_cells(mud, ring_buffer, rings, point_buffer, points, &rw, &pw);
            for (i = 0; i < rw; i++) all &= reserved_zero(&ring_buffer[i], offsetof(hibi_ring, reserved));
            printf("mud cells: status %u, rings %s, reserved 0 in every ring: %s\n", (unsigned)status,
                   yes(rw > 0 && rw == rings), yes(all));
        }
        hibi_mud_destroy(mud);
    }
    {
        hibi_glass_params params = hibi_glass_params_default();
        hibi_glass *glass = NULL;
        hibi_glass_progress progress;
        params.width = params.height = 160.0f;
        params.impact[0] = params.impact[1] = 80.0f;
        status = hibi_glass_create(&params, &glass);
        do {
            if (status == HIBI_OK) status = hibi_glass_step(glass, 100000, &progress);
        } while (status == HIBI_OK && !progress.finished);
        {
            static unsigned char scratch[1 << 22];
            static hibi_ring ring_buffer[4096];
            static hibi_vec2 point_buffer[1 << 16];
            size_t need = 0, rings = 0, points = 0, rw = 0, pw = 0, i;
            int all = 1;
            if (status == HIBI_OK) status = hibi_glass_scratch_size(glass, &need);
            if (status == HIBI_OK && need <= sizeof scratch)
                status = hibi_glass_fragment_counts(glass, scratch, sizeof scratch, &rings, &points);
            memset(ring_buffer, 0xAA, sizeof ring_buffer);
            if (status == HIBI_OK && rings <= 4096 && points <= (1u << 16))
                status = hibi_glass_fragments(glass, scratch, sizeof scratch, ring_buffer, rings, point_buffer, points,
                                              &rw, &pw);
            for (i = 0; i < rw; i++)
                all &= reserved_zero(&ring_buffer[i], offsetof(hibi_ring, reserved));
            printf("glass fragments: status %u, rings %s, reserved 0 in every ring: %s\n", (unsigned)status,
                   yes(rw > 0 && rw == rings), yes(all));
        }
        hibi_glass_destroy(glass);
    }
    {
        hibi_skin_params params = hibi_skin_params_default();
        hibi_skin *skin = NULL;
        hibi_skin_progress progress;
        params.width = params.height = 64;
        memset(&progress, 0xAA, sizeof progress);
        status = hibi_skin_create(&params, &skin);
        if (status == HIBI_OK) status = hibi_skin_step(skin, 100, &progress);
        printf("skin progress: status %u, size %u, reserved 0: %s\n", (unsigned)status, (unsigned)sizeof progress,
               yes(reserved_zero(&progress, offsetof(hibi_skin_progress, reserved))));
        hibi_skin_destroy(skin);
    }
    return 0;
}
