/*
 * wrapper.cpp: include/hibi.hpp against the C API it wraps. Each line it prints is checked
 * by tests/c_examples.rs; "yes" lines compare the wrapper's result with the raw C calls or
 * with a second way of computing it.
 */
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <thread>
#include <type_traits>
#include <utility>
#include <vector>

#include "hibi.hpp"
#if __cplusplus >= 202002L
#include <span>
#endif

namespace {

const char *yes(bool b) { return b ? "yes" : "no"; }

// Field by field: a ring record has padding.
bool same_rings(const std::vector<hibi_ring> &a, const std::vector<hibi_ring> &b) {
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
// Views: a pointer and a count, writable only from writable memory of the same type.
static_assert(std::is_trivially_copyable<hibi::Span<float>>::value && sizeof(hibi::Span<float>) == 2 * sizeof(void *),
              "a view is a pointer and a size");
static_assert(std::is_convertible<std::vector<float> &, hibi::Span<float>>::value, "a vector is a view");
static_assert(std::is_convertible<float (&)[4], hibi::Span<float>>::value, "a C array is a view");
static_assert(std::is_convertible<hibi::Span<float>, hibi::Span<const float>>::value, "adding const");
static_assert(std::is_convertible<const std::vector<float> &, hibi::Span<const float>>::value, "const input");
static_assert(!std::is_constructible<hibi::Span<float>, const std::vector<float> &>::value, "no writes to const");
static_assert(!std::is_constructible<hibi::Span<float>, std::vector<float> &&>::value, "no writes to a temporary");
static_assert(!std::is_constructible<hibi::Span<float>, hibi::Span<const float>>::value, "no dropping const");
static_assert(!std::is_constructible<hibi::Span<float>, std::vector<double> &>::value, "same element type");

// Views into memory of the caller's own that is not a std::vector (an engine's arena).
template <class T>
struct Block {
    explicit Block(std::size_t n) : data(new T[n == 0 ? 1 : n]), size(n) { fill(); }
    void fill() { std::memset(static_cast<void *>(data.get()), 0xA5, size * sizeof(T)); }
    // Every byte still the fill: the call wrote nothing.
    bool untouched() const {
        const unsigned char *bytes = reinterpret_cast<const unsigned char *>(data.get());
        return std::all_of(bytes, bytes + size * sizeof(T), [](unsigned char b) { return b == 0xA5; });
    }
    hibi::Span<T> view() { return {data.get(), size}; }
    // One short of `size`.
    hibi::Span<T> short_view() { return {data.get(), size - 1}; }
    std::vector<T> copy(std::size_t n) const { return std::vector<T>(data.get(), data.get() + n); }
    std::unique_ptr<T[]> data;
    std::size_t size;
};

// The status a too-short view's call throws (0 if none), and whether it left the view
// untouched.
template <class T, class F>
unsigned short_status(Block<T> &block, F call, bool &untouched) {
    block.fill();
    unsigned status = 0;
    try {
        call();
    } catch (const hibi::Error &e) {
        status = static_cast<unsigned>(e.status());
    }
    untouched = untouched && block.untouched();
    return status;
}

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

    {
        // The same network and cells built in budgeted steps and read in ranges of 5.
        hibi::MudNetworkBuild network_build = hibi::MudNetworkBuild::create(mud);
        hibi::MudCellBuild cell_build = hibi::MudCellBuild::create(mud);
        int steps = 0;
        while (!network_build.step(mud, 100).finished) steps++;
        while (!cell_build.step(mud, 100).finished) steps++;
        hibi::Mud::Network built;
        hibi::Mud::Cells built_cells;
        hibi_mud_network_vertex vertices[5];
        hibi_mud_network_edge edges[5];
        hibi_mud_network_point points[5];
        hibi_ring rings[5];
        hibi_vec2 ring_points[5];
        using Vertices = hibi::Span<hibi_mud_network_vertex>;
        using Edges = hibi::Span<hibi_mud_network_edge>;
        using Points = hibi::Span<hibi_mud_network_point>;
        for (std::size_t n; (n = network_build.vertices(built.vertices.size(), Vertices(vertices, 5))) > 0;)
            built.vertices.insert(built.vertices.end(), vertices, vertices + n);
        for (std::size_t n; (n = network_build.edges(built.edges.size(), Edges(edges, 5))) > 0;)
            built.edges.insert(built.edges.end(), edges, edges + n);
        for (std::size_t n; (n = network_build.points(built.points.size(), Points(points, 5))) > 0;)
            built.points.insert(built.points.end(), points, points + n);
        for (std::size_t n; (n = cell_build.rings(built_cells.rings.size(), hibi::Span<hibi_ring>(rings, 5))) > 0;)
            built_cells.rings.insert(built_cells.rings.end(), rings, rings + n);
        bool read = true;
        for (;;) {
            hibi::Result<std::size_t> n =
                cell_build.try_points(built_cells.points.size(), hibi::Span<hibi_vec2>(ring_points, 5));
            if (!n || *n == 0) {
                read = n.ok();
                break;
            }
            built_cells.points.insert(built_cells.points.end(), ring_points, ring_points + *n);
        }
        std::printf("mud builds in ranges: same as network and cells: %s, steps: %s\n",
                    yes(same_bytes(built.vertices, network.vertices) && same_bytes(built.edges, network.edges) &&
                        same_bytes(built.points, network.points) && same_rings(built_cells.rings, cells.rings) &&
                        same_bytes(built_cells.points, cells.points) && read),
                    yes(steps > 2));
    }

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

    // Views: each output written into caller memory, against the C call into a buffer of
    // its own; then each view one element short.
    {
        bool untouched = true;
        std::size_t n = mud.segment_count();
        Block<hibi_mud_segment> seg(n);
        std::vector<hibi_mud_segment> c_seg(n);
        std::size_t written = 0;
        hibi::check(hibi_mud_segments(mud.get(), c_seg.data(), c_seg.size(), &written));
        bool seg_ok = n == count && mud.segments(seg.view()) == written && same_bytes(seg.copy(n), c_seg) &&
                      same_bytes(seg.copy(n), segments);

        hibi::Mud::NetworkCounts nc = mud.network_counts();
        Block<hibi_mud_network_vertex> nv(nc.vertices);
        Block<hibi_mud_network_edge> ne(nc.edges);
        Block<hibi_mud_network_point> np(nc.points);
        hibi::Mud::NetworkCounts nw = mud.network(nv.view(), ne.view(), np.view());
        bool net_ok = nc.vertices == v && nc.edges == e && nc.points == p && nw.vertices == v && nw.edges == e &&
                      nw.points == p && same_bytes(nv.copy(v), network.vertices) &&
                      same_bytes(ne.copy(e), network.edges) && same_bytes(np.copy(p), network.points);
        {
            std::vector<hibi_mud_network_vertex> cv(v);
            std::vector<hibi_mud_network_edge> ce(e);
            std::vector<hibi_mud_network_point> cp(p);
            std::size_t a = 0, b = 0, c = 0;
            hibi::check(hibi_mud_network(mud.get(), cv.data(), v, ce.data(), e, cp.data(), p, &a, &b, &c));
            net_ok = net_ok && same_bytes(nv.copy(v), cv) && same_bytes(ne.copy(e), ce) && same_bytes(np.copy(p), cp);
        }

        hibi::Mud::CellCounts cc = mud.cell_counts();
        std::size_t cr = 0, cp = 0, cw = 0;
        hibi::check(hibi_mud_cell_counts(mud.get(), &cr, &cp, &cw));
        Block<hibi_ring> rings(cc.rings);
        Block<hibi_vec2> points(cc.points);
        std::vector<hibi_ring> c_rings(cr);
        std::vector<hibi_vec2> c_points(cp);
        std::size_t rw = 0, pw = 0;
        hibi::check(hibi_mud_cells(mud.get(), c_rings.data(), cr, c_points.data(), cp, &rw, &pw));
        hibi::RingCounts cw2 = mud.cells(rings.view(), points.view());
        bool cells_ok = cc.rings == cr && cc.points == cp && cc.wrapping == cw && cw2.rings == rw &&
                        cw2.points == pw && same_rings(rings.copy(rw), c_rings) &&
                        same_bytes(points.copy(pw), c_points) && same_rings(rings.copy(rw), cells.rings);

        const std::size_t px = static_cast<std::size_t>(render.width) * render.height;
        Block<std::uint8_t> m(px);
        Block<float> h(px), t(px);
        std::vector<float> c_h(px), c_t(px);
        hibi::check(hibi_mud_render(mud.get(), &render, HIBI_MUD_LAYER_HEIGHT, c_h.data(), px));
        hibi::check(hibi_mud_render(mud.get(), &render, HIBI_MUD_LAYER_TIME, c_t.data(), px));
        bool mask_ok = mud.render_mask(render, m.view()) == px && same_bytes(m.copy(px), raw);
        bool height_ok = mud.render_height(render, h.view()) == px && same_bytes(h.copy(px), c_h);
        bool time_ok = mud.render_time(render, t.view()) == px && same_bytes(t.copy(px), c_t);
        // A vector as the view, and a longer one: still width x height written.
        std::vector<std::uint8_t> longer(px + 5, 7);
        bool longer_ok = mud.render_mask(render, longer) == px &&
                         same_bytes(std::vector<std::uint8_t>(longer.begin(), longer.begin() + px), raw) &&
                         longer[px] == 7;
        std::printf("mud views as from C: segments %s, network %s, cells %s, mask %s, height %s, time %s, longer %s\n",
                    yes(seg_ok), yes(net_ok), yes(cells_ok), yes(mask_ok), yes(height_ok), yes(time_ok),
                    yes(longer_ok));

        unsigned s_seg = short_status(seg, [&] { mud.segments(seg.short_view()); }, untouched);
        nv.fill();
        np.fill();
        unsigned s_net = short_status(ne, [&] { mud.network(nv.view(), ne.short_view(), np.view()); }, untouched);
        untouched = untouched && nv.untouched() && np.untouched();
        untouched = untouched && short_status(np, [&] { mud.network(nv.view(), ne.view(), np.short_view()); },
                                              untouched) == s_net;
        untouched = untouched && nv.untouched() && ne.untouched();
        points.fill();
        unsigned s_cells = short_status(rings, [&] { mud.cells(rings.short_view(), points.view()); }, untouched);
        untouched = untouched && points.untouched();
        unsigned s_mask = short_status(m, [&] { mud.render_mask(render, m.short_view()); }, untouched);
        unsigned s_height = short_status(h, [&] { mud.render_height(render, h.short_view()); }, untouched);
        unsigned s_time = short_status(t, [&] { mud.render_time(render, t.short_view()); }, untouched);
        std::printf("mud short views: segments %u, network %u, cells %u, mask %u, height %u, time %u, untouched %s\n",
                    s_seg, s_net, s_cells, s_mask, s_height, s_time, yes(untouched));
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
    {
        // The same fragments built in budgeted steps and read in ranges of 5 rings and 7 points.
        hibi::FragmentBuild build = hibi::FragmentBuild::create(glass);
        int steps = 0;
        while (!build.step(glass, 100).finished) steps++;
        std::vector<hibi_ring> rings;
        std::vector<hibi_vec2> points;
        hibi_ring ring_range[5];
        hibi_vec2 point_range[7];
        for (std::size_t n; (n = build.rings(rings.size(), hibi::Span<hibi_ring>(ring_range, 5))) > 0;)
            rings.insert(rings.end(), ring_range, ring_range + n);
        bool read = true;
        for (;;) {
            hibi::Result<std::size_t> n = build.try_points(points.size(), hibi::Span<hibi_vec2>(point_range, 7));
            if (!n || *n == 0) {
                read = n.ok();
                break;
            }
            points.insert(points.end(), point_range, point_range + *n);
        }
        std::printf("glass fragment build in ranges: same as fragments: %s, steps: %s\n",
                    yes(same_rings(rings, fragments.rings) && same_bytes(points, fragments.points) && read),
                    yes(steps > 1));
    }

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

    // Views, against the C calls; then one element short.
    {
        bool untouched = true;
        bool points_ok = true;
        for (std::size_t i = 0; i < cracks; i++) {
            Block<hibi_glass_point> mine(glass.crack(i).points);
            std::vector<hibi_glass_point> c(mine.size);
            std::size_t written = 0;
            hibi::check(hibi_glass_points(glass.get(), i, c.data(), c.size(), &written));
            points_ok = points_ok && glass.points(i, mine.view()) == written && written == mine.size &&
                        same_bytes(mine.copy(written), c) && same_bytes(mine.copy(written), glass.points(i));
        }
        Block<hibi_glass_point> first(glass.crack(0).points);
        unsigned s_points = short_status(first, [&] { glass.points(0, first.short_view()); }, untouched);

        Block<hibi_ring> rings(counts.first);
        Block<hibi_vec2> fpoints(counts.second);
        std::vector<hibi_ring> c_rings(counts.first);
        std::vector<hibi_vec2> c_points(counts.second);
        std::size_t rw = 0, pw = 0;
        hibi::check(hibi_glass_fragments(glass.get(), scratch.data(), scratch.size(), c_rings.data(), c_rings.size(),
                                         c_points.data(), c_points.size(), &rw, &pw));
        hibi::RingCounts fw = glass.fragments(scratch, rings.view(), fpoints.view());
        bool fragments_ok = fw.rings == rw && fw.points == pw && rw == counts.first &&
                            same_rings(rings.copy(rw), c_rings) && same_bytes(fpoints.copy(pw), c_points) &&
                            same_rings(rings.copy(rw), fragments.rings);
        rings.fill();
        unsigned s_fragments =
            short_status(fpoints, [&] { glass.fragments(scratch, rings.view(), fpoints.short_view()); }, untouched);
        untouched = untouched && rings.untouched();

        const std::size_t px = static_cast<std::size_t>(render.width) * render.height;
        Block<std::uint8_t> m(px);
        Block<float> t(px);
        std::vector<std::uint8_t> c_m(px);
        std::vector<float> c_t(px);
        hibi::check(hibi_glass_render(glass.get(), &render, HIBI_GLASS_LAYER_MASK, c_m.data(), px));
        hibi::check(hibi_glass_render(glass.get(), &render, HIBI_GLASS_LAYER_TIME, c_t.data(), px));
        bool mask_ok = glass.render_mask(render, m.view()) == px && same_bytes(m.copy(px), c_m) &&
                       same_bytes(c_m, mask);
        bool time_ok = glass.render_time(render, t.view()) == px && same_bytes(t.copy(px), c_t) &&
                       same_bytes(c_t, time);
        unsigned s_mask = short_status(m, [&] { glass.render_mask(render, m.short_view()); }, untouched);
        unsigned s_time = short_status(t, [&] { glass.render_time(render, t.short_view()); }, untouched);
        std::printf("glass views as from C: points %s, fragments %s, mask %s, time %s\n", yes(points_ok),
                    yes(fragments_ok), yes(mask_ok), yes(time_ok));
        std::printf("glass short views: points %u, fragments %u, mask %u, time %u, untouched %s\n", s_points,
                    s_fragments, s_mask, s_time, yes(untouched));
    }

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

    // Concurrent renders of one skin from four threads (const calls that only read the skin;
    // each thread its own maps) equal the lone render.
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

    // Views, against the C calls; then one element short.
    {
        bool untouched = true;
        const std::size_t px = skin.pixels();
        Block<float> h(px), n(3 * px);
        Block<std::uint32_t> c(px);
        Block<std::uint8_t> shaded(3 * px);
        std::vector<float> c_h(px), c_n(3 * px);
        std::vector<std::uint32_t> c_c(px);
        std::vector<std::uint8_t> c_rgb(3 * px);
        const hibi::Skin::ShadeParams light = hibi::Skin::default_shade();
        hibi::check(hibi_skin_render(skin.get(), &render, HIBI_SKIN_LAYER_HEIGHT, c_h.data(), c_h.size()));
        hibi::check(hibi_skin_render(skin.get(), &render, HIBI_SKIN_LAYER_NORMAL, c_n.data(), c_n.size()));
        hibi::check(hibi_skin_render(skin.get(), &render, HIBI_SKIN_LAYER_CELLS, c_c.data(), c_c.size()));
        hibi::check(hibi_skin_shade(c_h.data(), c_h.size(), c_n.data(), c_n.size(), &light, c_rgb.data(),
                                    c_rgb.size()));
        bool height_ok = skin.render_height(render, h.view()) == px && same_bytes(h.copy(px), c_h) &&
                         same_bytes(c_h, height);
        bool normal_ok = skin.render_normal(render, n.view()) == 3 * px && same_bytes(n.copy(3 * px), c_n) &&
                         same_bytes(c_n, normal);
        bool cells_ok = skin.render_cells(render, c.view()) == px && same_bytes(c.copy(px), c_c) &&
                        same_bytes(c_c, map);
        // Inputs as const views of the caller's memory, the output into a view.
        hibi::Span<const float> h_in = h.view(), n_in = n.view();
        bool shade_ok = hibi::Skin::shade(h_in, n_in, light, shaded.view()) == 3 * px &&
                        same_bytes(shaded.copy(3 * px), c_rgb) && same_bytes(c_rgb, rgb);
        bool outline_ok = true;
        for (std::size_t i = 0; i < cells; i += 1 + cells / 16) {
            Block<double> xy(2 * static_cast<std::size_t>(skin.cell(i).vertex_count));
            std::vector<double> c_xy(xy.size);
            std::size_t written = 0;
            hibi::check(hibi_skin_outline(skin.get(), i, c_xy.data(), c_xy.size(), &written));
            outline_ok = outline_ok && skin.outline(i, xy.view()) == written && written == xy.size &&
                         same_bytes(xy.copy(written), c_xy) && same_bytes(xy.copy(written), skin.outline(i));
        }
        Block<double> xy0(2 * static_cast<std::size_t>(skin.cell(0).vertex_count));
        unsigned s_outline = short_status(xy0, [&] { skin.outline(0, xy0.short_view()); }, untouched);
        unsigned s_height = short_status(h, [&] { skin.render_height(render, h.short_view()); }, untouched);
        unsigned s_normal = short_status(n, [&] { skin.render_normal(render, n.short_view()); }, untouched);
        unsigned s_cells = short_status(c, [&] { skin.render_cells(render, c.short_view()); }, untouched);
        unsigned s_shade = short_status(
            shaded, [&] { hibi::Skin::shade(height, normal, light, shaded.short_view()); }, untouched);
        std::printf("skin views as from C: outline %s, height %s, normal %s, cells %s, shade %s\n", yes(outline_ok),
                    yes(height_ok), yes(normal_ok), yes(cells_ok), yes(shade_ok));
        std::printf("skin short views: outline %u, height %u, normal %u, cells %u, shade %u, untouched %s\n",
                    s_outline, s_height, s_normal, s_cells, s_shade, yes(untouched));
    }

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

    // Views: a C array and a pointer + size, against the C calls on a twin stream.
    hibi::Rng twin(1, 2), mine(1, 2);
    float c_uniform[8], c_normal[5], v_uniform[8];
    std::vector<float> v_normal(5);
    hibi::check(hibi_rng_uniform(twin.get(), c_uniform, 8));
    hibi::check(hibi_rng_normal(twin.get(), c_normal, 5));
    bool uniform_ok = mine.uniform(v_uniform) == 8 && std::memcmp(v_uniform, c_uniform, sizeof c_uniform) == 0;
    bool normal_ok = mine.normal(hibi::Span<float>(v_normal.data(), v_normal.size())) == 5 &&
                     std::memcmp(v_normal.data(), c_normal, sizeof c_normal) == 0;
    std::printf("rng views as from C: uniform %s, normal %s\n", yes(uniform_ok), yes(normal_ok));
}

#if __cplusplus >= 202002L
// C++20: std::span converts to hibi::Span, for outputs and for const inputs.
bool std_span_views() {
    hibi::Skin::Params params = hibi::Skin::preset("fig19a");
    params.width = 32;
    params.height = 32;
    hibi::Skin skin(params);
    skin.run();
    hibi::Skin::RenderParams render = hibi::Skin::default_render();
    std::vector<float> height(skin.pixels()), normal(3 * skin.pixels());
    std::vector<std::uint8_t> rgb(3 * skin.pixels());
    std::span<float> h(height), n(normal);
    std::span<std::uint8_t, std::dynamic_extent> out(rgb);
    skin.render_height(render, h);
    skin.render_normal(render, n);
    std::span<const float> h_in(height), n_in(normal);
    hibi::Skin::shade(h_in, n, hibi::Skin::default_shade(), out);
    float fixed[4];
    hibi::Rng rng(3, 4);
    rng.uniform(std::span<float, 4>(fixed));
    return same_bytes(height, skin.render_height(render)) && same_bytes(normal, skin.render_normal(render)) &&
           same_bytes(rgb, hibi::Skin::shade(height, normal, hibi::Skin::default_shade())) &&
           std::memcmp(fixed, hibi::Rng(3, 4).uniform(4).data(), sizeof fixed) == 0;
}
#endif

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
#if __cplusplus >= 202002L
        std::printf("std::span views: %s\n", yes(std_span_views()));
#else
        std::printf("std::span views: not C++20\n");
#endif
        return 0;
    } catch (const hibi::Error &e) {
        std::fprintf(stderr, "hibi error: %s (status %u) [%s]\n", e.what(), static_cast<unsigned>(e.status()),
                     e.argument().c_str());
        return 1;
    }
}
