// `trnkit register` as a user runs it (real processes): bad poses files and options are refused
// with one line naming the file:line or option; a pose that is not the best NCC fails the run
// and writes no AIR folder.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "../cli/cli_process.hpp"
#include "trn/io/image_io.hpp"
#include "../common/shared_data.hpp"

namespace {

std::string tmp(const std::string& name) { return testing::TempDir() + "/register_cli_" + name; }

// A small textured map and frame: enough for the command to get as far as the poses file.
void write_images(const std::string& map, const std::string& frame) {
    trn::GrayImage m{64, 64, std::vector<std::uint8_t>(64 * 64)};
    for (int i = 0; i < 64 * 64; ++i) m.pixels[i] = static_cast<std::uint8_t>((i * 37) % 251);
    trn::save_gray(map, m.view());
    trn::save_gray(frame, m.view().roi(0, 0, 16, 12));
}

}  // namespace

TEST(RegisterCli, BadPosesRowNamesFileAndLine) {
    const std::string map = tmp("map.png"), frame = tmp("frame_00000.png"), csv = tmp("bad.csv");
    write_images(map, frame);
    std::ofstream(csv) << "frame,x,y,yaw,scale,ncc\nframe_00000.png,10,10,0,1,0.5\nframe_00000.png,10,inf,0,1,0.5\n";
    const auto r = trn::test::run_trnkit("register --map " + map + " " + frame + " --verify " + csv);
    EXPECT_NE(r.code, 0);
    EXPECT_NE(r.output.find(csv + ":3:"), std::string::npos) << r.output;
}

TEST(RegisterCli, NonFiniteAnchorRefused) {
    const std::string map = tmp("map2.png"), frame = tmp("frame2_00000.png");
    write_images(map, frame);
    const auto r = trn::test::run_trnkit("register --map " + map + " " + frame + " " + frame + " --anchor 1 2 nan 1");
    EXPECT_NE(r.code, 0);
    EXPECT_NE(r.output.find("--anchor"), std::string::npos) << r.output;
}

TEST(RegisterCli, PoseThatIsNotTheBestFailsAndWritesNoAirFolder) {
    const std::string data = trn::test::shared_data_dir().string();
    if (trn::test::shared_data("realflight/frame_00008.png").empty())
        GTEST_SKIP() << "TRN_SHARED_DATA/realflight not found: real flight unavailable";
    // frame 8's committed pose (tests/data/realflight_poses.csv) moved 40 px along the road.
    const std::string csv = tmp("shifted.csv"), air = tmp("air");
    std::ofstream(csv) << "frame,x,y,yaw,scale,ncc\nframe_00008.png,1125.57,821.95,1.85729,1.09685,0.65\n";
    std::filesystem::remove_all(air);
    const auto r = trn::test::run_trnkit("register --map " + data + "/orthophoto.png " + data + "/realflight/frame_00008.png --verify " +
                                         csv + " --air-out " + air);
    EXPECT_EQ(r.code, 1) << r.output;
    EXPECT_NE(r.output.find("NOT THE BEST"), std::string::npos) << r.output;
    EXPECT_FALSE(std::filesystem::exists(air));
}
