/*
 * The caller-memory path allocates nothing: a stream, a mud run, a glass plate and a skin made
 * with *_create_in in this program's static memory, stepped to the end, queried, rendered and
 * destroyed. Run under Valgrind, whose heap summary must read "0 allocs" (the test checks it);
 * stdout gets a static buffer first, so that the program's own printing allocates nothing
 * either. The first hibi call installs hibi's panic hook, without allocating.
 */
#include <stdint.h>
#include <stdio.h>

#include "hibi.h"

#define ARENA (24u << 20)
static unsigned char arena[ARENA];
static size_t used;
static char out_buffer[4096];

/* `size` bytes of the arena at `align`, or NULL. */
static void *carve(size_t size, size_t align) {
    uintptr_t base = (uintptr_t)arena + used;
    size_t pad = (size_t)((align - base % align) % align);
    if (used + pad + size > ARENA) return NULL;
    used += pad + size;
    return arena + (used - size);
}

static float pixels[256 * 256 * 3];

int main(void) {
    hibi_status status;
    size_t size = 0;
    setvbuf(stdout, out_buffer, _IOFBF, sizeof out_buffer);
    {
        hibi_rng *rng = NULL;
        uint32_t bits = 0;
        size = hibi_rng_memory_size();
        status = hibi_rng_create_in(7, 1, carve(size, hibi_rng_memory_align()), size, &rng);
        if (status == HIBI_OK) status = hibi_rng_next_u32(rng, &bits);
        printf("rng: status %u\n", (unsigned)status);
        hibi_rng_destroy(rng);
    }
    {
        hibi_mud_params params = hibi_mud_params_default();
        hibi_mud *mud = NULL;
        hibi_mud_progress progress = {0};
        hibi_mud_render_params render = hibi_mud_render_params_default();
        size_t v = 0, e = 0, p = 0;
        params.columns = params.rows = 24;
        status = hibi_mud_memory_size(&params, &size);
        if (status == HIBI_OK) status = hibi_mud_create_in(&params, carve(size, hibi_mud_memory_align()), size, &mud);
        while (status == HIBI_OK && !progress.finished) status = hibi_mud_step(mud, 10000, &progress);
        if (status == HIBI_OK) status = hibi_mud_network_counts(mud, &v, &e, &p);
        render.width = render.height = 128;
        if (status == HIBI_OK) status = hibi_mud_render(mud, &render, HIBI_MUD_LAYER_HEIGHT, pixels, 128 * 128);
        printf("mud: status %u, cracks %s\n", (unsigned)status, e > 0 ? "yes" : "no");
        hibi_mud_destroy(mud);
    }
    {
        hibi_glass_params params = hibi_glass_params_default();
        hibi_glass *glass = NULL;
        hibi_glass_progress progress = {0};
        hibi_glass_render_params render = hibi_glass_render_params_default();
        size_t scratch_size = 0, rings = 0, points = 0;
        void *scratch;
        params.width = params.height = 256.0f;
        params.impact[0] = params.impact[1] = 128.0f;
        status = hibi_glass_memory_size(&params, &size);
        if (status == HIBI_OK)
            status = hibi_glass_create_in(&params, carve(size, hibi_glass_memory_align()), size, &glass);
        while (status == HIBI_OK && !progress.finished) status = hibi_glass_step(glass, 10000, &progress);
        if (status == HIBI_OK) status = hibi_glass_scratch_size(glass, &scratch_size);
        scratch = carve(scratch_size, 8);
        if (status == HIBI_OK) status = hibi_glass_fragment_counts(glass, scratch, scratch_size, &rings, &points);
        render.width = render.height = 256;
        if (status == HIBI_OK) status = hibi_glass_render(glass, &render, HIBI_GLASS_LAYER_TIME, pixels, 256 * 256);
        printf("glass: status %u, fragments %s\n", (unsigned)status, rings > 0 ? "yes" : "no");
        hibi_glass_destroy(glass);
    }
    {
        hibi_skin_params params = hibi_skin_params_default();
        hibi_skin *skin = NULL;
        hibi_skin_progress progress = {0};
        hibi_skin_render_params render = hibi_skin_render_params_default();
        params.width = params.height = 128;
        status = hibi_skin_memory_size(&params, &size);
        if (status == HIBI_OK) status = hibi_skin_create_in(&params, carve(size, hibi_skin_memory_align()), size, &skin);
        while (status == HIBI_OK && !progress.finished) status = hibi_skin_step(skin, 10000, &progress);
        if (status == HIBI_OK)
            status = hibi_skin_render(skin, &render, HIBI_SKIN_LAYER_NORMAL, pixels, 128 * 128 * 3);
        printf("skin: status %u\n", (unsigned)status);
        hibi_skin_destroy(skin);
    }
    return 0;
}
