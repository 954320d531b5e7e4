// Issue 17 through the CLI as a user runs it: the "-long" presets get a map that holds their whole
// loop at the highest altitude, and --template-width takes "full" (no downscaling) and refuses
// anything else that is not a width, naming the option.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <opencv2/imgcodecs.hpp>

#include "cli_process.hpp"
#include "trn/detail/angles.hpp"

namespace {

using trn::kPi;

using trn::test::run_trnkit;

class LongFlightCli : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = std::filesystem::temp_directory_path() / ("trnkit_cli_long_" + std::to_string(::getpid()));
        std::filesystem::remove_all(dir_);
        std::filesystem::create_directories(dir_);
    }
    void TearDown() override { std::filesystem::remove_all(dir_); }
    std::string path(const std::string& name) const { return (dir_ / name).string(); }
    std::filesystem::path dir_;
};

std::string read_text(const std::string& file) {
    std::ifstream in(file);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

// FR-200-long: a 4748 m rectangle loop (1400.5 x 980.4 m, turned 0.52 rad: 1702.5 m wide) flown
// up to 300 m, where the 640x480 60-degree footprint reaches 216.5 m from the centre. The map must
// hold both, or the loop is shrunk and the flight is no longer Table 2.2's length. (A map sized for
// the preset's own 200 m and the 1.1 x size rule would be 2000 m.)
TEST_F(LongFlightCli, SimulateMakesAMapThatHoldsTheLongLoopAtTheHighestAltitude) {
    const auto r = run_trnkit("simulate --scenario FR-200-long --frames 2 --mpp 2 --out " + path("fr"));
    ASSERT_EQ(r.code, 0) << r.output;
    const cv::Mat map = cv::imread(path("fr/map.png"), cv::IMREAD_GRAYSCALE);
    ASSERT_FALSE(map.empty());
    const double size = (4748 + (8 - 2 * kPi) * 40) / 3.4;
    const double loop_width = size * std::cos(0.52) + 0.7 * size * std::sin(0.52);
    const double footprint_radius = 0.5 * 800 * 300 / (320 / std::tan(kPi / 6));
    EXPECT_GE(map.cols * 2, loop_width + 2 * footprint_radius) << "2 m per pixel";
    const auto back = run_trnkit("simulate --read " + path("fr"));
    EXPECT_EQ(back.code, 0) << back.output;
    EXPECT_NE(back.output.find("scenario FR-200-long"), std::string::npos) << back.output;
}

TEST_F(LongFlightCli, DemoScoresFullResolutionTemplatesAndRefusesBadWidths) {
    const std::string demo = "demo --scenario FC-300-long --backend cpu --distance-km 0.012 --rate 1 --no-plots --seed 2 ";
    const auto full = run_trnkit(demo + "--template-width full --out " + path("full"));
    ASSERT_EQ(full.code, 0) << full.output;
    EXPECT_NE(full.output.find("FC-300-long, 0.012 km at 300 and 200 m"), std::string::npos) << full.output;
    EXPECT_NE(read_text(path("full/summary.json")).find("\"template_width\": 0"), std::string::npos);
    for (const char* bad : {"fullres", "4", "-1", "4097", "160.5"}) {
        const auto r = run_trnkit(demo + "--template-width " + bad + " --out " + path("bad"));
        EXPECT_NE(r.code, 0) << bad;
        EXPECT_NE(r.output.find("--template-width"), std::string::npos) << r.output;
        EXPECT_NE(r.output.find(std::string("'") + bad + "'"), std::string::npos) << r.output;
        EXPECT_NE(r.output.find("or 'full'"), std::string::npos) << r.output;
        EXPECT_FALSE(std::filesystem::exists(path("bad/summary.json"))) << bad;
    }
    // localize shares the option.
    const auto loc = run_trnkit("localize --template-width nope --dataset " + path("none"));
    EXPECT_NE(loc.code, 0);
    EXPECT_NE(loc.output.find("'nope'"), std::string::npos) << loc.output;
}

}  // namespace
