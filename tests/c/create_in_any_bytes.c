/*
 * Caller memory may hold anything: each model made with *_create_in over memory filled with
 * a byte pattern, and over memory fresh from malloc that nothing has written, grows the same
 * result, byte for byte, as *_create in library memory. Under Valgrind (the test runs this
 * program there too) a read of a byte hibi did not write is an error: creation writes only
 * the arrays it must, and the models read nothing before writing it.
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hibi.h"

#define SIDE 96
static float pixels[SIDE * SIDE * 3];

static uint64_t fnv(uint64_t h, const void *bytes, size_t len) {
    const unsigned char *b = bytes;
    size_t i;
    for (i = 0; i < len; i++) h = (h ^ b[i]) * 1099511628211u;
    return h;
}

/* Where a model's memory comes from: the library (`*_create`), or a caller's block filled
 * with `fill` (not written at all when `fill` is negative). */
typedef struct {
    const char *name;
    int library;
    int fill;
} source;

static const source SOURCES[] = {
    {"library", 1, 0}, {"bytes 0xa5", 0, 0xa5}, {"bytes 0xff", 0, 0xff}, {"unwritten", 0, -1}};
#define SOURCE_COUNT (sizeof SOURCES / sizeof SOURCES[0])

static void *block(const source *s, size_t size) {
    void *memory = malloc(size);
    if (memory != NULL && s->fill >= 0) memset(memory, s->fill, size);
    return memory;
}

static uint64_t mud_digest(const source *s) {
    hibi_mud_params params = hibi_mud_params_default();
    hibi_mud_render_params render = hibi_mud_render_params_default();
    hibi_mud_progress progress = {0};
    hibi_mud *mud = NULL;
    void *memory = NULL;
    size_t size = 0;
    hibi_status status;
    uint64_t h = 14695981039346656037u;
    params.columns = params.rows = 20;
    status = hibi_mud_memory_size(&params, &size);
    if (s->library) {
        if (status == HIBI_OK) status = hibi_mud_create(&params, &mud);
    } else {
        memory = block(s, size);
        if (status == HIBI_OK) status = hibi_mud_create_in(&params, memory, size, &mud);
    }
    while (status == HIBI_OK && !progress.finished) status = hibi_mud_step(mud, 5000, &progress);
    render.width = render.height = SIDE;
    if (status == HIBI_OK) status = hibi_mud_render(mud, &render, HIBI_MUD_LAYER_HEIGHT, pixels, SIDE * SIDE);
    h = fnv(h, &status, sizeof status);
    h = fnv(h, &progress, sizeof progress);
    h = fnv(h, pixels, SIDE * SIDE * sizeof *pixels);
    hibi_mud_destroy(mud);
    free(memory);
    return h;
}

static uint64_t glass_digest(const source *s) {
    hibi_glass_params params = hibi_glass_params_default();
    hibi_glass_render_params render = hibi_glass_render_params_default();
    hibi_glass_progress progress = {0};
    hibi_glass *glass = NULL;
    void *memory = NULL;
    size_t size = 0;
    hibi_status status;
    uint64_t h = 14695981039346656037u;
    params.width = params.height = (float)SIDE;
    params.impact[0] = params.impact[1] = SIDE / 2.0f;
    params.max_vertices = 4096;
    status = hibi_glass_memory_size(&params, &size);
    if (s->library) {
        if (status == HIBI_OK) status = hibi_glass_create(&params, &glass);
    } else {
        memory = block(s, size);
        if (status == HIBI_OK) status = hibi_glass_create_in(&params, memory, size, &glass);
    }
    while (status == HIBI_OK && !progress.finished) status = hibi_glass_step(glass, 5000, &progress);
    render.width = render.height = SIDE;
    if (status == HIBI_OK) status = hibi_glass_render(glass, &render, HIBI_GLASS_LAYER_TIME, pixels, SIDE * SIDE);
    h = fnv(h, &status, sizeof status);
    h = fnv(h, &progress, sizeof progress);
    h = fnv(h, pixels, SIDE * SIDE * sizeof *pixels);
    hibi_glass_destroy(glass);
    free(memory);
    return h;
}

static uint64_t skin_digest(const source *s) {
    hibi_skin_params params = hibi_skin_params_default();
    hibi_skin_render_params render = hibi_skin_render_params_default();
    hibi_skin_progress progress = {0};
    hibi_skin *skin = NULL;
    void *memory = NULL;
    size_t size = 0;
    hibi_status status;
    uint64_t h = 14695981039346656037u;
    /* Two levels, the second 2 px apart: each parent holds a few hundred centre points, which
     * the build buckets in its words. */
    params.width = params.height = SIDE;
    params.levels = 2;
    params.level[1].spacing = 2.0f;
    status = hibi_skin_memory_size(&params, &size);
    if (s->library) {
        if (status == HIBI_OK) status = hibi_skin_create(&params, &skin);
    } else {
        memory = block(s, size);
        if (status == HIBI_OK) status = hibi_skin_create_in(&params, memory, size, &skin);
    }
    while (status == HIBI_OK && !progress.finished) status = hibi_skin_step(skin, 5000, &progress);
    if (status == HIBI_OK) status = hibi_skin_render(skin, &render, HIBI_SKIN_LAYER_NORMAL, pixels, SIDE * SIDE * 3);
    h = fnv(h, &status, sizeof status);
    h = fnv(h, &progress, sizeof progress);
    h = fnv(h, pixels, SIDE * SIDE * 3 * sizeof *pixels);
    hibi_skin_destroy(skin);
    free(memory);
    return h;
}

int main(void) {
    static uint64_t (*const models[3])(const source *) = {mud_digest, glass_digest, skin_digest};
    static const char *const names[3] = {"mud", "glass", "skin"};
    size_t m, k;
    for (m = 0; m < 3; m++) {
        uint64_t library = models[m](&SOURCES[0]);
        for (k = 1; k < SOURCE_COUNT; k++) {
            printf("%s, %s: same as library memory: %s\n", names[m], SOURCES[k].name,
                   models[m](&SOURCES[k]) == library ? "yes" : "no");
        }
    }
    return 0;
}
