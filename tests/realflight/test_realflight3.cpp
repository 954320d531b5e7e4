// Issue 42: the third real flight (shared/data/realflight3: a 7 km fixed-wing mission over bare
// farmland, 167 photos 3-73 s apart, a map with 55 % no-data that the turns leave) as a test.
//   - The development folder realflight3/air localized with its heading: the filter's mean error
//     against the camera's GPS below the folder's own odometry's, and no re-initialisation although
//     whole frames lie over no-data (they are steps the frame told nothing: frame_weight 0).
//   - The four original photos imported without --sensor-width-mm: the Canon is in no table, its EXIF
//     FocalPlaneXResolution over PixelXDimension gives the sensor (6.197 mm, ~71.6 degrees).
// Skipped (visibly) without the shared data.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "../cli/cli_process.hpp"
#include "../common/shared_data.hpp"

namespace {

std::string data() {
    return trn::test::shared_data("realflight3");
}

class RealFlight3 : public testing::Test {
protected:
    void SetUp() override {
        if (data().empty() || !std::filesystem::exists(data() + "/air/metadata.csv"))
            GTEST_SKIP() << "TRN_SHARED_DATA/realflight3 not found: the third real flight is unavailable";
        dir_ = testing::TempDir() + "/realflight3_" + std::to_string(::getpid());
        std::filesystem::remove_all(dir_);
        std::filesystem::create_directories(dir_);
    }
    void TearDown() override {
        if (!dir_.empty()) std::filesystem::remove_all(dir_);
    }
    std::string dir_;
};

TEST_F(RealFlight3, TheFilterBeatsTheOdometryOverNoDataAndBareField) {
    const std::string out = dir_ + "/loc";
    const auto r = trn::test::run_trnkit("localize --dataset " + data() + "/air --map " + data() + "/air/map.png --rate 0.144 --backend cpu " +
                                         "--init-radius-m 50 --seed 1 --no-plots --out " + out);
    ASSERT_EQ(r.code, 0) << r.output;
    std::ifstream in(out + "/summary.json");
    const nlohmann::json s = nlohmann::json::parse(in);
    EXPECT_EQ(s.at("steps").get<int>(), 167);
    const double filter = s.at("filter_mean_error_m").get<double>(), odometry = s.at("odometry_mean_error_m").get<double>();
    // At 8fd5cd9 the filter's mean was 64 m (seven 300 m re-initialisations over no-data); now ~10 m
    // against the odometry's 12.5 m. The GPS is ~12 m from where the tilted camera looks (RESULTS.md),
    // so ~10 m is near what any localizer of the frames can show against it.
    EXPECT_LT(filter, 0.9 * odometry) << "filter " << filter << " m, odometry " << odometry << " m";
    EXPECT_EQ(s.at("reinitialisations").get<int>(), 0);
    // Steps whose every particle lay over no-data are counted as such and told nothing.
    std::ifstream csv(out + "/localization.csv");
    std::string header, line;
    std::getline(csv, header);
    std::size_t column = 0;
    {
        std::stringstream h(header);
        std::string cell;
        for (std::size_t i = 0; std::getline(h, cell, ','); ++i)
            if (cell == "frame_weight") column = i;
    }
    ASSERT_GT(column, 0u) << header;
    int blind = 0;
    while (std::getline(csv, line)) {
        std::stringstream l(line);
        std::string cell;
        for (std::size_t i = 0; std::getline(l, cell, ','); ++i)
            if (i == column) blind += std::stod(cell) == 0.0;
    }
    EXPECT_GE(blind, 1) << "a turn puts a whole frame over no-data (2 steps at seed 1)";
}

TEST_F(RealFlight3, PhotosOfACameraInNoTableImportByTheirFocalPlaneResolution) {
    const auto r = trn::test::run_trnkit("import-photos " + data() + "/photos --out " + dir_ + "/air --altitude-agl 60");
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("EXIF FocalPlaneXResolution"), std::string::npos) << r.output;
    std::ifstream in(dir_ + "/air/flight.json");
    const nlohmann::json f = nlohmann::json::parse(in);
    EXPECT_NEAR(f.at("camera").at("hfov_deg").get<double>(), 71.6, 0.1);
}

}  // namespace
