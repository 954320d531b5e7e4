// `trnkit localize` start prior and provenance, as a user runs it (real processes): each start
// option refused with a message naming it; a flight without ground truth (empty MapX/MapY) runs
// from --start and its summary says "no ground truth" instead of errors; summary.json records
// backend, device, version, commit, seed and the options.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <cstdio>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "../cli/cli_process.hpp"
#include "../common/test_images.hpp"
#include "trn/build_info.hpp"
#include "trn/sim/map.hpp"

namespace {

using trn::test::run_trnkit;

class LocalizeStartCli : public testing::Test {
protected:
    void SetUp() override {
        dir_ = std::filesystem::temp_directory_path() / ("trnkit_localize_start_" + std::to_string(::getpid()));
        std::filesystem::remove_all(dir_);
        std::filesystem::create_directories(dir_);
    }
    void TearDown() override { std::filesystem::remove_all(dir_); }

    // A tiny AIR flight of 4 rows on a 240x200 map; `map_xy` is the MapX,MapY pair of every row.
    std::string flight(const std::string& name, const std::string& map_xy, const std::string& extra_info = "") {
        const std::string d = (dir_ / name).string();
        std::filesystem::create_directories(d);
        cv::imwrite(d + "/map.png", trn::test::textured_image(240, 200, 1).mat());
        std::ofstream(d + "/flight.json") << R"({"scenario": "T", "map_file": "map.png", "metres_per_pixel": 1, )" << extra_info
                                          << R"("camera": {"width": 64, "height": 48, "hfov_deg": 60}, "fps": 5})";
        std::ofstream csv(d + "/metadata.csv");
        csv << "Filename,Latitude,Longitude,RelativeAltitude,ImuX,ImuY,ImuZ,ImuW,PoseX,PoseY,PoseZ,OrientationX,OrientationY,"
               "OrientationZ,OrientationW,MapX,MapY,SvoX,SvoY,SvoZ\n";
        for (int i = 0; i < 4; ++i) {
            const std::string file = "frame_00000" + std::to_string(i) + ".png";
            csv << file << ",47.1,8.2,200,0,0,0.7071068,0.7071068,0,0,200,0,0,0.7071068,0.7071068," << map_xy << ",0,0,200\n";
            cv::imwrite(d + "/" + file, trn::test::textured_image(64, 48, 3).mat());
        }
        return d;
    }
    static std::string localize(const std::string& folder) {
        return "localize --dataset " + folder + " --backend cpu --template-width 32 --max-particles 100 --min-particles 50 --no-plots --out " +
               folder + "/out";
    }
    static nlohmann::json summary(const std::string& folder) {
        std::ifstream in(folder + "/out/summary.json");
        return nlohmann::json::parse(in);
    }
    static std::string read(const std::string& path) {
        std::ostringstream os;
        os << std::ifstream(path).rdbuf();
        return os.str();
    }

    std::filesystem::path dir_;
};

TEST_F(LocalizeStartCli, EachStartOptionRefusedWithItsName) {
    const std::string f = flight("f", "120,100");
    const std::vector<std::pair<std::string, std::string>> cases = {
        {" --init-radius-m 0", "--init-radius-m: '0'"},
        {" --init-radius-m nan", "--init-radius-m"},
        {" --reinit-radius-m -5", "--reinit-radius-m: '-5'"},
        {" --start 12", "--start: expected X,Y"},
        {" --start 1,abc", "--start: expected X,Y"},
        {" --start -3,4", "--start: -3,4 is outside"},
        {" --start 500,20", "--start 500,20: map pixel"},  // parses, but is off the 240x200 map
        {" --start-latlon 95,8", "--start-latlon: 95,8 is outside"},
        {" --start-latlon 47.1,8.2", "--start-latlon: " + f + "/flight.json has no geo origin"},
        {" --start 1,2 --start-latlon 47.1,8.2", "--start and --start-latlon"},
        {" --start-heading-deg 1000", "--start-heading-deg: '1000'"},
        {" --heading-sd-deg -1", "--heading-sd-deg: '-1'"},
    };
    for (const auto& [extra, expect] : cases) {
        const auto r = run_trnkit(localize(f) + extra);
        EXPECT_NE(r.code, 0) << extra << "\n" << r.output;
        EXPECT_NE(r.output.find(expect), std::string::npos) << extra << "\nexpected: " << expect << "\ngot: " << r.output;
    }
}

// Compass-less (issue 25): --heading none runs, writes the heading as an output (CSV columns,
// summary.json figures), and each yaw-prior option is refused with its name when misused.
TEST_F(LocalizeStartCli, HeadingNoneRunsAndItsYawOptionsAreNamed) {
    const std::string f = flight("f", "120,100");
    const std::vector<std::pair<std::string, std::string>> cases = {
        {" --heading north", "--heading: north not in {compass,none}"},
        {" --start-yaw-deg 30", "--start-yaw-deg: only with --heading none"},
        {" --start-yaw-sd-deg 5", "--start-yaw-sd-deg: only with --heading none"},
        {" --heading none --start-yaw-sd-deg 5", "--start-yaw-sd-deg: needs --start-yaw-deg"},
        {" --heading none --start-yaw-deg 400", "--start-yaw-deg: '400'"},
        {" --heading none --start-yaw-deg 30 --start-yaw-sd-deg -2", "--start-yaw-sd-deg: '-2'"},
        {" --heading none --start-heading-deg 30", "--start-heading-deg: not with --heading none"},
        {" --heading none --heading-sd-deg 3", "--heading-sd-deg: not with --heading none"},
        {" --heading none --motion-yaw-sd -1", "--motion-yaw-sd: '-1'"},
    };
    for (const auto& [extra, expect] : cases) {
        const auto r = run_trnkit(localize(f) + extra);
        EXPECT_NE(r.code, 0) << extra << "\n" << r.output;
        EXPECT_NE(r.output.find(expect), std::string::npos) << extra << "\nexpected: " << expect << "\ngot: " << r.output;
    }
    const auto r = run_trnkit(localize(f) + " --heading none --start-yaw-deg 90 --start-yaw-sd-deg 5");
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("heading:      none; final yaw sd"), std::string::npos) << r.output;
    const nlohmann::json j = summary(f);
    EXPECT_EQ(j["heading"].get<std::string>().rfind("none", 0), 0u) << j.dump(2);
    EXPECT_EQ(j["start_heading"], "--heading none: yaw prior 90 +- 5 deg");
    EXPECT_EQ(j["start_yaw_deg"], 90);
    for (const char* key : {"mean_yaw_error_deg", "final_yaw_sd_deg", "converged_from_frame", "converged_mean_error_m"})
        EXPECT_TRUE(j.contains(key)) << key;
    const std::string csv = read(f + "/out/localization.csv");
    EXPECT_NE(csv.find(",odometry_source,truth_yaw_deg,estimate_yaw_deg,estimate_yaw_sd_deg,yaw_error_deg\n"), std::string::npos)
        << csv.substr(0, 400);
    // With a compass none of it appears: the outputs stay what they were.
    ASSERT_EQ(run_trnkit(localize(f) + " --force").code, 0);
    EXPECT_FALSE(summary(f).contains("heading"));
    EXPECT_EQ(read(f + "/out/localization.csv").find("yaw_sd"), std::string::npos);
}

TEST_F(LocalizeStartCli, FlightWithoutGroundTruthNeedsStartAndSaysNoGroundTruth) {
    const std::string f = flight("nt", ",");
    const auto refused = run_trnkit(localize(f));
    EXPECT_NE(refused.code, 0) << refused.output;
    EXPECT_NE(refused.output.find("--start: required: " + f + "/metadata.csv has no ground truth"), std::string::npos) << refused.output;

    const auto r = run_trnkit(localize(f) + " --start 120,100 --force");
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("no ground truth: errors not computed"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("nan"), std::string::npos) << r.output;
    const nlohmann::json j = summary(f);
    EXPECT_EQ(j["ground_truth"], false);
    EXPECT_FALSE(j.contains("filter_mean_error_m"));
    EXPECT_FALSE(j.contains("distance_m"));
    EXPECT_EQ(j["steps"], 4);
    const std::string csv = read(f + "/out/localization.csv");
    EXPECT_EQ(csv.find("nan"), std::string::npos) << csv;
    const std::string first_row = csv.substr(csv.find('\n') + 1, csv.find('\n', csv.find('\n') + 1) - csv.find('\n') - 1);
    EXPECT_NE(first_row.find(",0,,,"), std::string::npos) << first_row;  // distance 0, truth_x and truth_y empty
}

TEST_F(LocalizeStartCli, HalfAGroundTruthIsABrokenRow) {
    const std::string f = flight("half", "120,");
    const auto r = run_trnkit(localize(f) + " --start 120,100");
    EXPECT_NE(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("metadata.csv:2: MapY '' is not a number"), std::string::npos) << r.output;
}

TEST_F(LocalizeStartCli, StartLatLonIsPlacedThroughTheGeoOrigin) {
    const trn::sim::GeoOrigin origin{47.1, 8.2};
    const std::string f = flight("ll", ",", R"("origin": {"latitude_deg": 47.1, "longitude_deg": 8.2}, )");
    trn::sim::Map m;
    m.metres_per_pixel = 1;
    m.origin = origin;
    const trn::sim::LatLon ll = trn::sim::map_pixel_to_latlon(m, 130, 90);
    char arg[96];
    std::snprintf(arg, sizeof arg, " --start-latlon %.10f,%.10f", ll.latitude_deg, ll.longitude_deg);
    const auto r = run_trnkit(localize(f) + arg);
    ASSERT_EQ(r.code, 0) << r.output;
    const nlohmann::json j = summary(f);
    EXPECT_NEAR(j["start_x"].get<double>(), 130, 0.01);
    EXPECT_NEAR(j["start_y"].get<double>(), 90, 0.01);
}

TEST_F(LocalizeStartCli, SummaryRecordsProvenanceSeedAndOptions) {
    const std::string f = flight("p", "120,100", R"("origin": {"latitude_deg": 47.1, "longitude_deg": 8.2}, )");
    const auto r = run_trnkit(localize(f) + " --seed 7 --init-radius-m 20 --reinit-radius-m 80 --start-heading-deg 90 --heading-sd-deg 3");
    ASSERT_EQ(r.code, 0) << r.output;
    const nlohmann::json j = summary(f);
    EXPECT_EQ(j["backend"], "cpu");
    EXPECT_TRUE(j.contains("device") && !j["device"].get<std::string>().empty());
    EXPECT_EQ(j["trnkit_version"], std::string(trn::build_info().version));
    EXPECT_EQ(j["git_commit"], std::string(trn::build_info().git_commit));
    EXPECT_EQ(j["seed"], 7);
    EXPECT_EQ(j["init_radius_m"], 20);
    EXPECT_EQ(j["reinit_radius_m"], 80);
    EXPECT_EQ(j["start_heading_deg"], 90);
    EXPECT_EQ(j["heading_sd_deg"], 3);
    EXPECT_EQ(j["start_x"], 120);
    EXPECT_EQ(j["ground_truth"], true);
    EXPECT_TRUE(j["filter_mean_error_m"].is_number());
}

}  // namespace
