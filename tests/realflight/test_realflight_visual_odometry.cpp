// Visual odometry on the 16 real frames (issue 17 item 4) against their committed poses
// (tests/data/realflight_poses.csv, ~5 px uncertain): each consecutive pair's motion, turned into map
// pixels with the earlier frame's pose (yaw, scale), must land within 12 px of the next pose on
// average (the frames move ~49 px each, so standing still would be ~49 px off), and pairs of frames
// that do not overlap must give no motion. Skipped (visibly) without the shared data.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>

#include "trn/filter/frame_registration.hpp"
#include "trn/filter/visual_odometry.hpp"
#include "trn/io/image_io.hpp"
#include "../common/shared_data.hpp"

namespace {

struct RealFrames {
    std::vector<trn::reg::PoseRow> poses;
    std::vector<trn::GrayImage> frames;
};

bool load(RealFrames& r) {
    const std::string dir = trn::test::shared_data("realflight");
    if (dir.empty() || !std::filesystem::exists(dir + "/frame_00000.png")) return false;
    r.poses = trn::reg::read_pose_rows(TRN_POSES_CSV);
    for (const auto& p : r.poses) r.frames.push_back(trn::load_gray(dir + "/" + p.frame));
    return true;
}

}  // namespace

TEST(RealFlightVisualOdometry, ConsecutiveFramesMoveAsTheirPoses) {
    RealFrames r;
    if (!load(r)) GTEST_SKIP() << "TRN_SHARED_DATA/realflight not found: real flight unavailable";
    ASSERT_EQ(r.frames.size(), 16u);
    double sum = 0, worst = 0;
    for (std::size_t k = 0; k + 1 < r.frames.size(); ++k) {
        const trn::filter::FrameMotion m = trn::filter::estimate_frame_motion(r.frames[k].view(), r.frames[k + 1].view());
        ASSERT_TRUE(m.ok()) << r.poses[k].frame << " -> " << r.poses[k + 1].frame << ": " << m.failure;
        const trn::Pose& a = r.poses[k].pose;
        const trn::Pose& b = r.poses[k + 1].pose;
        const double c = std::cos(a.yaw) * a.scale, s = std::sin(a.yaw) * a.scale;  // frame px -> map px (camera.hpp)
        const double ex = c * m.dx_px - s * m.dy_px, ey = s * m.dx_px + c * m.dy_px;
        const double err = std::hypot(ex - (b.x - a.x), ey - (b.y - a.y)), moved = std::hypot(b.x - a.x, b.y - a.y);
        std::printf("%2zu->%2zu %s %4d inliers: moved %6.1f map px, VO off by %5.1f px\n", k, k + 1, to_string(m.method), m.inliers, moved, err);
        sum += err, worst = std::max(worst, err);
    }
    std::printf("mean %.1f px, worst %.1f px\n", sum / 15, worst);
    EXPECT_LT(sum / 15, 12.0);
}

TEST(RealFlightVisualOdometry, FramesThatDoNotOverlapGiveNoMotion) {
    RealFrames r;
    if (!load(r)) GTEST_SKIP() << "TRN_SHARED_DATA/realflight not found: real flight unavailable";
    int most = 0;
    double strongest = 0;
    for (std::size_t k = 0; k + 8 < r.frames.size(); ++k) {  // 8 frames (~390 map px) apart: no common ground
        // Both cut to their common size, so phase correlation (same-size frames only) is tried too.
        const trn::GrayImage &a = r.frames[k], &b = r.frames[k + 8];
        const int w = std::min(a.width, b.width), h = std::min(a.height, b.height);
        const trn::GrayView va{a.pixels.data(), w, h, a.width}, vb{b.pixels.data(), w, h, b.width};
        const trn::filter::FrameMotion m = trn::filter::estimate_frame_motion(va, vb);
        std::printf("%2zu->%2zu: %d inliers, phase peak %.3f: %s\n", k, k + 8, m.inliers, m.response, m.ok() ? "MOTION" : m.failure.c_str());
        EXPECT_FALSE(m.ok()) << k << " -> " << k + 8;
        most = std::max(most, m.inliers), strongest = std::max(strongest, m.response);
    }
    std::printf("most chance inliers %d, strongest phase peak %.3f\n", most, strongest);
}
