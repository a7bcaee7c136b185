/*
 * Every refusal names what the caller wrote. The mud scale errors name their fields, a bad
 * glass layer names the glass constants, a huge but valid light is a light,
 * hibi_error_argument() names a refused pointer argument, and the *_written counts are
 * required everywhere (the optional outputs are skipped when NULL).
 */
#include <stdio.h>

#include "hibi.h"

static void report(const char *what, hibi_status status) {
    printf("%s: status %u, %s [%s]\n", what, (unsigned)status, hibi_status_string(status), hibi_error_argument());
}

static void mud_scale(const char *what, hibi_mud_params params) {
    size_t size = 777;
    report(what, hibi_mud_memory_size(&params, &size));
}

int main(void) {
    hibi_mud_params mud_params = hibi_mud_params_default();
    hibi_glass_params glass_params = hibi_glass_params_default();
    hibi_glass_render_params render = hibi_glass_render_params_default();
    hibi_skin_shade_params light = hibi_skin_shade_params_default();
    hibi_glass *glass = NULL;
    hibi_mud *mud = NULL;
    hibi_mud_progress progress;
    float height[4] = {0.0f, 0.25f, 0.5f, 1.0f};
    float normal[12] = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
    unsigned char rgb[12];
    unsigned char pixel[1];
    hibi_glass_point points[4];
    hibi_mud_segment segments[1];
    size_t rings = 0, count = 0, written = 0;
    unsigned long long scratch[1] = {0};
    hibi_mud_params p;

    p = mud_params;
    p.young_modulus = 1e20f;
    mud_scale("young_modulus 1e20", p);
    p = mud_params;
    p.damping_factor = 1e9f;
    mud_scale("damping_factor 1e9", p);
    p = mud_params;
    p.short_step = 1e9f;
    mud_scale("short_step 1e9", p);
    p = mud_params;
    p.displacement_tolerance = 1e-12f;
    mud_scale("displacement_tolerance 1e-12", p);
    p = mud_params;
    p.stiffness_anisotropy_ratio = 1e9f;
    mud_scale("stiffness_anisotropy_ratio 1e9", p);

    if (hibi_glass_create(&glass_params, &glass) != HIBI_OK) return 1;
    report("glass layer 7", hibi_glass_render(glass, &render, 7, pixel, 1));

    light.light[0] = 0.0f;
    light.light[1] = 0.0f;
    light.light[2] = 1e30f;
    report("light (0, 0, 1e30)", hibi_skin_shade(height, 4, normal, 12, &light, rgb, 12));
    light.light[2] = 0.0f;
    report("light (0, 0, 0)", hibi_skin_shade(height, 4, normal, 12, &light, rgb, 12));
    report("shade without params", hibi_skin_shade(height, 4, normal, 12, NULL, rgb, 12));
    report("shade into NULL rgb", hibi_skin_shade(height, 4, normal, 12, &light, NULL, 12));

    report("fragment_counts with NULL points", hibi_glass_fragment_counts(glass, scratch, 1, &rings, NULL));
    report("fragment_counts with NULL scratch", hibi_glass_fragment_counts(glass, NULL, 1, &rings, &rings));
    report("fragment_counts with a 1-byte scratch", hibi_glass_fragment_counts(glass, scratch, 1, &rings, &rings));
    report("a call that succeeds clears the name", hibi_glass_crack_count(glass, &count));
    report("glass points with NULL written", hibi_glass_points(glass, 0, points, 4, NULL));
    report("glass step with NULL progress", hibi_glass_step(glass, 1, NULL));
    report("glass step on a NULL plate", hibi_glass_step(NULL, 1, NULL));
    report("glass impact with NULL counts", hibi_glass_impact(glass, 100.0f, 100.0f, NULL));
    hibi_glass_destroy(glass);

    mud_params.columns = 8;
    mud_params.rows = 8;
    if (hibi_mud_create(&mud_params, &mud) != HIBI_OK) return 1;
    report("mud step with NULL progress", hibi_mud_step(mud, 10, NULL));
    report("mud step", hibi_mud_step(mud, 10, &progress));
    report("mud segments with NULL written", hibi_mud_segments(mud, segments, 1, NULL));
    report("mud segments into NULL with a length", hibi_mud_segments(mud, NULL, 1, &written));
    report("mud create with NULL out", hibi_mud_create(&mud_params, NULL));
    report("mud create_in with NULL memory", hibi_mud_create_in(&mud_params, NULL, 1 << 20, &mud));
    hibi_mud_destroy(mud);
    return 0;
}
