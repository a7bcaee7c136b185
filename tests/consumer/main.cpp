/*
 * An out-of-tree consumer of an installed hibi: built by tests/package.rs through pkg-config
 * and through CMake (tests/consumer/CMakeLists.txt), shared and static. One object of each
 * model through include/hibi.hpp, and the version macros against hibi_version().
 */
#include <cstdio>
#include <string>
#include <vector>

#include <hibi.hpp>

int main() {
    try {
        const std::string macros = std::to_string(HIBI_VERSION_MAJOR) + "." + std::to_string(HIBI_VERSION_MINOR) +
                                   "." + std::to_string(HIBI_VERSION_PATCH);
        std::printf("hibi_version() %s, macros %s, equal: %s\n", hibi::version(), macros.c_str(),
                    macros == hibi::version() ? "yes" : "no");

        hibi::Mud::Params mud_params = hibi::Mud::default_params();
        mud_params.columns = 16;
        mud_params.rows = 16;
        hibi::Mud mud(mud_params);
        mud.run();
        std::printf("mud: %s\n", mud.segments().empty() ? "no cracks" : "cracks");

        hibi::Glass::Params glass_params = hibi::Glass::default_params();
        glass_params.width = 120.0f;
        glass_params.height = 120.0f;
        glass_params.impact[0] = 60.0f;
        glass_params.impact[1] = 60.0f;
        hibi::Glass glass(glass_params);
        glass.run();
        hibi::Scratch glass_scratch = glass.scratch();
        std::printf("glass: %s\n", glass.fragments(glass_scratch).rings.empty() ? "no fragments" : "fragments");

        hibi::Skin::Params skin_params = hibi::Skin::default_params();
        skin_params.width = 64;
        skin_params.height = 64;
        hibi::Skin skin(skin_params);
        skin.run();
        std::vector<float> height = skin.render_height(hibi::Skin::default_render());
        std::printf("skin: %zu cells, %zu heights\n", skin.cell_count() > 0 ? std::size_t{1} : std::size_t{0},
                    height.size());

        try {
            hibi::Glass::preset("no such figure");
        } catch (const hibi::Error &e) {
            std::printf("unknown preset: status %u\n", static_cast<unsigned>(e.status()));
        }
        return 0;
    } catch (const std::exception &e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
}
