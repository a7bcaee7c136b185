/*
 * hibi.hpp: a header-only C++17 wrapper over the C API in hibi.h. Nothing of its own: every
 * member is one or a few C calls; the models, their checks and their messages are the C
 * library's.
 *
 * The choices, once:
 *
 * - Errors are exceptions. A C call that returns a status other than HIBI_OK throws
 *   hibi::Error (a std::runtime_error): status() is the hibi_status, what() is
 *   hibi_status_string(status), and argument() is hibi_error_argument() read right after
 *   the failing call (the pointer argument it refused, "" for other failures). Functions
 *   that cannot fail in C (defaults, alignments) are noexcept. Allocation failures in the
 *   wrapper's own std::vector helpers are std::bad_alloc, as usual.
 * - Objects own their handle: hibi::Mud, hibi::Glass, hibi::Skin and hibi::Rng are move-only
 *   and call hibi_*_destroy when they die (NULL after a move, which the C API ignores).
 *   Library memory: the constructor (hibi_*_create). Caller memory: the static create_in
 *   (hibi_*_memory_size / hibi_*_memory_align, then hibi_*_create_in); the memory stays the
 *   caller's and must outlive the object (destroy frees nothing then). hibi::Buffer is an
 *   aligned byte block for it and for scratch, if you have no allocator of your own.
 * - Outputs go into the caller's memory, given as a hibi::Span<T> (a pointer and a count of
 *   T, nothing more): every output has an overload taking one view per C buffer (segments,
 *   network, cells, points, fragments, outline, render_*, shade, uniform/normal), which is
 *   the one C call with the view's pointer and size and returns what it wrote (a count, or
 *   a struct of counts). A Span comes from (T*, size), a std::vector<T>&, a T (&)[N], and
 *   under C++20 from a std::span<T>; a Span<T> converts to a Span<const T>. A view that is
 *   too short throws hibi::Error with HIBI_ERROR_BUFFER_TOO_SMALL, and the C call wrote
 *   nothing into it. The count calls that size the views are members too (segment_count(),
 *   network_counts(), cell_counts(), crack(i).points, fragment_counts(), cell(i).vertex_count;
 *   a render writes width x height values, three floats a pixel for the skin's normals).
 *   The std::vector helpers without a view (segments(), network(), ..., render_*()) are
 *   conveniences built on those overloads: they size vectors with the count calls and pass
 *   them as views. No C call hands out a pointer into an object (outputs are always copied
 *   into memory the caller passes), so there are no read-only views of the library's memory.
 *   render() takes a raw pointer and a length, as hibi_*_render does, for any layer.
 * - Threads: as in hibi.h. const members only read the object and may run concurrently on
 *   one object; step, impact, moves and destruction need it to themselves. The const calls
 *   that need working memory (Glass::fragment_counts, Glass::fragments) take a Scratch: one
 *   per thread.
 * - The C types are used as they are (hibi_mud_params, hibi_mud_segment, ...): a params
 *   struct comes from hibi::Mud::default_params() or ::preset(name) and its fields are
 *   changed in place, exactly as in C.
 */
#ifndef HIBI_HPP
#define HIBI_HPP

#include <cstddef>
#include <cstdint>
#include <memory>
#include <new>
#include <stdexcept>
#include <string>
#include <utility>
#include <type_traits>
#include <vector>
#if __cplusplus >= 202002L
#include <span>
#endif

#include "hibi.h"

namespace hibi {

/// A failed C call: its status, its message (what()) and the refused argument, if any.
class Error : public std::runtime_error {
public:
    Error(hibi_status status, std::string argument)
        : std::runtime_error(hibi_status_string(status)), status_(status), argument_(std::move(argument)) {}
    /// The hibi_status the C call returned (never HIBI_OK).
    hibi_status status() const noexcept { return status_; }
    /// hibi_error_argument() after the call: the refused pointer argument's name, or "".
    const std::string &argument() const noexcept { return argument_; }

private:
    hibi_status status_;
    std::string argument_;
};

/// Throws hibi::Error unless `status` is HIBI_OK. Call it right after the C call.
inline void check(hibi_status status) {
    if (status != HIBI_OK) throw Error(status, hibi_error_argument());
}

/// The library's version, "MAJOR.MINOR.PATCH" (hibi_version()).
inline const char *version() noexcept { return hibi_version(); }

/// An owned block of `size` bytes aligned to `align` (a power of two): caller memory for
/// create_in, or scratch.
class Buffer {
public:
    Buffer() noexcept = default;
    Buffer(std::size_t size, std::size_t align)
        : data_(::operator new(size == 0 ? 1 : size, std::align_val_t(align))), size_(size), align_(align) {}
    Buffer(Buffer &&other) noexcept
        : data_(std::exchange(other.data_, nullptr)), size_(std::exchange(other.size_, 0)), align_(other.align_) {}
    Buffer &operator=(Buffer &&other) noexcept {
        if (this != &other) {
            release();
            data_ = std::exchange(other.data_, nullptr);
            size_ = std::exchange(other.size_, 0);
            align_ = other.align_;
        }
        return *this;
    }
    Buffer(const Buffer &) = delete;
    Buffer &operator=(const Buffer &) = delete;
    ~Buffer() { release(); }

    void *data() const noexcept { return data_; }
    std::size_t size() const noexcept { return size_; }

private:
    void release() noexcept {
        if (data_ != nullptr) ::operator delete(data_, std::align_val_t(align_));
        data_ = nullptr;
    }
    void *data_ = nullptr;
    std::size_t size_ = 0;
    std::size_t align_ = 1;
};

/// Working memory of the const calls that need it (one per thread); from scratch().
using Scratch = Buffer;

/// A non-owning view of `size()` consecutive T in the caller's memory, where an output is
/// written (or, as Span<const T>, an input read). Nothing but a pointer and a count: it
/// neither allocates nor frees, and the memory must outlive the call it is passed to.
template <class T>
class Span {
    // U* converts to T* without slicing: T is U, or const U (as std::span requires).
    template <class U>
    using compatible = std::enable_if_t<std::is_convertible<U (*)[], T (*)[]>::value, int>;

public:
    using element_type = T;
    using value_type = std::remove_cv_t<T>;

    constexpr Span() noexcept = default;
    /// `size` T from `data` (which may be null only when `size` is 0).
    constexpr Span(T *data, std::size_t size) noexcept : data_(data), size_(size) {}
    /// A C array.
    template <std::size_t N>
    constexpr Span(T (&array)[N]) noexcept : data_(array), size_(N) {}
    /// A vector's elements as they are (its size, not its capacity).
    template <class U, class A, compatible<U> = 0>
    Span(std::vector<U, A> &vector) noexcept : data_(vector.data()), size_(vector.size()) {}
    /// A const vector, for a Span<const T>.
    template <class U, class A, compatible<const U> = 0>
    Span(const std::vector<U, A> &vector) noexcept : data_(vector.data()), size_(vector.size()) {}
    /// Span<U> to Span<const U>.
    template <class U, compatible<U> = 0>
    constexpr Span(Span<U> other) noexcept : data_(other.data()), size_(other.size()) {}
#if __cplusplus >= 202002L
    /// A std::span (C++20).
    template <class U, std::size_t E, compatible<U> = 0>
    constexpr Span(std::span<U, E> span) noexcept : data_(span.data()), size_(span.size()) {}
#endif

    constexpr T *data() const noexcept { return data_; }
    constexpr std::size_t size() const noexcept { return size_; }
    constexpr bool empty() const noexcept { return size_ == 0; }
    constexpr T *begin() const noexcept { return data_; }
    constexpr T *end() const noexcept { return data_ + size_; }
    constexpr T &operator[](std::size_t i) const noexcept { return data_[i]; }

private:
    T *data_ = nullptr;
    std::size_t size_ = 0;
};

/// How many rings and ring points a polygon query wrote or will write (Mud::cells,
/// Glass::fragments).
struct RingCounts {
    std::size_t rings = 0;
    std::size_t points = 0;
};

namespace detail {
struct MudDelete {
    void operator()(hibi_mud *p) const noexcept { hibi_mud_destroy(p); }
};
struct GlassDelete {
    void operator()(hibi_glass *p) const noexcept { hibi_glass_destroy(p); }
};
struct SkinDelete {
    void operator()(hibi_skin *p) const noexcept { hibi_skin_destroy(p); }
};
struct RngDelete {
    void operator()(hibi_rng *p) const noexcept { hibi_rng_destroy(p); }
};
}  // namespace detail

/// A random stream (hibi_rng).
class Rng {
public:
    Rng(std::uint64_t seed, std::uint64_t stream) {
        hibi_rng *raw = nullptr;
        check(hibi_rng_create(seed, stream, &raw));
        handle_.reset(raw);
    }
    static std::size_t memory_size() noexcept { return hibi_rng_memory_size(); }
    static std::size_t memory_align() noexcept { return hibi_rng_memory_align(); }
    static Rng create_in(std::uint64_t seed, std::uint64_t stream, void *memory, std::size_t len) {
        hibi_rng *raw = nullptr;
        check(hibi_rng_create_in(seed, stream, memory, len, &raw));
        return Rng(raw);
    }
    std::uint32_t next_u32() {
        std::uint32_t value = 0;
        check(hibi_rng_next_u32(handle_.get(), &value));
        return value;
    }
    /// Fills `values` with uniform draws in [0, 1); returns values.size().
    std::size_t uniform(Span<float> values) {
        check(hibi_rng_uniform(handle_.get(), values.data(), values.size()));
        return values.size();
    }
    std::vector<float> uniform(std::size_t n) {
        std::vector<float> values(n);
        uniform(Span<float>(values));
        return values;
    }
    /// Fills `values` with standard normal draws; returns values.size().
    std::size_t normal(Span<float> values) {
        check(hibi_rng_normal(handle_.get(), values.data(), values.size()));
        return values.size();
    }
    std::vector<float> normal(std::size_t n) {
        std::vector<float> values(n);
        normal(Span<float>(values));
        return values;
    }
    std::uint32_t poisson(double mean) {
        std::uint32_t value = 0;
        check(hibi_rng_poisson(handle_.get(), mean, &value));
        return value;
    }
    float rand(float x, float z, std::uint32_t spread) {
        float value = 0.0f;
        check(hibi_rng_rand(handle_.get(), x, z, spread, &value));
        return value;
    }
    hibi_rng *get() const noexcept { return handle_.get(); }

private:
    explicit Rng(hibi_rng *raw) noexcept : handle_(raw) {}
    std::unique_ptr<hibi_rng, detail::RngDelete> handle_;
};

/// Model A, drying mud (hibi_mud).
class Mud {
public:
    using Params = hibi_mud_params;
    using Progress = hibi_mud_progress;
    using RenderParams = hibi_mud_render_params;

    /// The crack network as a plane graph (hibi_mud_network).
    struct Network {
        std::vector<hibi_mud_network_vertex> vertices;
        std::vector<hibi_mud_network_edge> edges;
        std::vector<hibi_mud_network_point> points;
    };
    /// The cells as polygons (hibi_mud_cells), and the boundaries that wrap (not written).
    struct Cells {
        std::vector<hibi_mud_cell_ring> rings;
        std::vector<hibi_vec2> points;
        std::size_t wrapping = 0;
    };
    /// How many vertices, edges and points the network has (hibi_mud_network_counts), or
    /// were written.
    struct NetworkCounts {
        std::size_t vertices = 0;
        std::size_t edges = 0;
        std::size_t points = 0;
    };
    /// How many rings and points hibi_mud_cells will write, and the boundaries that wrap.
    struct CellCounts {
        std::size_t rings = 0;
        std::size_t points = 0;
        std::size_t wrapping = 0;
    };

    static Params default_params() noexcept { return hibi_mud_params_default(); }
    static Params preset(const char *name) {
        Params params{};
        check(hibi_mud_params_preset(name, &params));
        return params;
    }
    static RenderParams default_render() noexcept { return hibi_mud_render_params_default(); }
    static std::size_t memory_size(const Params &params) {
        std::size_t size = 0;
        check(hibi_mud_memory_size(&params, &size));
        return size;
    }
    static std::size_t memory_align() noexcept { return hibi_mud_memory_align(); }

    /// A run in library memory.
    explicit Mud(const Params &params) {
        hibi_mud *raw = nullptr;
        check(hibi_mud_create(&params, &raw));
        handle_.reset(raw);
    }
    /// A run in `memory` (memory_size(params) bytes aligned to memory_align()), which stays
    /// the caller's and must outlive the run.
    static Mud create_in(const Params &params, void *memory, std::size_t len) {
        hibi_mud *raw = nullptr;
        check(hibi_mud_create_in(&params, memory, len, &raw));
        return Mud(raw);
    }

    /// Advances by about `budget` units of work (springs and nodes visited; overruns by less
    /// than one piece: a piece of the setup the first calls do, at most HIBI_MUD_SETUP_PIECE
    /// units, a row of the lattice, a node's springs, or a piece of the network's tracing, at
    /// most HIBI_MUD_TRACE_PIECE units, which runs within the same budgets: see
    /// hibi_mud_step). Throws hibi::Error on HIBI_ERROR_MUD_SHORT_STEP_STABILITY (an irregular
    /// mesh that fails the explicit solver's stability test), and again on every later call.
    Progress step(std::uint64_t budget) {
        Progress progress{};
        check(hibi_mud_step(handle_.get(), budget, &progress));
        return progress;
    }
    /// Steps until finished, `budget` at a time; returns the last progress.
    Progress run(std::uint64_t budget = 1000000) {
        Progress progress = step(budget);
        while (!progress.finished) progress = step(budget);
        return progress;
    }

    std::size_t segment_count() const {
        std::size_t count = 0;
        check(hibi_mud_segment_count(handle_.get(), &count));
        return count;
    }
    /// Writes the crack segments into `out` (at least segment_count()); returns how many.
    std::size_t segments(Span<hibi_mud_segment> out) const {
        std::size_t written = 0;
        check(hibi_mud_segments(handle_.get(), out.data(), out.size(), &written));
        return written;
    }
    std::vector<hibi_mud_segment> segments() const {
        std::vector<hibi_mud_segment> out(segment_count());
        out.resize(segments(Span<hibi_mud_segment>(out)));
        return out;
    }
    /// Crack density, cells, junctions and dead ends of the traced network.
    hibi_mud_crack_statistics statistics() const {
        hibi_mud_crack_statistics stats{};
        check(hibi_mud_statistics(handle_.get(), &stats));
        return stats;
    }
    NetworkCounts network_counts() const {
        NetworkCounts counts;
        check(hibi_mud_network_counts(handle_.get(), &counts.vertices, &counts.edges, &counts.points));
        return counts;
    }
    /// Writes the network into the three views (each at least its network_counts() member);
    /// returns how many of each.
    NetworkCounts network(Span<hibi_mud_network_vertex> vertices, Span<hibi_mud_network_edge> edges,
                          Span<hibi_mud_network_point> points) const {
        NetworkCounts written;
        check(hibi_mud_network(handle_.get(), vertices.data(), vertices.size(), edges.data(), edges.size(),
                               points.data(), points.size(), &written.vertices, &written.edges, &written.points));
        return written;
    }
    Network network() const {
        NetworkCounts counts = network_counts();
        Network net;
        net.vertices.resize(counts.vertices);
        net.edges.resize(counts.edges);
        net.points.resize(counts.points);
        counts = network(Span<hibi_mud_network_vertex>(net.vertices), Span<hibi_mud_network_edge>(net.edges),
                         Span<hibi_mud_network_point>(net.points));
        net.vertices.resize(counts.vertices);
        net.edges.resize(counts.edges);
        net.points.resize(counts.points);
        return net;
    }
    CellCounts cell_counts() const {
        CellCounts counts;
        check(hibi_mud_cell_counts(handle_.get(), &counts.rings, &counts.points, &counts.wrapping));
        return counts;
    }
    /// Writes the cells into the two views (at least cell_counts().rings and .points);
    /// returns how many of each.
    RingCounts cells(Span<hibi_mud_cell_ring> rings, Span<hibi_vec2> points) const {
        RingCounts written;
        check(hibi_mud_cells(handle_.get(), rings.data(), rings.size(), points.data(), points.size(), &written.rings,
                             &written.points));
        return written;
    }
    Cells cells() const {
        CellCounts counts = cell_counts();
        Cells out;
        out.wrapping = counts.wrapping;
        out.rings.resize(counts.rings);
        out.points.resize(counts.points);
        RingCounts written = cells(Span<hibi_mud_cell_ring>(out.rings), Span<hibi_vec2>(out.points));
        out.rings.resize(written.rings);
        out.points.resize(written.points);
        return out;
    }

    /// Draws `layer` into caller pixels (`len` values of the layer's type).
    void render(const RenderParams &render, std::uint32_t layer, void *pixels, std::size_t len) const {
        check(hibi_mud_render(handle_.get(), &render, layer, pixels, len));
    }
    /// Draws a layer into `pixels` (at least params.width x params.height values); returns
    /// how many it wrote (width x height).
    std::size_t render_mask(const RenderParams &params, Span<std::uint8_t> pixels) const {
        return draw(params, HIBI_MUD_LAYER_MASK, pixels);
    }
    std::size_t render_height(const RenderParams &params, Span<float> pixels) const {
        return draw(params, HIBI_MUD_LAYER_HEIGHT, pixels);
    }
    std::size_t render_time(const RenderParams &params, Span<float> pixels) const {
        return draw(params, HIBI_MUD_LAYER_TIME, pixels);
    }
    std::vector<std::uint8_t> render_mask(const RenderParams &params) const {
        return draw<std::uint8_t>(params, HIBI_MUD_LAYER_MASK);
    }
    std::vector<float> render_height(const RenderParams &params) const {
        return draw<float>(params, HIBI_MUD_LAYER_HEIGHT);
    }
    std::vector<float> render_time(const RenderParams &params) const {
        return draw<float>(params, HIBI_MUD_LAYER_TIME);
    }

    hibi_mud *get() const noexcept { return handle_.get(); }

private:
    explicit Mud(hibi_mud *raw) noexcept : handle_(raw) {}
    template <class T>
    std::size_t draw(const RenderParams &params, std::uint32_t layer, Span<T> pixels) const {
        render(params, layer, pixels.data(), pixels.size());
        return static_cast<std::size_t>(params.width) * params.height;
    }
    template <class T>
    std::vector<T> draw(const RenderParams &params, std::uint32_t layer) const {
        std::vector<T> pixels(static_cast<std::size_t>(params.width) * params.height);
        draw(params, layer, Span<T>(pixels));
        return pixels;
    }
    std::unique_ptr<hibi_mud, detail::MudDelete> handle_;
};

/// Model B, a glass plate hit by a ball (hibi_glass).
class Glass {
public:
    using Params = hibi_glass_params;
    using Progress = hibi_glass_progress;
    using RenderParams = hibi_glass_render_params;

    /// The fragments as polygons (hibi_glass_fragments).
    struct Fragments {
        std::vector<hibi_glass_fragment_ring> rings;
        std::vector<hibi_vec2> points;
    };

    static Params default_params() noexcept { return hibi_glass_params_default(); }
    static Params preset(const char *name) {
        Params params{};
        check(hibi_glass_params_preset(name, &params));
        return params;
    }
    static RenderParams default_render() noexcept { return hibi_glass_render_params_default(); }
    static std::size_t memory_size(const Params &params) {
        std::size_t size = 0;
        check(hibi_glass_memory_size(&params, &size));
        return size;
    }
    static std::size_t memory_align() noexcept { return hibi_glass_memory_align(); }

    /// A plate in library memory, with its first impact at params.impact.
    explicit Glass(const Params &params) {
        hibi_glass *raw = nullptr;
        check(hibi_glass_create(&params, &raw));
        handle_.reset(raw);
    }
    /// A plate in caller memory (see Mud::create_in).
    static Glass create_in(const Params &params, void *memory, std::size_t len) {
        hibi_glass *raw = nullptr;
        check(hibi_glass_create_in(&params, memory, len, &raw));
        return Glass(raw);
    }

    hibi_glass_counts impact(float x, float y) {
        hibi_glass_counts counts{};
        check(hibi_glass_impact(handle_.get(), x, y, &counts));
        return counts;
    }
    /// Advances growth by `budget` units of work (grid cells and entries examined, cracks
    /// looked at, face-walk steps; overruns by less than HIBI_GLASS_STEP_PIECE units: see
    /// hibi_glass_step).
    Progress step(std::uint64_t budget) {
        Progress progress{};
        check(hibi_glass_step(handle_.get(), budget, &progress));
        return progress;
    }
    Progress run(std::uint64_t budget = 1000) {
        Progress progress = step(budget);
        while (!progress.finished) progress = step(budget);
        return progress;
    }

    std::size_t crack_count() const {
        std::size_t count = 0;
        check(hibi_glass_crack_count(handle_.get(), &count));
        return count;
    }
    hibi_glass_crack crack(std::size_t index) const {
        hibi_glass_crack info{};
        check(hibi_glass_crack_info(handle_.get(), index, &info));
        return info;
    }
    /// Writes crack `index`'s polyline into `out` (at least crack(index).points); returns
    /// how many points.
    std::size_t points(std::size_t index, Span<hibi_glass_point> out) const {
        std::size_t written = 0;
        check(hibi_glass_points(handle_.get(), index, out.data(), out.size(), &written));
        return written;
    }
    std::vector<hibi_glass_point> points(std::size_t index) const {
        std::vector<hibi_glass_point> out(crack(index).points);
        out.resize(points(index, Span<hibi_glass_point>(out)));
        return out;
    }

    std::size_t scratch_size() const {
        std::size_t size = 0;
        check(hibi_glass_scratch_size(handle_.get(), &size));
        return size;
    }
    /// Scratch for fragment_counts and fragments: one per thread.
    Scratch scratch() const { return Scratch(scratch_size(), memory_align()); }
    std::pair<std::size_t, std::size_t> fragment_counts(Scratch &scratch) const {
        std::size_t rings = 0, points = 0;
        check(hibi_glass_fragment_counts(handle_.get(), scratch.data(), scratch.size(), &rings, &points));
        return {rings, points};
    }
    /// Writes the fragments into the two views (at least fragment_counts()); returns how
    /// many rings and points.
    RingCounts fragments(Scratch &scratch, Span<hibi_glass_fragment_ring> rings, Span<hibi_vec2> points) const {
        RingCounts written;
        check(hibi_glass_fragments(handle_.get(), scratch.data(), scratch.size(), rings.data(), rings.size(),
                                   points.data(), points.size(), &written.rings, &written.points));
        return written;
    }
    Fragments fragments(Scratch &scratch) const {
        auto counts = fragment_counts(scratch);
        Fragments out;
        out.rings.resize(counts.first);
        out.points.resize(counts.second);
        RingCounts written =
            fragments(scratch, Span<hibi_glass_fragment_ring>(out.rings), Span<hibi_vec2>(out.points));
        out.rings.resize(written.rings);
        out.points.resize(written.points);
        return out;
    }

    void render(const RenderParams &render, std::uint32_t layer, void *pixels, std::size_t len) const {
        check(hibi_glass_render(handle_.get(), &render, layer, pixels, len));
    }
    /// Draws a layer into `pixels` (at least params.width x params.height values); returns
    /// how many it wrote (width x height).
    std::size_t render_mask(const RenderParams &params, Span<std::uint8_t> pixels) const {
        return draw(params, HIBI_GLASS_LAYER_MASK, pixels);
    }
    std::size_t render_time(const RenderParams &params, Span<float> pixels) const {
        return draw(params, HIBI_GLASS_LAYER_TIME, pixels);
    }
    std::vector<std::uint8_t> render_mask(const RenderParams &params) const {
        return draw<std::uint8_t>(params, HIBI_GLASS_LAYER_MASK);
    }
    /// The break-time raster.
    std::vector<float> render_time(const RenderParams &params) const {
        return draw<float>(params, HIBI_GLASS_LAYER_TIME);
    }

    hibi_glass *get() const noexcept { return handle_.get(); }

private:
    explicit Glass(hibi_glass *raw) noexcept : handle_(raw) {}
    template <class T>
    std::size_t draw(const RenderParams &params, std::uint32_t layer, Span<T> pixels) const {
        render(params, layer, pixels.data(), pixels.size());
        return static_cast<std::size_t>(params.width) * params.height;
    }
    template <class T>
    std::vector<T> draw(const RenderParams &params, std::uint32_t layer) const {
        std::vector<T> pixels(static_cast<std::size_t>(params.width) * params.height);
        draw(params, layer, Span<T>(pixels));
        return pixels;
    }
    std::unique_ptr<hibi_glass, detail::GlassDelete> handle_;
};

/// Model C, skin from hierarchical Voronoi cells (hibi_skin).
class Skin {
public:
    using Params = hibi_skin_params;
    using Progress = hibi_skin_progress;
    using RenderParams = hibi_skin_render_params;
    using ShadeParams = hibi_skin_shade_params;

    static Params default_params() noexcept { return hibi_skin_params_default(); }
    static Params preset(const char *name) {
        Params params{};
        check(hibi_skin_params_preset(name, &params));
        return params;
    }
    static RenderParams default_render() noexcept { return hibi_skin_render_params_default(); }
    static ShadeParams default_shade() noexcept { return hibi_skin_shade_params_default(); }
    static std::size_t memory_size(const Params &params) {
        std::size_t size = 0;
        check(hibi_skin_memory_size(&params, &size));
        return size;
    }
    static std::size_t memory_align() noexcept { return hibi_skin_memory_align(); }

    /// A skin in library memory.
    explicit Skin(const Params &params) : width_(params.width), height_(params.height) {
        hibi_skin *raw = nullptr;
        check(hibi_skin_create(&params, &raw));
        handle_.reset(raw);
    }
    /// A skin in caller memory (see Mud::create_in).
    static Skin create_in(const Params &params, void *memory, std::size_t len) {
        hibi_skin *raw = nullptr;
        check(hibi_skin_create_in(&params, memory, len, &raw));
        return Skin(raw, params);
    }

    /// Advances the build by about `budget` units of work (outline vertices, and one per
    /// level-0 centre point tried), one cell at a time: overruns it by at most one cell's.
    Progress step(std::uint64_t budget) {
        Progress progress{};
        check(hibi_skin_step(handle_.get(), budget, &progress));
        return progress;
    }
    Progress run(std::uint64_t budget = UINT64_MAX) {
        Progress progress = step(budget);
        while (!progress.finished) progress = step(budget);
        return progress;
    }

    std::uint32_t width() const noexcept { return width_; }
    std::uint32_t height() const noexcept { return height_; }
    std::size_t pixels() const noexcept { return static_cast<std::size_t>(width_) * height_; }

    std::size_t cell_count() const {
        std::size_t count = 0;
        check(hibi_skin_cell_count(handle_.get(), &count));
        return count;
    }
    hibi_skin_cell cell(std::size_t index) const {
        hibi_skin_cell info{};
        check(hibi_skin_cell_info(handle_.get(), index, &info));
        return info;
    }
    /// Writes cell `index`'s outline, x, y pairs in pixels, into `xy` (at least
    /// 2 x cell(index).vertex_count doubles); returns how many doubles.
    std::size_t outline(std::size_t index, Span<double> xy) const {
        std::size_t written = 0;
        check(hibi_skin_outline(handle_.get(), index, xy.data(), xy.size(), &written));
        return written;
    }
    /// Cell `index`'s outline, x, y pairs in pixels.
    std::vector<double> outline(std::size_t index) const {
        std::vector<double> xy(2 * static_cast<std::size_t>(cell(index).vertex_count));
        xy.resize(outline(index, Span<double>(xy)));
        return xy;
    }

    /// Draws `layer` into caller pixels (`len` values of the layer's type; floats for the
    /// normal layer, three per pixel).
    void render(const RenderParams &render, std::uint32_t layer, void *pixels, std::size_t len) const {
        check(hibi_skin_render(handle_.get(), &render, layer, pixels, len));
    }
    /// Draws a layer into `out` (at least pixels() values, 3 x pixels() for the normals);
    /// returns how many it wrote.
    std::size_t render_height(const RenderParams &params, Span<float> out) const {
        return draw(params, HIBI_SKIN_LAYER_HEIGHT, 1, out);
    }
    std::size_t render_normal(const RenderParams &params, Span<float> out) const {
        return draw(params, HIBI_SKIN_LAYER_NORMAL, 3, out);
    }
    std::size_t render_cells(const RenderParams &params, Span<std::uint32_t> out) const {
        return draw(params, HIBI_SKIN_LAYER_CELLS, 1, out);
    }
    std::vector<float> render_height(const RenderParams &params) const {
        return draw<float>(params, HIBI_SKIN_LAYER_HEIGHT, 1);
    }
    /// Three floats per pixel.
    std::vector<float> render_normal(const RenderParams &params) const {
        return draw<float>(params, HIBI_SKIN_LAYER_NORMAL, 3);
    }
    /// Per pixel the index of its cell at params.cell_level, HIBI_SKIN_NO_CELL where none is.
    std::vector<std::uint32_t> render_cells(const RenderParams &params) const {
        return draw<std::uint32_t>(params, HIBI_SKIN_LAYER_CELLS, 1);
    }
    /// 8-bit sRGB preview of a height and a normal map into `rgb` (three bytes per pixel, at
    /// least 3 x height.size()); returns how many bytes it wrote.
    static std::size_t shade(Span<const float> height, Span<const float> normal, const ShadeParams &params,
                             Span<std::uint8_t> rgb) {
        check(hibi_skin_shade(height.data(), height.size(), normal.data(), normal.size(), &params, rgb.data(),
                              rgb.size()));
        return 3 * height.size();
    }
    /// 8-bit sRGB preview of a height and a normal map (three bytes per pixel).
    static std::vector<std::uint8_t> shade(Span<const float> height, Span<const float> normal,
                                           const ShadeParams &params) {
        std::vector<std::uint8_t> rgb(3 * height.size());
        shade(height, normal, params, Span<std::uint8_t>(rgb));
        return rgb;
    }

    hibi_skin *get() const noexcept { return handle_.get(); }

private:
    Skin(hibi_skin *raw, const Params &params) noexcept
        : handle_(raw), width_(params.width), height_(params.height) {}
    /// The layer's raster over the skin's width x height, `per_pixel` values a pixel.
    template <class T>
    std::size_t draw(const RenderParams &params, std::uint32_t layer, std::size_t per_pixel, Span<T> out) const {
        render(params, layer, out.data(), out.size());
        return per_pixel * pixels();
    }
    template <class T>
    std::vector<T> draw(const RenderParams &params, std::uint32_t layer, std::size_t per_pixel) const {
        std::vector<T> out(per_pixel * pixels());
        draw(params, layer, per_pixel, Span<T>(out));
        return out;
    }
    std::unique_ptr<hibi_skin, detail::SkinDelete> handle_;
    std::uint32_t width_;
    std::uint32_t height_;
};

}  // namespace hibi

#endif /* HIBI_HPP */
