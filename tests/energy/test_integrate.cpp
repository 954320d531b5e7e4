// Synthetic traces with analytically known integrals.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <random>

#include "trn/error.hpp"
#include "trn/energy/integrate.hpp"
#include "trn/detail/angles.hpp"

using namespace trn::energy;

namespace {

PowerTrace sampled(const std::function<double(double)>& p, double t0, double t1, double dt, double jitter = 0) {
    PowerTrace tr;
    tr.source = "synthetic";
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> j(-jitter, jitter);
    for (double t = t0; t <= t1 + 1e-12; t += dt) {
        const double tj = std::clamp(t + j(rng), t0, t1);
        if (!tr.t.empty() && tj <= tr.t.back()) continue;
        tr.t.push_back(tj);
        tr.w.push_back(p(tj));
    }
    return tr;
}

using trn::kPi;

}  // namespace

TEST(Integrate, ConstantPowerBetweenSamples) {
    const PowerTrace tr = sampled([](double) { return 2.0; }, 0, 1, 1e-3);
    const IntervalEnergy e = integrate_interval(tr, 0.12345, 0.78901);
    ASSERT_TRUE(e.covered);
    EXPECT_NEAR(e.energy_j, 2.0 * (0.78901 - 0.12345), 1e-12);
    EXPECT_NEAR(e.other_j, e.energy_j, 1e-12);
}

TEST(Integrate, RampIsExactWithInterpolatedBoundaries) {
    const auto p = [](double t) { return 1.5 + 4.0 * t; };
    const PowerTrace tr = sampled(p, 0, 1, 0.01);
    const double a = 0.0137, b = 0.9513;
    const double exact = 1.5 * (b - a) + 2.0 * (b * b - a * a);
    const IntervalEnergy e = integrate_interval(tr, a, b);
    EXPECT_NEAR(e.energy_j, exact, 1e-9 * exact);
    // Hold lags the ramp by half a sample period: the bound must contain the true value.
    const IntervalEnergy h = integrate_interval(tr, a, b, Rule::Hold);
    EXPECT_LT(h.energy_j, exact);
    EXPECT_LE(std::abs(h.energy_j - exact), h.error_j);
}

TEST(Integrate, SmoothWaveWithJitteredSamplingWithinPointOnePercent) {
    const auto p = [](double t) { return 3.0 + std::sin(2 * kPi * t); };
    const PowerTrace tr = sampled(p, 0, 2, 1e-3, 2e-4);
    const double a = 0.1, b = 1.35;
    const double exact = 3.0 * (b - a) - (std::cos(2 * kPi * b) - std::cos(2 * kPi * a)) / (2 * kPi);
    const IntervalEnergy e = integrate_interval(tr, a, b);
    EXPECT_NEAR(e.energy_j, exact, 1e-3 * exact);
    EXPECT_LE(std::abs(e.energy_j - exact), e.error_j);
}

TEST(Integrate, PulseTrainFramesAndIdleBaseline) {
    // 20 ms at 5 W, 30 ms at 1 W, sampled at 100 kHz: each busy frame is 0.1 J gross, 0.08 J net.
    const auto p = [](double t) { return std::fmod(t, 0.05) < 0.02 ? 5.0 : 1.0; };
    const PowerTrace tr = sampled(p, 0, 0.5, 1e-5);
    std::vector<TimedInterval> iv;
    for (int k = 0; k < 9; ++k) {
        iv.push_back({"frame", k, k * 0.05 + 0.0000025, k * 0.05 + 0.0200025});
        iv.push_back({"idle", k, k * 0.05 + 0.025, k * 0.05 + 0.045});
    }
    const RunEnergy run = integrate_frames(tr, iv);
    EXPECT_NEAR(run.idle_w, 1.0, 1e-9);
    ASSERT_EQ(run.frames.size(), 9u);
    // Each frame starts 2.5 us after the rising edge and ends 2.5 us after the falling one.
    const double exact = 5.0 * (0.02 - 2.5e-6) + 1.0 * 2.5e-6;
    for (const auto& f : run.frames) {
        EXPECT_NEAR(f.gross_j, exact, 1e-3 * exact);
        EXPECT_NEAR(f.net_j, exact - 1.0 * 0.02, 1e-3 * 0.08);
        EXPECT_TRUE(f.flag.empty());
        EXPECT_LE(std::abs(f.gross_j - exact), f.error_j + 1e-12);
    }
    EXPECT_TRUE(run.warnings.empty());
}

TEST(Integrate, GapsAndUncoveredFramesAreFlaggedNotDropped) {
    PowerTrace tr = sampled([](double) { return 1.0; }, 0, 1, 1e-3);
    // Remove samples inside (0.4, 0.6): a logger gap.
    PowerTrace gappy;
    for (std::size_t i = 0; i < tr.size(); ++i)
        if (tr.t[i] <= 0.4 || tr.t[i] >= 0.6) gappy.t.push_back(tr.t[i]), gappy.w.push_back(tr.w[i]);
    const std::vector<TimedInterval> iv = {{"frame", 0, 0.1, 0.2}, {"frame", 1, 0.45, 0.55}, {"frame", 2, 0.9, 1.2}};
    const RunEnergy run = integrate_frames(gappy, iv);
    ASSERT_EQ(run.frames.size(), 3u);
    EXPECT_TRUE(run.frames[0].flag.empty());
    EXPECT_EQ(run.frames[1].flag, "0 sample(s) < 3");
    EXPECT_NEAR(run.frames[1].gross_j, 0.1, 1e-12);  // still integrated across the gap
    EXPECT_EQ(run.frames[2].flag, "not covered by the trace");
    EXPECT_EQ(run.frames[2].gross_j, 0.0);
    EXPECT_EQ(run.usable(), 1u);
}

TEST(Integrate, IntervalMeanTraceIsPiecewiseConstant) {
    PowerTrace tr;
    tr.kind = SampleKind::IntervalMean;
    tr.first_interval_start = 0.0;
    tr.t = {1, 2, 3, 4};
    tr.w = {10, 20, 30, 40};
    EXPECT_NEAR(integrate_interval(tr, 0, 4).energy_j, 100, 1e-12);
    EXPECT_NEAR(integrate_interval(tr, 0.5, 2.5).energy_j, 5 + 20 + 15, 1e-12);
}

TEST(Integrate, IdleDriftWarns) {
    const PowerTrace tr = sampled([](double t) { return 1.0 + 0.5 * t; }, 0, 1, 1e-3);
    const std::vector<TimedInterval> iv = {{"idle", 0, 0.0, 0.1}, {"frame", 0, 0.2, 0.8}, {"idle", 1, 0.9, 1.0}};
    const RunEnergy run = integrate_frames(tr, iv);
    ASSERT_FALSE(run.warnings.empty());
    EXPECT_NE(run.warnings[0].find("idle power drifted"), std::string::npos);
}
