#pragma once
// The fuzzers' deterministic random numbers (xorshift64): the same seed gives the same cases on
// every machine and compiler, so a finding is reproduced from its seed and case number alone.
#include <cstddef>
#include <cstdint>

namespace trn::fuzz {

struct XorshiftRng {
    std::uint64_t s;
    std::uint64_t next() {
        s ^= s << 13, s ^= s >> 7, s ^= s << 17;
        return s;
    }
    std::size_t below(std::size_t n) { return n ? static_cast<std::size_t>(next() % n) : 0; }
    bool chance(int percent) { return below(100) < static_cast<std::size_t>(percent); }
};

}  // namespace trn::fuzz
