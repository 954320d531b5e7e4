// Issue 12 item 4 on the real flight (real processes): an AIR folder without flight.json localizes
// from --map/--mpp/--hfov-deg exactly as with it; frames of differing sizes are each scored at
// their own scale; frames tilted beyond --max-tilt-deg are skipped and counted.
#include <cmath>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "real_air_fixture.hpp"
#include "trn/sim/air_format.hpp"
#include "trn/detail/angles.hpp"

using trn::test::RealAirFolder;
using trn::test::run_trnkit;

namespace {

using trn::kPi;
constexpr const char* kOptions = "--mpp 0.5 --hfov-deg 60";  // what register's flight.json says
}

TEST_F(RealAirFolder, LocalizesWithoutFlightJsonFromOptionsAsWithIt) {
    const auto with = localize("--map " + map(), 1, dir_ + "/with");  // register's flight.json names no map
    ASSERT_EQ(with.code, 0) << with.output;
    std::filesystem::remove(dir_ + "/flight.json");
    const auto without = localize(std::string("--map ") + map() + " " + kOptions, 1, dir_ + "/without");
    ASSERT_EQ(without.code, 0) << without.output;
    const auto a = summary(dir_ + "/with"), b = summary(dir_ + "/without");
    std::cout << "with flight.json " << a["filter_mean_error_m"] << " m, without " << b["filter_mean_error_m"] << " m (odometry "
              << b["odometry_mean_error_m"] << " m)\n";
    EXPECT_EQ(a["filter_mean_error_m"], b["filter_mean_error_m"]);  // same seed, same inputs: the same run
    EXPECT_EQ(a["steps"], 16);
    EXPECT_EQ(b["steps"], 16);
    EXPECT_LE(b["filter_mean_error_m"].get<double>(), 0.5 * b["odometry_mean_error_m"].get<double>());
    EXPECT_EQ(b["flight_json"], "absent (camera, map and resolution from options)");

    // A focal length instead of the field of view: 60 degrees over 455 px is 394.04 px.
    const auto focal = localize(std::string("--map ") + map() + " --mpp 0.5 --focal-px 394.0415 --focal-width 455", 1, dir_ + "/focal");
    ASSERT_EQ(focal.code, 0) << focal.output;
    EXPECT_NEAR(summary(dir_ + "/focal")["camera_hfov_deg"].get<double>(), 60, 1e-4);

    // Each missing piece is named.
    for (const auto& [args, named] : {std::pair{std::string(" --hfov-deg 60 --mpp 0.5"), "--map: required"},
                                      std::pair{" --hfov-deg 60 --map " + map(), "--mpp: required"},
                                      std::pair{" --mpp 0.5 --map " + map(), "--hfov-deg (or --focal-px with --focal-width): required"},
                                      std::pair{" --mpp 0.5 --focal-px 394 --map " + map(), "--focal-px and --focal-width go together"}}) {
        const auto r = localize(args, 1, dir_ + "/refused");
        EXPECT_EQ(r.code, 1) << args << "\n" << r.output;
        EXPECT_NE(r.output.find(named), std::string::npos) << args << "\n" << r.output;
        if (args.find("--focal-px") == std::string::npos)
            EXPECT_NE(r.output.find(dir_ + "/flight.json is absent"), std::string::npos) << r.output;
    }
}

TEST_F(RealAirFolder, OptionsBesideFlightJsonOverrideItAndSaySo) {
    const auto r = localize(std::string("--map ") + map() + " --hfov-deg 62 --mpp 0.5", 1, dir_ + "/over");
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("note: --hfov-deg 62 overrides flight.json's camera.hfov_deg 60"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("--mpp 0.5 overrides"), std::string::npos) << "an equal value is no override\n" << r.output;
    EXPECT_EQ(summary(dir_ + "/over")["camera_hfov_deg"], 62.0);
}

// The real frames are 454-487 px wide; every other one is resized to 400 px wide here. Before, any
// frame not of flight.json's camera size stopped the run ("would be scored at the wrong scale");
// now each frame's scale comes from its own width and the flight still locks.
TEST_F(RealAirFolder, FramesOfDifferingSizesAreEachScoredAtTheirOwnScale) {
    std::filesystem::remove(dir_ + "/flight.json");
    for (int k = 1; k < 16; k += 2) {
        char name[64];
        std::snprintf(name, sizeof name, "/frame_%05d.png", k);
        const cv::Mat f = cv::imread(dir_ + name, cv::IMREAD_GRAYSCALE);
        ASSERT_GT(f.cols, 450) << name;
        cv::Mat small;
        cv::resize(f, small, cv::Size(400, static_cast<int>(std::lround(f.rows * 400.0 / f.cols))), 0, 0, cv::INTER_AREA);
        ASSERT_TRUE(cv::imwrite(dir_ + name, small));
    }
    int good = 0;
    for (int seed = 1; seed <= 5; ++seed) {
        const std::string out = dir_ + "/loc" + std::to_string(seed);
        const auto r = localize(std::string("--map ") + map() + " " + kOptions, seed, out);
        ASSERT_EQ(r.code, 0) << r.output;
        const auto j = summary(out);
        const double filter = j["filter_mean_error_m"], odometry = j["odometry_mean_error_m"];
        std::cout << "mixed sizes, seed " << seed << ": filter mean " << filter << " m, odometry mean " << odometry << " m\n";
        good += filter <= 0.5 * odometry;
    }
    EXPECT_GE(good, 4);
}

// Rows 5 and 9 get a 20-degree roll in ImuX..W (heading kept), row 14 40 degrees: beyond the
// 10-degree default they are skipped, counted in summary.json and marked in the CSV; row 12 at 8
// degrees is warped and scored. 40 degrees leaves no level view (the nadir is outside a 60-degree
// lens), so it is skipped even under a generous --max-tilt-deg instead of stopping the run.
TEST_F(RealAirFolder, FramesTooObliqueAreSkippedAndCounted) {
    std::ifstream in(dir_ + "/metadata.csv");
    std::string header, line, text;
    std::getline(in, header);
    text = header + "\n";
    std::vector<std::string> names;
    {
        std::stringstream h(header);
        for (std::string c; std::getline(h, c, ',');) names.push_back(c);
    }
    auto col = [&](const std::string& n) { return static_cast<std::size_t>(std::find(names.begin(), names.end(), n) - names.begin()); };
    for (int row = 0; std::getline(in, line); ++row) {
        std::vector<std::string> cells;
        std::stringstream l(line);
        for (std::string c; std::getline(l, c, ',');) cells.push_back(c);
        const double roll_deg = row == 5 || row == 9 ? 20 : row == 12 ? 8 : row == 14 ? 40 : 0;
        if (roll_deg > 0) {
            const trn::sim::Quaternion q{std::stod(cells[col("ImuX")]), std::stod(cells[col("ImuY")]), std::stod(cells[col("ImuZ")]),
                                         std::stod(cells[col("ImuW")])};
            const trn::sim::Quaternion t = trn::sim::attitude_quaternion(trn::sim::heading_from_quaternion(q), roll_deg * kPi / 180);
            cells[col("ImuX")] = std::to_string(t.x), cells[col("ImuY")] = std::to_string(t.y);
            cells[col("ImuZ")] = std::to_string(t.z), cells[col("ImuW")] = std::to_string(t.w);
        }
        for (std::size_t i = 0; i < cells.size(); ++i) text += (i ? "," : "") + cells[i];
        text += "\n";
    }
    in.close();
    std::ofstream(dir_ + "/metadata.csv") << text;

    const auto r = localize("--map " + map(), 1, dir_ + "/tilt");
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("3 of 16 frames are tilted more than 10 deg from nadir (ImuX..W) and will be skipped"), std::string::npos)
        << r.output;
    EXPECT_NE(r.output.find("skipped:      3 frames too oblique to score"), std::string::npos) << r.output;
    const auto j = summary(dir_ + "/tilt");
    EXPECT_EQ(j["frames_too_oblique"], 3);
    EXPECT_EQ(j["frames_missing"], 0);
    const auto rows = csv(dir_ + "/tilt/localization.csv");
    ASSERT_EQ(rows.size(), 16u);
    for (std::size_t k = 0; k < rows.size(); ++k) {
        EXPECT_EQ(rows[k].at("too_oblique"), k == 5 || k == 9 || k == 14 ? "1" : "0") << "row " << k;
        EXPECT_EQ(rows[k].at("frame_missing"), "0") << "row " << k;
        EXPECT_NEAR(std::stod(rows[k].at("tilt_deg")), k == 5 || k == 9 ? 20 : k == 12 ? 8 : k == 14 ? 40 : 0, 1e-3) << "row " << k;
    }
    // A stricter limit skips the 8-degree row as well.
    const auto strict = localize("--map " + map() + " --max-tilt-deg 5", 1, dir_ + "/strict");
    ASSERT_EQ(strict.code, 0) << strict.output;
    EXPECT_EQ(summary(dir_ + "/strict")["frames_too_oblique"], 4);
    const auto generous = localize("--map " + map() + " --max-tilt-deg 60", 1, dir_ + "/generous");
    ASSERT_EQ(generous.code, 0) << generous.output;
    EXPECT_EQ(summary(dir_ + "/generous")["frames_too_oblique"], 1);  // row 14: no level view left
    EXPECT_EQ(csv(dir_ + "/generous/localization.csv")[14].at("too_oblique"), "1");
}
