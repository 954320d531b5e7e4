// Motion from the time between frames (issue 42: photos 3-73 s apart on realflight3). With frame
// times a lost odometry's held step is the last good step's velocity over this interval, and
// MotionModel::eps_tran_m_per_s adds position noise per second; without them (or with that rate 0)
// every draw and sum is the step model's, bit for bit.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "trn/filter/particle_filter.hpp"

namespace trn::filter {
namespace {

struct NeverCalled : ParticleScorer {  // every step below has no frame: the cloud only moves
    void score(GrayView, double, std::span<const Pose>, std::span<ParticleScore>, PhaseTimes*) override { ADD_FAILURE() << "scored"; }
};

FilterConfig quiet_config() {
    FilterConfig c;
    c.metres_per_pixel = 1;
    c.lock.enabled = false;
    c.init_radius_m = 0.5;
    c.max_particles = c.min_particles = c.initial_particles = 500;
    c.motion.alpha1 = c.motion.alpha2 = c.motion.alpha3 = 0;
    c.motion.eps_tran_m = 0.01, c.motion.eps_rot_deg = 0;
    return c;
}

FilterInput moved(double north_m, double dt_s) {
    FilterInput in;
    in.odometry_east_m = 0, in.odometry_north_m = north_m, in.heading_rad = 0, in.dt_s = dt_s;
    return in;
}

// Northward 10 m per 5 s frame, then one frame 20 s later with the odometry lost: how far north the cloud moved on it.
double held_step_north_m(double lost_dt_s, double good_dt_s) {
    NeverCalled scorer;
    ParticleFilter pf(scorer, quiet_config());
    pf.initialise(500, 500, 0);
    for (int i = 0; i < 3; ++i) pf.step(moved(10, good_dt_s));
    const double y0 = pf.estimate().y;
    const StepReport r = pf.step(moved(NAN, lost_dt_s));
    EXPECT_TRUE(r.odometry_lost);
    return y0 - r.estimate.y;  // y points south
}

TEST(FrameTimes, ALostOdometryHoldsTheLastVelocityOverTheInterval) {
    EXPECT_NEAR(held_step_north_m(20, 5), 40, 0.5) << "2 m/s held for 20 s";
    EXPECT_NEAR(held_step_north_m(2.5, 5), 5, 0.5) << "2 m/s held for 2.5 s";
    EXPECT_NEAR(held_step_north_m(NAN, NAN), 10, 0.5) << "no times: the last step";
    EXPECT_NEAR(held_step_north_m(20, NAN), 10, 0.5) << "the good step's interval unknown: the last step";
}

std::vector<Particle> after_one_step(double eps_per_s, double dt_s) {
    NeverCalled scorer;
    FilterConfig c = quiet_config();
    c.motion.eps_tran_m = 1, c.motion.eps_tran_m_per_s = eps_per_s;
    ParticleFilter pf(scorer, c);
    pf.initialise(500, 500, 0);
    pf.step(moved(10, dt_s));
    return pf.particles();
}

double spread_m(const std::vector<Particle>& ps) {
    double sx = 0, sy = 0, s2 = 0;
    for (const Particle& p : ps) sx += p.x, sy += p.y;
    const double n = static_cast<double>(ps.size()), mx = sx / n, my = sy / n;
    for (const Particle& p : ps) s2 += (p.x - mx) * (p.x - mx) + (p.y - my) * (p.y - my);
    return std::sqrt(s2 / n);
}

TEST(FrameTimes, PositionNoiseGrowsWithTheIntervalAndIsOffAtZeroRate) {
    const std::vector<Particle> untimed = after_one_step(0, NAN), timed_off = after_one_step(0, 40);
    ASSERT_EQ(untimed.size(), timed_off.size());
    for (std::size_t i = 0; i < untimed.size(); ++i) {  // rate 0: the step model, bit for bit
        EXPECT_EQ(untimed[i].x, timed_off[i].x);
        EXPECT_EQ(untimed[i].y, timed_off[i].y);
    }
    // sd per axis sqrt(1 + (0.25 dt)^2): 2-D rms sqrt(2) times that.
    EXPECT_NEAR(spread_m(after_one_step(0.25, 4)), std::sqrt(2.0) * std::sqrt(2.0), 0.2);
    EXPECT_NEAR(spread_m(after_one_step(0.25, 40)), std::sqrt(2.0) * std::sqrt(101.0), 1.0);
    EXPECT_NEAR(spread_m(after_one_step(0.25, NAN)), std::sqrt(2.0), 0.15) << "no time: no time noise";
}

TEST(FrameTimes, RateIsValidated) {
    FilterConfig c = quiet_config();
    c.motion.eps_tran_m_per_s = -1;
    EXPECT_THROW(c.validate(), Error);
    c.motion.eps_tran_m_per_s = NAN;
    EXPECT_THROW(c.validate(), Error);
}

}  // namespace
}  // namespace trn::filter
