/*
 * skin.c: model C (skin from hierarchical Voronoi cells, Ishii et al.) from C99. Loads the
 * paper's Fig. 19 a setting (three levels of perturbed cells) at 200 x 200 pixels, renders
 * its height and normal maps, shades them into a preview written as a binary PPM, walks the
 * cell hierarchy and its outlines, and builds the same skin in caller memory to show the
 * same bytes come out.
 *
 *   cc -std=c99 -Wall -Wextra -Wpedantic -Werror -Iinclude c_examples/skin.c \
 *      target/release/libhibi.a -lpthread -ldl -lm -o skin && ./skin skin.ppm
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hibi.h"

static int fail(const char *what, hibi_status status) {
    fprintf(stderr, "%s: %s (status %u)\n", what, hibi_status_string(status), (unsigned)status);
    return 1;
}

static void report(const char *what, hibi_status status) {
    printf("%s: status %u, %s\n", what, (unsigned)status, hibi_status_string(status));
}

/* Renders the height and normal maps of `skin`, one layer per call, and shades them into
   `rgb`. A render only reads the skin, so several threads may render one skin at once. */
static hibi_status preview(const hibi_skin *skin, size_t pixels, float *height, float *normal, unsigned char *rgb) {
    hibi_skin_render_params render = hibi_skin_render_params_default();
    hibi_skin_shade_params light = hibi_skin_shade_params_default();
    hibi_status status = hibi_skin_render(skin, &render, HIBI_SKIN_LAYER_HEIGHT, height, pixels);
    if (status != HIBI_OK) return status;
    status = hibi_skin_render(skin, &render, HIBI_SKIN_LAYER_NORMAL, normal, 3 * pixels);
    if (status != HIBI_OK) return status;
    return hibi_skin_shade(height, pixels, normal, 3 * pixels, &light, rgb, 3 * pixels);
}

int main(int argc, char **argv) {
    const char *path = argc > 1 ? argv[1] : "skin.ppm";
    hibi_skin_params params, bad;
    hibi_skin_render_params render = hibi_skin_render_params_default();
    hibi_skin *skin = NULL, *placed = NULL;
    hibi_skin_cell cell;
    hibi_status status;
    size_t cells = 0, pixels, i, k, bytes = 0, written = 0, per_level[HIBI_SKIN_MAX_LEVELS] = {0};
    size_t capacity = 0, steps = 0;
    hibi_skin_progress progress;
    double area[HIBI_SKIN_MAX_LEVELS] = {0.0}, *xy = NULL;
    float *height, *normal;
    uint32_t *map;
    unsigned char *rgb, *again;
    void *memory;
    FILE *file;

    status = hibi_skin_params_preset("fig99", &params);
    report("unknown preset fig99", status);
    status = hibi_skin_params_preset("fig19a", &params);
    if (status != HIBI_OK) return fail("hibi_skin_params_preset", status);
    params.width = 200;
    params.height = 200;
    pixels = (size_t)params.width * params.height;

    bad = params;
    bad.level[1].roundness = 1.5f;
    status = hibi_skin_create(&bad, &skin);
    report("roundness 1.5 at level 1", status);
    bad = params;
    bad.layout = 7;
    status = hibi_skin_create(&bad, &skin);
    report("layout 7", status);
    memset(&bad, 0, sizeof bad);
    status = hibi_skin_create(&bad, &skin);
    report("params not from the default", status);

    status = hibi_skin_create(&params, &skin);
    if (status != HIBI_OK) return fail("hibi_skin_create", status);
    /* Build the cells in slices, as a frame-sliced engine would. */
    steps = 0;
    do {
        status = hibi_skin_step(skin, 20000, &progress);
        if (status != HIBI_OK) return fail("hibi_skin_step", status);
        steps++;
    } while (!progress.finished);
    printf("built in %lu steps: %lu cells from %lu level-0 centres\n", (unsigned long)steps,
           (unsigned long)progress.cells, (unsigned long)progress.roots);

    /* The hierarchy: every cell's level, and its outline in pixels. */
    status = hibi_skin_cell_count(skin, &cells);
    if (status != HIBI_OK) return fail("hibi_skin_cell_count", status);
    for (i = 0; i < cells; i++) {
        double twice = 0.0;
        size_t n;
        status = hibi_skin_cell_info(skin, i, &cell);
        if (status != HIBI_OK) return fail("hibi_skin_cell_info", status);
        n = 2 * (size_t)cell.vertex_count;
        if (n > capacity) {
            free(xy);
            capacity = n;
            xy = malloc(capacity * sizeof *xy);
            if (xy == NULL) return 1;
        }
        status = hibi_skin_outline(skin, i, xy, n, &written);
        if (status != HIBI_OK) return fail("hibi_skin_outline", status);
        for (k = 0; k < written; k += 2) {
            size_t next = (k + 2) % written;
            twice += xy[k] * xy[next + 1] - xy[next] * xy[k + 1];
        }
        per_level[cell.level]++;
        area[cell.level] += twice / 2.0;
    }
    printf("cells: %lu (level 0: %lu, level 1: %lu, level 2: %lu)\n", (unsigned long)cells,
           (unsigned long)per_level[0], (unsigned long)per_level[1], (unsigned long)per_level[2]);
    for (k = 0; k < params.levels; k++) {
        printf("level %lu outlines cover %.1f of %lu square pixels\n", (unsigned long)k, area[k],
               (unsigned long)pixels);
    }
    status = hibi_skin_cell_info(skin, cells, &cell);
    report("cell index past the end", status);
    status = hibi_skin_outline(skin, 0, xy, 2, &written);
    report("outline into a short buffer", status);
    free(xy);

    height = malloc(pixels * sizeof *height);
    normal = malloc(3 * pixels * sizeof *normal);
    rgb = malloc(3 * pixels);
    again = malloc(3 * pixels);
    map = malloc(pixels * sizeof *map);
    if (height == NULL || normal == NULL || rgb == NULL || again == NULL || map == NULL) return 1;
    status = hibi_skin_render(skin, &render, HIBI_SKIN_LAYER_NORMAL, normal, 3 * pixels - 1);
    report("short normal buffer", status);
    render.cell_level = 3;
    status = hibi_skin_render(skin, &render, HIBI_SKIN_LAYER_CELLS, map, pixels);
    report("cell map of level 3", status);
    render.cell_level = 2;
    status = hibi_skin_render(skin, &render, HIBI_SKIN_LAYER_CELLS, map, pixels);
    if (status != HIBI_OK) return fail("hibi_skin_render", status);
    i = map[100 * params.width + 100];
    status = hibi_skin_cell_info(skin, i, &cell);
    if (status != HIBI_OK) return fail("hibi_skin_cell_info", status);
    printf("pixel (100, 100) lies in cell %lu of level %u, its parent is cell %u\n", (unsigned long)i,
           (unsigned)cell.level, (unsigned)cell.parent);
    status = preview(skin, pixels, height, normal, rgb);
    if (status != HIBI_OK) return fail("preview", status);
    hibi_skin_destroy(skin);

    file = fopen(path, "wb");
    if (file == NULL) {
        perror(path);
        return 1;
    }
    fprintf(file, "P6\n%u %u\n255\n", (unsigned)params.width, (unsigned)params.height);
    fwrite(rgb, 1, 3 * pixels, file);
    fclose(file);
    printf("wrote %s\n", path);

    /* The same skin in caller memory. */
    status = hibi_skin_memory_size(&params, &bytes);
    if (status != HIBI_OK) return fail("hibi_skin_memory_size", status);
    memory = malloc(bytes);
    if (memory == NULL) return 1;
    status = hibi_skin_create_in(&params, memory, bytes, &placed);
    if (status != HIBI_OK) return fail("hibi_skin_create_in", status);
    status = hibi_skin_step(placed, UINT64_MAX, NULL);
    if (status != HIBI_OK) return fail("hibi_skin_step", status);
    status = preview(placed, pixels, height, normal, again);
    if (status != HIBI_OK) return fail("preview", status);
    printf("caller memory, same bytes: %s\n", memcmp(rgb, again, 3 * pixels) == 0 ? "yes" : "no");
    hibi_skin_destroy(placed);
    free(memory);
    free(height);
    free(normal);
    free(rgb);
    free(again);
    free(map);
    return 0;
}
