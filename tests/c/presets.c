/*
 * Every model's presets can be listed from C: hibi_*_preset_name(i) counts up from 0 to the
 * NULL after the last, and each name it gives is one hibi_*_params_preset accepts. Prints one
 * line per model: its presets' names, space-separated.
 */
#include <stdio.h>

#include "hibi.h"

int main(void) {
    size_t i;
    const char *name;
    printf("mud:");
    for (i = 0; (name = hibi_mud_preset_name(i)) != NULL; i++) {
        hibi_mud_params params;
        printf(" %s%s", name, hibi_mud_params_preset(name, &params) == HIBI_OK ? "" : "(refused)");
    }
    printf("\nglass:");
    for (i = 0; (name = hibi_glass_preset_name(i)) != NULL; i++) {
        hibi_glass_params params;
        printf(" %s%s", name, hibi_glass_params_preset(name, &params) == HIBI_OK ? "" : "(refused)");
    }
    printf("\nskin:");
    for (i = 0; (name = hibi_skin_preset_name(i)) != NULL; i++) {
        hibi_skin_params params;
        printf(" %s%s", name, hibi_skin_params_preset(name, &params) == HIBI_OK ? "" : "(refused)");
    }
    printf("\npast the end: %s\n", hibi_glass_preset_name((size_t)-1) == NULL ? "NULL" : "a name");
    return 0;
}
