/*
 * results.cpp: the hibi::Result API of include/hibi.hpp, built with exceptions (where the
 * try_ twins sit beside the throwing calls), with -fno-exceptions -fno-rtti and with
 * HIBI_NO_EXCEPTIONS (where every call returns its Result). Every entry point on its success
 * path, compared with the C call, and on a failure path: a refused parameter or argument (the C
 * status and argument name, no value), a view one element short (HIBI_ERROR_BUFFER_TOO_SMALL,
 * nothing written into it), or an object without a handle (HIBI_ERROR_NULL_POINTER). Each line
 * it prints is checked by tests/c_examples.rs: "name: yes; status S [argument]", where yes says
 * the success path equals the C call and the failed call wrote nothing.
 */
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "hibi.hpp"
#if __cplusplus >= 202002L
#include <span>
#endif

namespace {

const char *yes(bool b) { return b ? "yes" : "no"; }

// "status S [argument]" of a failed result; the message is hibi_status_string's.
template <class R>
std::string failure(const R &r) {
    char text[160];
    std::snprintf(text, sizeof text, "status %u [%s]%s%s", static_cast<unsigned>(r.status()), r.argument(),
                  r.ok() || static_cast<bool>(r) ? ", but ok" : "",
                  std::strcmp(r.message(), hibi_status_string(r.status())) == 0 ? "" : ", another message");
    return text;
}

// A C call of the comparisons, which must succeed.
void must(hibi_status status) {
    if (status != HIBI_OK) {
        std::fprintf(stderr, "C call failed: %s [%s]\n", hibi_status_string(status), hibi_error_argument());
        std::exit(1);
    }
}

void report(const char *name, bool ok, const std::string &failed) {
    std::printf("%s: %s; %s\n", name, yes(ok), failed.c_str());
}

template <class T>
bool same_bytes(const T *a, const T *b, std::size_t n) {
    return n == 0 || std::memcmp(a, b, n * sizeof(T)) == 0;
}
template <class T>
bool same_bytes(const std::vector<T> &a, const std::vector<T> &b) {
    return a.size() == b.size() && same_bytes(a.data(), b.data(), a.size());
}

// Every layer of hibi::Layers equal, byte for byte.
bool same_layers(const hibi::Layers &a, const hibi::Layers &b) {
    return same_bytes(a.mask, b.mask) && same_bytes(a.height, b.height) && same_bytes(a.height16, b.height16) &&
           same_bytes(a.normal, b.normal) && same_bytes(a.normal_rgb8, b.normal_rgb8) && same_bytes(a.time, b.time) &&
           same_bytes(a.cell, b.cell) && same_bytes(a.preview, b.preview);
}

// Every layer a crack model (mud, glass) draws, or a skin.
constexpr unsigned crack_layers = hibi::layer::mask | hibi::layer::height | hibi::layer::height16 |
                                  hibi::layer::normal | hibi::layer::normal_rgb8 | hibi::layer::time |
                                  hibi::layer::preview;
constexpr unsigned skin_layers = (crack_layers & ~hibi::layer::time) | hibi::layer::cell;

// A model's render_layers: one pass equals the C call's layers, and a layer the model lacks is
// refused naming it, nothing written.
template <class Model, class CModel, class Params, class CCall>
void layered(const char *name, const Model &model, CModel *c, const Params &render, std::uint32_t width,
             std::uint32_t height, unsigned which, unsigned lacking, CCall c_call) {
    hibi::Layers c_layers(width, height, which);
    const hibi_layers c_struct = c_layers.c();
    must(c_call(c, &render, nullptr, &c_struct));
    hibi::Layers layers(width, height, which);
    hibi::Status drawn = model.try_render_layers(render, layers);
    bool ok = drawn.ok() && same_layers(layers, c_layers) && !c_layers.mask.empty();
    hibi::Layers refused(width, height, which | lacking);
    refused.mask.assign(refused.mask.size(), 0xA5);
    hibi::Status failed = model.try_render_layers(render, refused);
    ok = ok && refused.mask[0] == 0xA5;
    char label[64];
    std::snprintf(label, sizeof label, "%s try_render_layers", name);
    report(label, ok, failure(failed));
}
// Field by field: a ring record has padding.
template <class Ring>
bool same_rings(const std::vector<Ring> &a, const std::vector<Ring> &b) {
    return std::equal(a.begin(), a.end(), b.begin(), b.end(), [](const Ring &x, const Ring &y) {
        return x.area == y.area && x.first_point == y.first_point && x.point_count == y.point_count &&
               x.hole_of == y.hole_of;
    });
}

// Caller memory filled with 0xA5, to see that a failed call wrote nothing.
template <class T>
struct Block {
    explicit Block(std::size_t n) : data(n == 0 ? 1 : n) { fill(); }
    void fill() { std::memset(static_cast<void *>(data.data()), 0xA5, data.size() * sizeof(T)); }
    bool untouched() const {
        const unsigned char *bytes = reinterpret_cast<const unsigned char *>(data.data());
        return std::all_of(bytes, bytes + data.size() * sizeof(T), [](unsigned char b) { return b == 0xA5; });
    }
    hibi::Span<T> view(std::size_t n) { return {data.data(), n}; }
    std::vector<T> copy(std::size_t n) const { return std::vector<T>(data.begin(), data.begin() + n); }
    std::vector<T> data;
};

// The mode's signatures: with exceptions, today's; without, every call is its try_ twin.
using Progress = hibi::Mud::Progress;
#if HIBI_EXCEPTIONS
static_assert(std::is_same<decltype(std::declval<hibi::Mud &>().step(1)), Progress>::value, "values");
static_assert(std::is_same<decltype(hibi::Mud::create(hibi::Mud::Params())), hibi::Mud>::value, "objects");
static_assert(std::is_constructible<hibi::Mud, const hibi::Mud::Params &>::value, "throwing constructors");
static_assert(std::is_void<decltype(std::declval<hibi::Skin &>().render({}, 0, nullptr, 0))>::value, "void");
#else
static_assert(std::is_same<decltype(std::declval<hibi::Mud &>().step(1)), hibi::Result<Progress>>::value, "results");
static_assert(std::is_same<decltype(hibi::Mud::create(hibi::Mud::Params())), hibi::Result<hibi::Mud>>::value, "");
static_assert(!std::is_constructible<hibi::Mud, const hibi::Mud::Params &>::value, "no throwing constructors");
static_assert(!std::is_constructible<hibi::Rng, std::uint64_t, std::uint64_t>::value, "no throwing constructors");
static_assert(std::is_same<decltype(std::declval<hibi::Skin &>().render({}, 0, nullptr, 0)), hibi::Status>::value,
              "statuses");
static_assert(std::is_same<decltype(hibi::Glass::preset("")), hibi::Result<hibi::Glass::Params>>::value, "");
#endif
static_assert(std::is_same<decltype(std::declval<hibi::Mud &>().try_step(1)), hibi::Result<Progress>>::value, "");
static_assert(noexcept(std::declval<const hibi::Mud &>().try_segments(hibi::Span<hibi_mud_segment>())), "noexcept");
static_assert(std::is_nothrow_move_constructible<hibi::Result<hibi::Glass>>::value, "results move");
static_assert(std::is_nothrow_default_constructible<hibi::Skin>::value, "an empty object");

void mode() {
    std::printf("mode: %s, language exceptions %s, rtti %s\n", HIBI_EXCEPTIONS ? "exceptions" : "results",
#if defined(__cpp_exceptions) || defined(__EXCEPTIONS)
                "on",
#else
                "off",
#endif
#if defined(__cpp_rtti) || defined(__GXX_RTTI)
                "on"
#else
                "off"
#endif
    );
}

void basics() {
    hibi::Status fine = hibi::try_check(HIBI_OK);
    std::uint32_t value = 0;
    hibi::Status refused = hibi::try_check(hibi_rng_next_u32(nullptr, &value));
    report("try_check", fine.ok() && static_cast<bool>(fine) && fine.status() == HIBI_OK &&
                            std::strcmp(fine.argument(), "") == 0 && !refused,
           failure(refused));
    hibi::Result<std::size_t> count = hibi::Mud().try_segment_count();
    report("value_or", count.value_or(7u) == 7 && hibi::Result<std::size_t>(3).value_or(7u) == 3, failure(count));
#if HIBI_EXCEPTIONS
    bool threw = false;
    try {
        (void)count.value();
    } catch (const hibi::Error &e) {
        threw = e.status() == count.status() && e.argument() == count.argument();
    }
    std::printf("value of a failure: throws hibi::Error: %s\n", yes(threw));
#else
    // Without exceptions, a Buffer that cannot be allocated is empty, and the C call refuses it.
    hibi::Buffer huge(std::size_t(1) << 62, 64);
    hibi::Result<hibi::Rng> in_huge = hibi::Rng::try_create_in(1, 2, huge.data(), huge.size());
    report("buffer of 2^62 bytes", huge.data() == nullptr && huge.size() == 0, failure(in_huge));
#endif
}

void rng() {
    hibi_rng *c = nullptr;
    must(hibi_rng_create(42, 7, &c));
    hibi::Result<hibi::Rng> made = hibi::Rng::try_create(42, 7);
    hibi::Buffer memory(hibi::Rng::memory_size() + 1, hibi::Rng::memory_align());
    hibi::Result<hibi::Rng> misaligned =
        hibi::Rng::try_create_in(42, 7, static_cast<unsigned char *>(memory.data()) + 1, hibi::Rng::memory_size());
    hibi::Result<hibi::Rng> placed = hibi::Rng::try_create_in(42, 7, memory.data(), hibi::Rng::memory_size());
    hibi::Result<hibi::Rng> short_memory =
        hibi::Rng::try_create_in(42, 7, memory.data(), hibi::Rng::memory_size() - 1);
    report("rng try_create_in, misaligned", placed.ok(), failure(misaligned));
    report("rng try_create_in, short", placed.ok(), failure(short_memory));
    hibi::Rng &rng = *made;
    hibi::Rng empty;

    std::uint32_t c_u32 = 0;
    must(hibi_rng_next_u32(c, &c_u32));
    hibi::Result<std::uint32_t> u32 = rng.try_next_u32();
    report("rng try_create, try_next_u32", made.ok() && u32.ok() && *u32 == c_u32 && placed->try_next_u32().value() == c_u32,
           failure(empty.try_next_u32()));

    float c_values[5], values[5];
    Block<float> untouched(5);
    must(hibi_rng_uniform(c, c_values, 5));
    hibi::Result<std::size_t> n = rng.try_uniform(values);
    report("rng try_uniform(view)", n.ok() && *n == 5 && same_bytes(values, c_values, 5),
           failure(rng.try_uniform(hibi::Span<float>(nullptr, 3))));
    must(hibi_rng_uniform(c, c_values, 5));
    hibi::Result<std::vector<float>> uniform = rng.try_uniform(5);
    report("rng try_uniform(n)", uniform.ok() && same_bytes(uniform->data(), c_values, 5),
           failure(empty.try_uniform(5)));
    must(hibi_rng_normal(c, c_values, 5));
    n = rng.try_normal(values);
    report("rng try_normal(view)", n.ok() && *n == 5 && same_bytes(values, c_values, 5),
           failure(empty.try_normal(untouched.view(5))) + (untouched.untouched() ? "" : ", written"));
    must(hibi_rng_normal(c, c_values, 5));
    hibi::Result<std::vector<float>> normal = rng.try_normal(5);
    report("rng try_normal(n)", normal.ok() && same_bytes(normal->data(), c_values, 5),
           failure(empty.try_normal(5)));
    std::uint32_t c_poisson = 0;
    must(hibi_rng_poisson(c, 100.0, &c_poisson));
    hibi::Result<std::uint32_t> poisson = rng.try_poisson(100.0);
    report("rng try_poisson", poisson.ok() && *poisson == c_poisson, failure(rng.try_poisson(-1.0)));
    float c_rand = 0.0f;
    must(hibi_rng_rand(c, 40.0f, 0.3f, HIBI_SPREAD_NORMAL, &c_rand));
    hibi::Result<float> rand = rng.try_rand(40.0f, 0.3f, HIBI_SPREAD_NORMAL);
    report("rng try_rand", rand.ok() && *rand == c_rand, failure(rng.try_rand(40.0f, 0.3f, 9)));
    hibi_rng_destroy(c);
}

void mud() {
    hibi::Mud::Params params = hibi::Mud::default_params();
    params.columns = 32;
    params.rows = 32;
    params.seed = 7;
    hibi::Mud::Params bad = params;
    bad.young_modulus = -1.0f;
    hibi::Mud empty;

    hibi_mud_params c_preset{};
    must(hibi_mud_params_preset(hibi_mud_preset_name(0), &c_preset));
    hibi::Result<hibi::Mud::Params> preset = hibi::Mud::try_preset(hibi_mud_preset_name(0));
    // Field by field: the params struct has padding.
    report("mud try_preset",
           preset.ok() && preset->columns == c_preset.columns && preset->seed == c_preset.seed &&
               preset->young_modulus == c_preset.young_modulus &&
               preset->break_stretch_mean == c_preset.break_stretch_mean,
           failure(hibi::Mud::try_preset("no such preset")));
    std::size_t c_size = 0;
    must(hibi_mud_memory_size(&params, &c_size));
    hibi::Result<std::size_t> size = hibi::Mud::try_memory_size(params);
    report("mud try_memory_size", size.ok() && *size == c_size, failure(hibi::Mud::try_memory_size(bad)));

    hibi_mud *c = nullptr;
    must(hibi_mud_create(&params, &c));
    hibi::Result<hibi::Mud> made = hibi::Mud::try_create(params);
    report("mud try_create", made.ok() && made->get() != nullptr, failure(hibi::Mud::try_create(bad)));
    hibi::Mud &mud = *made;
    hibi::Buffer memory(c_size, hibi::Mud::memory_align());
    hibi::Result<hibi::Mud> placed = hibi::Mud::try_create_in(params, memory.data(), memory.size());
    report("mud try_create_in", placed.ok(), failure(hibi::Mud::try_create_in(params, memory.data(), c_size - 1)));

    // Step by step, against the C run of the same parameters.
    bool steps_ok = true;
    unsigned steps = 0;
    for (;;) {
        hibi_mud_progress c_progress{};
        must(hibi_mud_step(c, 50000, &c_progress));
        hibi::Result<Progress> progress = mud.try_step(50000);
        steps_ok = steps_ok && progress.ok() && same_bytes(&*progress, &c_progress, 1);
        steps++;
        if (!progress.ok() || progress->finished) break;
    }
    report("mud try_step", steps_ok && steps > 1, failure(empty.try_step(50000)));
    hibi::Result<Progress> run = placed->try_run(1u << 30);
    report("mud try_run", run.ok() && run->finished == 1, failure(empty.try_run()));

    std::size_t c_count = 0;
    must(hibi_mud_segment_count(c, &c_count));
    hibi::Result<std::size_t> count = mud.try_segment_count();
    report("mud try_segment_count", count.ok() && *count == c_count && c_count > 0,
           failure(empty.try_segment_count()));
    std::vector<hibi_mud_segment> c_segments(c_count);
    std::size_t c_written = 0;
    must(hibi_mud_segments(c, c_segments.data(), c_count, &c_written));
    Block<hibi_mud_segment> segments(c_count);
    hibi::Result<std::size_t> written = mud.try_segments(segments.view(c_count));
    bool segments_ok = written.ok() && *written == c_written && same_bytes(segments.copy(c_count), c_segments);
    segments.fill();
    hibi::Result<std::size_t> short_segments = mud.try_segments(segments.view(c_count - 1));
    report("mud try_segments(view)", segments_ok && segments.untouched(), failure(short_segments));
    hibi::Result<std::vector<hibi_mud_segment>> segment_vector = mud.try_segments();
    report("mud try_segments()", segment_vector.ok() && same_bytes(*segment_vector, c_segments),
           failure(empty.try_segments()));

    hibi_mud_crack_statistics c_stats{};
    must(hibi_mud_statistics(c, &c_stats));
    hibi::Result<hibi_mud_crack_statistics> stats = mud.try_statistics();
    report("mud try_statistics", stats.ok() && same_bytes(&*stats, &c_stats, 1) && c_stats.cells > 0,
           failure(empty.try_statistics()));

    std::size_t v = 0, e = 0, p = 0;
    must(hibi_mud_network_counts(c, &v, &e, &p));
    hibi::Result<hibi::Mud::NetworkCounts> counts = mud.try_network_counts();
    report("mud try_network_counts",
           counts.ok() && counts->vertices == v && counts->edges == e && counts->points == p && e > 0,
           failure(empty.try_network_counts()));
    std::vector<hibi_mud_network_vertex> cv(v);
    std::vector<hibi_mud_network_edge> ce(e);
    std::vector<hibi_mud_network_point> cp(p);
    std::size_t a = 0, b = 0, d = 0;
    must(hibi_mud_network(c, cv.data(), v, ce.data(), e, cp.data(), p, &a, &b, &d));
    Block<hibi_mud_network_vertex> nv(v);
    Block<hibi_mud_network_edge> ne(e);
    Block<hibi_mud_network_point> np(p);
    hibi::Result<hibi::Mud::NetworkCounts> net = mud.try_network(nv.view(v), ne.view(e), np.view(p));
    bool net_ok = net.ok() && net->vertices == a && net->edges == b && net->points == d &&
                  same_bytes(nv.copy(v), cv) && same_bytes(ne.copy(e), ce) && same_bytes(np.copy(p), cp);
    nv.fill();
    ne.fill();
    np.fill();
    hibi::Result<hibi::Mud::NetworkCounts> short_net = mud.try_network(nv.view(v), ne.view(e - 1), np.view(p));
    report("mud try_network(views)", net_ok && nv.untouched() && ne.untouched() && np.untouched(),
           failure(short_net));
    hibi::Result<hibi::Mud::Network> network = mud.try_network();
    report("mud try_network()",
           network.ok() && same_bytes(network->vertices, cv) && same_bytes(network->edges, ce) &&
               same_bytes(network->points, cp),
           failure(empty.try_network()));

    std::size_t cr = 0, cpts = 0, cw = 0;
    must(hibi_mud_cell_counts(c, &cr, &cpts, &cw));
    hibi::Result<hibi::Mud::CellCounts> cell_counts = mud.try_cell_counts();
    report("mud try_cell_counts",
           cell_counts.ok() && cell_counts->rings == cr && cell_counts->points == cpts && cell_counts->wrapping == cw,
           failure(empty.try_cell_counts()));
    std::vector<hibi_ring> c_rings(cr);
    std::vector<hibi_vec2> c_points(cpts);
    must(hibi_mud_cells(c, c_rings.data(), cr, c_points.data(), cpts, &a, &b));
    Block<hibi_ring> rings(cr);
    Block<hibi_vec2> points(cpts);
    hibi::Result<hibi::RingCounts> cells_written = mud.try_cells(rings.view(cr), points.view(cpts));
    bool cells_ok = cells_written.ok() && cells_written->rings == a && cells_written->points == b &&
                    same_rings(rings.copy(a), c_rings) && same_bytes(points.copy(b), c_points);
    rings.fill();
    points.fill();
    hibi::Result<hibi::RingCounts> short_cells = mud.try_cells(rings.view(cr - 1), points.view(cpts));
    report("mud try_cells(views)", cells_ok && rings.untouched() && points.untouched(), failure(short_cells));
    hibi::Result<hibi::Mud::Cells> cells = mud.try_cells();
    report("mud try_cells()",
           cells.ok() && same_rings(cells->rings, c_rings) && same_bytes(cells->points, c_points) &&
               cells->wrapping == cw,
           failure(empty.try_cells()));

    hibi::Mud::RenderParams render = hibi::Mud::default_render();
    render.width = 64;
    render.height = 64;
    const std::size_t px = 64 * 64;
    std::vector<std::uint8_t> c_mask(px);
    std::vector<float> c_height(px), c_time(px);
    must(hibi_mud_render(c, &render, HIBI_MUD_LAYER_MASK, c_mask.data(), px));
    must(hibi_mud_render(c, &render, HIBI_MUD_LAYER_HEIGHT, c_height.data(), px));
    must(hibi_mud_render(c, &render, HIBI_MUD_LAYER_TIME, c_time.data(), px));
    Block<std::uint8_t> mask(px);
    hibi::Status rendered = mud.try_render(render, HIBI_MUD_LAYER_MASK, mask.data.data(), px);
    bool render_ok = rendered.ok() && same_bytes(mask.copy(px), c_mask);
    mask.fill();
    report("mud try_render", render_ok && mask.untouched(),
           failure(mud.try_render(render, 7, mask.data.data(), px)));
    hibi::Result<std::size_t> drawn = mud.try_render_mask(render, mask.view(px));
    render_ok = drawn.ok() && *drawn == px && same_bytes(mask.copy(px), c_mask);
    mask.fill();
    hibi::Result<std::size_t> short_mask = mud.try_render_mask(render, mask.view(px - 1));
    report("mud try_render_mask(view)", render_ok && mask.untouched(), failure(short_mask));
    Block<float> layer(px);
    drawn = mud.try_render_height(render, layer.view(px));
    render_ok = drawn.ok() && *drawn == px && same_bytes(layer.copy(px), c_height);
    layer.fill();
    report("mud try_render_height(view)", render_ok && !mud.try_render_height(render, layer.view(px - 1)) &&
                                              layer.untouched(),
           failure(mud.try_render_height(render, layer.view(px - 1))));
    drawn = mud.try_render_time(render, layer.view(px));
    render_ok = drawn.ok() && *drawn == px && same_bytes(layer.copy(px), c_time);
    layer.fill();
    report("mud try_render_time(view)", render_ok && !mud.try_render_time(render, layer.view(px - 1)) &&
                                            layer.untouched(),
           failure(mud.try_render_time(render, layer.view(px - 1))));
    hibi::Result<std::vector<std::uint8_t>> mask_vector = mud.try_render_mask(render);
    report("mud try_render_mask()", mask_vector.ok() && same_bytes(*mask_vector, c_mask),
           failure(empty.try_render_mask(render)));
    hibi::Result<std::vector<float>> height_vector = mud.try_render_height(render);
    report("mud try_render_height()", height_vector.ok() && same_bytes(*height_vector, c_height),
           failure(empty.try_render_height(render)));
    hibi::Result<std::vector<float>> time_vector = mud.try_render_time(render);
    report("mud try_render_time()", time_vector.ok() && same_bytes(*time_vector, c_time),
           failure(empty.try_render_time(render)));
    hibi::Result<std::vector<std::uint8_t>> placed_mask = placed->try_render_mask(render);
    std::printf("mud caller memory, same mask: %s\n", yes(placed_mask.ok() && same_bytes(*placed_mask, c_mask)));
    layered("mud", mud, c, render, 64, 64, crack_layers, hibi::layer::cell, hibi_mud_render_layers);
    hibi_mud_destroy(c);
}

void glass() {
    hibi::Glass::Params params = hibi::Glass::default_params();
    params.width = 200.0f;
    params.height = 200.0f;
    params.impact[0] = 100.0f;
    params.impact[1] = 100.0f;
    params.seed = 7;
    hibi::Glass::Params bad = params;
    bad.impact[0] = 300.0f;
    hibi::Glass empty;

    hibi_glass_params c_preset{};
    must(hibi_glass_params_preset(hibi_glass_preset_name(0), &c_preset));
    hibi::Result<hibi::Glass::Params> preset = hibi::Glass::try_preset(hibi_glass_preset_name(0));
    report("glass try_preset",
           preset.ok() && preset->width == c_preset.width && preset->seed == c_preset.seed &&
               preset->radial_mean == c_preset.radial_mean,
           failure(hibi::Glass::try_preset("no such preset")));
    std::size_t c_size = 0;
    must(hibi_glass_memory_size(&params, &c_size));
    hibi::Result<std::size_t> size = hibi::Glass::try_memory_size(params);
    hibi::Glass::Params wide = params;
    wide.width = 1e20f;
    report("glass try_memory_size", size.ok() && *size == c_size, failure(hibi::Glass::try_memory_size(wide)));

    hibi_glass *c = nullptr;
    must(hibi_glass_create(&params, &c));
    hibi::Result<hibi::Glass> made = hibi::Glass::try_create(params);
    report("glass try_create", made.ok(), failure(hibi::Glass::try_create(bad)));
    hibi::Glass &glass = *made;
    hibi::Buffer memory(c_size, hibi::Glass::memory_align());
    hibi::Result<hibi::Glass> placed = hibi::Glass::try_create_in(params, memory.data(), memory.size());
    report("glass try_create_in", placed.ok(),
           failure(hibi::Glass::try_create_in(params, memory.data(), c_size - 1)));

    bool steps_ok = true;
    unsigned steps = 0;
    for (;;) {
        hibi_glass_progress c_progress{};
        must(hibi_glass_step(c, 100, &c_progress));
        hibi::Result<hibi::Glass::Progress> progress = glass.try_step(100);
        steps_ok = steps_ok && progress.ok() && same_bytes(&*progress, &c_progress, 1);
        steps++;
        if (!progress.ok() || progress->finished) break;
    }
    report("glass try_step", steps_ok && steps > 1, failure(empty.try_step(100)));
    hibi::Result<hibi::Glass::Progress> run = placed->try_run(100);
    report("glass try_run", run.ok() && run->finished == 1, failure(empty.try_run()));

    std::size_t c_cracks = 0;
    must(hibi_glass_crack_count(c, &c_cracks));
    hibi::Result<std::size_t> cracks = glass.try_crack_count();
    report("glass try_crack_count", cracks.ok() && *cracks == c_cracks && c_cracks > 0,
           failure(empty.try_crack_count()));
    hibi_glass_crack c_crack{};
    must(hibi_glass_crack_info(c, 0, &c_crack));
    hibi::Result<hibi_glass_crack> crack = glass.try_crack(0);
    report("glass try_crack", crack.ok() && same_bytes(&*crack, &c_crack, 1), failure(glass.try_crack(c_cracks)));
    std::vector<hibi_glass_point> c_points(c_crack.points);
    std::size_t c_written = 0;
    must(hibi_glass_points(c, 0, c_points.data(), c_points.size(), &c_written));
    Block<hibi_glass_point> points(c_crack.points);
    hibi::Result<std::size_t> written = glass.try_points(0, points.view(c_crack.points));
    bool points_ok = written.ok() && *written == c_written && same_bytes(points.copy(c_written), c_points);
    points.fill();
    hibi::Result<std::size_t> short_points = glass.try_points(0, points.view(c_crack.points - 1));
    report("glass try_points(view)", points_ok && points.untouched(), failure(short_points));
    hibi::Result<std::vector<hibi_glass_point>> point_vector = glass.try_points(0);
    report("glass try_points()", point_vector.ok() && same_bytes(*point_vector, c_points),
           failure(glass.try_points(c_cracks)));

    std::size_t c_scratch = 0;
    must(hibi_glass_scratch_size(c, &c_scratch));
    hibi::Result<std::size_t> scratch_size = glass.try_scratch_size();
    report("glass try_scratch_size", scratch_size.ok() && *scratch_size == c_scratch,
           failure(empty.try_scratch_size()));
    hibi::Result<hibi::Scratch> scratch = glass.try_scratch();
    report("glass try_scratch", scratch.ok() && scratch->size() == c_scratch, failure(empty.try_scratch()));
    hibi::Buffer c_memory(c_scratch, hibi::Glass::memory_align());
    std::size_t cr = 0, cp = 0;
    must(hibi_glass_fragment_counts(c, c_memory.data(), c_memory.size(), &cr, &cp));
    hibi::Result<std::pair<std::size_t, std::size_t>> counts = glass.try_fragment_counts(*scratch);
    hibi::Scratch tiny(1, hibi::Glass::memory_align());
    report("glass try_fragment_counts", counts.ok() && counts->first == cr && counts->second == cp && cr > 0,
           failure(glass.try_fragment_counts(tiny)));
    std::vector<hibi_ring> c_rings(cr);
    std::vector<hibi_vec2> c_ring_points(cp);
    std::size_t a = 0, b = 0;
    must(hibi_glass_fragments(c, c_memory.data(), c_memory.size(), c_rings.data(), cr, c_ring_points.data(), cp,
                                     &a, &b));
    Block<hibi_ring> rings(cr);
    Block<hibi_vec2> ring_points(cp);
    hibi::Result<hibi::RingCounts> fragments_written =
        glass.try_fragments(*scratch, rings.view(cr), ring_points.view(cp));
    bool fragments_ok = fragments_written.ok() && fragments_written->rings == a && fragments_written->points == b &&
                        same_rings(rings.copy(a), c_rings) && same_bytes(ring_points.copy(b), c_ring_points);
    rings.fill();
    ring_points.fill();
    hibi::Result<hibi::RingCounts> short_fragments = glass.try_fragments(*scratch, rings.view(cr), ring_points.view(cp - 1));
    report("glass try_fragments(views)", fragments_ok && rings.untouched() && ring_points.untouched(),
           failure(short_fragments));
    hibi::Result<hibi::Glass::Fragments> fragments = glass.try_fragments(*scratch);
    hibi::Scratch none;
    report("glass try_fragments()",
           fragments.ok() && same_rings(fragments->rings, c_rings) && same_bytes(fragments->points, c_ring_points),
           failure(glass.try_fragments(none)));

    // The fragments' pieces: each twin equals its C call; a ring past the points, a short
    // scratch and short views are refused.
    {
        std::size_t c_words = 0, c_tri = 0, c_conv = 0, w = 0;
        must(hibi_pieces_scratch_size(c_rings.data(), cr, c_ring_points.data(), cp, &c_words));
        std::vector<std::uint32_t> words(c_words);
        must(hibi_pieces_counts(c_rings.data(), cr, c_ring_points.data(), cp, words.data(), c_words, &c_tri, &c_conv));
        std::vector<hibi_triangle> c_triangles(c_tri);
        std::vector<hibi_convex_piece> c_pieces(c_conv);
        must(hibi_triangulate(c_rings.data(), cr, c_ring_points.data(), cp, words.data(), c_words, c_triangles.data(),
                              c_tri, &w));
        must(hibi_convex_pieces(c_rings.data(), cr, c_ring_points.data(), cp, words.data(), c_words, c_pieces.data(),
                                c_conv, &w));
        std::vector<hibi_ring> past(1, c_rings[0]);
        past[0].first_point = static_cast<std::uint32_t>(cp);
        hibi::Result<std::size_t> size = hibi::try_pieces_scratch_size(c_rings, c_ring_points);
        report("pieces try_pieces_scratch_size", size.ok() && *size == c_words,
               failure(hibi::try_pieces_scratch_size(past, c_ring_points)));
        std::vector<std::uint32_t> scratch_words(c_words), short_words(c_words - 1);
        hibi::Result<hibi::PieceCounts> counts_of = hibi::try_piece_counts(c_rings, c_ring_points, scratch_words);
        report("pieces try_piece_counts",
               counts_of.ok() && counts_of->triangles == c_tri && counts_of->pieces == c_conv && c_conv < c_tri,
               failure(hibi::try_piece_counts(c_rings, c_ring_points, short_words)));
        Block<hibi_triangle> triangles(c_tri);
        hibi::Result<std::size_t> tw = hibi::try_triangulate(c_rings, c_ring_points, scratch_words, triangles.view(c_tri));
        bool triangles_ok = tw.ok() && *tw == c_tri && same_bytes(triangles.copy(c_tri), c_triangles);
        triangles.fill();
        hibi::Result<std::size_t> short_triangles =
            hibi::try_triangulate(c_rings, c_ring_points, scratch_words, triangles.view(c_tri - 1));
        report("pieces try_triangulate(views)", triangles_ok && triangles.untouched(), failure(short_triangles));
        hibi::Result<std::vector<hibi_triangle>> all_triangles = hibi::try_triangulate(c_rings, c_ring_points);
        report("pieces try_triangulate()", all_triangles.ok() && same_bytes(*all_triangles, c_triangles),
               failure(hibi::try_triangulate(past, c_ring_points)));
        Block<hibi_convex_piece> pieces(c_conv);
        hibi::Result<std::size_t> pw = hibi::try_convex_pieces(c_rings, c_ring_points, scratch_words, pieces.view(c_conv));
        bool pieces_ok = pw.ok() && *pw == c_conv && same_bytes(pieces.copy(c_conv), c_pieces);
        pieces.fill();
        hibi::Result<std::size_t> short_pieces =
            hibi::try_convex_pieces(c_rings, c_ring_points, scratch_words, pieces.view(c_conv - 1));
        report("pieces try_convex_pieces(views)", pieces_ok && pieces.untouched(), failure(short_pieces));
        hibi::Result<std::vector<hibi_convex_piece>> all_pieces = hibi::try_convex_pieces(c_rings, c_ring_points);
        report("pieces try_convex_pieces()", all_pieces.ok() && same_bytes(*all_pieces, c_pieces),
               failure(hibi::try_convex_pieces(past, c_ring_points)));
    }

    hibi::Glass::RenderParams render = hibi::Glass::default_render();
    render.width = 64;
    render.height = 64;
    const std::size_t px = 64 * 64;
    std::vector<std::uint8_t> c_mask(px);
    std::vector<float> c_time(px);
    must(hibi_glass_render(c, &render, HIBI_GLASS_LAYER_MASK, c_mask.data(), px));
    must(hibi_glass_render(c, &render, HIBI_GLASS_LAYER_TIME, c_time.data(), px));
    Block<std::uint8_t> mask(px);
    hibi::Status rendered = glass.try_render(render, HIBI_GLASS_LAYER_MASK, mask.data.data(), px);
    bool render_ok = rendered.ok() && same_bytes(mask.copy(px), c_mask);
    mask.fill();
    report("glass try_render", render_ok && mask.untouched(),
           failure(glass.try_render(render, 7, mask.data.data(), px)));
    hibi::Result<std::size_t> drawn = glass.try_render_mask(render, mask.view(px));
    render_ok = drawn.ok() && *drawn == px && same_bytes(mask.copy(px), c_mask);
    mask.fill();
    hibi::Result<std::size_t> short_mask = glass.try_render_mask(render, mask.view(px - 1));
    report("glass try_render_mask(view)", render_ok && mask.untouched(), failure(short_mask));
    Block<float> time(px);
    drawn = glass.try_render_time(render, time.view(px));
    render_ok = drawn.ok() && *drawn == px && same_bytes(time.copy(px), c_time);
    time.fill();
    hibi::Result<std::size_t> short_time = glass.try_render_time(render, time.view(px - 1));
    report("glass try_render_time(view)", render_ok && time.untouched(), failure(short_time));
    hibi::Result<std::vector<std::uint8_t>> mask_vector = glass.try_render_mask(render);
    report("glass try_render_mask()", mask_vector.ok() && same_bytes(*mask_vector, c_mask),
           failure(empty.try_render_mask(render)));
    hibi::Result<std::vector<float>> time_vector = glass.try_render_time(render);
    report("glass try_render_time()", time_vector.ok() && same_bytes(*time_vector, c_time),
           failure(empty.try_render_time(render)));

    layered("glass", glass, c, render, 64, 64, crack_layers, hibi::layer::cell, hibi_glass_render_layers);

    hibi_glass_counts c_counts{};
    must(hibi_glass_impact(c, 40.0f, 40.0f, &c_counts));
    hibi::Result<hibi_glass_counts> impact = glass.try_impact(40.0f, 40.0f);
    report("glass try_impact", impact.ok() && same_bytes(&*impact, &c_counts, 1) && c_counts.radial > 0,
           failure(glass.try_impact(-5.0f, 40.0f)));
    hibi_glass_destroy(c);
}

void skin() {
    hibi::Skin::Params params = hibi::Skin::try_preset("fig19a").value();
    params.width = 64;
    params.height = 64;
    hibi::Skin::Params bad = params;
    bad.width = 0;
    hibi::Skin empty;

    hibi_skin_params c_preset{};
    must(hibi_skin_params_preset("fig19a", &c_preset));
    hibi::Result<hibi::Skin::Params> preset = hibi::Skin::try_preset("fig19a");
    report("skin try_preset", preset.ok() && same_bytes(&*preset, &c_preset, 1),
           failure(hibi::Skin::try_preset("fig99")));
    std::size_t c_size = 0;
    must(hibi_skin_memory_size(&params, &c_size));
    hibi::Result<std::size_t> size = hibi::Skin::try_memory_size(params);
    report("skin try_memory_size", size.ok() && *size == c_size, failure(hibi::Skin::try_memory_size(bad)));

    hibi_skin *c = nullptr;
    must(hibi_skin_create(&params, &c));
    hibi::Result<hibi::Skin> made = hibi::Skin::try_create(params);
    report("skin try_create", made.ok() && made->width() == 64 && made->pixels() == 64 * 64,
           failure(hibi::Skin::try_create(bad)));
    hibi::Skin &skin = *made;
    hibi::Buffer memory(c_size, hibi::Skin::memory_align());
    hibi::Result<hibi::Skin> placed = hibi::Skin::try_create_in(params, memory.data(), memory.size());
    report("skin try_create_in", placed.ok(), failure(hibi::Skin::try_create_in(params, memory.data(), c_size - 1)));

    bool steps_ok = true;
    unsigned steps = 0;
    for (;;) {
        hibi_skin_progress c_progress{};
        must(hibi_skin_step(c, 2000, &c_progress));
        hibi::Result<hibi::Skin::Progress> progress = skin.try_step(2000);
        steps_ok = steps_ok && progress.ok() && same_bytes(&*progress, &c_progress, 1);
        steps++;
        if (!progress.ok() || progress->finished) break;
    }
    report("skin try_step", steps_ok && steps > 1, failure(empty.try_step(2000)));
    hibi::Result<hibi::Skin::Progress> run = placed->try_run();
    report("skin try_run", run.ok() && run->finished == 1, failure(empty.try_run()));

    std::size_t c_cells = 0;
    must(hibi_skin_cell_count(c, &c_cells));
    hibi::Result<std::size_t> cells = skin.try_cell_count();
    report("skin try_cell_count", cells.ok() && *cells == c_cells && c_cells > 0, failure(empty.try_cell_count()));
    hibi_skin_cell c_cell{};
    must(hibi_skin_cell_info(c, 0, &c_cell));
    hibi::Result<hibi_skin_cell> cell = skin.try_cell(0);
    report("skin try_cell", cell.ok() && same_bytes(&*cell, &c_cell, 1), failure(skin.try_cell(c_cells)));
    const std::size_t n = 2 * static_cast<std::size_t>(c_cell.vertex_count);
    std::vector<double> c_xy(n);
    std::size_t c_written = 0;
    must(hibi_skin_outline(c, 0, c_xy.data(), n, &c_written));
    Block<double> xy(n);
    hibi::Result<std::size_t> written = skin.try_outline(0, xy.view(n));
    bool outline_ok = written.ok() && *written == c_written && same_bytes(xy.copy(n), c_xy);
    xy.fill();
    hibi::Result<std::size_t> short_outline = skin.try_outline(0, xy.view(n - 1));
    report("skin try_outline(view)", outline_ok && xy.untouched(), failure(short_outline));
    hibi::Result<std::vector<double>> outline = skin.try_outline(0);
    report("skin try_outline()", outline.ok() && same_bytes(*outline, c_xy), failure(skin.try_outline(c_cells)));

    hibi::Skin::RenderParams render = hibi::Skin::default_render();
    render.cell_level = 1;
    hibi::Skin::RenderParams deep = render;
    deep.cell_level = 9;
    const std::size_t px = skin.pixels();
    std::vector<float> c_height(px), c_normal(3 * px);
    std::vector<std::uint32_t> c_map(px);
    std::vector<std::uint8_t> c_rgb(3 * px);
    const hibi::Skin::ShadeParams light = hibi::Skin::default_shade();
    must(hibi_skin_render(c, &render, HIBI_SKIN_LAYER_HEIGHT, c_height.data(), px));
    must(hibi_skin_render(c, &render, HIBI_SKIN_LAYER_NORMAL, c_normal.data(), 3 * px));
    must(hibi_skin_render(c, &render, HIBI_SKIN_LAYER_CELLS, c_map.data(), px));
    must(hibi_skin_shade(c_height.data(), px, c_normal.data(), 3 * px, &light, c_rgb.data(), 3 * px));
    Block<float> height(px), normal(3 * px);
    Block<std::uint32_t> map(px);
    Block<std::uint8_t> rgb(3 * px);
    hibi::Status rendered = skin.try_render(render, HIBI_SKIN_LAYER_HEIGHT, height.data.data(), px);
    bool render_ok = rendered.ok() && same_bytes(height.copy(px), c_height);
    height.fill();
    report("skin try_render", render_ok && height.untouched(),
           failure(skin.try_render(render, 7, height.data.data(), px)));
    hibi::Result<std::size_t> drawn = skin.try_render_height(render, height.view(px));
    render_ok = drawn.ok() && *drawn == px && same_bytes(height.copy(px), c_height);
    height.fill();
    hibi::Result<std::size_t> short_height = skin.try_render_height(render, height.view(px - 1));
    report("skin try_render_height(view)", render_ok && height.untouched(), failure(short_height));
    drawn = skin.try_render_normal(render, normal.view(3 * px));
    render_ok = drawn.ok() && *drawn == 3 * px && same_bytes(normal.copy(3 * px), c_normal);
    normal.fill();
    hibi::Result<std::size_t> short_normal = skin.try_render_normal(render, normal.view(3 * px - 1));
    report("skin try_render_normal(view)", render_ok && normal.untouched(), failure(short_normal));
    drawn = skin.try_render_cells(render, map.view(px));
    render_ok = drawn.ok() && *drawn == px && same_bytes(map.copy(px), c_map);
    map.fill();
    hibi::Result<std::size_t> short_map = skin.try_render_cells(render, map.view(px - 1));
    report("skin try_render_cells(view)", render_ok && map.untouched(), failure(short_map));
    hibi::Result<std::vector<float>> height_vector = skin.try_render_height(render);
    report("skin try_render_height()", height_vector.ok() && same_bytes(*height_vector, c_height),
           failure(empty.try_render_height(render)));
    hibi::Result<std::vector<float>> normal_vector = skin.try_render_normal(render);
    report("skin try_render_normal()", normal_vector.ok() && same_bytes(*normal_vector, c_normal),
           failure(empty.try_render_normal(render)));
    hibi::Result<std::vector<std::uint32_t>> map_vector = skin.try_render_cells(render);
    report("skin try_render_cells()", map_vector.ok() && same_bytes(*map_vector, c_map),
           failure(skin.try_render_cells(deep)));

    layered("skin", skin, c, render, static_cast<std::uint32_t>(params.width), static_cast<std::uint32_t>(params.height),
            skin_layers, hibi::layer::time, hibi_skin_render_layers);

    hibi::Span<const float> h_in(c_height), n_in(c_normal);
    drawn = hibi::Skin::try_shade(h_in, n_in, light, rgb.view(3 * px));
    bool shade_ok = drawn.ok() && *drawn == 3 * px && same_bytes(rgb.copy(3 * px), c_rgb);
    rgb.fill();
    hibi::Result<std::size_t> short_rgb = hibi::Skin::try_shade(h_in, n_in, light, rgb.view(3 * px - 1));
    report("skin try_shade(views)", shade_ok && rgb.untouched(), failure(short_rgb));
    hibi::Result<std::vector<std::uint8_t>> shaded = hibi::Skin::try_shade(c_height, c_normal, light);
    report("skin try_shade()", shaded.ok() && same_bytes(*shaded, c_rgb),
           failure(hibi::Skin::try_shade(h_in, hibi::Span<const float>(c_normal.data(), px), light)));
#if __cplusplus >= 202002L
    std::vector<float> spanned(px);
    hibi::Result<std::size_t> from_span = placed->try_render_height(render, std::span<float>(spanned));
    std::printf("std::span views: %s\n", yes(from_span.ok() && same_bytes(spanned, c_height)));
#else
    std::printf("std::span views: not C++20\n");
#endif
    hibi_skin_destroy(c);
}

// The calls without try_: with exceptions they throw what their twin returns; without, they
// are their twin.
void plain() {
    hibi::Mud::Params bad = hibi::Mud::default_params();
    bad.young_modulus = -1.0f;
    hibi::Result<hibi::Mud> twin = hibi::Mud::try_create(bad);
    hibi::Glass empty;
    hibi::Glass::RenderParams render = hibi::Glass::default_render();
    hibi::Status twin_render = empty.try_render(render, HIBI_GLASS_LAYER_MASK, nullptr, 0);
#if HIBI_EXCEPTIONS
    bool same = false, same_render = false;
    try {
        hibi::Mud mud(bad);
    } catch (const hibi::Error &e) {
        same = e.status() == twin.status() && e.argument() == twin.argument() &&
               std::strcmp(e.what(), twin.message()) == 0;
    }
    try {
        empty.render(render, HIBI_GLASS_LAYER_MASK, nullptr, 0);
    } catch (const hibi::Error &e) {
        same_render = e.status() == twin_render.status() && e.argument() == twin_render.argument();
    }
    std::printf("calls without try_: throw what the twin returns: %s\n", yes(same && same_render));
#else
    hibi::Result<hibi::Mud> mud = hibi::Mud::create(bad);
    hibi::Status status = empty.render(render, HIBI_GLASS_LAYER_MASK, nullptr, 0);
    std::printf("calls without try_: return what the twin returns: %s\n",
                yes(!mud && mud.status() == twin.status() && std::strcmp(mud.argument(), twin.argument()) == 0 &&
                    !status && status.status() == twin_render.status() &&
                    std::strcmp(status.argument(), twin_render.argument()) == 0));
#endif
}

}  // namespace

// Every member of the budgeted builds compiles in this mode, used or not.
template class hibi::detail::Build<hibi::FragmentBuild, hibi::Glass, hibi_glass_fragment_build,
                                   hibi_glass_fragment_progress>;
template class hibi::detail::Build<hibi::MudNetworkBuild, hibi::Mud, hibi_mud_network_build,
                                   hibi_mud_network_build_progress>;
template class hibi::detail::Build<hibi::MudCellBuild, hibi::Mud, hibi_mud_cell_build, hibi_mud_cell_build_progress>;

int main() {
    mode();
    basics();
    rng();
    mud();
    glass();
    skin();
    plain();
    return 0;
}
