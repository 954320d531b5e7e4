#pragma once
// What every fuzz entry shares: a broken invariant aborts (libFuzzer and the replay driver both
// report an abort as a failure and keep the input), and the raw bytes as text.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string_view>

namespace trn::fuzz {

[[noreturn]] inline void violation(const char* what) {
    std::fprintf(stderr, "fuzz: invariant broken: %s\n", what);
    std::abort();
}

inline void require(bool ok, const char* what) {
    if (!ok) violation(what);
}

inline std::string_view as_text(const std::uint8_t* data, std::size_t size) {
    return {reinterpret_cast<const char*>(data), size};
}

}  // namespace trn::fuzz
