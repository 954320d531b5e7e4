// The lock monitor alone: contrast against random places, consistency with dead reckoning, the
// verdict "lost" and its cooldown.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "trn/error.hpp"
#include "trn/filter/lock_monitor.hpp"

namespace trn::filter {
namespace {

// Probe scores spread evenly around `mean` (sd ~ `spread` * 0.58).
std::vector<ParticleScore> probes(double mean, double spread, int n = 48) {
    std::vector<ParticleScore> out(n);
    for (int i = 0; i < n; ++i) {
        out[i].ncc = static_cast<float>(mean + spread * (2.0 * i / (n - 1) - 1));
        out[i].valid_samples = 100;
    }
    return out;
}

LockMonitorConfig config() {
    LockMonitorConfig c;
    c.weak_steps = 3;
    c.cooldown_steps = 2;
    return c;
}

TEST(LockMonitor, ProbesLieInTheRingAroundTheEstimate) {
    LockMonitor m(config(), 0.5, 1);
    std::vector<Pose> poses;
    EXPECT_EQ(m.add_probes(1000, 2000, 0.3f, poses), 48u);
    ASSERT_EQ(poses.size(), 48u);
    for (const Pose& p : poses) {
        const double r_m = std::hypot(p.x - 1000, p.y - 2000) * 0.5;
        EXPECT_GE(r_m, 150 - 1e-3);
        EXPECT_LE(r_m, 600 + 1e-3);
        EXPECT_FLOAT_EQ(p.yaw, 0.3f);
    }
}

TEST(LockMonitor, AStandOutScoreIsConfidentAMediocreOneIsWeakAndThenLost) {
    LockMonitor m(config(), 1.0, 1);
    m.reset(0, 0, 300);
    const auto random_places = probes(0.1, 0.2);
    LockReport r = m.assess(0.8, random_places, 0, 0, 0);
    EXPECT_FALSE(r.weak);
    EXPECT_GT(r.contrast, 3);
    EXPECT_FALSE(r.lost);
    // The best particle scores like a random place: weak, and lost after weak_steps in a row.
    for (int i = 0; i < 2; ++i) {
        r = m.assess(0.25, random_places, 0, 0, 0);
        EXPECT_TRUE(r.weak);
        EXPECT_FALSE(r.lost) << i;
    }
    r = m.assess(0.25, random_places, 0, 0, 0);
    EXPECT_TRUE(r.lost);
    // Cooldown: no verdict for two steps, even though still weak.
    EXPECT_FALSE(m.assess(0.25, random_places, 0, 0, 0).lost);
    EXPECT_FALSE(m.assess(0.25, random_places, 0, 0, 0).lost);
}

TEST(LockMonitor, LeavingDeadReckoningIsInconsistentAndLost) {
    LockMonitor m(config(), 1.0, 1);
    m.reset(0, 0, 0);
    const auto random_places = probes(0.1, 0.2);
    for (int i = 0; i < 10; ++i) {  // 100 m east, tracked with confidence
        m.predict(10, 0);
        EXPECT_FALSE(m.assess(0.8, random_places, 10.0 * (i + 1), 0, 0).lost);
    }
    m.predict(10, 0);
    // The estimate jumps 200 m north while the odometry says 10 m east: far beyond 40 m + 15 %,
    // and its score is good but not outstanding.
    const LockReport r = m.assess(0.55, random_places, 110, -200, 0);
    EXPECT_FALSE(r.weak);
    EXPECT_FALSE(r.confident);
    EXPECT_TRUE(r.inconsistent);
    EXPECT_TRUE(r.lost);
    EXPECT_NEAR(r.drift_m, 200, 1e-9);
    EXPECT_NEAR(r.widen_radius_m, 40 + 0.15 * 10, 1e-9);  // no wider than the odometry's drift bound
    EXPECT_NEAR(m.dead_reckoning_x(), 110, 1e-9);  // the wider search goes where the odometry says
    EXPECT_NEAR(m.dead_reckoning_y(), 0, 1e-9);
}

TEST(LockMonitor, AnOutstandingMatchFarFromDeadReckoningIsANewFix) {
    // How a wrong start is left behind: the true place, once found, stands out.
    LockMonitor m(config(), 1.0, 1);
    m.reset(0, 0, 300);
    m.predict(10, 0);
    const LockReport r = m.assess(0.8, probes(0.1, 0.2), 10, -500, 0);
    EXPECT_TRUE(r.confident);
    EXPECT_TRUE(r.inconsistent);
    EXPECT_FALSE(r.lost);
    EXPECT_NEAR(m.dead_reckoning_y(), -500, 1e-9);
}

TEST(LockMonitor, WhileTheCloudIsStillSpreadThereIsNoFixAndNoInconsistency) {
    // Converging from a wide prior, the weighted mean wanders: it must neither anchor dead
    // reckoning nor count as leaving it.
    LockMonitor m(config(), 1.0, 1);
    m.reset(0, 0, 0);
    const LockReport r = m.assess(0.8, probes(0.1, 0.2), 0, -500, 120);
    EXPECT_FALSE(r.confident);
    EXPECT_FALSE(r.inconsistent);
    EXPECT_FALSE(r.lost);
    EXPECT_NEAR(m.dead_reckoning_y(), 0, 1e-9);
}

TEST(LockMonitor, TooFewProbesOnTheMapGiveNoContrastVerdict) {
    LockMonitor m(config(), 1.0, 1);
    m.reset(0, 0, 300);
    auto few = probes(0.1, 0.2, 48);
    for (std::size_t i = 5; i < few.size(); ++i) few[i].flags = kTooFewSamples;  // off the map
    for (int i = 0; i < 5; ++i) {
        const LockReport r = m.assess(0.05, few, 0, 0, 0);
        EXPECT_TRUE(std::isnan(r.contrast));
        EXPECT_FALSE(r.weak);
        EXPECT_FALSE(r.lost);
    }
}

TEST(LockMonitor, ValidateNamesTheBadField) {
    LockMonitorConfig c;
    c.widen_fraction = 1.5;
    try {
        LockMonitor m(c, 1.0, 1);
        FAIL() << "no throw";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("widen_fraction"), std::string::npos) << e.what();
    }
    c = LockMonitorConfig{};
    c.min_contrast = NAN;
    EXPECT_THROW(c.validate(), Error);
}

}  // namespace
}  // namespace trn::filter
