// The committed ground truth of the 16 real frames (tests/data/realflight_poses.csv, found by
// `trnkit register`): at every pose the NCC on the cpu backend is the single best within +-160 map
// px at that yaw and scale, and equals the NCC recorded in the file. Needs the shared data.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "frame_registration.hpp"
#include "trn/error.hpp"
#include "trn/registry.hpp"

namespace {

std::string shared_data() {
    const char* d = std::getenv("TRN_SHARED_DATA");
    if (!d) return "";
    const std::string p(d);
    return std::filesystem::exists(p + "/orthophoto.png") && std::filesystem::is_directory(p + "/realflight") ? p : "";
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
