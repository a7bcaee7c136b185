/* A C99 consumer of the Conan package: the header's version is the library's, and a glass
 * plate cracks. */
#include <stdio.h>
#include <string.h>

#include <hibi.h>

int main(void) {
    char macros[32];
    snprintf(macros, sizeof macros, "%d.%d.%d", HIBI_VERSION_MAJOR, HIBI_VERSION_MINOR, HIBI_VERSION_PATCH);
    if (strcmp(macros, hibi_version()) != 0) {
        fprintf(stderr, "header %s, library %s\n", macros, hibi_version());
        return 1;
    }

    hibi_glass_params params = hibi_glass_params_default();
    params.width = 120.0f;
    params.height = 120.0f;
    params.impact[0] = 60.0f;
    params.impact[1] = 60.0f;
    hibi_glass *glass = NULL;
    hibi_status status = hibi_glass_create(&params, &glass);
    if (status != HIBI_OK) {
        fprintf(stderr, "hibi_glass_create: %s\n", hibi_status_string(status));
        return 1;
    }
    hibi_glass_progress progress;
    do {
        status = hibi_glass_step(glass, 100000, &progress);
    } while (status == HIBI_OK && !progress.finished);
    size_t cracks = 0;
    if (status == HIBI_OK) {
        status = hibi_glass_crack_count(glass, &cracks);
    }
    hibi_glass_destroy(glass);
    if (status != HIBI_OK || cracks == 0) {
        fprintf(stderr, "glass: %s, %zu cracks\n", hibi_status_string(status), cracks);
        return 1;
    }
    printf("hibi %s (C): a 120 x 120 plate, %zu cracks\n", hibi_version(), cracks);
    return 0;
}
