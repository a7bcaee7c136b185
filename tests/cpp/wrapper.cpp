/*
 * wrapper.cpp: include/hibi.hpp against the C API it wraps (issue 26). Each line it prints
 * is checked by tests/c_examples.rs; "yes" lines compare the wrapper's result with the raw C
 * calls or with a second way of computing it.
 */
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <thread>
#include <type_traits>
#include <utility>
#include <vector>

#include "hibi.hpp"

namespace {

const char *yes(bool b) { return b ? "yes" : "no"; }

// Field by field: a ring record has padding.
bool same_rings(const std::vector<hibi_glass_fragment_ring> &a, const std::vector<hibi_glass_fragment_ring> &b) {
    return std::equal(a.begin(), a.end(), b.begin(), b.end(), [](const auto &x, const auto &y) {
        return x.area == y.area && x.first_point == y.first_point && x.point_count == y.point_count &&
               x.hole_of == y.hole_of;
    });
}

// Byte equality for records without padding and for pixels (NaN-safe, -0 != 0).
template <class T>
bool same_bytes(const std::vector<T> &a, const std::vector<T> &b) {
    return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

static_assert(!std::is_copy_constructible<hibi::Mud>::value, "objects are move-only");
static_assert(std::is_nothrow_move_constructible<hibi::Glass>::value, "moves do not throw");
static_assert(std::is_base_of<std::runtime_error, hibi::Error>::value, "hibi::Error is a runtime_error");

void errors() {
    hibi::Mud::Params bad = hibi::Mud::default_params();
    bad.young_modulus = -1.0f;
    try {
        hibi::Mud mud(bad);
        std::printf("negative young_modulus: no throw\n");
    } catch (const hibi::Error &e) {
        std::printf("negative young_modulus: status %u, %s, argument \"%s\", same message as C: %s\n",
                    static_cast<unsigned>(e.status()), e.what(), e.argument().c_str(),
                    yes(std::strcmp(e.what(), hibi_status_string(e.status())) == 0));
    }
    try {
        hibi::Skin::preset("fig99");
        std::printf("preset fig99: no throw\n");
    } catch (const hibi::Error &e) {
        std::printf("preset fig99: status %u\n", static_cast<unsigned>(e.status()));
    }
    // Misaligned caller memory: the C call refuses the pointer and names it.
    hibi::Mud::Params params = hibi::Mud::default_params();
    params.columns = 8;
    params.rows = 8;
    std::size_t size = hibi::Mud::memory_size(params);
    hibi::Buffer memory(size + 1, hibi::Mud::memory_align());
    try {
        hibi::Mud::create_in(params, static_cast<unsigned char *>(memory.data()) + 1, size);
        std::printf("misaligned memory: no throw\n");
    } catch (const hibi::Error &e) {
        std::printf("misaligned memory: status %u, argument \"%s\"\n", static_cast<unsigned>(e.status()),
                    e.argument().c_str());
    }
    try {
        hibi::Mud::create_in(params, memory.data(), size - 1);
        std::printf("short memory: no throw\n");
    } catch (const hibi::Error &e) {
        std::printf("short memory: status %u, %s\n", static_cast<unsigned>(e.status()), e.what());
    }
}

void mud() {
    hibi::Mud::Params params = hibi::Mud::default_params();
    params.columns = 32;
    params.rows = 32;
    params.seed = 7;
    hibi::Mud mud(params);
    hibi::Mud::Progress progress = mud.step(50000);
    unsigned calls = 1;
    while (!progress.finished) {
        progress = mud.step(50000);
        calls++;
    }
    std::printf("mud finished: %s, in more than one step: %s\n", yes(progress.finished == 1), yes(calls > 1));

    std::vector<hibi_mud_segment> segments = mud.segments();
    std::size_t count = 0;
    hibi::check(hibi_mud_segment_count(mud.get(), &count));
    std::printf("mud segments: %s\n", yes(!segments.empty() && segments.size() == count));

    hibi::Mud::Network network = mud.network();
    std::size_t v = 0, e = 0, p = 0;
    hibi::check(hibi_mud_network_counts(mud.get(), &v, &e, &p));
    std::printf("mud network matches its counts: %s\n",
                yes(network.vertices.size() == v && network.edges.size() == e && network.points.size() == p &&
                    e > 0));

    hibi::Mud::Cells cells = mud.cells();
    double area = 0.0;
    for (const auto &ring : cells.rings) area += ring.area;
    std::printf("mud cells: %s rings, area %.1f of %u\n", cells.rings.empty() ? "no" : "some", area,
                static_cast<unsigned>(params.columns * params.rows));

    hibi_mud_crack_statistics stats = mud.statistics(), raw_stats{};
    hibi::check(hibi_mud_statistics(mud.get(), &raw_stats));
    std::printf("mud statistics as from C: %s\n",
                yes(stats.cells == raw_stats.cells && stats.crack_density == raw_stats.crack_density &&
                    stats.cells > 0));

    hibi::Mud::RenderParams render = hibi::Mud::default_render();
    render.width = 128;
    render.height = 128;
    std::vector<std::uint8_t> mask = mud.render_mask(render);
    std::vector<std::uint8_t> raw(mask.size());
    hibi::check(hibi_mud_render(mud.get(), &render, HIBI_MUD_LAYER_MASK, raw.data(), raw.size()));
    std::printf("mud mask as from C: %s\n", yes(same_bytes(mask, raw)));
    std::printf("mud height and time layers: %s\n",
                yes(mud.render_height(render).size() == mask.size() && mud.render_time(render).size() == mask.size()));
    try {
        mud.render(render, HIBI_MUD_LAYER_MASK, raw.data(), raw.size() - 1);
        std::printf("mud short pixels: no throw\n");
    } catch (const hibi::Error &err) {
        std::printf("mud short pixels: status %u\n", static_cast<unsigned>(err.status()));
    }

    // The same run in caller memory, then moved: same picture.
    hibi::Buffer memory(hibi::Mud::memory_size(params), hibi::Mud::memory_align());
    hibi::Mud placed = hibi::Mud::create_in(params, memory.data(), memory.size());
    placed.run(1u << 30);
    hibi::Mud moved = std::move(placed);
    std::printf("mud caller memory, same mask: %s\n", yes(same_bytes(moved.render_mask(render), mask)));
}

void glass() {
    hibi::Glass::Params params = hibi::Glass::default_params();
    params.width = 200.0f;
    params.height = 200.0f;
    params.impact[0] = 100.0f;
    params.impact[1] = 100.0f;
    params.seed = 7;
    hibi::Glass glass(params);
    hibi::Glass::Progress progress = glass.run(100);
    std::size_t cracks = glass.crack_count();
    std::size_t points = 0;
    for (std::size_t i = 0; i < cracks; i++) points += glass.points(i).size();
    std::printf("glass: %s, every crack has points: %s\n", yes(progress.finished == 1 && cracks > 0),
                yes(points >= 2 * cracks));
    try {
        glass.crack(cracks);
        std::printf("glass crack past the end: no throw\n");
    } catch (const hibi::Error &e) {
        std::printf("glass crack past the end: status %u\n", static_cast<unsigned>(e.status()));
    }

    hibi::Scratch scratch = glass.scratch();
    hibi::Glass::Fragments fragments = glass.fragments(scratch);
    auto counts = glass.fragment_counts(scratch);
    double area = 0.0;
    for (const auto &ring : fragments.rings) area += ring.area;
    std::printf("glass fragments match their counts: %s, area %.1f\n",
                yes(fragments.rings.size() == counts.first && fragments.points.size() == counts.second &&
                    counts.first > 0),
                area);

    hibi::Glass::RenderParams render = hibi::Glass::default_render();
    render.width = 100;
    render.height = 100;
    std::vector<float> time = glass.render_time(render);
    std::vector<std::uint8_t> mask = glass.render_mask(render);

    // Concurrent reads of one plate from four threads, each with its own scratch.
    std::vector<int> equal(4, 0);
    std::vector<std::thread> threads;
    for (int t = 0; t < 4; t++) {
        threads.emplace_back([&glass, &render, &fragments, &time, &equal, t] {
            hibi::Scratch mine = glass.scratch();
            hibi::Glass::Fragments f = glass.fragments(mine);
            equal[static_cast<std::size_t>(t)] = same_rings(f.rings, fragments.rings) &&
                                                 same_bytes(f.points, fragments.points) &&
                                                 same_bytes(glass.render_time(render), time);
        });
    }
    for (auto &thread : threads) thread.join();
    std::printf("glass from four threads equals the lone result: %s\n",
                yes(equal[0] && equal[1] && equal[2] && equal[3]));

    hibi::Buffer memory(hibi::Glass::memory_size(params), hibi::Glass::memory_align());
    hibi::Glass placed = hibi::Glass::create_in(params, memory.data(), memory.size());
    placed.run(100);
    std::printf("glass caller memory, same mask: %s\n", yes(same_bytes(placed.render_mask(render), mask)));
    hibi_glass_counts second = glass.impact(40.0f, 40.0f);
    std::printf("glass second impact: %s\n", yes(second.radial > 0));
}

void skin() {
    hibi::Skin::Params params = hibi::Skin::preset("fig19a");
    params.width = 96;
    params.height = 96;
    hibi::Skin skin(params);
    hibi::Skin::Progress progress = skin.step(5000);
    unsigned calls = 1;
    while (!progress.finished) {
        progress = skin.step(5000);
        calls++;
    }
    std::size_t cells = skin.cell_count();
    std::printf("skin built: %s, cells %s\n", yes(calls > 1 && progress.cells == cells),
                yes(cells > 0 && skin.outline(0).size() == 2 * skin.cell(0).vertex_count));

    hibi::Skin::RenderParams render = hibi::Skin::default_render();
    render.cell_level = 1;
    std::vector<float> height = skin.render_height(render);
    std::vector<float> normal = skin.render_normal(render);
    std::vector<std::uint32_t> map = skin.render_cells(render);
    std::vector<std::uint8_t> rgb = hibi::Skin::shade(height, normal, hibi::Skin::default_shade());

    // Issue 26 item 4: concurrent renders of one skin from four threads (const calls that
    // only read the skin; each thread its own maps) equal the lone render.
    std::vector<int> equal(4, 0);
    std::vector<std::thread> threads;
    for (int t = 0; t < 4; t++) {
        threads.emplace_back([&skin, &render, &height, &normal, &map, &equal, t] {
            std::vector<float> h(skin.pixels()), n(3 * skin.pixels());
            std::vector<std::uint32_t> m(skin.pixels());
            for (int round = 0; round < 3; round++) {
                skin.render(render, HIBI_SKIN_LAYER_HEIGHT, h.data(), h.size());
                skin.render(render, HIBI_SKIN_LAYER_NORMAL, n.data(), n.size());
                skin.render(render, HIBI_SKIN_LAYER_CELLS, m.data(), m.size());
            }
            equal[static_cast<std::size_t>(t)] = same_bytes(h, height) && same_bytes(n, normal) && same_bytes(m, map);
        });
    }
    for (auto &thread : threads) thread.join();
    std::printf("skin renders from four threads equal the lone render: %s\n",
                yes(equal[0] && equal[1] && equal[2] && equal[3]));

    try {
        hibi::Skin::RenderParams deep = render;
        deep.cell_level = 9;
        skin.render_cells(deep);
        std::printf("skin cell map of level 9: no throw\n");
    } catch (const hibi::Error &e) {
        std::printf("skin cell map of level 9: status %u\n", static_cast<unsigned>(e.status()));
    }

    hibi::Buffer memory(hibi::Skin::memory_size(params), hibi::Skin::memory_align());
    hibi::Skin placed = hibi::Skin::create_in(params, memory.data(), memory.size());
    placed.run();
    std::vector<std::uint8_t> again =
        hibi::Skin::shade(placed.render_height(render), placed.render_normal(render), hibi::Skin::default_shade());
    std::printf("skin caller memory, same preview: %s\n", yes(same_bytes(again, rgb)));
}

void rng() {
    hibi::Rng a(42, 7);
    hibi::Buffer memory(hibi::Rng::memory_size(), hibi::Rng::memory_align());
    hibi::Rng b = hibi::Rng::create_in(42, 7, memory.data(), memory.size());
    std::printf("rng caller memory, same draws: %s\n", yes(a.next_u32() == b.next_u32() && a.uniform(3) == b.uniform(3)));
}

}  // namespace

int main() {
    try {
        std::printf("hibi %s\n", hibi::version());
        std::printf("macros %d.%d.%d\n", HIBI_VERSION_MAJOR, HIBI_VERSION_MINOR, HIBI_VERSION_PATCH);
        errors();
        mud();
        glass();
        skin();
        rng();
        return 0;
    } catch (const hibi::Error &e) {
        std::fprintf(stderr, "hibi error: %s (status %u) [%s]\n", e.what(), static_cast<unsigned>(e.status()),
                     e.argument().c_str());
        return 1;
    }
}
