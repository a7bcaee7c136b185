/* Every layer of every model in one call: a finished mud run, a glass plate and a skin, each
 * rendered with all the layers it has by one hibi_*_render_layers call; then a tile of each,
 * compared pixel for pixel with the whole image. Prints each layer's size and FNV-1a hash;
 * given a directory, also writes each layer's bytes there (MODEL.LAYER) for the test to
 * compare with Rust's render and the CLI's PNGs. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hibi.h"

static void check(hibi_status status, const char *what) {
    if (status != HIBI_OK) {
        printf("%s: status %u, %s (%s)\n", what, (unsigned)status, hibi_status_string(status), hibi_error_argument());
        exit(1);
    }
}

static uint64_t fnv(const void *data, size_t bytes) {
    const unsigned char *p = data;
    uint64_t h = 0xcbf29ce484222325u;
    for (size_t i = 0; i < bytes; i++) h = (h ^ p[i]) * 0x100000001b3u;
    return h;
}

/* Buffers for every layer of a width x height image or tile. */
typedef struct {
    uint32_t width, height;
    hibi_layers layers;
} buffers;

static void *zeroed(size_t count, size_t size) {
    void *p = calloc(count, size);
    if (p == NULL) {
        printf("out of memory\n");
        exit(1);
    }
    return p;
}

/* `crack`: mud or glass (a time layer, no cell layer); otherwise skin (the reverse). */
static buffers make(uint32_t width, uint32_t height, int crack) {
    buffers b;
    size_t n = (size_t)width * height;
    memset(&b, 0, sizeof b);
    b.width = width;
    b.height = height;
    b.layers.mask = zeroed(n, 1);
    b.layers.height = zeroed(n, sizeof(float));
    b.layers.height16 = zeroed(n, sizeof(uint16_t));
    b.layers.normal = zeroed(n * 3, sizeof(float));
    b.layers.normal_rgb8 = zeroed(n * 3, 1);
    if (crack) b.layers.time = zeroed(n, sizeof(float));
    if (!crack) b.layers.cell = zeroed(n, sizeof(uint32_t));
    b.layers.preview = zeroed(n * 4, 1);
    b.layers.pixels_len = n;
    check(hibi_render_scratch_len(width, height, &b.layers.scratch_len), "scratch length");
    b.layers.scratch = zeroed(b.layers.scratch_len, sizeof(uint32_t));
    return b;
}

static void release(buffers *b) {
    free(b->layers.mask);
    free(b->layers.height);
    free(b->layers.height16);
    free(b->layers.normal);
    free(b->layers.normal_rgb8);
    free(b->layers.time);
    free(b->layers.cell);
    free(b->layers.preview);
    free(b->layers.scratch);
}

/* One layer's bytes per pixel and where they are. */
typedef struct {
    const char *name;
    const unsigned char *data;
    size_t per_pixel;
} plane;

static size_t planes(const buffers *b, plane out[8]) {
    const hibi_layers *l = &b->layers;
    plane all[8] = {
        {"mask", (const unsigned char *)l->mask, 1},
        {"height", (const unsigned char *)l->height, 4},
        {"height16", (const unsigned char *)l->height16, 2},
        {"normal", (const unsigned char *)l->normal, 12},
        {"normal_rgb8", (const unsigned char *)l->normal_rgb8, 3},
        {"time", (const unsigned char *)l->time, 4},
        {"cell", (const unsigned char *)l->cell, 4},
        {"preview", (const unsigned char *)l->preview, 4},
    };
    size_t count = 0;
    for (size_t i = 0; i < 8; i++)
        if (all[i].data != NULL) out[count++] = all[i];
    return count;
}

/* Prints (and with a directory, writes) every layer of `whole`. */
static void report(const char *model, const buffers *whole, const char *dir) {
    plane p[8];
    size_t count = planes(whole, p);
    size_t n = (size_t)whole->width * whole->height;
    printf("%s %ux%u:", model, (unsigned)whole->width, (unsigned)whole->height);
    for (size_t i = 0; i < count; i++) {
        printf(" %s %016llx", p[i].name, (unsigned long long)fnv(p[i].data, n * p[i].per_pixel));
        if (dir != NULL) {
            char path[4096];
            snprintf(path, sizeof path, "%s/%s.%s", dir, model, p[i].name);
            FILE *f = fopen(path, "wb");
            if (f == NULL || fwrite(p[i].data, p[i].per_pixel, n, f) != n || fclose(f) != 0) {
                printf("\ncannot write %s\n", path);
                exit(1);
            }
        }
    }
    printf("\n");
}

/* Whether every pixel of `part` (the tile at x, y) equals the whole image's, every layer. */
static int tile_matches(const buffers *whole, const buffers *part, uint32_t x0, uint32_t y0) {
    plane w[8], t[8];
    size_t count = planes(whole, w);
    planes(part, t);
    for (size_t i = 0; i < count; i++)
        for (uint32_t y = 0; y < part->height; y++) {
            size_t bytes = part->width * w[i].per_pixel;
            const unsigned char *a = t[i].data + (size_t)y * bytes;
            const unsigned char *b = w[i].data + ((size_t)(y0 + y) * whole->width + x0) * w[i].per_pixel;
            if (memcmp(a, b, bytes) != 0) {
                printf("tile differs: layer %s, row %u\n", w[i].name, (unsigned)y);
                return 0;
            }
        }
    return 1;
}

int main(int argc, char **argv) {
    const char *dir = argc > 1 ? argv[1] : NULL;
    hibi_tile tile = {37, 21, 50, 33};

    hibi_mud_params mp = hibi_mud_params_default();
    mp.columns = 32;
    mp.rows = 32;
    hibi_mud *mud;
    check(hibi_mud_create(&mp, &mud), "mud create");
    hibi_mud_progress progress;
    do check(hibi_mud_step(mud, 1000000, &progress), "mud step");
    while (!progress.finished);
    hibi_mud_render_params mr;
    check(hibi_mud_render_params_fit(mud, 128, &mr), "mud fit");
    buffers whole = make(mr.width, mr.height, 1), part = make(tile.width, tile.height, 1);
    check(hibi_mud_render_layers(mud, &mr, NULL, &whole.layers), "mud render");
    check(hibi_mud_render_layers(mud, &mr, &tile, &part.layers), "mud tile");
    report("mud", &whole, dir);
    printf("mud tile equal: %s\n", tile_matches(&whole, &part, tile.x, tile.y) ? "yes" : "no");
    hibi_layers cells = whole.layers;
    cells.cell = (uint32_t *)part.layers.time; /* any buffer: mud has no cell layer */
    hibi_status refused = hibi_mud_render_layers(mud, &mr, NULL, &cells);
    printf("mud cell layer: status %u, %s\n", (unsigned)refused, hibi_error_argument());
    release(&whole);
    release(&part);
    hibi_mud_destroy(mud);

    hibi_glass_params gp = hibi_glass_params_default();
    gp.width = 160;
    gp.height = 120;
    gp.impact[0] = 70;
    gp.impact[1] = 50;
    hibi_glass *glass;
    check(hibi_glass_create(&gp, &glass), "glass create");
    hibi_glass_progress gprogress;
    do check(hibi_glass_step(glass, 1000000, &gprogress), "glass step");
    while (!gprogress.finished);
    hibi_glass_render_params gr = hibi_glass_render_params_default();
    gr.width = 160;
    gr.height = 120;
    whole = make(gr.width, gr.height, 1);
    part = make(tile.width, tile.height, 1);
    check(hibi_glass_render_layers(glass, &gr, NULL, &whole.layers), "glass render");
    check(hibi_glass_render_layers(glass, &gr, &tile, &part.layers), "glass tile");
    report("glass", &whole, dir);
    printf("glass tile equal: %s\n", tile_matches(&whole, &part, tile.x, tile.y) ? "yes" : "no");
    hibi_tile outside = {150, 0, 20, 10};
    refused = hibi_glass_render_layers(glass, &gr, &outside, &part.layers);
    printf("glass tile past the edge: status %u, %s\n", (unsigned)refused, hibi_error_argument());
    release(&whole);
    release(&part);
    hibi_glass_destroy(glass);

    hibi_skin_params sp;
    check(hibi_skin_params_preset("fig19a", &sp), "skin preset");
    sp.width = 120;
    sp.height = 100;
    hibi_skin *skin;
    check(hibi_skin_create(&sp, &skin), "skin create");
    hibi_skin_progress sprogress;
    do check(hibi_skin_step(skin, 1000000, &sprogress), "skin step");
    while (!sprogress.finished);
    hibi_skin_render_params sr = hibi_skin_render_params_default();
    sr.cell_level = 1;
    whole = make(sp.width, sp.height, 0);
    part = make(tile.width, tile.height, 0);
    check(hibi_skin_render_layers(skin, &sr, NULL, &whole.layers), "skin render");
    check(hibi_skin_render_layers(skin, &sr, &tile, &part.layers), "skin tile");
    report("skin", &whole, dir);
    printf("skin tile equal: %s\n", tile_matches(&whole, &part, tile.x, tile.y) ? "yes" : "no");
    hibi_layers no_scratch = whole.layers;
    no_scratch.scratch = NULL;
    no_scratch.scratch_len = 0;
    refused = hibi_skin_render_layers(skin, &sr, NULL, &no_scratch);
    printf("skin mask without scratch: status %u, %s\n", (unsigned)refused, hibi_error_argument());
    release(&whole);
    release(&part);
    hibi_skin_destroy(skin);
    return 0;
}
