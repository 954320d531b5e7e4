// The project's one random-number generator (trn/detail/splitmix.hpp). Simulated flights, the
// filter's particles, the studies and random sampling plans are all drawn from it, and published
// figures (docs/RESULTS.md) depend on its exact sequences, so the values are pinned: next64
// against the SplitMix64 reference implementation's published output, uniform and normal against
// what the four copies it replaced produced (computed with the pre-change host/sim/random.hpp).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

#include "trn/detail/splitmix.hpp"

namespace trn {
namespace {

TEST(SplitMix, Next64MatchesTheReferenceImplementation) {
    // splitmix64.c (Vigna), state 0: the first four outputs.
    std::uint64_t state = 0;
    EXPECT_EQ(splitmix::next64(state), 0xE220A8397B1DCDAFull);
    EXPECT_EQ(splitmix::next64(state), 0x6E789E6AA1B965F4ull);
    EXPECT_EQ(splitmix::next64(state), 0x06C45D188009454Full);
    EXPECT_EQ(splitmix::next64(state), 0xF88BB8A8724C81ECull);
    EXPECT_EQ(state, 4 * splitmix::kGamma);
    EXPECT_EQ(splitmix::mix64(12345), 0xF36CF1164265DD51ull);
}

TEST(SplitMix, UniformAndNormalKeepTheSequencesResultsDependOn) {
    std::uint64_t state = 1;
    EXPECT_EQ(splitmix::uniform(state), 0.5665615751722809);  // exact: 53 bits times 2^-53
    EXPECT_EQ(splitmix::uniform(state), 0.74578175726270113);
    EXPECT_EQ(splitmix::uniform(state), 0.97100275358679622);
    state = 2;  // libm's log and cos may differ in the last place between platforms
    EXPECT_DOUBLE_EQ(splitmix::normal(state), -0.0071460226801007085);
    EXPECT_DOUBLE_EQ(splitmix::normal(state), 0.13016878525205222);
    EXPECT_DOUBLE_EQ(splitmix::normal(state), -0.49297833927418677);
    EXPECT_DOUBLE_EQ(splitmix::normal(state), -0.1102997738270235);
    EXPECT_EQ(state, 2 + 8 * splitmix::kGamma);  // two draws per deviate
    // The particle filter's stream: seed 7 mixed with its salt, as ParticleFilter seeds it.
    state = splitmix::mix64(7 ^ 0x5DEECE66Dull);
    EXPECT_DOUBLE_EQ(splitmix::normal(state), -0.32916815432919705);
    EXPECT_DOUBLE_EQ(splitmix::normal(state), -1.0446603858891741);
    EXPECT_DOUBLE_EQ(splitmix::normal(state), -0.15858369044752513);
}

TEST(SplitMix, DistributionsHaveTheirMoments) {
    constexpr int n = 200000;
    std::uint64_t state = 99;
    double su = 0, sn = 0, snn = 0;
    for (int i = 0; i < n; ++i) {
        const double u = splitmix::uniform(state);
        ASSERT_TRUE(u >= 0 && u < 1) << u;
        ASSERT_EQ(std::ldexp(u, 53), std::floor(std::ldexp(u, 53)));  // a multiple of 2^-53
        su += u;
        const double z = splitmix::normal(state);
        ASSERT_TRUE(std::isfinite(z));
        sn += z, snn += z * z;
    }
    // Standard errors: uniform mean 0.00065, normal mean 0.0022, normal variance 0.0032.
    EXPECT_NEAR(su / n, 0.5, 0.004);
    EXPECT_NEAR(sn / n, 0.0, 0.012);
    EXPECT_NEAR(snn / n - (sn / n) * (sn / n), 1.0, 0.02);
}

}  // namespace
}  // namespace trn
