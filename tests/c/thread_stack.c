/*
 * What a thread's stack needs: every model's heaviest calls (create, step, render, the
 * outputs, shade) run on a thread of THREAD_STACK bytes, the size the header and the guide
 * promise is enough (hibi's calls take at most 16 KiB of it; glibc keeps the thread's TLS and
 * guard in the same block, so the thread needs more than 16 KiB). Sanitizer builds need far
 * more stack for their own instrumentation and get a larger thread.
 */
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>

#include "hibi.h"

#define THREAD_STACK (24 * 1024)

#if defined(__SANITIZE_ADDRESS__)
#define SANITIZED 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define SANITIZED 1
#endif
#endif

static float height[96 * 96], normal[96 * 96 * 3];
static uint8_t rgb[96 * 96 * 3];

static void *work(void *result) {
    hibi_status *status = result;
    hibi_mud_params mp = hibi_mud_params_default();
    hibi_mud *mud = NULL;
    hibi_mud_progress mpr = {0};
    hibi_glass_params gp = hibi_glass_params_default();
    hibi_glass *glass = NULL;
    hibi_glass_progress gpr = {0};
    hibi_skin_params sp;
    hibi_skin *skin = NULL;
    size_t v, e, p, rings, points, wrapping;
    mp.columns = mp.rows = 16;
    *status = hibi_mud_create(&mp, &mud);
    while (*status == HIBI_OK && !mpr.finished) *status = hibi_mud_step(mud, 1000000, &mpr);
    if (*status == HIBI_OK) *status = hibi_mud_network_counts(mud, &v, &e, &p);
    if (*status == HIBI_OK) *status = hibi_mud_cell_counts(mud, &rings, &points, &wrapping);
    hibi_mud_destroy(mud);
    gp.width = gp.height = 160.0f;
    gp.impact[0] = gp.impact[1] = 80.0f;
    if (*status == HIBI_OK) *status = hibi_glass_create(&gp, &glass);
    while (*status == HIBI_OK && !gpr.finished) *status = hibi_glass_step(glass, 1000000, &gpr);
    if (*status == HIBI_OK) {
        hibi_glass_render_params render = hibi_glass_render_params_default();
        render.width = render.height = 96;
        *status = hibi_glass_render(glass, &render, HIBI_GLASS_LAYER_TIME, height, 96 * 96);
    }
    hibi_glass_destroy(glass);
    if (*status == HIBI_OK) *status = hibi_skin_params_preset("fig19a", &sp);
    sp.width = sp.height = 96;
    if (*status == HIBI_OK) *status = hibi_skin_create(&sp, &skin);
    if (*status == HIBI_OK) *status = hibi_skin_step(skin, UINT64_MAX, NULL);
    if (*status == HIBI_OK) {
        hibi_skin_render_params render = hibi_skin_render_params_default();
        *status = hibi_skin_render(skin, &render, HIBI_SKIN_LAYER_HEIGHT, height, 96 * 96);
        if (*status == HIBI_OK) *status = hibi_skin_render(skin, &render, HIBI_SKIN_LAYER_NORMAL, normal, 96 * 96 * 3);
    }
    if (*status == HIBI_OK) {
        hibi_skin_shade_params shade = hibi_skin_shade_params_default();
        *status = hibi_skin_shade(height, 96 * 96, normal, 96 * 96 * 3, &shade, rgb, 96 * 96 * 3);
    }
    hibi_skin_destroy(skin);
    return NULL;
}

int main(void) {
    pthread_attr_t attr;
    pthread_t thread;
    hibi_status status = 12345;
#ifdef SANITIZED
    size_t stack = 1024 * 1024;
#else
    size_t stack = THREAD_STACK;
#endif
    if (pthread_attr_init(&attr) != 0 || pthread_attr_setstacksize(&attr, stack) != 0) return 1;
    if (pthread_create(&thread, &attr, work, &status) != 0) return 1;
    pthread_join(thread, NULL);
    printf("every model on a %u KiB thread: status %u\n", (unsigned)(THREAD_STACK / 1024), (unsigned)status);
    return 0;
}
