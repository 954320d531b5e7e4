// The generalised motion model (eqs. 2.7-2.11 along the odometry's displacement, not along the
// heading): exact on a crabbing track without noise, each noise term where it belongs, and
// option checks that name the field.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "trn/error.hpp"
#include "trn/filter/motion_model.hpp"
#include "trn/detail/angles.hpp"

namespace trn::filter {
namespace {

const std::array<double, 5> kNoNoise{0, 0, 0, 0, 0};

// A curved track (course turning from east towards south) flown with a crab angle that swings
// between 15 and 35 degrees: the camera (and so the measured heading) never points along the track.
struct CrabStep {
    double east_m, north_m, heading_rad;
};
std::vector<CrabStep> crabbing_track(int steps) {
    std::vector<CrabStep> out;
    for (int i = 0; i < steps; ++i) {
        const double course = (90 + 0.8 * i) * kDeg, crab = (25 + 10 * std::cos(i * 0.07)) * kDeg;
        const double d = 2.4;  // 12 m/s at 5 Hz
        out.push_back({d * std::sin(course), d * std::cos(course), course + crab});
    }
    return out;
}

// Runs one particle over the track without noise; returns its distance (m) from the true end.
double noise_free_error(bool along_heading, double mpp) {
    MotionModel model;
    model.along_heading = along_heading;
    double x = 100, y = 200, yaw = 0, tx = 100, ty = 200, last = NAN;
    for (const CrabStep& s : crabbing_track(100)) {
        const StepMotion m = make_step_motion(s.east_m, s.north_m, s.heading_rad, s.heading_rad, std::isfinite(last) ? s.heading_rad - last : 0, mpp);
        last = s.heading_rad;
        propagate_particle(model, m, mpp, kNoNoise, x, y, yaw);
        tx += s.east_m / mpp, ty -= s.north_m / mpp;
        EXPECT_NEAR(yaw, std::remainder(s.heading_rad, 2 * kPi), 1e-12);  // the template keeps the measured heading
    }
    return std::hypot(x - tx, y - ty) * mpp;
}

TEST(MotionModel, NoiseFreeParticleAtTheTrueHeadingFollowsACrabbingTrackExactly) {
    EXPECT_LT(noise_free_error(false, 1.0), 1e-9);
    EXPECT_LT(noise_free_error(false, 0.5), 1e-9);
}

TEST(MotionModel, TheAlongHeadingModelDoesNotFollowTheCrab) {
    // Our model without its crab offset (--motion-along-heading) moves the distance along the
    // heading, as the dissertation's equations also do: 240 m of track with a 15-35 degree crab
    // leaves it ~100 m off.
    EXPECT_GT(noise_free_error(true, 1.0), 40.0);
}

TEST(MotionModel, CourseOffsetIsTheCrabAngle) {
    // Heading north-east (45 deg), moving due east: the odometry's course is 45 deg right of the heading.
    const StepMotion m = make_step_motion(3, 0, 45 * kDeg, 45 * kDeg, 0, 1.0);
    EXPECT_NEAR(m.course_offset_rad, 45 * kDeg, 1e-12);
    EXPECT_NEAR(m.distance_px, 3, 1e-12);
    // No heading ever known: the increment is taken as straight ahead of each particle.
    EXPECT_EQ(make_step_motion(3, 0, NAN, NAN, 0, 1.0).course_offset_rad, 0);
}

TEST(MotionModel, EachNoiseTermActsOnItsOwnAxis) {
    const StepMotion m = make_step_motion(0, 10, 0, 0, 0.5, 1.0);  // 10 m north, heading north, turned 0.5 rad
    auto moved = [&](const MotionModel& model, const std::array<double, 5>& z) {
        double x = 0, y = 0, yaw = 0;
        propagate_particle(model, m, 1.0, z, x, y, yaw);
        return std::array<double, 3>{x, -y, yaw};  // east, north, yaw
    };
    MotionModel only;
    only.alpha1 = only.alpha2 = only.alpha3 = only.eps_tran_m = only.eps_rot_deg = 0;
    MotionModel a1 = only;
    a1.alpha1 = 0.1;  // along track: 10 m * (1 + 0.1 * 1)
    auto r = moved(a1, {0, 1, 0, 0, 0});
    EXPECT_NEAR(r[0], 0, 1e-12);
    EXPECT_NEAR(r[1], 11, 1e-12);
    MotionModel a2 = only;
    a2.alpha2 = 0.1;  // course turned by 0.1 rad
    r = moved(a2, {0, 0, 1, 0, 0});
    EXPECT_NEAR(std::atan2(r[0], r[1]), 0.1, 1e-12);
    EXPECT_NEAR(std::hypot(r[0], r[1]), 10, 1e-12);
    MotionModel a3 = only;
    a3.alpha3 = 0.2;  // 0.2 per radian turned, 0.5 rad turned: course sd 0.1
    r = moved(a3, {0, 0, 1, 0, 0});
    EXPECT_NEAR(std::atan2(r[0], r[1]), 0.1, 1e-12);
    MotionModel et = only;
    et.eps_tran_m = 2;  // isotropic, metres
    r = moved(et, {0, 0, 0, 1, 1});
    EXPECT_NEAR(r[0], 2, 1e-12);
    EXPECT_NEAR(r[1], 12, 1e-12);
    MotionModel er = only;
    er.eps_rot_deg = 3;  // heading, and the course with it
    r = moved(er, {1, 0, 0, 0, 0});
    EXPECT_NEAR(r[2], 3 * kDeg, 1e-12);
    EXPECT_NEAR(std::atan2(r[0], r[1]), 3 * kDeg, 1e-12);
}

TEST(MotionModel, ValidateNamesTheBadField) {
    auto message = [](MotionModel m) {
        try {
            m.validate();
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    MotionModel m;
    EXPECT_EQ(message(m), "no error");
    m.alpha2 = NAN;
    EXPECT_NE(message(m).find("alpha2"), std::string::npos) << message(m);
    m = MotionModel{};
    m.eps_rot_deg = -1;
    EXPECT_NE(message(m).find("eps_rot_deg"), std::string::npos) << message(m);
    m = MotionModel{};
    m.alpha1 = INFINITY;
    EXPECT_NE(message(m).find("alpha1"), std::string::npos) << message(m);
}

}  // namespace
}  // namespace trn::filter
