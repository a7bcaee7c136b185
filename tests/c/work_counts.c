/*
 * Create and render take time bounded by sizes and capacities whatever the float fields
 * hold, measured as work. hibi reports no work count for create or render, so
 * tests/c_examples.rs runs this program under Callgrind (`--collect-atstart=no`) and counts
 * the instructions of each measured call: collection is on only inside the call, and each
 * call's count is dumped under its case's name. Each case is a pair: the call with an
 * extreme value, and its twin with a moderate value of the same sizes and capacities that
 * already saturates what the value can change (a ring count formula beyond max_cracks, a
 * stroke wider than the raster, ...). The program prints a digest of each call's result, so
 * the test can also check that the twin gives the same result where the value cannot matter.
 * Outside Callgrind the requests do nothing: the program runs under the sanitizers and
 * Valgrind as every C test does.
 */
#include <float.h>
#include <malloc.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <valgrind/callgrind.h>

#include "hibi.h"

static uint64_t fnv(uint64_t h, const void *bytes, size_t len) {
    const unsigned char *b = bytes;
    size_t i;
    for (i = 0; i < len; i++) {
        h = (h ^ b[i]) * 1099511628211u;
    }
    return h;
}

#define FNV_START 14695981039346656037u

/* Runs `call` with collection on, then dumps its count as `name`. */
#define MEASURE(name, status, call)         \
    do {                                    \
        CALLGRIND_TOGGLE_COLLECT;           \
        status = (call);                    \
        CALLGRIND_TOGGLE_COLLECT;           \
        CALLGRIND_DUMP_STATS_AT(name);      \
    } while (0)

static void report(const char *name, hibi_status status, uint64_t digest) {
    printf("%s: status %u, digest %016llx\n", name, (unsigned)status, (unsigned long long)digest);
}

/* ------------------------------------------------------------------------------------- */
/* Glass create */

static hibi_glass_params glass_base(void) {
    hibi_glass_params p = hibi_glass_params_default();
    p.width = 128.0f;
    p.height = 128.0f;
    p.impact[0] = 64.0f;
    p.impact[1] = 64.0f;
    p.max_cracks = 128;
    p.max_vertices = 2048;
    return p;
}

/* The plate as created: its cracks (start points) and their polylines. */
static uint64_t glass_digest(const hibi_glass *glass) {
    uint64_t h = FNV_START;
    size_t count = 0, i, written = 0;
    hibi_glass_point points[64];
    hibi_glass_crack_count(glass, &count);
    h = fnv(h, &count, sizeof count);
    for (i = 0; i < count; i++) {
        hibi_glass_crack crack;
        hibi_glass_crack_info(glass, i, &crack);
        h = fnv(h, &crack, sizeof crack);
        if (crack.points <= 64 && hibi_glass_points(glass, i, points, 64, &written) == HIBI_OK) {
            h = fnv(h, points, written * sizeof *points);
        }
    }
    return h;
}

static void glass_create(const char *name, const hibi_glass_params *p) {
    hibi_glass *glass = NULL;
    hibi_status status;
    MEASURE(name, status, hibi_glass_create(p, &glass));
    report(name, status, status == HIBI_OK ? glass_digest(glass) : 0);
    hibi_glass_destroy(glass);
}

#define GLASS_CREATE(name, change)            \
    do {                                      \
        hibi_glass_params p_ = glass_base();  \
        change;                               \
        glass_create(name, &p_);              \
    } while (0)

/* hibi_glass_create_in over memory from malloc that nothing has written: the plate writes no
 * array of it, whatever its capacities. */
static void glass_create_in(const char *name, const hibi_glass_params *p) {
    hibi_glass *glass = NULL;
    hibi_status status;
    size_t size = 0;
    void *memory;
    if (hibi_glass_memory_size(p, &size) != HIBI_OK || (memory = malloc(size)) == NULL) {
        printf("%s: no memory\n", name);
        return;
    }
    MEASURE(name, status, hibi_glass_create_in(p, memory, size, &glass));
    report(name, status, status == HIBI_OK ? glass_digest(glass) : 0);
    hibi_glass_destroy(glass);
    free(memory);
}

/* ------------------------------------------------------------------------------------- */
/* Mud and skin create */

static hibi_mud_params mud_base(void) {
    hibi_mud_params p = hibi_mud_params_default();
    p.columns = 16;
    p.rows = 16;
    return p;
}

static void mud_create(const char *name, const hibi_mud_params *p) {
    hibi_mud *mud = NULL;
    hibi_status status;
    MEASURE(name, status, hibi_mud_create(p, &mud));
    report(name, status, 0);
    hibi_mud_destroy(mud);
}

#define MUD_CREATE(name, change)          \
    do {                                  \
        hibi_mud_params p_ = mud_base();  \
        change;                           \
        mud_create(name, &p_);            \
    } while (0)

static hibi_skin_params skin_base(void) {
    hibi_skin_params p = hibi_skin_params_default();
    p.width = 48;
    p.height = 48;
    p.levels = 2;
    p.level[0].spacing = 16.0f;
    p.level[1].spacing = 16.0f / 3.0f;
    return p;
}

static void skin_create(const char *name, const hibi_skin_params *p) {
    hibi_skin *skin = NULL;
    hibi_status status;
    MEASURE(name, status, hibi_skin_create(p, &skin));
    report(name, status, 0);
    hibi_skin_destroy(skin);
}

#define SKIN_CREATE(name, change)          \
    do {                                   \
        hibi_skin_params p_ = skin_base(); \
        change;                            \
        skin_create(name, &p_);            \
    } while (0)

/* ------------------------------------------------------------------------------------- */
/* Renders */

/* Small: a saturating stroke visits every pixel of the raster (9 copies when periodic). */
#define SIDE 4
#define PIXELS (SIDE * SIDE)

static void mud_render(const char *name, const hibi_mud *mud, const hibi_mud_render_params *r, uint32_t layer) {
    static float pixels[PIXELS];
    hibi_status status;
    memset(pixels, 0, sizeof pixels);
    MEASURE(name, status, hibi_mud_render(mud, r, layer, pixels, PIXELS));
    report(name, status,
           layer == HIBI_MUD_LAYER_MASK ? fnv(FNV_START, pixels, PIXELS) : fnv(FNV_START, pixels, sizeof pixels));
}

static hibi_mud *mud_run(uint32_t boundary) {
    hibi_mud_params p = mud_base();
    hibi_mud *mud = NULL;
    hibi_mud_progress progress;
    p.columns = 8;
    p.rows = 8;
    p.boundary = boundary;
    if (hibi_mud_create(&p, &mud) != HIBI_OK) {
        printf("mud create failed\n");
        exit(1);
    }
    do {
        if (hibi_mud_step(mud, UINT64_MAX, &progress) != HIBI_OK) {
            printf("mud step failed\n");
            exit(1);
        }
    } while (!progress.finished);
    return mud;
}

#define MUD_RENDER(name, mud, layer, change)                              \
    do {                                                                  \
        hibi_mud_render_params r_ = hibi_mud_render_params_default();     \
        r_.width = SIDE;                                                  \
        r_.height = SIDE;                                                 \
        change;                                                           \
        mud_render(name, mud, &r_, layer);                                \
    } while (0)

static void glass_render(const char *name, const hibi_glass *glass, float line_width) {
    static unsigned char pixels[PIXELS];
    hibi_glass_render_params r = hibi_glass_render_params_default();
    hibi_status status;
    r.width = SIDE;
    r.height = SIDE;
    r.line_width = line_width;
    memset(pixels, 0, sizeof pixels);
    MEASURE(name, status, hibi_glass_render(glass, &r, HIBI_GLASS_LAYER_MASK, pixels, PIXELS));
    report(name, status, fnv(FNV_START, pixels, PIXELS));
}

/* A skin of one level whose cells a strong anisotropic stretch and a perturbation make reach
 * far past the surface (the skin fuzz target's finding 14: 10^7 rows beyond a 33-row surface,
 * each scanned): its height map is drawn on the surface's rows only. */
#define SKIN_SIDE 33

static void skin_render(const char *name, const hibi_skin_params *p) {
    static float pixels[SKIN_SIDE * SKIN_SIDE];
    hibi_skin_render_params r = hibi_skin_render_params_default();
    hibi_skin *skin = NULL;
    hibi_skin_progress progress;
    hibi_status status;
    if (hibi_skin_create(p, &skin) != HIBI_OK || hibi_skin_step(skin, UINT64_MAX, &progress) != HIBI_OK) {
        printf("skin create or step failed\n");
        exit(1);
    }
    memset(pixels, 0, sizeof pixels);
    MEASURE(name, status, hibi_skin_render(skin, &r, HIBI_SKIN_LAYER_HEIGHT, pixels, SKIN_SIDE * SKIN_SIDE));
    report(name, status, fnv(FNV_START, pixels, sizeof pixels));
    hibi_skin_destroy(skin);
}

#define SKIN_RENDER(name, is_periodic, change)                 \
    do {                                                       \
        hibi_skin_params p_ = hibi_skin_params_default();      \
        p_.layout = HIBI_SKIN_LAYOUT_SQUARE;                   \
        p_.periodic = is_periodic;                             \
        p_.width = SKIN_SIDE;                                  \
        p_.height = SKIN_SIDE;                                 \
        p_.seed = 6802178615612166738u;                        \
        p_.jitter_ratio = 0.0f;                                \
        p_.levels = 1;                                         \
        p_.level[0].spacing = 40.0f;                           \
        p_.level[0].perturbation = 0.1f;                       \
        p_.level[0].perturbation_depth = 2;                    \
        change;                                                \
        skin_render(name, &p_);                                \
    } while (0)

int main(void) {
    hibi_mud *open, *periodic;
    hibi_glass *glass = NULL;
    hibi_glass_params gp = glass_base();
    hibi_glass_progress progress;

    /* hibi_*_create takes its block zeroed from calloc, whose cost is glibc's: a block it maps
     * fresh is zero already, one it reuses it clears, and which it does depends on the blocks
     * freed before (its mmap threshold moves). A fixed threshold makes that the same for a
     * case and its twin: every block of 128 KiB or more is mapped fresh. */
    mallopt(M_MMAP_THRESHOLD, 128 * 1024);

    /* Ring and large-crack counts: beyond max_cracks either way. */
    GLASS_CREATE("glass-create ring_slope twin", p_.ring_slope = 1e4f);
    GLASS_CREATE("glass-create ring_slope extreme", p_.ring_slope = 1e30f);
    GLASS_CREATE("glass-create ring_offset twin", p_.ring_offset = 1e4f);
    GLASS_CREATE("glass-create ring_offset extreme", p_.ring_offset = 1e30f);
    GLASS_CREATE("glass-create large_slope twin", p_.large_slope = 1e4f);
    GLASS_CREATE("glass-create large_slope extreme", p_.large_slope = 1e30f);
    GLASS_CREATE("glass-create ring_radius_slope twin", p_.ring_radius_slope = 1e4f);
    GLASS_CREATE("glass-create ring_radius_slope extreme", p_.ring_radius_slope = 1e30f);
    GLASS_CREATE("glass-create speeds twin", (p_.large_speed = p_.radial_speed = p_.ring_speed = 1e4f));
    GLASS_CREATE("glass-create speeds extreme", (p_.large_speed = p_.radial_speed = p_.ring_speed = 1e30f));
    /* The radial count is a Poisson draw of mean radial_mean (at most 10000). */
    /* The vertex, edge and word arrays are not written: the block's size does not matter. */
    GLASS_CREATE("glass-create max_vertices twin", p_.max_vertices = 2048);
    GLASS_CREATE("glass-create max_vertices extreme", p_.max_vertices = 2000000);
    GLASS_CREATE("glass-create radial_mean twin", p_.radial_mean = 100.0f);
    GLASS_CREATE("glass-create radial_mean extreme", p_.radial_mean = 10000.0f);
    /* Caller memory: no crack slot is written either (2 000 000 slots are 176 MB). */
    {
        hibi_glass_params p_ = glass_base();
        glass_create_in("glass-create_in max_cracks twin", &p_);
        p_.max_cracks = 2000000;
        glass_create_in("glass-create_in max_cracks extreme", &p_);
    }

    MUD_CREATE("mud-create break_stretch_mean twin", p_.break_stretch_mean = 1e4f);
    MUD_CREATE("mud-create break_stretch_mean extreme", p_.break_stretch_mean = 1e30f);
    MUD_CREATE("mud-create anisotropy twin", (p_.anisotropy_ratio = 1e4f, p_.anisotropy_direction = 3.0f));
    MUD_CREATE("mud-create anisotropy extreme", (p_.anisotropy_ratio = 1e30f, p_.anisotropy_direction = 1e30f));
    MUD_CREATE("mud-create target_crack_density twin", p_.target_crack_density = 1e4f);
    MUD_CREATE("mud-create target_crack_density extreme", p_.target_crack_density = 1e30f);

    SKIN_CREATE("skin-create perturbation twin", p_.level[0].perturbation = 1.0f);
    SKIN_CREATE("skin-create perturbation extreme", p_.level[0].perturbation = 1e30f);
    SKIN_CREATE("skin-create stretch twin", (p_.level[0].stretch[0] = p_.level[0].stretch[1] = 1e4f));
    SKIN_CREATE("skin-create stretch extreme", (p_.level[0].stretch[0] = p_.level[0].stretch[1] = 1e30f));

    SKIN_RENDER("skin-render stretch twin", 0, (p_.level[0].stretch[0] = 1.0f, p_.level[0].stretch[1] = 1e3f));
    SKIN_RENDER("skin-render stretch extreme", 0, (p_.level[0].stretch[0] = 1.0f, p_.level[0].stretch[1] = 1e30f));
    SKIN_RENDER("skin-render periodic stretch twin", 1, (p_.level[0].stretch[0] = 1.0f, p_.level[0].stretch[1] = 2e10f));
    SKIN_RENDER("skin-render periodic stretch extreme", 1,
                (p_.level[0].stretch[0] = 1.0f, p_.level[0].stretch[1] = 1e30f));

    /* Strokes wider than the raster: 4 (width + height) pixels already cover all of it. */
    open = mud_run(HIBI_MUD_OPEN);
    periodic = mud_run(HIBI_MUD_PERIODIC);
    MUD_RENDER("mud-render min_width twin", open, HIBI_MUD_LAYER_MASK, r_.min_width = 8.0f * SIDE);
    MUD_RENDER("mud-render min_width extreme", open, HIBI_MUD_LAYER_MASK, r_.min_width = FLT_MAX);
    MUD_RENDER("mud-render periodic min_width twin", periodic, HIBI_MUD_LAYER_MASK, r_.min_width = 8.0f * SIDE);
    MUD_RENDER("mud-render periodic min_width extreme", periodic, HIBI_MUD_LAYER_MASK, r_.min_width = FLT_MAX);
    MUD_RENDER("mud-render width_scale twin", open, HIBI_MUD_LAYER_MASK, r_.width_scale = 1e12f);
    MUD_RENDER("mud-render width_scale extreme", open, HIBI_MUD_LAYER_MASK, r_.width_scale = FLT_MAX);
    MUD_RENDER("mud-render groove_depth twin", open, HIBI_MUD_LAYER_HEIGHT, r_.groove_depth = 1.0f);
    MUD_RENDER("mud-render groove_depth extreme", open, HIBI_MUD_LAYER_HEIGHT, r_.groove_depth = FLT_MAX);
    MUD_RENDER("mud-render height width_scale twin", open, HIBI_MUD_LAYER_HEIGHT, r_.width_scale = 1e12f);
    MUD_RENDER("mud-render height width_scale extreme", open, HIBI_MUD_LAYER_HEIGHT, r_.width_scale = FLT_MAX);
    /* An offset moves the view: at most as much drawing as the plate in view. */
    MUD_RENDER("mud-render offset twin", open, HIBI_MUD_LAYER_TIME, (void)0);
    MUD_RENDER("mud-render offset extreme", open, HIBI_MUD_LAYER_TIME, (r_.offset[0] = 1e30f, r_.offset[1] = -1e30f));
    MUD_RENDER("mud-render periodic offset twin", periodic, HIBI_MUD_LAYER_TIME, (void)0);
    MUD_RENDER("mud-render periodic offset extreme", periodic, HIBI_MUD_LAYER_TIME,
               (r_.offset[0] = 1e30f, r_.offset[1] = -1e30f));
    hibi_mud_destroy(open);
    hibi_mud_destroy(periodic);

    if (hibi_glass_create(&gp, &glass) != HIBI_OK) {
        printf("glass create failed\n");
        exit(1);
    }
    do {
        hibi_status status = hibi_glass_step(glass, UINT64_MAX, &progress);
        if (status == HIBI_ERROR_GLASS_CAPACITY) {
            break;
        }
        if (status != HIBI_OK) {
            printf("glass step failed\n");
            exit(1);
        }
    } while (!progress.finished);
    {
        size_t cracks = 0;
        hibi_glass_crack_count(glass, &cracks);
        printf("glass-render cracks: %s\n", cracks > 0 ? "some" : "none");
    }
    glass_render("glass-render line_width twin", glass, 8.0f * SIDE);
    glass_render("glass-render line_width extreme", glass, FLT_MAX);
    hibi_glass_destroy(glass);
    return 0;
}
