// A C++17 consumer of the Conan package through hibi.hpp: a skin's height map.
#include <cstdio>
#include <exception>
#include <vector>

#include <hibi.hpp>

int main() {
    try {
        hibi::Skin::Params params = hibi::Skin::default_params();
        params.width = 64;
        params.height = 64;
        hibi::Skin skin(params);
        skin.run();
        std::vector<float> height = skin.render_height(hibi::Skin::default_render());
        if (skin.cell_count() == 0 || height.size() != 64 * 64) {
            std::fprintf(stderr, "skin: %zu cells, %zu heights\n", static_cast<std::size_t>(skin.cell_count()),
                         height.size());
            return 1;
        }
        std::printf("hibi %s (C++): a 64 x 64 skin, %zu cells\n", hibi::version(),
                    static_cast<std::size_t>(skin.cell_count()));
        return 0;
    } catch (const std::exception &e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
}
