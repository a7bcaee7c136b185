/*
 * engine.cpp: hibi in a game loop, from C++17 through include/hibi.hpp. A glass impact, a
 * mud run and a skin live in memory from the engine's own allocator (an arena, through
 * *_create_in); each frame advances each of them by a bounded amount of work with
 * step(budget), a few frames of the break-time rasters (glass and mud) are written as PGM
 * files, and at the end the program reports the largest work any frame did against its
 * budget, and checks that the budgeted objects came out as one unbudgeted run of each. Mud
 * runs twice: with the quasi-static solver (the default) and with the explicit one (the
 * paper's loop, whose short steps are cut between rows of the lattice); a mud run traces its
 * crack network live, within the same budget, and every frame renders what it shows: the
 * program counts the frames with cracks from the first break on and checks that the cracks
 * shown never fall. Once the models are done, every layer an engine uploads (mask, 16-bit
 * height, RGB8 normals, time or cells, an RGBA preview) is streamed a 32 x 32 tile per call,
 * and checked against one call's whole image; the mud's crack network and cells are built a
 * frame's budget per call and read 64 elements per call, and checked against one call's
 * outputs.
 *
 *   c++ -std=c++17 -Wall -Wextra -Wpedantic -Werror -Iinclude c_examples/engine.cpp \
 *       target/release/libhibi.a -lpthread -ldl -lm -o engine && ./engine frames/
 */
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "hibi.hpp"

namespace {

/// The engine's allocator: one block, handed out front to back, freed all at once.
class Arena {
public:
    explicit Arena(std::size_t bytes) : block_(bytes, alignof(std::max_align_t)) {}
    void *allocate(std::size_t size, std::size_t align) {
        std::size_t at = (used_ + align - 1) / align * align;
        if (at + size > block_.size()) throw std::bad_alloc();
        used_ = at + size;
        return static_cast<unsigned char *>(block_.data()) + at;
    }
    std::size_t used() const { return used_; }

private:
    hibi::Buffer block_;
    std::size_t used_ = 0;
};

/// A break-time raster as a PGM: no crack white, cracks from black (first) to grey (last).
bool write_pgm(const std::string &path, const std::vector<float> &time, std::uint32_t width, std::uint32_t height) {
    float last = 0.0f;
    for (float t : time) {
        if (std::isfinite(t)) last = std::max(last, t);
    }
    std::vector<unsigned char> grey(time.size());
    for (std::size_t i = 0; i < time.size(); i++) {
        grey[i] = std::isfinite(time[i])
                      ? static_cast<unsigned char>(last > 0.0f ? 180.0f * time[i] / last : 0.0f)
                      : static_cast<unsigned char>(255);
    }
    std::FILE *file = std::fopen(path.c_str(), "wb");
    if (file == nullptr) return false;
    std::fprintf(file, "P5\n%u %u\n255\n", static_cast<unsigned>(width), static_cast<unsigned>(height));
    bool ok = std::fwrite(grey.data(), 1, grey.size(), file) == grey.size();
    return std::fclose(file) == 0 && ok;
}

/// The largest work one frame did, from the work total each model's progress counts (and
/// apart, the work of the frame that finished).
struct Budget {
    std::uint64_t per_frame;
    std::uint64_t largest = 0;
    std::uint64_t last_total = 0;
    void frame(std::uint64_t total) {
        largest = std::max(largest, total - last_total);
        last_total = total;
    }
};

/// A mud run's frames as an engine shows them: each frame renders the run's mask, and the
/// springs broken in the network it shows are counted.
struct Live {
    unsigned frames = 0;
    long first_break = -1;   // the frame in which the first spring broke
    long first_shown = -1;   // the first frame whose render shows a crack
    unsigned blank_after = 0; // frames after that whose render shows no crack
    unsigned networks = 0;   // times the network shown changed
    unsigned falls = 0;      // times the springs shown fell
    std::uint32_t shown = 0; // springs broken in the network shown now
    std::vector<std::uint8_t> mask;

    void frame(const hibi::Mud &mud, const hibi::Mud::Progress &p, const hibi::Mud::RenderParams &render) {
        mask.resize(static_cast<std::size_t>(render.width) * render.height);
        mud.render_mask(render, hibi::Span<std::uint8_t>(mask.data(), mask.size()));
        bool cracked = std::any_of(mask.begin(), mask.end(), [](std::uint8_t m) { return m != 0; });
        std::uint32_t now = mud.shown_broken_springs();
        if (first_break < 0 && p.broken_springs > 0) first_break = frames;
        if (first_shown < 0 && cracked) first_shown = frames;
        if (first_shown >= 0 && !cracked) blank_after++;
        if (now != shown) networks++;
        if (now < shown) falls++;
        shown = now;
        frames++;
    }
    void report(const char *name) const {
        std::printf("%s live: first break in frame %ld, cracks shown from frame %ld on, %u of the %ld frames from "
                    "there blank; %u networks shown, the springs they show rising to %u, falling %u times\n",
                    name, first_break, first_shown, blank_after, static_cast<long>(frames) - first_shown, networks,
                    static_cast<unsigned>(shown), falls);
    }
};

bool same(const std::vector<float> &a, const std::vector<float> &b) {
    return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0);
}

template <class T>
bool same_bytes(const std::vector<T> &a, const std::vector<T> &b) {
    return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

/// A finished build read `range` elements per call (per frame, in an engine), appended to
/// `out`; `read(first, part)` copies from element `first` on and returns how many.
template <class T, class Read>
void read_in_ranges(Read read, std::vector<T> &out, std::size_t range, unsigned &calls) {
    std::vector<T> part(range);
    for (;;) {
        std::size_t n = read(out.size(), hibi::Span<T>(part));
        calls++;
        out.insert(out.end(), part.begin(), part.begin() + static_cast<std::ptrdiff_t>(n));
        if (n < range) return;
    }
}

/// A mud run's network and cells as an engine takes them: built a frame's budget per call,
/// then read 64 elements per call, so that no call walks the whole lattice. Prints the
/// largest work of a call against the budget, beside the longest crack and the largest ring
/// (which bound a call's one piece), and whether they equal the one-call outputs.
void mud_outputs(const hibi::Mud &mud, std::uint64_t budget) {
    Budget network_budget{budget};
    hibi::MudNetworkBuild network_build = hibi::MudNetworkBuild::create(mud);
    unsigned build_calls = 0;
    for (;;) {
        hibi::MudNetworkBuild::Progress p = network_build.step(mud, budget);
        network_budget.frame(p.work);
        build_calls++;
        if (p.finished) break;
    }
    Budget cell_budget{budget};
    hibi::MudCellBuild cell_build = hibi::MudCellBuild::create(mud);
    for (;;) {
        hibi::MudCellBuild::Progress p = cell_build.step(mud, budget);
        cell_budget.frame(p.work);
        build_calls++;
        if (p.finished) break;
    }
    unsigned read_calls = 0;
    hibi::Mud::Network network;
    read_in_ranges<hibi_mud_network_vertex>(
        [&](std::size_t first, hibi::Span<hibi_mud_network_vertex> part) { return network_build.vertices(first, part); },
        network.vertices, 64, read_calls);
    read_in_ranges<hibi_mud_network_edge>(
        [&](std::size_t first, hibi::Span<hibi_mud_network_edge> part) { return network_build.edges(first, part); },
        network.edges, 64, read_calls);
    read_in_ranges<hibi_mud_network_point>(
        [&](std::size_t first, hibi::Span<hibi_mud_network_point> part) { return network_build.points(first, part); },
        network.points, 64, read_calls);
    hibi::Mud::Cells cells;
    read_in_ranges<hibi_ring>(
        [&](std::size_t first, hibi::Span<hibi_ring> part) { return cell_build.rings(first, part); }, cells.rings, 64,
        read_calls);
    read_in_ranges<hibi_vec2>(
        [&](std::size_t first, hibi::Span<hibi_vec2> part) { return cell_build.points(first, part); }, cells.points,
        64, read_calls);
    std::uint32_t longest = 0, largest_ring = 0;
    for (const hibi_mud_network_edge &e : network.edges) longest = std::max(longest, e.point_count);
    for (const hibi_ring &r : cells.rings) largest_ring = std::max(largest_ring, r.point_count);
    const hibi::Mud::Network whole_network = mud.network();
    const hibi::Mud::Cells whole_cells = mud.cells();
    const bool network_same = same_bytes(network.vertices, whole_network.vertices) &&
                              same_bytes(network.edges, whole_network.edges) &&
                              same_bytes(network.points, whole_network.points);
    const bool cells_same = same_bytes(cells.rings, whole_cells.rings) && same_bytes(cells.points, whole_cells.points);
    std::printf("mud outputs: %u build calls, the largest network work %llu and cell work %llu of budget %llu "
                "(longest crack %u points, largest ring %u points); %u range reads of at most 64; "
                "built = whole: network %s, cells %s\n",
                build_calls, static_cast<unsigned long long>(network_budget.largest),
                static_cast<unsigned long long>(cell_budget.largest), static_cast<unsigned long long>(budget),
                static_cast<unsigned>(longest), static_cast<unsigned>(largest_ring), read_calls,
                network_same ? "yes" : "no", cells_same ? "yes" : "no");
}

/// A finished model's layers drawn a tile per frame, as an engine streams a large texture in:
/// each call draws one `tile` × `tile` rectangle (its cost set by the tile's pixels and one pass
/// over the cracks or cells, not by the image), copied into the full image. Returns whether
/// the streamed image equals the one-call render of the whole, byte for byte, and counts the
/// calls and the largest one's pixels.
template <class Model, class Params>
bool stream_tiles(const Model &model, const Params &render, std::uint32_t width, std::uint32_t height,
                  unsigned which, std::uint32_t tile, unsigned &calls, std::size_t &largest) {
    hibi::Layers whole(width, height, which), streamed(width, height, which);
    model.render_layers(render, whole);
    for (std::uint32_t y = 0; y < height; y += tile) {
        for (std::uint32_t x = 0; x < width; x += tile) {
            const hibi_tile t{x, y, std::min(tile, width - x), std::min(tile, height - y)};
            hibi::Layers part(t.width, t.height, which);
            model.render_layers(render, part, &t);  // one frame's call
            calls++;
            largest = std::max(largest, static_cast<std::size_t>(t.width) * t.height);
            // Copy each layer's rows into place (bytes per pixel from the layer's size).
            auto place = [&](auto &to, const auto &from) {
                if (from.empty()) return;
                const std::size_t per = from.size() / (static_cast<std::size_t>(t.width) * t.height);
                for (std::uint32_t row = 0; row < t.height; row++) {
                    std::copy_n(from.begin() + static_cast<std::ptrdiff_t>(per * row * t.width), per * t.width,
                                to.begin() + static_cast<std::ptrdiff_t>(per * ((y + row) * std::size_t{width} + x)));
                }
            };
            place(streamed.mask, part.mask);
            place(streamed.height16, part.height16);
            place(streamed.normal_rgb8, part.normal_rgb8);
            place(streamed.time, part.time);
            place(streamed.cell, part.cell);
            place(streamed.preview, part.preview);
        }
    }
    return streamed.mask == whole.mask && streamed.height16 == whole.height16 &&
           streamed.normal_rgb8 == whole.normal_rgb8 && same(streamed.time, whole.time) &&
           streamed.cell == whole.cell && streamed.preview == whole.preview;
}

}  // namespace

int main(int argc, char **argv) {
    const std::string dir = argc > 1 ? std::string(argv[1]) + "/" : std::string();
    try {
        hibi::Glass::Params glass_params = hibi::Glass::default_params();
        glass_params.width = 160.0f;
        glass_params.height = 160.0f;
        glass_params.impact[0] = 70.0f;
        glass_params.impact[1] = 90.0f;
        glass_params.seed = 11;
        hibi::Mud::Params mud_params = hibi::Mud::default_params();
        mud_params.columns = 40;
        mud_params.rows = 40;
        mud_params.seed = 11;
        // The explicit solver takes far more steps: a smaller lattice, at ten times the paper's
        // short step (within its stability test).
        hibi::Mud::Params explicit_params = mud_params;
        explicit_params.solver = HIBI_MUD_EXPLICIT;
        explicit_params.columns = 16;
        explicit_params.rows = 16;
        explicit_params.short_step = 0.01f;
        hibi::Skin::Params skin_params = hibi::Skin::preset("fig19a");
        skin_params.width = 96;
        skin_params.height = 96;

        // One arena for all three, sized from the C API's own figures.
        const std::size_t glass_bytes = hibi::Glass::memory_size(glass_params);
        const std::size_t mud_bytes = hibi::Mud::memory_size(mud_params);
        const std::size_t explicit_bytes = hibi::Mud::memory_size(explicit_params);
        const std::size_t skin_bytes = hibi::Skin::memory_size(skin_params);
        const std::size_t slack =
            hibi::Glass::memory_align() + 2 * hibi::Mud::memory_align() + hibi::Skin::memory_align();
        Arena arena(glass_bytes + mud_bytes + explicit_bytes + skin_bytes + slack);
        hibi::Glass glass = hibi::Glass::create_in(
            glass_params, arena.allocate(glass_bytes, hibi::Glass::memory_align()), glass_bytes);
        hibi::Mud mud =
            hibi::Mud::create_in(mud_params, arena.allocate(mud_bytes, hibi::Mud::memory_align()), mud_bytes);
        hibi::Mud explicit_mud = hibi::Mud::create_in(
            explicit_params, arena.allocate(explicit_bytes, hibi::Mud::memory_align()), explicit_bytes);
        hibi::Skin skin =
            hibi::Skin::create_in(skin_params, arena.allocate(skin_bytes, hibi::Skin::memory_align()), skin_bytes);
        std::printf("arena: %zu bytes (glass %zu, mud %zu, explicit mud %zu, skin %zu)\n", arena.used(), glass_bytes,
                    mud_bytes, explicit_bytes, skin_bytes);

        // The frame budgets, in each model's units of work.
        Budget mud_budget{20000};
        Budget explicit_budget{20000};
        Budget skin_budget{1500};
        Budget glass_budget{5000};
        std::printf("budgets per frame: mud %llu, skin %llu, glass %llu\n",
                    static_cast<unsigned long long>(mud_budget.per_frame),
                    static_cast<unsigned long long>(skin_budget.per_frame),
                    static_cast<unsigned long long>(glass_budget.per_frame));

        hibi::Glass::RenderParams glass_render = hibi::Glass::default_render();
        glass_render.width = 160;
        glass_render.height = 160;
        hibi::Mud::RenderParams mud_render = hibi::Mud::default_render();
        mud_render.width = 160;
        mud_render.height = 160;
        hibi::Skin::RenderParams skin_render = hibi::Skin::default_render();

        bool glass_done = false, mud_done = false, explicit_done = false, skin_done = false;
        unsigned frame = 0, glass_frames = 0, mud_frames = 0, explicit_frames = 0, skin_frames = 0, written = 0;
        Live mud_live, explicit_live;
        const unsigned stride = 6, max_written = 3;
        while (!(glass_done && mud_done && explicit_done && skin_done)) {
            if (!glass_done) {
                hibi::Glass::Progress p = glass.step(glass_budget.per_frame);
                glass_budget.frame(p.work);
                glass_done = p.finished != 0;
                glass_frames = frame + 1;
            }
            if (!mud_done) {
                hibi::Mud::Progress p = mud.step(mud_budget.per_frame);
                mud_done = p.finished != 0;
                mud_budget.frame(p.work);
                mud_frames = frame + 1;
                mud_live.frame(mud, p, mud_render);
            }
            if (!explicit_done) {
                hibi::Mud::Progress p = explicit_mud.step(explicit_budget.per_frame);
                explicit_done = p.finished != 0;
                explicit_budget.frame(p.work);
                explicit_frames = frame + 1;
                explicit_live.frame(explicit_mud, p, mud_render);
            }
            if (!skin_done) {
                hibi::Skin::Progress p = skin.step(skin_budget.per_frame);
                skin_budget.frame(p.work);
                skin_done = p.finished != 0;
                skin_frames = frame + 1;
            }
            // A few frames of the break as it happens, then the last one.
            bool last = glass_done && mud_done && explicit_done && skin_done;
            if ((frame % stride == 0 && written < max_written) || last) {
                char name[32];
                std::snprintf(name, sizeof name, "%02u", written);
                if (!write_pgm(dir + "glass_time_" + name + ".pgm", glass.render_time(glass_render),
                               glass_render.width, glass_render.height) ||
                    !write_pgm(dir + "mud_time_" + name + ".pgm", mud.render_time(mud_render), mud_render.width,
                               mud_render.height)) {
                    std::fprintf(stderr, "cannot write frame %u into %s\n", written, dir.c_str());
                    return 1;
                }
                written++;
            }
            frame++;
        }
        std::printf("frames: %u (glass done after %u, mud after %u, explicit mud after %u, skin after %u)\n", frame,
                    glass_frames, mud_frames, explicit_frames, skin_frames);
        std::printf("wrote %u frames of each break-time raster\n", written);
        mud_live.report("mud");
        explicit_live.report("explicit mud");
        std::printf("mud: largest frame work %llu of budget %llu, the network's tracing included\n",
                    static_cast<unsigned long long>(mud_budget.largest),
                    static_cast<unsigned long long>(mud_budget.per_frame));
        std::printf("explicit mud: largest frame work %llu of budget %llu, the network's tracing included\n",
                    static_cast<unsigned long long>(explicit_budget.largest),
                    static_cast<unsigned long long>(explicit_budget.per_frame));
        std::printf("skin: largest frame work %llu of budget %llu\n",
                    static_cast<unsigned long long>(skin_budget.largest),
                    static_cast<unsigned long long>(skin_budget.per_frame));
        std::printf("glass: largest frame work %llu of budget %llu\n",
                    static_cast<unsigned long long>(glass_budget.largest),
                    static_cast<unsigned long long>(glass_budget.per_frame));

        // The finished models' textures, streamed a 32 x 32 tile per call (per frame, in an
        // engine): every layer an engine uploads, equal to one call's whole image.
        namespace layer = hibi::layer;
        const unsigned cracks = layer::mask | layer::height16 | layer::normal_rgb8 | layer::time | layer::preview;
        const unsigned cells = layer::mask | layer::height16 | layer::normal_rgb8 | layer::cell | layer::preview;
        unsigned tile_calls = 0;
        std::size_t tile_pixels = 0;
        const bool glass_tiles = stream_tiles(glass, glass_render, glass_render.width, glass_render.height, cracks,
                                              32, tile_calls, tile_pixels);
        const bool mud_tiles =
            stream_tiles(mud, mud_render, mud_render.width, mud_render.height, cracks, 32, tile_calls, tile_pixels);
        const bool skin_tiles = stream_tiles(skin, skin_render, static_cast<std::uint32_t>(skin_params.width),
                                             static_cast<std::uint32_t>(skin_params.height), cells, 32, tile_calls,
                                             tile_pixels);
        std::printf("tiles: %u render calls, the largest %zu pixels; streamed = whole: glass %s, mud %s, skin %s\n",
                    tile_calls, tile_pixels, glass_tiles ? "yes" : "no", mud_tiles ? "yes" : "no",
                    skin_tiles ? "yes" : "no");

        // The finished mud's network and cells, built and read in bounded calls.
        mud_outputs(mud, mud_budget.per_frame);

        // The models do not depend on the budgets: the same objects, run in one go.
        hibi::Glass whole_glass(glass_params);
        whole_glass.run(UINT64_MAX);
        hibi::Mud whole_mud(mud_params);
        whole_mud.run(UINT64_MAX);
        hibi::Mud whole_explicit(explicit_params);
        whole_explicit.run(UINT64_MAX);
        hibi::Skin whole_skin(skin_params);
        whole_skin.run();
        std::printf("budgeted = one go: glass %s, mud %s, explicit mud %s, skin %s\n",
                    same(glass.render_time(glass_render), whole_glass.render_time(glass_render)) ? "yes" : "no",
                    same(mud.render_time(mud_render), whole_mud.render_time(mud_render)) ? "yes" : "no",
                    same(explicit_mud.render_time(mud_render), whole_explicit.render_time(mud_render)) ? "yes"
                                                                                                          : "no",
                    same(skin.render_height(skin_render), whole_skin.render_height(skin_render)) ? "yes" : "no");
        return 0;
    } catch (const hibi::Error &e) {
        std::fprintf(stderr, "hibi: %s (status %u)\n", e.what(), static_cast<unsigned>(e.status()));
        return 1;
    } catch (const std::exception &e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
}
