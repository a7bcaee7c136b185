/*
 * Polygons and rasters share their axes: x to the right along a row, y down the rows, row 0
 * at y = 0. Each model's polygons (glass fragments, mud cells) are laid over its crack mask,
 * drawn at the domain's aspect: the midpoints of their edges (those not on the plate's
 * border) fall on crack pixels, and with y flipped they mostly do not; every outer ring has
 * a positive signed area in those axes (clockwise as the raster shows it).
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include "hibi.h"

/* Whether a crack pixel lies within one pixel of (x, y), pixels; `wrap` for a periodic
 * domain. */
static int on_crack(const uint8_t *mask, uint32_t w, uint32_t h, double x, double y, int wrap) {
    long cx = (long)floor(x), cy = (long)floor(y), dx, dy;
    for (dy = -1; dy <= 1; dy++) {
        for (dx = -1; dx <= 1; dx++) {
            long px = cx + dx, py = cy + dy;
            if (wrap) {
                px = ((px % (long)w) + (long)w) % (long)w;
                py = ((py % (long)h) + (long)h) % (long)h;
            }
            if (px >= 0 && py >= 0 && px < (long)w && py < (long)h && mask[(size_t)py * w + (size_t)px] > 0) return 1;
        }
    }
    return 0;
}

typedef struct {
    size_t edges, hits, flipped_hits, outer, outer_positive;
} overlay;

/* Lays `rings` (points in domain units, `scale` pixels a unit) over `mask`. */
static overlay lay(const hibi_ring *rings, size_t ring_count, const hibi_vec2 *points,
                   const uint8_t *mask, uint32_t w, uint32_t h, double scale[2], double domain[2], int wrap) {
    overlay o = {0, 0, 0, 0, 0};
    size_t r, i;
    for (r = 0; r < ring_count; r++) {
        const hibi_ring *ring = &rings[r];
        double twice_area = 0.0;
        for (i = 0; i < ring->point_count; i++) {
            hibi_vec2 a = points[ring->first_point + i];
            hibi_vec2 b = points[ring->first_point + (i + 1) % ring->point_count];
            double mx = 0.5 * ((double)a.x + b.x), my = 0.5 * ((double)a.y + b.y);
            int border_x = (a.x <= 0.0f && b.x <= 0.0f) || (a.x >= domain[0] && b.x >= domain[0]);
            int border_y = (a.y <= 0.0f && b.y <= 0.0f) || (a.y >= domain[1] && b.y >= domain[1]);
            twice_area += (double)a.x * b.y - (double)b.x * a.y;
            if (!wrap && (border_x || border_y)) continue;
            o.edges++;
            o.hits += (size_t)on_crack(mask, w, h, mx * scale[0], my * scale[1], wrap);
            o.flipped_hits += (size_t)on_crack(mask, w, h, mx * scale[0], (domain[1] - my) * scale[1], wrap);
        }
        if (ring->area > 0.0) {
            o.outer++;
            o.outer_positive += twice_area > 0.0;
        }
    }
    return o;
}

static void report(const char *model, overlay o) {
    printf("%s: %zu edges, on cracks %.3f, flipped %.3f; outer rings positive %zu of %zu\n", model, o.edges,
           (double)o.hits / (double)o.edges, (double)o.flipped_hits / (double)o.edges, o.outer_positive, o.outer);
}

static void glass(void) {
    hibi_glass_params p = hibi_glass_params_default();
    hibi_glass_render_params render = hibi_glass_render_params_default();
    hibi_glass_progress progress = {0};
    hibi_glass *glass = NULL;
    size_t scratch_size = 0, ring_count = 0, point_count = 0, rw = 0, pw = 0;
    void *scratch;
    hibi_ring *rings;
    hibi_vec2 *points;
    uint8_t *mask;
    double scale[2], domain[2];
    p.impact[0] = 0.4f * p.width;
    p.impact[1] = 0.3f * p.height; /* off-centre, so that a flip in y shows */
    if (hibi_glass_create(&p, &glass) != HIBI_OK) exit(1);
    while (!progress.finished) {
        if (hibi_glass_step(glass, 100000, &progress) != HIBI_OK) exit(1);
    }
    hibi_glass_scratch_size(glass, &scratch_size);
    scratch = malloc(scratch_size);
    if (hibi_glass_fragment_counts(glass, scratch, scratch_size, &ring_count, &point_count) != HIBI_OK) exit(1);
    rings = malloc(ring_count * sizeof *rings);
    points = malloc(point_count * sizeof *points);
    if (hibi_glass_fragments(glass, scratch, scratch_size, rings, ring_count, points, point_count, &rw, &pw) != HIBI_OK)
        exit(1);
    render.width = (uint32_t)p.width;
    render.height = (uint32_t)p.height;
    mask = malloc((size_t)render.width * render.height);
    if (hibi_glass_render(glass, &render, HIBI_GLASS_LAYER_MASK, mask, (size_t)render.width * render.height) != HIBI_OK)
        exit(1);
    scale[0] = render.width / (double)p.width;
    scale[1] = render.height / (double)p.height;
    domain[0] = p.width;
    domain[1] = p.height;
    report("glass", lay(rings, rw, points, mask, render.width, render.height, scale, domain, 0));
    free(mask);
    free(points);
    free(rings);
    free(scratch);
    hibi_glass_destroy(glass);
}

static void mud(void) {
    hibi_mud_params p = hibi_mud_params_default();
    hibi_mud_render_params render;
    hibi_mud_progress progress = {0};
    hibi_mud *mud = NULL;
    hibi_vec2 extent;
    size_t ring_count = 0, point_count = 0, wrapping = 0, rw = 0, pw = 0;
    hibi_ring *rings;
    hibi_vec2 *points;
    uint8_t *mask;
    double scale[2], domain[2];
    p.columns = 48;
    p.rows = 64;
    if (hibi_mud_create(&p, &mud) != HIBI_OK) exit(1);
    while (!progress.finished) {
        if (hibi_mud_step(mud, 1000000, &progress) != HIBI_OK) exit(1);
    }
    if (hibi_mud_extent(mud, &extent) != HIBI_OK) exit(1);
    if (hibi_mud_render_params_fit(mud, 384, &render) != HIBI_OK) exit(1);
    printf("mud extent %.4f x %.4f, render %u x %u (aspect kept: %s)\n", extent.x, extent.y, render.width,
           render.height,
           fabs(render.width / (double)render.height - extent.x / (double)extent.y) < 2.0 / render.height ? "yes" : "no");
    if (hibi_mud_cell_counts(mud, &ring_count, &point_count, &wrapping) != HIBI_OK) exit(1);
    rings = malloc(ring_count * sizeof *rings);
    points = malloc(point_count * sizeof *points);
    if (hibi_mud_cells(mud, rings, ring_count, points, point_count, &rw, &pw) != HIBI_OK) exit(1);
    mask = malloc((size_t)render.width * render.height);
    if (hibi_mud_render(mud, &render, HIBI_MUD_LAYER_MASK, mask, (size_t)render.width * render.height) != HIBI_OK)
        exit(1);
    scale[0] = render.width / (double)extent.x;
    scale[1] = render.height / (double)extent.y;
    domain[0] = extent.x;
    domain[1] = extent.y;
    report("mud", lay(rings, rw, points, mask, render.width, render.height, scale, domain, p.boundary == HIBI_MUD_PERIODIC));
    free(mask);
    free(points);
    free(rings);
    hibi_mud_destroy(mud);
}

int main(void) {
    glass();
    mud();
    return 0;
}
