/*
 * rng.cpp: the hibi frame from C++17, the way an engine wraps a C library: RAII handles,
 * statuses turned into exceptions, caller memory from an aligned stack buffer.
 *
 *   c++ -std=c++17 -Wall -Wextra -Wpedantic -Werror -Iinclude c_examples/rng.cpp \
 *       -Ltarget/release -lhibi -Wl,-rpath,target/release -o rng_cpp && ./rng_cpp
 */
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <new>
#include <stdexcept>
#include <string>
#include <vector>

#include "hibi.h"

namespace {

struct Error : std::runtime_error {
    hibi_status status;
    explicit Error(hibi_status s) : std::runtime_error(hibi_status_string(s)), status(s) {}
};

void check(hibi_status status) {
    if (status != HIBI_OK) throw Error(status);
}

struct RngDeleter {
    void operator()(hibi_rng *rng) const noexcept { hibi_rng_destroy(rng); }
};
using Rng = std::unique_ptr<hibi_rng, RngDeleter>;

Rng make_rng(std::uint64_t seed, std::uint64_t stream) {
    hibi_rng *raw = nullptr;
    check(hibi_rng_create(seed, stream, &raw));
    return Rng(raw);
}

std::uint32_t next(hibi_rng *rng) {
    std::uint32_t value = 0;
    check(hibi_rng_next_u32(rng, &value));
    return value;
}

}  // namespace

int main() {
    try {
        std::printf("hibi %s\n", hibi_version());
        Rng rng = make_rng(42, 7);
        std::array<std::uint32_t, 4> bits{};
        for (auto &b : bits) b = next(rng.get());
        std::printf("next_u32: %lu %lu %lu %lu\n", static_cast<unsigned long>(bits[0]),
                    static_cast<unsigned long>(bits[1]), static_cast<unsigned long>(bits[2]),
                    static_cast<unsigned long>(bits[3]));
        std::vector<float> uniform(3);
        check(hibi_rng_uniform(rng.get(), uniform.data(), uniform.size()));
        std::printf("uniform: %.9g %.9g %.9g\n", uniform[0], uniform[1], uniform[2]);

        try {
            std::uint32_t count = 0;
            check(hibi_rng_poisson(rng.get(), -1.0, &count));
            std::printf("poisson(-1) did not fail\n");
        } catch (const Error &e) {
            std::printf("poisson(-1) threw: %s\n", e.what());
        }

        // Caller memory on the stack, as an engine's frame allocator would hand it.
        alignas(std::max_align_t) std::array<std::byte, 64> storage{};
        if (hibi_rng_memory_size() > storage.size() || hibi_rng_memory_align() > alignof(std::max_align_t)) {
            std::printf("stack storage too small\n");
            return 1;
        }
        hibi_rng *placed = nullptr;
        check(hibi_rng_create_in(42, 7, storage.data(), storage.size(), &placed));
        std::printf("caller memory, same seed, same first draw: %s\n", next(placed) == bits[0] ? "yes" : "no");
        return 0;
    } catch (const std::exception &e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
}
