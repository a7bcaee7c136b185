/*
 * The bad-input table (docs/src/bad-input.md): one case per row, each printed as
 * "<row>: status <n>" and, where the call has an output, whether the output was left
 * untouched. tests/c_examples.rs reads the table, runs this program, and checks every row's
 * status against the constant the table names, and that every status include/hibi.h declares
 * is reached here (or listed in the table as unreachable).
 */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hibi.h"

/* Each row ends with what hibi_error_argument() names for the call just made, in brackets. */
static void row(const char *id, hibi_status status) {
    printf("%s: status %u [%s]\n", id, (unsigned)status, hibi_error_argument());
}

static void row_kept(const char *id, hibi_status status, int untouched) {
    printf("%s: status %u, output untouched: %s [%s]\n", id, (unsigned)status, untouched ? "yes" : "no",
           hibi_error_argument());
}

/* A parameter row: memory_size and create must agree, and neither writes anything. */
static void mud_row(const char *id, const hibi_mud_params *p) {
    size_t size = 777;
    hibi_mud *mud = NULL;
    hibi_status sized = hibi_mud_memory_size(p, &size);
    hibi_status created = hibi_mud_create(p, &mud);
    if (created == HIBI_OK) {
        hibi_mud_destroy(mud);
    }
    if (sized != created) {
        printf("%s: memory_size %u but create %u\n", id, (unsigned)sized, (unsigned)created);
        return;
    }
    row_kept(id, sized, size == 777 && mud == NULL);
}

static void glass_row(const char *id, const hibi_glass_params *p) {
    size_t size = 777;
    hibi_glass *glass = NULL;
    hibi_status sized = hibi_glass_memory_size(p, &size);
    hibi_status created = hibi_glass_create(p, &glass);
    if (created == HIBI_OK) {
        hibi_glass_destroy(glass);
    }
    if (sized != created) {
        printf("%s: memory_size %u but create %u\n", id, (unsigned)sized, (unsigned)created);
        return;
    }
    row_kept(id, sized, size == 777 && glass == NULL);
}

static void skin_row(const char *id, const hibi_skin_params *p) {
    size_t size = 777;
    hibi_skin *skin = NULL;
    hibi_status sized = hibi_skin_memory_size(p, &size);
    hibi_status created = hibi_skin_create(p, &skin);
    if (created == HIBI_OK) {
        hibi_skin_destroy(skin);
    }
    if (sized != created) {
        printf("%s: memory_size %u but create %u\n", id, (unsigned)sized, (unsigned)created);
        return;
    }
    row_kept(id, sized, size == 777 && skin == NULL);
}

static hibi_mud_params small_mud(void) {
    hibi_mud_params p = hibi_mud_params_default();
    p.columns = 8;
    p.rows = 8;
    return p;
}

static hibi_skin_params small_skin(void) {
    hibi_skin_params p = hibi_skin_params_default();
    p.width = 64;
    p.height = 48;
    p.levels = 2;
    return p;
}

#define MUD(id, change)                      \
    do {                                     \
        hibi_mud_params p_ = small_mud();    \
        change;                              \
        mud_row(id, &p_);                    \
    } while (0)

#define GLASS(id, change)                                   \
    do {                                                    \
        hibi_glass_params p_ = hibi_glass_params_default(); \
        change;                                             \
        glass_row(id, &p_);                                 \
    } while (0)

#define SKIN(id, change)                   \
    do {                                   \
        hibi_skin_params p_ = small_skin(); \
        change;                            \
        skin_row(id, &p_);                 \
    } while (0)

/* A sentinel for untouched float outputs. */
#define KEPT 12345.0f

static void calls_and_buffers(void) {
    hibi_rng *rng = NULL;
    hibi_mud *mud = NULL;
    hibi_mud_params mud_params = small_mud();
    hibi_glass_params glass_params = hibi_glass_params_default();
    hibi_skin_params skin_params = small_skin();
    hibi_glass *glass = NULL;
    hibi_skin *skin = NULL;
    size_t size = 777, count = 777, written = 777;
    float values[4] = {KEPT, KEPT, KEPT, KEPT};
    uint32_t bits = 777;
    /* 8-byte aligned storage for the misaligned and short caller-memory rows. */
    uint64_t storage[64];
    unsigned char *bytes = (unsigned char *)storage;
    void *memory;
    size_t glass_size = 0;
    hibi_mud_segment segment;

    if (hibi_rng_create(42, 7, &rng) != HIBI_OK || hibi_mud_create(&mud_params, &mud) != HIBI_OK ||
        hibi_glass_create(&glass_params, &glass) != HIBI_OK || hibi_skin_create(&skin_params, &skin) != HIBI_OK) {
        printf("setup failed\n");
        exit(1);
    }

    row_kept("null-params", hibi_mud_memory_size(NULL, &size), size == 777);
    row("null-size-output", hibi_glass_memory_size(&glass_params, NULL));
    row("null-object-output", hibi_skin_create(&skin_params, NULL));
    row_kept("null-object", hibi_skin_cell_count(NULL, &count), count == 777);
    row("null-buffer-with-length", hibi_rng_uniform(rng, NULL, 4));
    row_kept("null-written", hibi_mud_segments(mud, &segment, 1, NULL), 1);
    row("null-preset-name", hibi_mud_params_preset(NULL, &mud_params));
    row_kept("null-caller-memory", hibi_glass_create_in(&glass_params, NULL, 1 << 20, &glass), glass != NULL);

    {
        float *odd = (float *)(void *)(bytes + 1);
        memset(storage, 0xA5, sizeof storage);
        row_kept("misaligned-buffer", hibi_rng_uniform(rng, odd, 2), bytes[1] == 0xA5 && bytes[8] == 0xA5);
    }
    {
        hibi_rng *in = NULL;
        memset(storage, 0xA5, sizeof storage);
        row_kept("misaligned-memory", hibi_rng_create_in(1, 2, bytes + 4, hibi_rng_memory_size(), &in),
                 in == NULL && bytes[4] == 0xA5);
    }
    {
        hibi_rng *in = NULL;
        memset(storage, 0xA5, sizeof storage);
        row_kept("short-memory", hibi_rng_create_in(1, 2, storage, hibi_rng_memory_size() - 1, &in),
                 in == NULL && bytes[0] == 0xA5);
    }
    if (hibi_glass_memory_size(&glass_params, &glass_size) != HIBI_OK) {
        printf("glass memory size failed\n");
        exit(1);
    }
    memory = malloc(glass_size);
    {
        hibi_glass *in = NULL;
        memset(memory, 0xA5, glass_size);
        row_kept("short-memory-from-memory-size",
                 hibi_glass_create_in(&glass_params, memory, glass_size - 1, &in),
                 in == NULL && ((unsigned char *)memory)[0] == 0xA5);
    }
    free(memory);
    {
        hibi_mud_render_params render = hibi_mud_render_params_default();
        unsigned char pixels[16];
        memset(pixels, 0xA5, sizeof pixels);
        render.width = 4;
        render.height = 4;
        row_kept("short-pixel-buffer", hibi_mud_render(mud, &render, HIBI_MUD_LAYER_MASK, pixels, 15),
                 pixels[0] == 0xA5);
    }
    {
        size_t rings = 0, points = 0;
        hibi_ring ring;
        hibi_vec2 point;
        size_t rings_written = 777, points_written = 777, scratch_size = 0;
        void *scratch = NULL;
        if (hibi_glass_scratch_size(glass, &scratch_size) != HIBI_OK || (scratch = malloc(scratch_size)) == NULL ||
            hibi_glass_fragment_counts(glass, scratch, scratch_size, &rings, &points) != HIBI_OK) {
            printf("fragment counts failed\n");
            exit(1);
        }
        /* The fresh plate has one fragment, the whole plate: a point buffer of one is short. */
        row_kept("short-output-buffer",
                 hibi_glass_fragments(glass, scratch, scratch_size, &ring, 1, &point, points > 0 ? 1 : 0,
                                      &rings_written, &points_written),
                 rings_written == 777 && points_written == 777);
        rings = points = 777;
        row_kept("short-scratch", hibi_glass_fragment_counts(glass, scratch, scratch_size - 1, &rings, &points),
                 rings == 777 && points == 777);
        row_kept("null-scratch", hibi_glass_fragment_counts(glass, NULL, scratch_size, &rings, &points),
                 rings == 777 && points == 777);
        free(scratch);
    }
    row("null-optional-glass-progress", hibi_glass_step(glass, 1, NULL));
    row("null-optional-glass-counts", hibi_glass_impact(glass, 100.0f, 120.0f, NULL));
    row("null-optional-mud-progress", hibi_mud_step(mud, 1, NULL));
    row("null-optional-skin-progress", hibi_skin_step(skin, 1, NULL));
    row_kept("unknown-enum-argument", hibi_rng_rand(rng, 40.0f, 0.3f, 9, &values[0]), values[0] == KEPT);
    row_kept("huge-length", hibi_rng_uniform(rng, values, SIZE_MAX / 2), values[0] == KEPT);
    {
        hibi_glass_params huge = hibi_glass_params_default();
        hibi_glass *big = NULL;
        size_t need = 0;
        huge.max_cracks = 1u << 28;
        huge.max_vertices = 1u << 28;
        /* The largest valid capacities, whose block (54 GiB) no allocator here gives. */
        if (hibi_glass_memory_size(&huge, &need) != HIBI_OK || need < ((size_t)1 << 35)) {
            printf("huge-capacities: the block is not huge (%zu bytes)\n", need);
        }
        row_kept("huge-capacities", hibi_glass_create(&huge, &big), big == NULL);
    }

    row_kept("poisson-mean-nan", hibi_rng_poisson(rng, NAN, &bits), bits == 777);
    row_kept("poisson-mean-huge", hibi_rng_poisson(rng, 1e7, &bits), bits == 777);
    row_kept("rand-spread-ratio-inf", hibi_rng_rand(rng, 40.0f, INFINITY, HIBI_SPREAD_NORMAL, &values[0]),
             values[0] == KEPT);
    row_kept("rand-mean-nan", hibi_rng_rand(rng, NAN, 0.3f, HIBI_SPREAD_UNIFORM, &values[0]), values[0] == KEPT);
    row_kept("rand-range-past-flt-max", hibi_rng_rand(rng, FLT_MAX, 0.9f, HIBI_SPREAD_UNIFORM, &values[0]),
             values[0] == KEPT);

    /* Objects: indices and states. */
    {
        hibi_glass_crack crack;
        memset(&crack, 0xA5, sizeof crack);
        if (hibi_glass_crack_count(glass, &count) != HIBI_OK) {
            exit(1);
        }
        row_kept("crack-index-past-the-end", hibi_glass_crack_info(glass, count, &crack),
                 ((unsigned char *)&crack)[0] == 0xA5);
        written = 777;
        row_kept("crack-points-index-past-the-end",
                 hibi_glass_points(glass, SIZE_MAX, NULL, 0, &written), written == 777);
    }
    {
        hibi_vec2 points[3] = {{0.0f, 0.0f}, {1.0f, 0.0f}, {1.0f, 1.0f}};
        hibi_ring rings[2] = {{0.5, 1, 3, HIBI_RING_NOT_A_HOLE, 0}, {-0.5, 0, 3, 1, 0}};
        uint32_t scratch[64];
        hibi_triangle triangles[4];
        hibi_convex_piece pieces[4];
        size_t len = 777, written = 777, triangle_count = 777, piece_count = 777;
        hibi_ring *many = calloc(65537, sizeof(hibi_ring));
        hibi_vec2 *grid = calloc(16384, sizeof(hibi_vec2));
        size_t k;
        memset(triangles, 0xA5, sizeof triangles);
        memset(pieces, 0xA5, sizeof pieces);
        row_kept("ring-points-past-the-end", hibi_pieces_scratch_size(rings, 1, points, 3, &len), len == 777);
        rings[0].first_point = 0;
        row_kept("ring-hole-of-itself", hibi_triangulate(rings, 2, points, 3, scratch, 64, triangles, 4, &written),
                 written == 777 && ((unsigned char *)triangles)[0] == 0xA5);
        points[2].y = NAN;
        row_kept("ring-point-nan", hibi_convex_pieces(rings, 1, points, 3, scratch, 64, pieces, 4, &written),
                 written == 777 && ((unsigned char *)pieces)[0] == 0xA5);
        points[2].y = 1.0f;
        if (many == NULL || grid == NULL) {
            printf("out of memory\n");
            exit(1);
        }
        many[0].point_count = 16384;
        many[0].hole_of = HIBI_RING_NOT_A_HOLE;
        for (k = 1; k < 65537; k++) {
            many[k].point_count = 16384;
            many[k].hole_of = 0;
        }
        row_kept("ring-polygon-too-large",
                 hibi_pieces_counts(many, 65537, grid, 16384, scratch, 64, &triangle_count, &piece_count),
                 triangle_count == 777 && piece_count == 777);
        free(many);
        free(grid);
        if (hibi_pieces_scratch_size(rings, 1, points, 3, &len) != HIBI_OK || len > 64) {
            printf("hibi_pieces_scratch_size failed\n");
            exit(1);
        }
        row_kept("short-pieces-buffer", hibi_convex_pieces(rings, 1, points, 3, scratch, len, pieces, 0, &written),
                 written == 777 && ((unsigned char *)pieces)[0] == 0xA5);
        {
            hibi_vec2 tie[4] = {{0.0f, 0.0f}, {1.0f, 1.0f}, {1.0f, 0.0f}, {0.0f, 1.0f}};
            hibi_ring bow[1] = {{0.0, 0, 4, HIBI_RING_NOT_A_HOLE, 0}};
            row_kept("ring-crosses-itself", hibi_convex_pieces(bow, 1, tie, 4, scratch, 64, pieces, 4, &written),
                     written == 777 && ((unsigned char *)pieces)[0] == 0xA5);
        }
    }
    {
        hibi_glass_counts counts;
        memset(&counts, 0xA5, sizeof counts);
        row_kept("impact-outside-the-plate", hibi_glass_impact(glass, -1.0f, 10.0f, &counts),
                 ((unsigned char *)&counts)[0] == 0xA5);
        row_kept("impact-nan", hibi_glass_impact(glass, NAN, 10.0f, &counts), ((unsigned char *)&counts)[0] == 0xA5);
    }
    {
        hibi_glass_render_params render = hibi_glass_render_params_default();
        unsigned char pixels[16];
        memset(pixels, 0xA5, sizeof pixels);
        render.width = 4;
        render.height = 4;
        row_kept("glass-unknown-layer", hibi_glass_render(glass, &render, 2, pixels, 16), pixels[0] == 0xA5);
        render.line_width = NAN;
        row_kept("glass-line-width-nan", hibi_glass_render(glass, &render, HIBI_GLASS_LAYER_MASK, pixels, 16),
                 pixels[0] == 0xA5);
        render.line_width = 1.0f;
        render.width = 0;
        row_kept("glass-render-zero-width", hibi_glass_render(glass, &render, HIBI_GLASS_LAYER_MASK, pixels, 16),
                 pixels[0] == 0xA5);
        render.width = 4;
        {
            float normals[3 * 16];
            hibi_layers layers;
            hibi_tile tile = {3, 0, 2, 1};
            memset(&layers, 0, sizeof layers);
            normals[0] = KEPT;
            layers.mask = pixels;
            layers.pixels_len = 16;
            row_kept("layers-tile-past-the-edge", hibi_glass_render_layers(glass, &render, &tile, &layers),
                     pixels[0] == 0xA5);
            layers.normal = normals;
            row_kept("layers-normal-without-scratch", hibi_glass_render_layers(glass, &render, NULL, &layers),
                     pixels[0] == 0xA5 && normals[0] == KEPT);
            layers.normal = NULL;
            render.until = NAN;
            row_kept("glass-until-nan", hibi_glass_render_layers(glass, &render, NULL, &layers), pixels[0] == 0xA5);
        }
    }
    {
        hibi_mud_render_params render = hibi_mud_render_params_default();
        unsigned char pixels[16];
        memset(pixels, 0xA5, sizeof pixels);
        render.width = 4;
        render.height = 4;
        row_kept("mud-unknown-layer", hibi_mud_render(mud, &render, 3, pixels, 16), pixels[0] == 0xA5);
        render.width = UINT32_MAX;
        render.height = UINT32_MAX;
        row_kept("mud-render-huge-size", hibi_mud_render(mud, &render, HIBI_MUD_LAYER_MASK, pixels, 16),
                 pixels[0] == 0xA5);
        {
            hibi_mud_render_params fit = render;
            row_kept("mud-render-fit-width-zero", hibi_mud_render_params_fit(mud, 0, &fit),
                     fit.width == UINT32_MAX && fit.height == UINT32_MAX);
        }
        render.width = 4;
        render.height = 4;
        render.width_scale = -1.0f;
        row_kept("mud-width-scale-negative", hibi_mud_render(mud, &render, HIBI_MUD_LAYER_MASK, pixels, 16),
                 pixels[0] == 0xA5);
        render.width_scale = 1.0f;
        render.min_width = INFINITY;
        row_kept("mud-min-width-inf", hibi_mud_render(mud, &render, HIBI_MUD_LAYER_MASK, pixels, 16),
                 pixels[0] == 0xA5);
        render.min_width = 0.0f;
        render.groove_depth = NAN;
        row_kept("mud-groove-depth-nan", hibi_mud_render(mud, &render, HIBI_MUD_LAYER_HEIGHT, pixels, 16),
                 pixels[0] == 0xA5);
        render.groove_depth = 1.0f;
        render.offset[1] = -INFINITY;
        row_kept("mud-offset-inf", hibi_mud_render(mud, &render, HIBI_MUD_LAYER_MASK, pixels, 16), pixels[0] == 0xA5);
        render.offset[1] = 0.0f;
        {
            uint32_t cells[16];
            hibi_layers layers;
            memset(&layers, 0, sizeof layers);
            cells[0] = 777;
            layers.mask = pixels;
            layers.cell = cells;
            layers.pixels_len = 16;
            row_kept("layers-mud-cell", hibi_mud_render_layers(mud, &render, NULL, &layers),
                     pixels[0] == 0xA5 && cells[0] == 777);
            layers.cell = NULL;
            render.bump = NAN;
            row_kept("mud-bump-nan", hibi_mud_render_layers(mud, &render, NULL, &layers), pixels[0] == 0xA5);
        }
    }
    {
        hibi_skin_cell cell;
        hibi_skin_render_params render = hibi_skin_render_params_default();
        double xy[4] = {KEPT, KEPT, KEPT, KEPT};
        uint32_t *cells = malloc(64 * 48 * sizeof *cells);
        if (cells == NULL) {
            exit(1);
        }
        cells[0] = 777;
        memset(&cell, 0xA5, sizeof cell);
        if (hibi_skin_cell_count(skin, &count) != HIBI_OK) {
            exit(1);
        }
        row_kept("cell-index-past-the-end", hibi_skin_cell_info(skin, count, &cell), ((unsigned char *)&cell)[0] == 0xA5);
        written = 777;
        row_kept("outline-index-huge", hibi_skin_outline(skin, SIZE_MAX, xy, 4, &written),
                 written == 777 && xy[0] == KEPT);
        row_kept("skin-unknown-layer", hibi_skin_render(skin, &render, 3, cells, 64 * 48), cells[0] == 777);
        row_kept("short-cell-map", hibi_skin_render(skin, &render, HIBI_SKIN_LAYER_CELLS, cells, 4), cells[0] == 777);
        render.cell_level = 2;
        row_kept("cell-level-past-the-levels", hibi_skin_render(skin, &render, HIBI_SKIN_LAYER_CELLS, cells, 64 * 48),
                 cells[0] == 777);
        free(cells);
    }
    {
        hibi_skin_params p = small_skin();
        hibi_skin *full = NULL;
        hibi_skin_progress progress;
        memset(&progress, 0xA5, sizeof progress);
        /* A parent holding more centre points than the build can sort. */
        p.width = 128;
        p.height = 128;
        p.level[0].spacing = 128.0f;
        p.level[1].spacing = 1.5f;
        p.level[0].perturbation_depth = 0;
        p.level[1].perturbation_depth = 0;
        if (hibi_skin_create(&p, &full) != HIBI_OK) {
            printf("skin create failed\n");
            exit(1);
        }
        row_kept("skin-outgrows-its-capacity", hibi_skin_step(full, UINT64_MAX, &progress),
                 ((unsigned char *)&progress)[0] == 0xA5);
        hibi_skin_destroy(full);
    }
    {
        hibi_glass_params p = hibi_glass_params_default();
        hibi_glass *full = NULL;
        hibi_glass_progress progress;
        hibi_glass_counts counts;
        hibi_status status = HIBI_OK;
        int calls = 0;
        p.max_vertices = 80;
        if (hibi_glass_create(&p, &full) != HIBI_OK) {
            printf("glass create failed\n");
            exit(1);
        }
        do {
            status = hibi_glass_step(full, 1000, &progress);
        } while (status == HIBI_OK && !progress.finished && ++calls < 10000);
        row("glass-outgrows-its-capacity", status);
        memset(&counts, 0xA5, sizeof counts);
        row_kept("glass-impact-after-capacity", hibi_glass_impact(full, 100.0f, 120.0f, &counts),
                 ((unsigned char *)&counts)[0] == 0xA5);
        hibi_glass_destroy(full);
    }
    {
        float height[2] = {0.0f, 1.0f};
        float normal[6] = {0, 0, 1, 0, 0, 1};
        unsigned char rgb[6] = {0xA5, 0xA5, 0xA5, 0xA5, 0xA5, 0xA5};
        hibi_skin_shade_params shade = hibi_skin_shade_params_default();
        shade.light[0] = shade.light[1] = shade.light[2] = 0.0f;
        row_kept("shade-light-zero", hibi_skin_shade(height, 2, normal, 6, &shade, rgb, 6), rgb[0] == 0xA5);
        shade = hibi_skin_shade_params_default();
        shade.ridge[1] = NAN;
        row_kept("shade-ridge-nan", hibi_skin_shade(height, 2, normal, 6, &shade, rgb, 6), rgb[0] == 0xA5);
        shade = hibi_skin_shade_params_default();
        shade.furrow[2] = 2.0f;
        row_kept("shade-furrow-above-1", hibi_skin_shade(height, 2, normal, 6, &shade, rgb, 6), rgb[0] == 0xA5);
        shade = hibi_skin_shade_params_default();
        shade.ambient = -0.5f;
        row_kept("shade-ambient-negative", hibi_skin_shade(height, 2, normal, 6, &shade, rgb, 6), rgb[0] == 0xA5);
        shade = hibi_skin_shade_params_default();
        shade.specular = INFINITY;
        row_kept("shade-specular-inf", hibi_skin_shade(height, 2, normal, 6, &shade, rgb, 6), rgb[0] == 0xA5);
        shade = hibi_skin_shade_params_default();
        shade.light[0] = shade.light[1] = 0.0f;
        shade.light[2] = 1e30f;
        {
            hibi_status status = hibi_skin_shade(height, 2, normal, 6, &shade, rgb, 6);
            printf("shade-light-huge: status %u, output written: %s [%s]\n", (unsigned)status, rgb[0] != 0xA5 ? "yes" : "no",
                   hibi_error_argument());
        }
        memset(rgb, 0xA5, sizeof rgb);
        shade = hibi_skin_shade_params_default();
        row_kept("shade-short-rgb", hibi_skin_shade(height, 2, normal, 6, &shade, rgb, 5), rgb[0] == 0xA5);
        /* Five floats are one whole normal, not two: the call must refuse, not return
         * HIBI_OK with the second pixel unwritten. No byte of rgb may change. */
        row_kept("shade-short-normal", hibi_skin_shade(height, 2, normal, 5, &shade, rgb, 6),
                 rgb[0] == 0xA5 && rgb[1] == 0xA5 && rgb[2] == 0xA5 && rgb[3] == 0xA5 && rgb[4] == 0xA5 &&
                     rgb[5] == 0xA5);
    }
    {
        hibi_mud_params out = small_mud();
        hibi_glass_params glass_out = hibi_glass_params_default();
        hibi_skin_params skin_out = small_skin();
        out.columns = 777;
        glass_out.max_cracks = 777;
        skin_out.width = 777;
        row_kept("mud-unknown-preset", hibi_mud_params_preset("fig99", &out), out.columns == 777);
        row_kept("glass-unknown-preset", hibi_glass_params_preset("fig99", &glass_out), glass_out.max_cracks == 777);
        row_kept("skin-unknown-preset", hibi_skin_params_preset("fig99", &skin_out), skin_out.width == 777);
    }

    hibi_skin_destroy(skin);
    hibi_glass_destroy(glass);
    hibi_mud_destroy(mud);
    hibi_rng_destroy(rng);
}

static void parameters(void) {
    hibi_mud_params zeroed;
    hibi_glass_params glass_zeroed;
    hibi_skin_params skin_zeroed;
    memset(&zeroed, 0, sizeof zeroed);
    memset(&glass_zeroed, 0, sizeof glass_zeroed);
    memset(&skin_zeroed, 0, sizeof skin_zeroed);
    mud_row("mud-params-zeroed", &zeroed);
    glass_row("glass-params-zeroed", &glass_zeroed);
    skin_row("skin-params-zeroed", &skin_zeroed);

    MUD("mud-unknown-topology", p_.topology = 3);
    MUD("mud-unknown-solver", p_.solver = 7);
    MUD("mud-columns-1", p_.columns = 1);
    MUD("mud-periodic-hexagonal-odd-rows", (p_.boundary = HIBI_MUD_PERIODIC, p_.topology = HIBI_MUD_HEXAGONAL,
                                             p_.rows = 5));
    MUD("mud-layer-thickness-zero", p_.layer_thickness = 0.0f);
    MUD("mud-element-size-nan", p_.element_size = NAN);
    MUD("mud-long-step-inf", p_.long_step = INFINITY);
    MUD("mud-short-step-negative", p_.short_step = -1.0f);
    MUD("mud-shrink-ratio-1", p_.shrink_ratio = 1.0f);
    MUD("mud-growth-step-too-large", (p_.drive = HIBI_MUD_GROWTH, p_.shrink_ratio = 0.001f));
    MUD("mud-displacement-tolerance-zero", p_.displacement_tolerance = 0.0f);
    MUD("mud-damping-factor-minus-inf", p_.damping_factor = -INFINITY);
    MUD("mud-density-negative", p_.density = -2.0f);
    MUD("mud-young-modulus-nan", p_.young_modulus = NAN);
    MUD("mud-shear-modulus-negative", p_.shear_modulus = -1.0f);
    MUD("mud-break-stretch-mean-1", p_.break_stretch_mean = 1.0f);
    MUD("mud-break-stretch-spread-negative", p_.break_stretch_spread = -0.001f);
    MUD("mud-break-stretch-size-exponent-nan", p_.break_stretch_size_exponent = NAN);
    MUD("mud-anisotropy-direction-inf", p_.anisotropy_direction = INFINITY);
    MUD("mud-anisotropy-ratio-below-1", p_.anisotropy_ratio = 0.5f);
    MUD("mud-stiffness-anisotropy-ratio-huge", p_.stiffness_anisotropy_ratio = 1e9f);
    MUD("mud-target-shrink-1", p_.target_shrink = 1.0f);
    MUD("mud-target-crack-density-negative", p_.target_crack_density = -1.0f);
    MUD("mud-lattice-too-large", (p_.columns = UINT32_MAX, p_.rows = UINT32_MAX - 1));
    MUD("mud-lattice-over-2-28-nodes", (p_.columns = 16385, p_.rows = 16384));
    MUD("mud-irregular-too-wide", (p_.topology = HIBI_MUD_IRREGULAR, p_.columns = 1048577, p_.rows = 8));
    MUD("mud-shear-out-of-scale", p_.young_modulus = 1e20f);
    MUD("mud-damping-out-of-scale", p_.damping_factor = 1e9f);
    MUD("mud-short-step-out-of-scale", p_.short_step = 1e9f);
    MUD("mud-tolerance-out-of-scale", p_.displacement_tolerance = 1e-12f);
    MUD("mud-spread-out-of-scale", p_.break_stretch_spread = FLT_MAX);
    MUD("mud-short-step-unstable", (p_.solver = HIBI_MUD_EXPLICIT, p_.short_step = 1.0f));
    {
        /* An irregular lattice's explicit run is tested on its mesh, which the first steps
         * build: creation accepts it, and the step that finds the failing node refuses it,
         * writing no progress. */
        hibi_mud_params p = small_mud();
        hibi_mud *mud = NULL;
        hibi_mud_progress progress;
        hibi_status status;
        int kept = 0;
        p.topology = HIBI_MUD_IRREGULAR;
        p.solver = HIBI_MUD_EXPLICIT;
        p.short_step = 1.0f;
        p.columns = 12;
        p.rows = 12;
        status = hibi_mud_create(&p, &mud);
        if (status == HIBI_OK) {
            do {
                memset(&progress, 0x5a, sizeof progress);
                status = hibi_mud_step(mud, 1000, &progress);
            } while (status == HIBI_OK && !progress.finished);
            kept = progress.work == 0x5a5a5a5a5a5a5a5aull && progress.finished == 0x5a5a5a5au;
            hibi_mud_destroy(mud);
        }
        row_kept("mud-irregular-short-step-unstable", status, kept);
    }

    GLASS("glass-unknown-spread", p_.spread = 5);
    GLASS("glass-width-nan", p_.width = NAN);
    GLASS("glass-width-past-65536", p_.width = 1e20f);
    GLASS("glass-impact-outside", (p_.impact[0] = 700.0f, p_.impact[1] = 10.0f));
    GLASS("glass-radial-mean-negative", p_.radial_mean = -1.0f);
    GLASS("glass-ring-threshold-nan", p_.ring_threshold = NAN);
    GLASS("glass-large-slope-inf", p_.large_slope = INFINITY);
    GLASS("glass-ring-radius-offset-negative", p_.ring_radius_offset = -1.0f);
    GLASS("glass-speed-zero", p_.ring_speed = 0.0f);
    GLASS("glass-spread-ratio-1", p_.spread_ratio = 1.0f);
    GLASS("glass-turn-limit-negative", p_.turn_limit = -0.1f);
    GLASS("glass-turn-delay-zero", p_.turn_delay = 0.0f);
    GLASS("glass-sector-radius-negative", p_.sector_radius = -5.0f);
    GLASS("glass-wander-nan", p_.wander = NAN);
    GLASS("glass-max-vertices-1", p_.max_vertices = 1);
    GLASS("glass-max-vertices-over-2-28", p_.max_vertices = 268435457u);
    GLASS("glass-max-cracks-over-2-28", p_.max_cracks = 268435457u);

    SKIN("skin-unknown-layout", p_.layout = 3);
    SKIN("skin-periodic-2", p_.periodic = 2);
    SKIN("skin-width-zero", p_.width = 0);
    SKIN("skin-jitter-ratio-nan", p_.jitter_ratio = NAN);
    SKIN("skin-levels-5", p_.levels = 5);
    SKIN("skin-spacing-below-one-pixel", p_.level[1].spacing = 0.5f);
    SKIN("skin-perturbation-decay-negative", p_.level[0].perturbation_decay = -1.0f);
    SKIN("skin-perturbation-depth-6", p_.level[0].perturbation_depth = 6);
    SKIN("skin-stretch-zero", p_.level[1].stretch[0] = 0.0f);
    SKIN("skin-stretch-tiny", p_.level[0].stretch[0] = 1e-30f);
    SKIN("skin-profile-no-segments", p_.level[0].profile.segments = 0);
    SKIN("skin-profile-point-inf", p_.level[0].profile.points[1][0] = INFINITY);
    SKIN("skin-roundness-1.5", p_.level[1].roundness = 1.5f);
    SKIN("skin-too-large", (p_.width = 32768, p_.height = 32768, p_.levels = 4));
}

int main(void) {
    calls_and_buffers();
    parameters();
    return 0;
}
