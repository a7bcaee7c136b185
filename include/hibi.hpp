/*
 * hibi.hpp: a header-only C++17 wrapper over the C API in hibi.h. Nothing of its own: every
 * member is one or a few C calls; the models, their checks and their messages are the C
 * library's.
 *
 * The choices, once:
 *
 * - Errors are exceptions, or results. A C call that returns a status other than HIBI_OK
 *   throws hibi::Error (a std::runtime_error): status() is the hibi_status, what() is
 *   hibi_status_string(status), and argument() is hibi_error_argument() read right after
 *   the failing call (the pointer argument it refused, "" for other failures). Functions
 *   that cannot fail in C (defaults, alignments) are noexcept. Allocation failures in the
 *   wrapper's own std::vector helpers are std::bad_alloc, as usual.
 *   Every call that can fail, f, has a twin try_f that never throws and returns a
 *   hibi::Result<T> (the status, the refused argument, the message, and the value on
 *   success; hibi::Status, a Result<void>, where f returns nothing); the constructors' twins
 *   are the static create (Mud::create(params), Rng::create(seed, stream)).
 *   Built without exceptions (-fno-exceptions: no __cpp_exceptions, __EXCEPTIONS or
 *   _CPPUNWIND), or with HIBI_NO_EXCEPTIONS defined before this header, f is try_f: it
 *   returns the Result, hibi::Error and the throwing constructors do not exist, and
 *   hibi::Buffer reports a failed allocation as an empty block (data() NULL, size() 0) that
 *   the C calls then refuse. HIBI_EXCEPTIONS says which mode a build is in (1 or 0). The
 *   mode is part of the classes' names (an inline namespace in the result mode), so
 *   translation units built in different modes link without clashing.
 * - Objects own their handle: hibi::Mud, hibi::Glass, hibi::Skin and hibi::Rng are move-only
 *   and call hibi_*_destroy when they die (NULL after a move or from the default
 *   constructor, which the C API ignores and refuses as a handle). Library memory: the
 *   constructor or create (hibi_*_create). Caller memory: the static create_in
 *   (hibi_*_memory_size / hibi_*_memory_align, then hibi_*_create_in); the memory stays the
 *   caller's and must outlive the object (destroy frees nothing then). hibi::Buffer is an
 *   aligned byte block for it and for scratch, if you have no allocator of your own.
 * - Outputs go into the caller's memory, given as a hibi::Span<T> (a pointer and a count of
 *   T, nothing more): every output has an overload taking one view per C buffer (segments,
 *   network, cells, points, fragments, outline, render_*, shade, uniform/normal), which is
 *   the one C call with the view's pointer and size and returns what it wrote (a count, or
 *   a struct of counts). A Span comes from (T*, size), a std::vector<T>&, a T (&)[N], and
 *   under C++20 from a std::span<T>; a Span<T> converts to a Span<const T>. A view that is
 *   too short fails with HIBI_ERROR_BUFFER_TOO_SMALL, and the C call wrote nothing into it.
 *   The count calls that size the views are members too (segment_count(),
 *   network_counts(), cell_counts(), crack(i).points, fragment_counts(), cell(i).vertex_count;
 *   a render writes width x height values, three floats a pixel for the skin's normals).
 *   The std::vector helpers without a view (segments(), network(), ..., render_*()) are
 *   conveniences built on those overloads: they size vectors with the count calls and pass
 *   them as views (without exceptions, a failed allocation in std::vector ends the program
 *   as the standard library does: use the views to keep allocation in your hands). No C
 *   call hands out a pointer into an object (outputs are always copied into memory the
 *   caller passes), so there are no read-only views of the library's memory.
 *   render() takes a raw pointer and a length, as hibi_*_render does, for any layer.
 * - Threads: as in hibi.h. const members only read the object and may run concurrently on
 *   one object; step, impact, moves and destruction need it to themselves. The const calls
 *   that need working memory (Glass::fragment_counts, Glass::fragments) take a Scratch: one
 *   per thread.
 * - Pieces for a physics engine are free functions over rings and points (a fragments' or
 *   cells' rings and points, or any in that shape): pieces_scratch_size, piece_counts,
 *   triangulate and convex_pieces, with views of uint32_t scratch and of the output, or
 *   returning vectors.
 * - The C types are used as they are (hibi_mud_params, hibi_mud_segment, ...): a params
 *   struct comes from hibi::Mud::default_params() or ::preset(name) and its fields are
 *   changed in place, exactly as in C.
 */
#ifndef HIBI_HPP
#define HIBI_HPP

#if defined(HIBI_NO_EXCEPTIONS) || !(defined(__cpp_exceptions) || defined(__EXCEPTIONS) || defined(_CPPUNWIND))
#define HIBI_EXCEPTIONS 0
#else
#define HIBI_EXCEPTIONS 1
#endif

#include <cstddef>
#include <cstdint>
#include <memory>
#include <new>
#include <optional>
#include <utility>
#include <type_traits>
#include <vector>
#if HIBI_EXCEPTIONS
#include <stdexcept>
#include <string>
#else
#include <cstdio>
#include <cstdlib>
#endif
#if __cplusplus >= 202002L
#include <span>
#endif

#include "hibi.h"

namespace hibi {

/// The library's version, "MAJOR.MINOR.PATCH" (hibi_version()).
inline const char *version() noexcept { return hibi_version(); }

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

#if !HIBI_EXCEPTIONS
inline namespace results {
#endif

#if HIBI_EXCEPTIONS
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
#endif

namespace detail {
/// Reading the value of a failed result: hibi::Error with exceptions; without, a message on
/// stderr and std::abort (a bug in the caller, never an error the C library reports).
[[noreturn]] inline void bad_access(hibi_status status, const char *argument) {
#if HIBI_EXCEPTIONS
    throw Error(status, argument);
#else
    std::fprintf(stderr, "hibi: the value of a failed result was read: %s [%s]\n", hibi_status_string(status),
                 argument);
    std::abort();
#endif
}
}  // namespace detail

/// The outcome of a C call without exceptions: its status, and on success the value.
/// Failures carry hibi_error_argument() as read right after the call.
template <class T>
class [[nodiscard]] Result {
public:
    using value_type = T;

    /// A success.
    Result(T value) : value_(std::move(value)) {}
    /// A failure: `status` (not HIBI_OK) and the refused argument's name, a static string
    /// ("" for none), as hibi_error_argument() gives it.
    Result(hibi_status status, const char *argument) noexcept : status_(status), argument_(argument) {}

    /// Whether the call succeeded (status() is HIBI_OK, and there is a value).
    bool ok() const noexcept { return value_.has_value(); }
    explicit operator bool() const noexcept { return ok(); }
    /// The hibi_status the C call returned: HIBI_OK on success.
    hibi_status status() const noexcept { return status_; }
    /// The refused pointer argument's name (hibi_error_argument()), or "".
    const char *argument() const noexcept { return argument_; }
    /// hibi_status_string(status()): names the field and its range for a parameter error.
    const char *message() const noexcept { return hibi_status_string(status_); }

    /// The value; on a failure, hibi::Error with exceptions, a message and std::abort without.
    T &value() & {
        if (!ok()) detail::bad_access(status_, argument_);
        return *value_;
    }
    const T &value() const & {
        if (!ok()) detail::bad_access(status_, argument_);
        return *value_;
    }
    T &&value() && {
        if (!ok()) detail::bad_access(status_, argument_);
        return std::move(*value_);
    }
    /// The value, or `fallback` on a failure.
    template <class U>
    T value_or(U &&fallback) const & {
        return ok() ? *value_ : static_cast<T>(std::forward<U>(fallback));
    }
    template <class U>
    T value_or(U &&fallback) && {
        return ok() ? std::move(*value_) : static_cast<T>(std::forward<U>(fallback));
    }
    /// As value().
    T &operator*() & { return value(); }
    const T &operator*() const & { return value(); }
    T &&operator*() && { return std::move(*this).value(); }
    T *operator->() { return &value(); }
    const T *operator->() const { return &value(); }

private:
    std::optional<T> value_;
    hibi_status status_ = HIBI_OK;
    const char *argument_ = "";
};

/// The outcome of a C call that returns nothing but its status.
template <>
class [[nodiscard]] Result<void> {
public:
    using value_type = void;

    /// A success.
    Result() noexcept = default;
    /// A failure (see Result<T>).
    Result(hibi_status status, const char *argument) noexcept : status_(status), argument_(argument) {}

    bool ok() const noexcept { return status_ == HIBI_OK; }
    explicit operator bool() const noexcept { return ok(); }
    hibi_status status() const noexcept { return status_; }
    const char *argument() const noexcept { return argument_; }
    const char *message() const noexcept { return hibi_status_string(status_); }

private:
    hibi_status status_ = HIBI_OK;
    const char *argument_ = "";
};

/// The outcome of a call without a value.
using Status = Result<void>;

namespace detail {
/// A C call's status as a Status, with the refused argument read right after the call.
inline Status status(hibi_status status) noexcept {
    if (status == HIBI_OK) return Status();
    return Status(status, hibi_error_argument());
}
/// A C call's status and, on success, the value it wrote: `value` is taken by reference and
/// read here, after the call (an argument's copy could be made before it).
template <class T>
Result<std::decay_t<T>> result(hibi_status status, T &&value) {
    if (status == HIBI_OK) return Result<std::decay_t<T>>(std::forward<T>(value));
    return Result<std::decay_t<T>>(status, hibi_error_argument());
}
/// A failed result of another type, passed on.
template <class T, class U>
Result<T> failure(const Result<U> &failed) noexcept {
    return Result<T>(failed.status(), failed.argument());
}

#if HIBI_EXCEPTIONS
/// What a call without try_ returns: its value, or it throws hibi::Error.
template <class T>
using Returned = T;
template <class T>
T returned(Result<T> &&result) {
    return std::move(result).value();
}
inline void returned(Status &&status) {
    if (!status) throw Error(status.status(), status.argument());
}
#else
/// What a call without try_ returns: the Result of its try_ twin.
template <class T>
using Returned = Result<T>;
template <class T>
Result<T> returned(Result<T> &&result) noexcept {
    return std::move(result);
}
#endif
}  // namespace detail

/// A C call's status as a Status (with hibi_error_argument() if it failed). Call it right
/// after the C call.
inline Status try_check(hibi_status status) noexcept { return detail::status(status); }
/// Throws hibi::Error unless `status` is HIBI_OK (without exceptions: try_check). Call it
/// right after the C call.
inline detail::Returned<void> check(hibi_status status) { return detail::returned(try_check(status)); }

/// An owned block of `size` bytes aligned to `align` (a power of two): caller memory for
/// create_in, or scratch. Without exceptions, a failed allocation leaves it empty (data()
/// NULL, size() 0), which create_in and the scratch calls refuse as a NULL pointer.
class Buffer {
public:
    Buffer() noexcept = default;
#if HIBI_EXCEPTIONS
    Buffer(std::size_t size, std::size_t align)
        : data_(::operator new(size == 0 ? 1 : size, std::align_val_t(align))), size_(size), align_(align) {}
#else
    Buffer(std::size_t size, std::size_t align) noexcept
        : data_(::operator new(size == 0 ? 1 : size, std::align_val_t(align), std::nothrow)),
          size_(data_ == nullptr ? 0 : size),
          align_(align) {}
#endif
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

namespace detail {
/// A budgeted build in memory it owns (FragmentBuild, MudNetworkBuild, MudCellBuild): made
/// in the same work at any size, stepped with its model until finished, then read in ranges.
/// `Self` names its C calls: `size_call`, `create_call` and `step_call`.
template <class Self, class Model, class Handle, class Progress>
class Build {
public:
    /// No build (as after a move): every call on it fails with HIBI_ERROR_NULL_POINTER.
    Build() noexcept = default;
    Build(Build &&other) noexcept : memory_(std::move(other.memory_)), handle_(std::exchange(other.handle_, nullptr)) {}
    Build &operator=(Build &&other) noexcept {
        if (this != &other) {
            memory_ = std::move(other.memory_);
            handle_ = std::exchange(other.handle_, nullptr);
        }
        return *this;
    }
    /// A build of `model`'s output.
    static Result<Self> try_create(const Model &model) {
        std::size_t size = 0;
        hibi_status status = Self::size_call(model.get(), &size);
        if (status != HIBI_OK) return Result<Self>(status, hibi_error_argument());
        Self out;
        out.memory_ = Buffer(size, Model::memory_align());
        if (out.memory_.data() == nullptr) return Result<Self>(HIBI_ERROR_OUT_OF_MEMORY, "");
        status = Self::create_call(model.get(), out.memory_.data(), out.memory_.size(), &out.handle_);
        return detail::result(status, std::move(out));
    }
    static Returned<Self> create(const Model &model) { return returned(try_create(model)); }

    /// Goes on until about `budget` units are done in this call, or the build is finished.
    Result<Progress> try_step(const Model &model, std::uint64_t budget) noexcept {
        Progress progress{};
        return detail::result(Self::step_call(handle_, model.get(), budget, &progress), progress);
    }
    Returned<Progress> step(const Model &model, std::uint64_t budget) {
        return returned(try_step(model, budget));
    }

    Handle *get() const noexcept { return handle_; }

protected:
    /// Copies the elements from `first` on into `out` with the C range read `call`, as many
    /// as there are (none before the build is finished); returns how many.
    template <class T>
    Result<std::size_t> read(hibi_status (*call)(const Handle *, std::size_t, T *, std::size_t, std::size_t *),
                             std::size_t first, Span<T> out) const noexcept {
        std::size_t written = 0;
        return detail::result(call(handle_, first, out.data(), out.size(), &written), written);
    }

    Buffer memory_;
    Handle *handle_ = nullptr;
};
}  // namespace detail

/// The layers a layered render (render_layers) can draw, as flags for hibi::Layers.
namespace layer {
constexpr unsigned mask = 1u, height = 2u, height16 = 4u, normal = 8u, normal_rgb8 = 16u, time = 32u, cell = 64u,
                   preview = 128u;
}  // namespace layer

/// Owned buffers for one layered render (render_layers) of a width x height image or tile:
/// a vector per layer asked for (the others empty), and the scratch they need. Its members
/// are plain vectors, read them after the render; c() is the hibi_layers over them.
class Layers {
public:
    /// Buffers for the layers in `which` (hibi::layer flags, or-ed).
    Layers(std::uint32_t width, std::uint32_t height, unsigned which)
        : width_(width), height_(height) {
        const std::size_t n = static_cast<std::size_t>(width) * height;
        auto size = [&](unsigned flag, std::size_t per) { return (which & flag) ? n * per : 0; };
        mask.resize(size(layer::mask, 1));
        height16.resize(size(layer::height16, 1));
        this->height.resize(size(layer::height, 1));
        normal.resize(size(layer::normal, 3));
        normal_rgb8.resize(size(layer::normal_rgb8, 3));
        time.resize(size(layer::time, 1));
        cell.resize(size(layer::cell, 1));
        preview.resize(size(layer::preview, 4));
        std::size_t len = 0;
        if (hibi_render_scratch_len(width, height, &len) == HIBI_OK) scratch.resize(len);
    }

    std::vector<std::uint8_t> mask;
    std::vector<float> height;
    std::vector<std::uint16_t> height16;
    std::vector<float> normal;
    std::vector<std::uint8_t> normal_rgb8;
    std::vector<float> time;
    std::vector<std::uint32_t> cell;
    std::vector<std::uint8_t> preview;
    std::vector<std::uint32_t> scratch;

    /// The C struct over these buffers (an empty vector is a layer not drawn).
    hibi_layers c() noexcept {
        auto at = [](auto &v) { return v.empty() ? nullptr : v.data(); };
        hibi_layers out{};
        out.mask = at(mask);
        out.height = at(height);
        out.height16 = at(height16);
        out.normal = at(normal);
        out.normal_rgb8 = at(normal_rgb8);
        out.time = at(time);
        out.cell = at(cell);
        out.preview = at(preview);
        out.pixels_len = static_cast<std::size_t>(width_) * height_;
        out.scratch = at(scratch);
        out.scratch_len = scratch.size();
        return out;
    }

private:
    std::uint32_t width_, height_;
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
    /// No stream (as after a move): every call on it fails with HIBI_ERROR_NULL_POINTER.
    Rng() noexcept = default;
#if HIBI_EXCEPTIONS
    Rng(std::uint64_t seed, std::uint64_t stream) : Rng(create(seed, stream)) {}
#endif
    static Result<Rng> try_create(std::uint64_t seed, std::uint64_t stream) noexcept {
        hibi_rng *raw = nullptr;
        hibi_status status = hibi_rng_create(seed, stream, &raw);
        return detail::result(status, Rng(raw));
    }
    static detail::Returned<Rng> create(std::uint64_t seed, std::uint64_t stream) {
        return detail::returned(try_create(seed, stream));
    }
    static std::size_t memory_size() noexcept { return hibi_rng_memory_size(); }
    static std::size_t memory_align() noexcept { return hibi_rng_memory_align(); }
    static Result<Rng> try_create_in(std::uint64_t seed, std::uint64_t stream, void *memory,
                                     std::size_t len) noexcept {
        hibi_rng *raw = nullptr;
        hibi_status status = hibi_rng_create_in(seed, stream, memory, len, &raw);
        return detail::result(status, Rng(raw));
    }
    static detail::Returned<Rng> create_in(std::uint64_t seed, std::uint64_t stream, void *memory, std::size_t len) {
        return detail::returned(try_create_in(seed, stream, memory, len));
    }
    Result<std::uint32_t> try_next_u32() noexcept {
        std::uint32_t value = 0;
        return detail::result(hibi_rng_next_u32(handle_.get(), &value), value);
    }
    detail::Returned<std::uint32_t> next_u32() { return detail::returned(try_next_u32()); }
    /// Fills `values` with uniform draws in [0, 1); returns values.size().
    Result<std::size_t> try_uniform(Span<float> values) noexcept {
        return detail::result(hibi_rng_uniform(handle_.get(), values.data(), values.size()), values.size());
    }
    detail::Returned<std::size_t> uniform(Span<float> values) { return detail::returned(try_uniform(values)); }
    Result<std::vector<float>> try_uniform(std::size_t n) {
        std::vector<float> values(n);
        Result<std::size_t> written = try_uniform(Span<float>(values));
        if (!written) return detail::failure<std::vector<float>>(written);
        return Result<std::vector<float>>(std::move(values));
    }
    detail::Returned<std::vector<float>> uniform(std::size_t n) { return detail::returned(try_uniform(n)); }
    /// Fills `values` with standard normal draws; returns values.size().
    Result<std::size_t> try_normal(Span<float> values) noexcept {
        return detail::result(hibi_rng_normal(handle_.get(), values.data(), values.size()), values.size());
    }
    detail::Returned<std::size_t> normal(Span<float> values) { return detail::returned(try_normal(values)); }
    Result<std::vector<float>> try_normal(std::size_t n) {
        std::vector<float> values(n);
        Result<std::size_t> written = try_normal(Span<float>(values));
        if (!written) return detail::failure<std::vector<float>>(written);
        return Result<std::vector<float>>(std::move(values));
    }
    detail::Returned<std::vector<float>> normal(std::size_t n) { return detail::returned(try_normal(n)); }
    Result<std::uint32_t> try_poisson(double mean) noexcept {
        std::uint32_t value = 0;
        return detail::result(hibi_rng_poisson(handle_.get(), mean, &value), value);
    }
    detail::Returned<std::uint32_t> poisson(double mean) { return detail::returned(try_poisson(mean)); }
    Result<float> try_rand(float x, float z, std::uint32_t spread) noexcept {
        float value = 0.0f;
        return detail::result(hibi_rng_rand(handle_.get(), x, z, spread, &value), value);
    }
    detail::Returned<float> rand(float x, float z, std::uint32_t spread) {
        return detail::returned(try_rand(x, z, spread));
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
        std::vector<hibi_ring> rings;
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
    static Result<Params> try_preset(const char *name) noexcept {
        Params params{};
        return detail::result(hibi_mud_params_preset(name, &params), params);
    }
    static detail::Returned<Params> preset(const char *name) { return detail::returned(try_preset(name)); }
    static RenderParams default_render() noexcept { return hibi_mud_render_params_default(); }
    static Result<std::size_t> try_memory_size(const Params &params) noexcept {
        std::size_t size = 0;
        return detail::result(hibi_mud_memory_size(&params, &size), size);
    }
    static detail::Returned<std::size_t> memory_size(const Params &params) {
        return detail::returned(try_memory_size(params));
    }
    static std::size_t memory_align() noexcept { return hibi_mud_memory_align(); }

    /// No run (as after a move): every call on it fails with HIBI_ERROR_NULL_POINTER.
    Mud() noexcept = default;
#if HIBI_EXCEPTIONS
    /// A run in library memory.
    explicit Mud(const Params &params) : Mud(create(params)) {}
#endif
    /// A run in library memory.
    static Result<Mud> try_create(const Params &params) noexcept {
        hibi_mud *raw = nullptr;
        hibi_status status = hibi_mud_create(&params, &raw);
        return detail::result(status, Mud(raw));
    }
    static detail::Returned<Mud> create(const Params &params) { return detail::returned(try_create(params)); }
    /// A run in `memory` (memory_size(params) bytes aligned to memory_align()), which stays
    /// the caller's and must outlive the run.
    static Result<Mud> try_create_in(const Params &params, void *memory, std::size_t len) noexcept {
        hibi_mud *raw = nullptr;
        hibi_status status = hibi_mud_create_in(&params, memory, len, &raw);
        return detail::result(status, Mud(raw));
    }
    static detail::Returned<Mud> create_in(const Params &params, void *memory, std::size_t len) {
        return detail::returned(try_create_in(params, memory, len));
    }

    /// Advances by about `budget` units of work (springs and nodes visited; overruns by less
    /// than one piece: a piece of the setup the first calls do, at most HIBI_MUD_SETUP_PIECE
    /// units, a row of the lattice, a node's springs, or a piece of the network's tracing, at
    /// most HIBI_MUD_TRACE_PIECE units: the network is traced live, within the same budgets,
    /// see hibi_mud_step). Fails with HIBI_ERROR_MUD_SHORT_STEP_STABILITY on an irregular mesh
    /// that fails the explicit solver's stability test, and again on every later call.
    Result<Progress> try_step(std::uint64_t budget) noexcept {
        Progress progress{};
        return detail::result(hibi_mud_step(handle_.get(), budget, &progress), progress);
    }
    detail::Returned<Progress> step(std::uint64_t budget) { return detail::returned(try_step(budget)); }
    /// Steps until finished, `budget` at a time; returns the last progress.
    Result<Progress> try_run(std::uint64_t budget = 1000000) noexcept {
        Result<Progress> progress = try_step(budget);
        while (progress && !progress->finished) progress = try_step(budget);
        return progress;
    }
    detail::Returned<Progress> run(std::uint64_t budget = 1000000) { return detail::returned(try_run(budget)); }

    Result<std::size_t> try_segment_count() const noexcept {
        std::size_t count = 0;
        return detail::result(hibi_mud_segment_count(handle_.get(), &count), count);
    }
    detail::Returned<std::size_t> segment_count() const { return detail::returned(try_segment_count()); }
    /// Springs broken when the network shown was traced (see hibi_mud_shown_broken_springs).
    Result<std::uint32_t> try_shown_broken_springs() const noexcept {
        std::uint32_t count = 0;
        return detail::result(hibi_mud_shown_broken_springs(handle_.get(), &count), count);
    }
    detail::Returned<std::uint32_t> shown_broken_springs() const {
        return detail::returned(try_shown_broken_springs());
    }
    /// Writes the crack segments into `out` (at least segment_count()); returns how many.
    Result<std::size_t> try_segments(Span<hibi_mud_segment> out) const noexcept {
        std::size_t written = 0;
        return detail::result(hibi_mud_segments(handle_.get(), out.data(), out.size(), &written), written);
    }
    detail::Returned<std::size_t> segments(Span<hibi_mud_segment> out) const {
        return detail::returned(try_segments(out));
    }
    Result<std::vector<hibi_mud_segment>> try_segments() const {
        Result<std::size_t> count = try_segment_count();
        if (!count) return detail::failure<std::vector<hibi_mud_segment>>(count);
        std::vector<hibi_mud_segment> out(*count);
        Result<std::size_t> written = try_segments(Span<hibi_mud_segment>(out));
        if (!written) return detail::failure<std::vector<hibi_mud_segment>>(written);
        out.resize(*written);
        return Result<std::vector<hibi_mud_segment>>(std::move(out));
    }
    detail::Returned<std::vector<hibi_mud_segment>> segments() const { return detail::returned(try_segments()); }
    /// Width and height of the domain, lattice units (hibi_mud_extent).
    Result<hibi_vec2> try_extent() const noexcept {
        hibi_vec2 extent{};
        return detail::result(hibi_mud_extent(handle_.get(), &extent), extent);
    }
    detail::Returned<hibi_vec2> extent() const { return detail::returned(try_extent()); }
    /// The default drawing `width` pixels wide at the domain's aspect
    /// (hibi_mud_render_params_fit).
    Result<RenderParams> try_render_fit(std::uint32_t width) const noexcept {
        RenderParams params{};
        return detail::result(hibi_mud_render_params_fit(handle_.get(), width, &params), params);
    }
    detail::Returned<RenderParams> render_fit(std::uint32_t width) const {
        return detail::returned(try_render_fit(width));
    }
    /// Crack density, cells, junctions and dead ends of the traced network.
    Result<hibi_mud_crack_statistics> try_statistics() const noexcept {
        hibi_mud_crack_statistics stats{};
        return detail::result(hibi_mud_statistics(handle_.get(), &stats), stats);
    }
    detail::Returned<hibi_mud_crack_statistics> statistics() const { return detail::returned(try_statistics()); }
    Result<NetworkCounts> try_network_counts() const noexcept {
        NetworkCounts counts;
        return detail::result(
            hibi_mud_network_counts(handle_.get(), &counts.vertices, &counts.edges, &counts.points), counts);
    }
    detail::Returned<NetworkCounts> network_counts() const { return detail::returned(try_network_counts()); }
    /// Writes the network into the three views (each at least its network_counts() member);
    /// returns how many of each.
    Result<NetworkCounts> try_network(Span<hibi_mud_network_vertex> vertices, Span<hibi_mud_network_edge> edges,
                                      Span<hibi_mud_network_point> points) const noexcept {
        NetworkCounts written;
        return detail::result(hibi_mud_network(handle_.get(), vertices.data(), vertices.size(), edges.data(),
                                               edges.size(), points.data(), points.size(), &written.vertices,
                                               &written.edges, &written.points),
                              written);
    }
    detail::Returned<NetworkCounts> network(Span<hibi_mud_network_vertex> vertices, Span<hibi_mud_network_edge> edges,
                                            Span<hibi_mud_network_point> points) const {
        return detail::returned(try_network(vertices, edges, points));
    }
    Result<Network> try_network() const {
        Result<NetworkCounts> counts = try_network_counts();
        if (!counts) return detail::failure<Network>(counts);
        Network net;
        net.vertices.resize(counts->vertices);
        net.edges.resize(counts->edges);
        net.points.resize(counts->points);
        counts = try_network(Span<hibi_mud_network_vertex>(net.vertices), Span<hibi_mud_network_edge>(net.edges),
                             Span<hibi_mud_network_point>(net.points));
        if (!counts) return detail::failure<Network>(counts);
        net.vertices.resize(counts->vertices);
        net.edges.resize(counts->edges);
        net.points.resize(counts->points);
        return Result<Network>(std::move(net));
    }
    detail::Returned<Network> network() const { return detail::returned(try_network()); }
    Result<CellCounts> try_cell_counts() const noexcept {
        CellCounts counts;
        return detail::result(hibi_mud_cell_counts(handle_.get(), &counts.rings, &counts.points, &counts.wrapping),
                              counts);
    }
    detail::Returned<CellCounts> cell_counts() const { return detail::returned(try_cell_counts()); }
    /// Writes the cells into the two views (at least cell_counts().rings and .points);
    /// returns how many of each.
    Result<RingCounts> try_cells(Span<hibi_ring> rings, Span<hibi_vec2> points) const noexcept {
        RingCounts written;
        return detail::result(hibi_mud_cells(handle_.get(), rings.data(), rings.size(), points.data(), points.size(),
                                             &written.rings, &written.points),
                              written);
    }
    detail::Returned<RingCounts> cells(Span<hibi_ring> rings, Span<hibi_vec2> points) const {
        return detail::returned(try_cells(rings, points));
    }
    Result<Cells> try_cells() const {
        Result<CellCounts> counts = try_cell_counts();
        if (!counts) return detail::failure<Cells>(counts);
        Cells out;
        out.wrapping = counts->wrapping;
        out.rings.resize(counts->rings);
        out.points.resize(counts->points);
        Result<RingCounts> written = try_cells(Span<hibi_ring>(out.rings), Span<hibi_vec2>(out.points));
        if (!written) return detail::failure<Cells>(written);
        out.rings.resize(written->rings);
        out.points.resize(written->points);
        return Result<Cells>(std::move(out));
    }
    detail::Returned<Cells> cells() const { return detail::returned(try_cells()); }

    /// Draws `layer` into caller pixels (`len` values of the layer's type).
    Status try_render(const RenderParams &render, std::uint32_t layer, void *pixels, std::size_t len) const noexcept {
        return detail::status(hibi_mud_render(handle_.get(), &render, layer, pixels, len));
    }
    detail::Returned<void> render(const RenderParams &render, std::uint32_t layer, void *pixels,
                                  std::size_t len) const {
        return detail::returned(try_render(render, layer, pixels, len));
    }
    /// Draws a layer into `pixels` (at least params.width x params.height values); returns
    /// how many it wrote (width x height).
    Result<std::size_t> try_render_mask(const RenderParams &params, Span<std::uint8_t> pixels) const noexcept {
        return draw(params, HIBI_MUD_LAYER_MASK, pixels);
    }
    Result<std::size_t> try_render_height(const RenderParams &params, Span<float> pixels) const noexcept {
        return draw(params, HIBI_MUD_LAYER_HEIGHT, pixels);
    }
    Result<std::size_t> try_render_time(const RenderParams &params, Span<float> pixels) const noexcept {
        return draw(params, HIBI_MUD_LAYER_TIME, pixels);
    }
    Result<std::vector<std::uint8_t>> try_render_mask(const RenderParams &params) const {
        return draw<std::uint8_t>(params, HIBI_MUD_LAYER_MASK);
    }
    Result<std::vector<float>> try_render_height(const RenderParams &params) const {
        return draw<float>(params, HIBI_MUD_LAYER_HEIGHT);
    }
    Result<std::vector<float>> try_render_time(const RenderParams &params) const {
        return draw<float>(params, HIBI_MUD_LAYER_TIME);
    }
    detail::Returned<std::size_t> render_mask(const RenderParams &params, Span<std::uint8_t> pixels) const {
        return detail::returned(try_render_mask(params, pixels));
    }
    detail::Returned<std::size_t> render_height(const RenderParams &params, Span<float> pixels) const {
        return detail::returned(try_render_height(params, pixels));
    }
    detail::Returned<std::size_t> render_time(const RenderParams &params, Span<float> pixels) const {
        return detail::returned(try_render_time(params, pixels));
    }
    detail::Returned<std::vector<std::uint8_t>> render_mask(const RenderParams &params) const {
        return detail::returned(try_render_mask(params));
    }
    detail::Returned<std::vector<float>> render_height(const RenderParams &params) const {
        return detail::returned(try_render_height(params));
    }
    detail::Returned<std::vector<float>> render_time(const RenderParams &params) const {
        return detail::returned(try_render_time(params));
    }

    /// Draws every layer `layers` gives of `tile` (nullptr: the whole image) in one pass
    /// (hibi_mud_render_layers).
    Status try_render_layers(const RenderParams &render, const hibi_layers &layers,
                             const hibi_tile *tile = nullptr) const noexcept {
        return detail::status(hibi_mud_render_layers(handle_.get(), &render, tile, &layers));
    }
    Status try_render_layers(const RenderParams &render, Layers &layers, const hibi_tile *tile = nullptr) const noexcept {
        const hibi_layers c = layers.c();
        return try_render_layers(render, c, tile);
    }
    detail::Returned<void> render_layers(const RenderParams &render, const hibi_layers &layers,
                                         const hibi_tile *tile = nullptr) const {
        return detail::returned(try_render_layers(render, layers, tile));
    }
    detail::Returned<void> render_layers(const RenderParams &render, Layers &layers,
                                         const hibi_tile *tile = nullptr) const {
        return detail::returned(try_render_layers(render, layers, tile));
    }

    hibi_mud *get() const noexcept { return handle_.get(); }

private:
    explicit Mud(hibi_mud *raw) noexcept : handle_(raw) {}
    template <class T>
    Result<std::size_t> draw(const RenderParams &params, std::uint32_t layer, Span<T> pixels) const noexcept {
        return detail::result(hibi_mud_render(handle_.get(), &params, layer, pixels.data(), pixels.size()),
                              static_cast<std::size_t>(params.width) * params.height);
    }
    template <class T>
    Result<std::vector<T>> draw(const RenderParams &params, std::uint32_t layer) const {
        std::vector<T> pixels(static_cast<std::size_t>(params.width) * params.height);
        Result<std::size_t> written = draw(params, layer, Span<T>(pixels));
        if (!written) return detail::failure<std::vector<T>>(written);
        return Result<std::vector<T>>(std::move(pixels));
    }
    std::unique_ptr<hibi_mud, detail::MudDelete> handle_;
};

/// A budgeted build of a run's crack network in memory it owns (hibi_mud_network_build_*): made in
/// the same work at any size, stepped with the run until finished (hibi_mud_network_build_step),
/// then read in ranges. The vertices, edges and points are those of Mud::network, bit for bit.
class MudNetworkBuild : public detail::Build<MudNetworkBuild, Mud, hibi_mud_network_build, hibi_mud_network_build_progress> {
public:
    using Progress = hibi_mud_network_build_progress;

    /// Copies the vertices from `first` on into `out`, as many as there are (none before the
    /// build is finished); returns how many.
    Result<std::size_t> try_vertices(std::size_t first, Span<hibi_mud_network_vertex> out) const noexcept {
        return read(hibi_mud_network_build_vertices, first, out);
    }
    detail::Returned<std::size_t> vertices(std::size_t first, Span<hibi_mud_network_vertex> out) const {
        return detail::returned(try_vertices(first, out));
    }
    /// Copies the edges from `first` on into `out`, as many as there are (none before the
    /// build is finished); returns how many.
    Result<std::size_t> try_edges(std::size_t first, Span<hibi_mud_network_edge> out) const noexcept {
        return read(hibi_mud_network_build_edges, first, out);
    }
    detail::Returned<std::size_t> edges(std::size_t first, Span<hibi_mud_network_edge> out) const {
        return detail::returned(try_edges(first, out));
    }
    /// Copies the points from `first` on into `out`, as many as there are (none before the
    /// build is finished); returns how many.
    Result<std::size_t> try_points(std::size_t first, Span<hibi_mud_network_point> out) const noexcept {
        return read(hibi_mud_network_build_points, first, out);
    }
    detail::Returned<std::size_t> points(std::size_t first, Span<hibi_mud_network_point> out) const {
        return detail::returned(try_points(first, out));
    }

private:
    friend Build;
    static constexpr auto size_call = hibi_mud_network_build_size;
    static constexpr auto create_call = hibi_mud_network_build_create_in;
    static constexpr auto step_call = hibi_mud_network_build_step;
};

/// A budgeted build of a run's cells in memory it owns (hibi_mud_cell_build_*): made in
/// the same work at any size, stepped with the run until finished (hibi_mud_cell_build_step),
/// then read in ranges. The rings and points are those of Mud::cells, bit for bit.
class MudCellBuild : public detail::Build<MudCellBuild, Mud, hibi_mud_cell_build, hibi_mud_cell_build_progress> {
public:
    using Progress = hibi_mud_cell_build_progress;

    /// Copies the rings from `first` on into `out`, as many as there are (none before the
    /// build is finished); returns how many.
    Result<std::size_t> try_rings(std::size_t first, Span<hibi_ring> out) const noexcept {
        return read(hibi_mud_cell_build_rings, first, out);
    }
    detail::Returned<std::size_t> rings(std::size_t first, Span<hibi_ring> out) const {
        return detail::returned(try_rings(first, out));
    }
    /// Copies the points from `first` on into `out`, as many as there are (none before the
    /// build is finished); returns how many.
    Result<std::size_t> try_points(std::size_t first, Span<hibi_vec2> out) const noexcept {
        return read(hibi_mud_cell_build_points, first, out);
    }
    detail::Returned<std::size_t> points(std::size_t first, Span<hibi_vec2> out) const {
        return detail::returned(try_points(first, out));
    }

private:
    friend Build;
    static constexpr auto size_call = hibi_mud_cell_build_size;
    static constexpr auto create_call = hibi_mud_cell_build_create_in;
    static constexpr auto step_call = hibi_mud_cell_build_step;
};

/// Model B, a glass plate hit by a ball (hibi_glass).
class Glass {
public:
    using Params = hibi_glass_params;
    using Progress = hibi_glass_progress;
    using RenderParams = hibi_glass_render_params;

    /// The fragments as polygons (hibi_glass_fragments).
    struct Fragments {
        std::vector<hibi_ring> rings;
        std::vector<hibi_vec2> points;
    };

    static Params default_params() noexcept { return hibi_glass_params_default(); }
    static Result<Params> try_preset(const char *name) noexcept {
        Params params{};
        return detail::result(hibi_glass_params_preset(name, &params), params);
    }
    static detail::Returned<Params> preset(const char *name) { return detail::returned(try_preset(name)); }
    static RenderParams default_render() noexcept { return hibi_glass_render_params_default(); }
    static Result<std::size_t> try_memory_size(const Params &params) noexcept {
        std::size_t size = 0;
        return detail::result(hibi_glass_memory_size(&params, &size), size);
    }
    static detail::Returned<std::size_t> memory_size(const Params &params) {
        return detail::returned(try_memory_size(params));
    }
    static std::size_t memory_align() noexcept { return hibi_glass_memory_align(); }

    /// No plate (as after a move): every call on it fails with HIBI_ERROR_NULL_POINTER.
    Glass() noexcept = default;
#if HIBI_EXCEPTIONS
    /// A plate in library memory, with its first impact at params.impact.
    explicit Glass(const Params &params) : Glass(create(params)) {}
#endif
    /// A plate in library memory, with its first impact at params.impact.
    static Result<Glass> try_create(const Params &params) noexcept {
        hibi_glass *raw = nullptr;
        hibi_status status = hibi_glass_create(&params, &raw);
        return detail::result(status, Glass(raw));
    }
    static detail::Returned<Glass> create(const Params &params) { return detail::returned(try_create(params)); }
    /// A plate in caller memory (see Mud::create_in).
    static Result<Glass> try_create_in(const Params &params, void *memory, std::size_t len) noexcept {
        hibi_glass *raw = nullptr;
        hibi_status status = hibi_glass_create_in(&params, memory, len, &raw);
        return detail::result(status, Glass(raw));
    }
    static detail::Returned<Glass> create_in(const Params &params, void *memory, std::size_t len) {
        return detail::returned(try_create_in(params, memory, len));
    }

    Result<hibi_glass_counts> try_impact(float x, float y) noexcept {
        hibi_glass_counts counts{};
        return detail::result(hibi_glass_impact(handle_.get(), x, y, &counts), counts);
    }
    detail::Returned<hibi_glass_counts> impact(float x, float y) { return detail::returned(try_impact(x, y)); }
    /// Advances growth by `budget` units of work (grid cells and entries examined, cracks
    /// looked at, face-walk steps; overruns by less than HIBI_GLASS_STEP_PIECE units: see
    /// hibi_glass_step).
    Result<Progress> try_step(std::uint64_t budget) noexcept {
        Progress progress{};
        return detail::result(hibi_glass_step(handle_.get(), budget, &progress), progress);
    }
    detail::Returned<Progress> step(std::uint64_t budget) { return detail::returned(try_step(budget)); }
    Result<Progress> try_run(std::uint64_t budget = 1000) noexcept {
        Result<Progress> progress = try_step(budget);
        while (progress && !progress->finished) progress = try_step(budget);
        return progress;
    }
    detail::Returned<Progress> run(std::uint64_t budget = 1000) { return detail::returned(try_run(budget)); }

    Result<std::size_t> try_crack_count() const noexcept {
        std::size_t count = 0;
        return detail::result(hibi_glass_crack_count(handle_.get(), &count), count);
    }
    detail::Returned<std::size_t> crack_count() const { return detail::returned(try_crack_count()); }
    Result<hibi_glass_crack> try_crack(std::size_t index) const noexcept {
        hibi_glass_crack info{};
        return detail::result(hibi_glass_crack_info(handle_.get(), index, &info), info);
    }
    detail::Returned<hibi_glass_crack> crack(std::size_t index) const { return detail::returned(try_crack(index)); }
    /// Writes crack `index`'s polyline into `out` (at least crack(index).points); returns
    /// how many points.
    Result<std::size_t> try_points(std::size_t index, Span<hibi_glass_point> out) const noexcept {
        std::size_t written = 0;
        return detail::result(hibi_glass_points(handle_.get(), index, out.data(), out.size(), &written), written);
    }
    detail::Returned<std::size_t> points(std::size_t index, Span<hibi_glass_point> out) const {
        return detail::returned(try_points(index, out));
    }
    Result<std::vector<hibi_glass_point>> try_points(std::size_t index) const {
        Result<hibi_glass_crack> info = try_crack(index);
        if (!info) return detail::failure<std::vector<hibi_glass_point>>(info);
        std::vector<hibi_glass_point> out(info->points);
        Result<std::size_t> written = try_points(index, Span<hibi_glass_point>(out));
        if (!written) return detail::failure<std::vector<hibi_glass_point>>(written);
        out.resize(*written);
        return Result<std::vector<hibi_glass_point>>(std::move(out));
    }
    detail::Returned<std::vector<hibi_glass_point>> points(std::size_t index) const {
        return detail::returned(try_points(index));
    }

    Result<std::size_t> try_scratch_size() const noexcept {
        std::size_t size = 0;
        return detail::result(hibi_glass_scratch_size(handle_.get(), &size), size);
    }
    detail::Returned<std::size_t> scratch_size() const { return detail::returned(try_scratch_size()); }
    /// Scratch for fragment_counts and fragments: one per thread.
    Result<Scratch> try_scratch() const {
        Result<std::size_t> size = try_scratch_size();
        if (!size) return detail::failure<Scratch>(size);
        return Result<Scratch>(Scratch(*size, memory_align()));
    }
    detail::Returned<Scratch> scratch() const { return detail::returned(try_scratch()); }
    Result<std::pair<std::size_t, std::size_t>> try_fragment_counts(Scratch &scratch) const noexcept {
        std::pair<std::size_t, std::size_t> counts{0, 0};
        return detail::result(hibi_glass_fragment_counts(handle_.get(), scratch.data(), scratch.size(),
                                                         &counts.first, &counts.second),
                              counts);
    }
    detail::Returned<std::pair<std::size_t, std::size_t>> fragment_counts(Scratch &scratch) const {
        return detail::returned(try_fragment_counts(scratch));
    }
    /// Writes the fragments into the two views (at least fragment_counts()); returns how
    /// many rings and points.
    Result<RingCounts> try_fragments(Scratch &scratch, Span<hibi_ring> rings,
                                     Span<hibi_vec2> points) const noexcept {
        RingCounts written;
        return detail::result(hibi_glass_fragments(handle_.get(), scratch.data(), scratch.size(), rings.data(),
                                                   rings.size(), points.data(), points.size(), &written.rings,
                                                   &written.points),
                              written);
    }
    detail::Returned<RingCounts> fragments(Scratch &scratch, Span<hibi_ring> rings,
                                           Span<hibi_vec2> points) const {
        return detail::returned(try_fragments(scratch, rings, points));
    }
    Result<Fragments> try_fragments(Scratch &scratch) const {
        Result<std::pair<std::size_t, std::size_t>> counts = try_fragment_counts(scratch);
        if (!counts) return detail::failure<Fragments>(counts);
        Fragments out;
        out.rings.resize(counts->first);
        out.points.resize(counts->second);
        Result<RingCounts> written =
            try_fragments(scratch, Span<hibi_ring>(out.rings), Span<hibi_vec2>(out.points));
        if (!written) return detail::failure<Fragments>(written);
        out.rings.resize(written->rings);
        out.points.resize(written->points);
        return Result<Fragments>(std::move(out));
    }
    detail::Returned<Fragments> fragments(Scratch &scratch) const { return detail::returned(try_fragments(scratch)); }

    Status try_render(const RenderParams &render, std::uint32_t layer, void *pixels, std::size_t len) const noexcept {
        return detail::status(hibi_glass_render(handle_.get(), &render, layer, pixels, len));
    }
    detail::Returned<void> render(const RenderParams &render, std::uint32_t layer, void *pixels,
                                  std::size_t len) const {
        return detail::returned(try_render(render, layer, pixels, len));
    }
    /// Draws a layer into `pixels` (at least params.width x params.height values); returns
    /// how many it wrote (width x height).
    Result<std::size_t> try_render_mask(const RenderParams &params, Span<std::uint8_t> pixels) const noexcept {
        return draw(params, HIBI_GLASS_LAYER_MASK, pixels);
    }
    Result<std::size_t> try_render_time(const RenderParams &params, Span<float> pixels) const noexcept {
        return draw(params, HIBI_GLASS_LAYER_TIME, pixels);
    }
    Result<std::vector<std::uint8_t>> try_render_mask(const RenderParams &params) const {
        return draw<std::uint8_t>(params, HIBI_GLASS_LAYER_MASK);
    }
    /// The break-time raster.
    Result<std::vector<float>> try_render_time(const RenderParams &params) const {
        return draw<float>(params, HIBI_GLASS_LAYER_TIME);
    }
    detail::Returned<std::size_t> render_mask(const RenderParams &params, Span<std::uint8_t> pixels) const {
        return detail::returned(try_render_mask(params, pixels));
    }
    detail::Returned<std::size_t> render_time(const RenderParams &params, Span<float> pixels) const {
        return detail::returned(try_render_time(params, pixels));
    }
    detail::Returned<std::vector<std::uint8_t>> render_mask(const RenderParams &params) const {
        return detail::returned(try_render_mask(params));
    }
    detail::Returned<std::vector<float>> render_time(const RenderParams &params) const {
        return detail::returned(try_render_time(params));
    }

    /// Draws every layer `layers` gives of `tile` (nullptr: the whole image) in one pass
    /// (hibi_glass_render_layers).
    Status try_render_layers(const RenderParams &render, const hibi_layers &layers,
                             const hibi_tile *tile = nullptr) const noexcept {
        return detail::status(hibi_glass_render_layers(handle_.get(), &render, tile, &layers));
    }
    Status try_render_layers(const RenderParams &render, Layers &layers, const hibi_tile *tile = nullptr) const noexcept {
        const hibi_layers c = layers.c();
        return try_render_layers(render, c, tile);
    }
    detail::Returned<void> render_layers(const RenderParams &render, const hibi_layers &layers,
                                         const hibi_tile *tile = nullptr) const {
        return detail::returned(try_render_layers(render, layers, tile));
    }
    detail::Returned<void> render_layers(const RenderParams &render, Layers &layers,
                                         const hibi_tile *tile = nullptr) const {
        return detail::returned(try_render_layers(render, layers, tile));
    }

    hibi_glass *get() const noexcept { return handle_.get(); }

private:
    explicit Glass(hibi_glass *raw) noexcept : handle_(raw) {}
    template <class T>
    Result<std::size_t> draw(const RenderParams &params, std::uint32_t layer, Span<T> pixels) const noexcept {
        return detail::result(hibi_glass_render(handle_.get(), &params, layer, pixels.data(), pixels.size()),
                              static_cast<std::size_t>(params.width) * params.height);
    }
    template <class T>
    Result<std::vector<T>> draw(const RenderParams &params, std::uint32_t layer) const {
        std::vector<T> pixels(static_cast<std::size_t>(params.width) * params.height);
        Result<std::size_t> written = draw(params, layer, Span<T>(pixels));
        if (!written) return detail::failure<std::vector<T>>(written);
        return Result<std::vector<T>>(std::move(pixels));
    }
    std::unique_ptr<hibi_glass, detail::GlassDelete> handle_;
};

/// A budgeted build of a plate's fragments in memory it owns (hibi_glass_fragment_build_*):
/// made in the same work at any size, stepped with the plate until finished
/// (hibi_glass_fragment_build_step), then read in ranges. The rings and points are those of
/// Glass::fragments, bit for bit.
class FragmentBuild
    : public detail::Build<FragmentBuild, Glass, hibi_glass_fragment_build, hibi_glass_fragment_progress> {
public:
    using Progress = hibi_glass_fragment_progress;

    /// Copies the rings from `first` on into `out`, as many as there are (none before the
    /// build is finished); returns how many.
    Result<std::size_t> try_rings(std::size_t first, Span<hibi_ring> out) const noexcept {
        return read(hibi_glass_fragment_build_rings, first, out);
    }
    detail::Returned<std::size_t> rings(std::size_t first, Span<hibi_ring> out) const {
        return detail::returned(try_rings(first, out));
    }
    /// Copies the points from `first` on into `out`, as try_rings does.
    Result<std::size_t> try_points(std::size_t first, Span<hibi_vec2> out) const noexcept {
        return read(hibi_glass_fragment_build_points, first, out);
    }
    detail::Returned<std::size_t> points(std::size_t first, Span<hibi_vec2> out) const {
        return detail::returned(try_points(first, out));
    }

private:
    friend Build;
    static constexpr auto size_call = hibi_glass_fragment_build_size;
    static constexpr auto create_call = hibi_glass_fragment_build_create_in;
    static constexpr auto step_call = hibi_glass_fragment_build_step;
};

/// Model C, skin from hierarchical Voronoi cells (hibi_skin).
class Skin {
public:
    using Params = hibi_skin_params;
    using Progress = hibi_skin_progress;
    using RenderParams = hibi_skin_render_params;
    using ShadeParams = hibi_skin_shade_params;

    static Params default_params() noexcept { return hibi_skin_params_default(); }
    static Result<Params> try_preset(const char *name) noexcept {
        Params params{};
        return detail::result(hibi_skin_params_preset(name, &params), params);
    }
    static detail::Returned<Params> preset(const char *name) { return detail::returned(try_preset(name)); }
    static RenderParams default_render() noexcept { return hibi_skin_render_params_default(); }
    static ShadeParams default_shade() noexcept { return hibi_skin_shade_params_default(); }
    static Result<std::size_t> try_memory_size(const Params &params) noexcept {
        std::size_t size = 0;
        return detail::result(hibi_skin_memory_size(&params, &size), size);
    }
    static detail::Returned<std::size_t> memory_size(const Params &params) {
        return detail::returned(try_memory_size(params));
    }
    static std::size_t memory_align() noexcept { return hibi_skin_memory_align(); }

    /// No skin (as after a move): every call on it fails with HIBI_ERROR_NULL_POINTER, and
    /// its width and height are 0.
    Skin() noexcept = default;
#if HIBI_EXCEPTIONS
    /// A skin in library memory.
    explicit Skin(const Params &params) : Skin(create(params)) {}
#endif
    /// A skin in library memory.
    static Result<Skin> try_create(const Params &params) noexcept {
        hibi_skin *raw = nullptr;
        hibi_status status = hibi_skin_create(&params, &raw);
        return detail::result(status, Skin(raw, params));
    }
    static detail::Returned<Skin> create(const Params &params) { return detail::returned(try_create(params)); }
    /// A skin in caller memory (see Mud::create_in).
    static Result<Skin> try_create_in(const Params &params, void *memory, std::size_t len) noexcept {
        hibi_skin *raw = nullptr;
        hibi_status status = hibi_skin_create_in(&params, memory, len, &raw);
        return detail::result(status, Skin(raw, params));
    }
    static detail::Returned<Skin> create_in(const Params &params, void *memory, std::size_t len) {
        return detail::returned(try_create_in(params, memory, len));
    }

    /// Advances the build by about `budget` units of work (outline vertices, and one per
    /// level-0 centre point tried), one cell at a time: overruns it by at most one cell's.
    Result<Progress> try_step(std::uint64_t budget) noexcept {
        Progress progress{};
        return detail::result(hibi_skin_step(handle_.get(), budget, &progress), progress);
    }
    detail::Returned<Progress> step(std::uint64_t budget) { return detail::returned(try_step(budget)); }
    Result<Progress> try_run(std::uint64_t budget = UINT64_MAX) noexcept {
        Result<Progress> progress = try_step(budget);
        while (progress && !progress->finished) progress = try_step(budget);
        return progress;
    }
    detail::Returned<Progress> run(std::uint64_t budget = UINT64_MAX) { return detail::returned(try_run(budget)); }

    std::uint32_t width() const noexcept { return width_; }
    std::uint32_t height() const noexcept { return height_; }
    std::size_t pixels() const noexcept { return static_cast<std::size_t>(width_) * height_; }

    Result<std::size_t> try_cell_count() const noexcept {
        std::size_t count = 0;
        return detail::result(hibi_skin_cell_count(handle_.get(), &count), count);
    }
    detail::Returned<std::size_t> cell_count() const { return detail::returned(try_cell_count()); }
    Result<hibi_skin_cell> try_cell(std::size_t index) const noexcept {
        hibi_skin_cell info{};
        return detail::result(hibi_skin_cell_info(handle_.get(), index, &info), info);
    }
    detail::Returned<hibi_skin_cell> cell(std::size_t index) const { return detail::returned(try_cell(index)); }
    /// Writes cell `index`'s outline, x, y pairs in pixels, into `xy` (at least
    /// 2 x cell(index).vertex_count doubles); returns how many doubles.
    Result<std::size_t> try_outline(std::size_t index, Span<double> xy) const noexcept {
        std::size_t written = 0;
        return detail::result(hibi_skin_outline(handle_.get(), index, xy.data(), xy.size(), &written), written);
    }
    detail::Returned<std::size_t> outline(std::size_t index, Span<double> xy) const {
        return detail::returned(try_outline(index, xy));
    }
    /// Cell `index`'s outline, x, y pairs in pixels.
    Result<std::vector<double>> try_outline(std::size_t index) const {
        Result<hibi_skin_cell> info = try_cell(index);
        if (!info) return detail::failure<std::vector<double>>(info);
        std::vector<double> xy(2 * static_cast<std::size_t>(info->vertex_count));
        Result<std::size_t> written = try_outline(index, Span<double>(xy));
        if (!written) return detail::failure<std::vector<double>>(written);
        xy.resize(*written);
        return Result<std::vector<double>>(std::move(xy));
    }
    detail::Returned<std::vector<double>> outline(std::size_t index) const {
        return detail::returned(try_outline(index));
    }

    /// Draws `layer` into caller pixels (`len` values of the layer's type; floats for the
    /// normal layer, three per pixel).
    Status try_render(const RenderParams &render, std::uint32_t layer, void *pixels, std::size_t len) const noexcept {
        return detail::status(hibi_skin_render(handle_.get(), &render, layer, pixels, len));
    }
    detail::Returned<void> render(const RenderParams &render, std::uint32_t layer, void *pixels,
                                  std::size_t len) const {
        return detail::returned(try_render(render, layer, pixels, len));
    }
    /// Draws a layer into `out` (at least pixels() values, 3 x pixels() for the normals);
    /// returns how many it wrote.
    Result<std::size_t> try_render_height(const RenderParams &params, Span<float> out) const noexcept {
        return draw(params, HIBI_SKIN_LAYER_HEIGHT, 1, out);
    }
    Result<std::size_t> try_render_normal(const RenderParams &params, Span<float> out) const noexcept {
        return draw(params, HIBI_SKIN_LAYER_NORMAL, 3, out);
    }
    Result<std::size_t> try_render_cells(const RenderParams &params, Span<std::uint32_t> out) const noexcept {
        return draw(params, HIBI_SKIN_LAYER_CELLS, 1, out);
    }
    Result<std::vector<float>> try_render_height(const RenderParams &params) const {
        return draw<float>(params, HIBI_SKIN_LAYER_HEIGHT, 1);
    }
    /// Three floats per pixel.
    Result<std::vector<float>> try_render_normal(const RenderParams &params) const {
        return draw<float>(params, HIBI_SKIN_LAYER_NORMAL, 3);
    }
    /// Per pixel the index of its cell at params.cell_level, HIBI_SKIN_NO_CELL where none is.
    Result<std::vector<std::uint32_t>> try_render_cells(const RenderParams &params) const {
        return draw<std::uint32_t>(params, HIBI_SKIN_LAYER_CELLS, 1);
    }
    detail::Returned<std::size_t> render_height(const RenderParams &params, Span<float> out) const {
        return detail::returned(try_render_height(params, out));
    }
    detail::Returned<std::size_t> render_normal(const RenderParams &params, Span<float> out) const {
        return detail::returned(try_render_normal(params, out));
    }
    detail::Returned<std::size_t> render_cells(const RenderParams &params, Span<std::uint32_t> out) const {
        return detail::returned(try_render_cells(params, out));
    }
    detail::Returned<std::vector<float>> render_height(const RenderParams &params) const {
        return detail::returned(try_render_height(params));
    }
    detail::Returned<std::vector<float>> render_normal(const RenderParams &params) const {
        return detail::returned(try_render_normal(params));
    }
    detail::Returned<std::vector<std::uint32_t>> render_cells(const RenderParams &params) const {
        return detail::returned(try_render_cells(params));
    }
    /// 8-bit sRGB preview of a height and a normal map into `rgb` (three bytes per pixel, at
    /// least 3 x height.size()); returns how many bytes it wrote.
    static Result<std::size_t> try_shade(Span<const float> height, Span<const float> normal, const ShadeParams &params,
                                         Span<std::uint8_t> rgb) noexcept {
        return detail::result(hibi_skin_shade(height.data(), height.size(), normal.data(), normal.size(), &params,
                                              rgb.data(), rgb.size()),
                              3 * height.size());
    }
    static detail::Returned<std::size_t> shade(Span<const float> height, Span<const float> normal,
                                               const ShadeParams &params, Span<std::uint8_t> rgb) {
        return detail::returned(try_shade(height, normal, params, rgb));
    }
    /// 8-bit sRGB preview of a height and a normal map (three bytes per pixel).
    static Result<std::vector<std::uint8_t>> try_shade(Span<const float> height, Span<const float> normal,
                                                       const ShadeParams &params) {
        std::vector<std::uint8_t> rgb(3 * height.size());
        Result<std::size_t> written = try_shade(height, normal, params, Span<std::uint8_t>(rgb));
        if (!written) return detail::failure<std::vector<std::uint8_t>>(written);
        return Result<std::vector<std::uint8_t>>(std::move(rgb));
    }
    static detail::Returned<std::vector<std::uint8_t>> shade(Span<const float> height, Span<const float> normal,
                                                             const ShadeParams &params) {
        return detail::returned(try_shade(height, normal, params));
    }

    /// Draws every layer `layers` gives of `tile` (nullptr: the whole image) in one pass
    /// (hibi_skin_render_layers).
    Status try_render_layers(const RenderParams &render, const hibi_layers &layers,
                             const hibi_tile *tile = nullptr) const noexcept {
        return detail::status(hibi_skin_render_layers(handle_.get(), &render, tile, &layers));
    }
    Status try_render_layers(const RenderParams &render, Layers &layers, const hibi_tile *tile = nullptr) const noexcept {
        const hibi_layers c = layers.c();
        return try_render_layers(render, c, tile);
    }
    detail::Returned<void> render_layers(const RenderParams &render, const hibi_layers &layers,
                                         const hibi_tile *tile = nullptr) const {
        return detail::returned(try_render_layers(render, layers, tile));
    }
    detail::Returned<void> render_layers(const RenderParams &render, Layers &layers,
                                         const hibi_tile *tile = nullptr) const {
        return detail::returned(try_render_layers(render, layers, tile));
    }

    hibi_skin *get() const noexcept { return handle_.get(); }

private:
    Skin(hibi_skin *raw, const Params &params) noexcept
        : handle_(raw), width_(params.width), height_(params.height) {}
    /// The layer's raster over the skin's width x height, `per_pixel` values a pixel.
    template <class T>
    Result<std::size_t> draw(const RenderParams &params, std::uint32_t layer, std::size_t per_pixel,
                             Span<T> out) const noexcept {
        return detail::result(hibi_skin_render(handle_.get(), &params, layer, out.data(), out.size()),
                              per_pixel * pixels());
    }
    template <class T>
    Result<std::vector<T>> draw(const RenderParams &params, std::uint32_t layer, std::size_t per_pixel) const {
        std::vector<T> out(per_pixel * pixels());
        Result<std::size_t> written = draw(params, layer, per_pixel, Span<T>(out));
        if (!written) return detail::failure<std::vector<T>>(written);
        return Result<std::vector<T>>(std::move(out));
    }
    std::unique_ptr<hibi_skin, detail::SkinDelete> handle_;
    std::uint32_t width_ = 0;
    std::uint32_t height_ = 0;
};

/// Pieces for a physics engine (hibi_pieces_*, hibi_triangulate, hibi_convex_pieces): the
/// triangles and convex pieces of polygons given as rings over points, such as
/// Glass::fragments and Mud::cells write. How many of each (hibi_pieces_counts).
struct PieceCounts {
    std::size_t triangles = 0;
    std::size_t pieces = 0;
};

/// The uint32_t words of scratch the piece calls need (hibi_pieces_scratch_size); checks the
/// rings.
inline Result<std::size_t> try_pieces_scratch_size(Span<const hibi_ring> rings,
                                                   Span<const hibi_vec2> points) noexcept {
    std::size_t words = 0;
    return detail::result(hibi_pieces_scratch_size(rings.data(), rings.size(), points.data(), points.size(), &words),
                          words);
}
inline detail::Returned<std::size_t> pieces_scratch_size(Span<const hibi_ring> rings, Span<const hibi_vec2> points) {
    return detail::returned(try_pieces_scratch_size(rings, points));
}
/// How many triangles and convex pieces the rings make (hibi_pieces_counts), working in
/// `scratch` (at least pieces_scratch_size words).
inline Result<PieceCounts> try_piece_counts(Span<const hibi_ring> rings, Span<const hibi_vec2> points,
                                            Span<std::uint32_t> scratch) noexcept {
    PieceCounts counts;
    return detail::result(hibi_pieces_counts(rings.data(), rings.size(), points.data(), points.size(), scratch.data(),
                                             scratch.size(), &counts.triangles, &counts.pieces),
                          counts);
}
inline detail::Returned<PieceCounts> piece_counts(Span<const hibi_ring> rings, Span<const hibi_vec2> points,
                                                  Span<std::uint32_t> scratch) {
    return detail::returned(try_piece_counts(rings, points, scratch));
}
/// Writes the triangles into the view (at least piece_counts().triangles); returns how many.
inline Result<std::size_t> try_triangulate(Span<const hibi_ring> rings, Span<const hibi_vec2> points,
                                           Span<std::uint32_t> scratch, Span<hibi_triangle> out) noexcept {
    std::size_t written = 0;
    return detail::result(hibi_triangulate(rings.data(), rings.size(), points.data(), points.size(), scratch.data(),
                                           scratch.size(), out.data(), out.size(), &written),
                          written);
}
inline detail::Returned<std::size_t> triangulate(Span<const hibi_ring> rings, Span<const hibi_vec2> points,
                                                 Span<std::uint32_t> scratch, Span<hibi_triangle> out) {
    return detail::returned(try_triangulate(rings, points, scratch, out));
}
/// Writes the convex pieces into the view (at least piece_counts().pieces); returns how many.
inline Result<std::size_t> try_convex_pieces(Span<const hibi_ring> rings, Span<const hibi_vec2> points,
                                             Span<std::uint32_t> scratch, Span<hibi_convex_piece> out) noexcept {
    std::size_t written = 0;
    return detail::result(hibi_convex_pieces(rings.data(), rings.size(), points.data(), points.size(), scratch.data(),
                                             scratch.size(), out.data(), out.size(), &written),
                          written);
}
inline detail::Returned<std::size_t> convex_pieces(Span<const hibi_ring> rings, Span<const hibi_vec2> points,
                                                   Span<std::uint32_t> scratch, Span<hibi_convex_piece> out) {
    return detail::returned(try_convex_pieces(rings, points, scratch, out));
}

namespace detail {
/// The pieces of the rings in vectors: scratch and output sized by the count calls, then
/// `write` (try_triangulate or try_convex_pieces) into them.
template <class Piece, class Write>
Result<std::vector<Piece>> pieces(Span<const hibi_ring> rings, Span<const hibi_vec2> points, bool triangles,
                                  Write write) {
    Result<std::size_t> words = try_pieces_scratch_size(rings, points);
    if (!words) return failure<std::vector<Piece>>(words);
    std::vector<std::uint32_t> scratch(*words);
    Result<PieceCounts> counts = try_piece_counts(rings, points, Span<std::uint32_t>(scratch));
    if (!counts) return failure<std::vector<Piece>>(counts);
    std::vector<Piece> out(triangles ? counts->triangles : counts->pieces);
    Result<std::size_t> written = write(rings, points, Span<std::uint32_t>(scratch), Span<Piece>(out));
    if (!written) return failure<std::vector<Piece>>(written);
    out.resize(*written);
    return Result<std::vector<Piece>>(std::move(out));
}
}  // namespace detail

/// The triangles in a vector (scratch and output allocated here).
inline Result<std::vector<hibi_triangle>> try_triangulate(Span<const hibi_ring> rings, Span<const hibi_vec2> points) {
    return detail::pieces<hibi_triangle>(rings, points, true, [](auto... a) { return try_triangulate(a...); });
}
inline detail::Returned<std::vector<hibi_triangle>> triangulate(Span<const hibi_ring> rings,
                                                                Span<const hibi_vec2> points) {
    return detail::returned(try_triangulate(rings, points));
}
/// The convex pieces in a vector (scratch and output allocated here).
inline Result<std::vector<hibi_convex_piece>> try_convex_pieces(Span<const hibi_ring> rings,
                                                                Span<const hibi_vec2> points) {
    return detail::pieces<hibi_convex_piece>(rings, points, false, [](auto... a) { return try_convex_pieces(a...); });
}
inline detail::Returned<std::vector<hibi_convex_piece>> convex_pieces(Span<const hibi_ring> rings,
                                                                      Span<const hibi_vec2> points) {
    return detail::returned(try_convex_pieces(rings, points));
}

#if !HIBI_EXCEPTIONS
}  // inline namespace results
#endif

}  // namespace hibi

#endif /* HIBI_HPP */
