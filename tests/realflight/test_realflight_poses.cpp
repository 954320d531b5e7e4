// The committed ground truth of the 16 real frames (tests/data/realflight_poses.csv, found by
// `trnkit register`): at every pose the NCC on the cpu backend is the single best within +-160 map
// px at that yaw and scale, and equals the NCC recorded in the file. Needs the shared data.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "trn/filter/frame_registration.hpp"
#include "trn/filter/real_air_folder.hpp"
#include "trn/sim/air_format.hpp"
#include "trn/sim/camera.hpp"
#include "trn/error.hpp"
#include "trn/registry.hpp"
#include "trn/detail/angles.hpp"
#include "../common/shared_data.hpp"

namespace {

using trn::kPi;

std::string shared_data() {
    const std::string p = trn::test::shared_data_dir().string();
    return !trn::test::shared_data("orthophoto.png").empty() && std::filesystem::is_directory(p + "/realflight") ? p : "";
}

#define NEED_DATA()                                   \
    const std::string data = shared_data();           \
    if (data.empty()) GTEST_SKIP() << "TRN_SHARED_DATA/orthophoto.png or realflight/ not found: real flight unavailable"

struct MapOnCpu {
    std::unique_ptr<trn::Backend> backend = trn::default_registry().create("cpu");
    trn::GrayImage map;
    trn::MapHandle handle;
    explicit MapOnCpu(const std::string& data) : map(trn::load_gray(data + "/orthophoto.png")), handle(backend->upload_map(map.view())) {}
};

}  // namespace

TEST(RealFlightPoses, EachIsTheBestNccWithin160px) {
    NEED_DATA();
    MapOnCpu s(data);
    const std::vector<trn::reg::PoseRow> rows = trn::reg::read_pose_rows(TRN_POSES_CSV);
    ASSERT_EQ(rows.size(), 16u);
    for (const trn::reg::PoseRow& row : rows) {
        const trn::GrayImage frame = trn::load_gray(data + "/realflight/" + row.frame);
        const trn::reg::Uniqueness u = trn::reg::check_unique(*s.backend, s.handle, frame, row.pose, 160, 2);
        EXPECT_NEAR(u.ncc_at_pose, row.ncc, 0.002) << row.frame;
        EXPECT_LE(u.best_dist, trn::reg::kShoulderPx) << row.frame << ": best NCC " << u.best_ncc << " at " << u.best.x << ","
                                                      << u.best.y;
        EXPECT_GT(u.ncc_at_pose, 0.3) << row.frame;
    }
}

// The check can fail: the same frame placed 40 px along the road (the ambiguity of the area) is
// not the best of its window.
TEST(RealFlightPoses, ShiftedPoseIsNotTheBest) {
    NEED_DATA();
    MapOnCpu s(data);
    const std::vector<trn::reg::PoseRow> rows = trn::reg::read_pose_rows(TRN_POSES_CSV);
    trn::Pose p = rows.at(8).pose;
    const trn::GrayImage frame = trn::load_gray(data + "/realflight/" + rows.at(8).frame);
    p.x += 33;
    p.y += 22;
    const trn::reg::Uniqueness u = trn::reg::check_unique(*s.backend, s.handle, frame, p, 160, 2);
    EXPECT_GT(u.best_dist, trn::reg::kShoulderPx);
}

TEST(RealFlightPoses, BadRowNamesFileAndLine) {
    const std::string path = testing::TempDir() + "/bad_poses.csv";
    {
        std::ofstream(path) << "frame,x,y,yaw,scale,ncc\nf0.png,1,2,0.1,1,0.5\nf1.png,1,nan,0.1,1,0.5\n";
    }
    try {
        trn::reg::read_pose_rows(path);
        FAIL() << "no error";
    } catch (const trn::Error& e) {
        EXPECT_NE(std::string(e.what()).find(path + ":3:"), std::string::npos) << e.what();
    }
}

// The AIR folder written from the committed poses reads back with the truth equal to the poses,
// every frame at the camera's size with an altitude that gives back the pose scale, and the
// simulated magnetometer within its +-2 degree bound of the true heading.
TEST(RealFlightAir, FolderReadsBackWithThePosesAsTruth) {
    NEED_DATA();
    const std::vector<trn::reg::PoseRow> rows = trn::reg::read_pose_rows(TRN_POSES_CSV);
    std::vector<trn::GrayImage> frames;
    for (const auto& r : rows) frames.push_back(trn::load_gray(data + "/realflight/" + r.frame));
    const std::string dir = testing::TempDir() + "/realflight_air";
    std::filesystem::remove_all(dir);
    const trn::reg::RealAirOptions o;
    trn::reg::write_real_air_folder(dir, rows, frames, o);

    const trn::sim::FlightInfo info = trn::sim::read_flight_info(dir + "/flight.json");
    EXPECT_EQ(info.frames, rows.size());
    EXPECT_EQ(info.camera.width, frames[0].width);
    trn::sim::AirReader reader(dir);
    trn::sim::AirRecord r;
    std::size_t k = 0;
    for (; reader.next(r); ++k) {
        ASSERT_LT(k, rows.size());
        const trn::Pose& p = rows[k].pose;
        EXPECT_EQ(r.filename, rows[k].frame);
        EXPECT_NEAR(r.map_x, p.x, 1e-3);
        EXPECT_NEAR(r.map_y, p.y, 1e-3);
        const double truth = trn::sim::heading_from_quaternion(r.orientation);
        EXPECT_NEAR(std::remainder(truth - p.yaw, 2 * kPi), 0, 1e-6) << r.filename;
        EXPECT_LE(std::abs(std::remainder(trn::sim::heading_from_quaternion(r.imu) - truth, 2 * kPi)), 2.0 * kPi / 180 + 1e-9);
        // Each frame as it is, at its own size; the scale with its own focal length is the found one.
        const trn::GrayImage img = reader.load_image(r);
        EXPECT_EQ(img.pixels, frames[k].pixels) << r.filename;
        const trn::sim::Camera own{img.width, img.height, info.camera.hfov_deg};
        EXPECT_NEAR(trn::sim::template_scale(own, r.relative_altitude_m, info.metres_per_pixel), p.scale, 1e-6) << r.filename;
        // Odometry: near the true displacement (3 % scale error, 1 degree bias), never identical.
        const double true_e = (p.x - rows[0].pose.x) * o.metres_per_pixel, true_n = -(p.y - rows[0].pose.y) * o.metres_per_pixel;
        EXPECT_NEAR(r.pose_m.x, true_e, 1e-3);
        EXPECT_NEAR(r.pose_m.y, true_n, 1e-3);
        EXPECT_LE(std::hypot(r.svo_m.x - true_e, r.svo_m.y - true_n), 0.1 * std::hypot(true_e, true_n) + 5) << r.filename;
        if (k > 0) EXPECT_GT(std::hypot(r.svo_m.x - true_e, r.svo_m.y - true_n), 0.0) << r.filename;
    }
    EXPECT_EQ(k, rows.size());
}
