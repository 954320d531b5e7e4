// `--odometry` of `trnkit demo` (simulated | visual) and `trnkit localize` (folder | visual), as a
// user runs them (real processes, issue 17 item 4): a value that is not a choice fails before any
// work with one line naming the option; the odometry that ran is in summary.json and in each row
// of the per-step CSV (last column, odometry_source), and the visual one is computed from the frames.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "../cli/cli_process.hpp"

namespace {

using trn::test::run_trnkit;

class OdometryOptionCli : public testing::Test {
protected:
    void SetUp() override {
        dir_ = (std::filesystem::temp_directory_path() / ("trnkit_odometry_option_" + std::to_string(::getpid()))).string();
        std::filesystem::remove_all(dir_);
        std::filesystem::create_directories(dir_);
    }
    void TearDown() override { std::filesystem::remove_all(dir_); }
    static nlohmann::json summary(const std::string& out) {
        std::ifstream in(out + "/summary.json");
        return nlohmann::json::parse(in);
    }
    // The last cell of every data row of the per-step CSV, after checking the header names it.
    static std::vector<std::string> sources(const std::string& out) {
        std::ifstream in(out + "/localization.csv");
        std::string line;
        std::getline(in, line);
        EXPECT_EQ(line.substr(line.rfind(',') + 1), "odometry_source");
        std::vector<std::string> cells;
        while (std::getline(in, line)) cells.push_back(line.substr(line.rfind(',') + 1));
        return cells;
    }
    static void expect_one_line_naming(const trn::test::CliResult& r, const std::string& option) {
        EXPECT_NE(r.code, 0) << r.output;
        EXPECT_NE(r.output.find(option), std::string::npos) << r.output;
        EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
    }
    std::string dir_;
};

TEST_F(OdometryOptionCli, AValueThatIsNoChoiceIsRefusedByName) {
    expect_one_line_naming(run_trnkit("demo --odometry optical --out " + dir_ + "/d"), "--odometry");
    expect_one_line_naming(run_trnkit("localize --dataset " + dir_ + " --odometry simulated"), "--odometry");  // demo's choice, not localize's
    expect_one_line_naming(run_trnkit("demo --odometry folder --out " + dir_ + "/d"), "--odometry");         // localize's, not demo's
    EXPECT_FALSE(std::filesystem::exists(dir_ + "/d"));
}

TEST_F(OdometryOptionCli, DemoRunsOnVisualOdometryAndSaysSo) {
    const std::string common = "demo --scenario FL-200 --distance-km 0.1 --rate 2 --template-width 64 --backend cpu --no-plots --seed 3 --out ";
    const auto visual = run_trnkit(common + dir_ + "/visual --odometry visual");
    ASSERT_EQ(visual.code, 0) << visual.output;
    EXPECT_NE(visual.output.find("visual odometry: "), std::string::npos) << visual.output;
    const nlohmann::json j = summary(dir_ + "/visual");
    EXPECT_EQ(j["odometry"].get<std::string>().rfind("visual", 0), 0u) << j["odometry"];
    const auto cells = sources(dir_ + "/visual");
    ASSERT_GE(cells.size(), 10u);
    EXPECT_EQ(cells.front(), "visual:start");
    for (std::size_t i = 1; i < cells.size(); ++i) EXPECT_EQ(cells[i], "visual:features") << "row " << i;
    EXPECT_EQ(j["visual_odometry_feature_steps"].get<double>(), cells.size() - 1.0);
    // Straight line at 200 m, ~100 m: the VO track stays within metres, the simulated drift (3 % scale) does not matter here.
    EXPECT_LT(j["odometry_final_error_m"].get<double>(), 2.0);

    const auto simulated = run_trnkit(common + dir_ + "/simulated");  // the default
    ASSERT_EQ(simulated.code, 0) << simulated.output;
    EXPECT_EQ(summary(dir_ + "/simulated")["odometry"], "simulated");
    for (const std::string& c : sources(dir_ + "/simulated")) EXPECT_EQ(c, "simulated");
}

TEST_F(OdometryOptionCli, LocalizeRunsOnVisualOdometryOfAnAirFolder) {
    const std::string air = dir_ + "/air";
    const auto sim = run_trnkit("simulate --scenario FR-200 --frames 150 --size-m 800 --map-year 2010 --out " + air);
    ASSERT_EQ(sim.code, 0) << sim.output;
    const std::string common = "localize --dataset " + air + " --backend cpu --max-particles 300 --template-width 64 --no-plots --seed 3 --out ";
    const auto visual = run_trnkit(common + air + "/visual --odometry visual");
    ASSERT_EQ(visual.code, 0) << visual.output;
    EXPECT_EQ(summary(air + "/visual")["odometry"].get<std::string>().rfind("visual", 0), 0u);
    const auto cells = sources(air + "/visual");
    ASSERT_EQ(cells.size(), 15u);
    // These low-contrast forest frames give ORB only 1-2 matches: phase correlation carries the
    // steps (docs/RESULTS.md "Visual odometry"); no step may be lost.
    for (std::size_t i = 1; i < cells.size(); ++i) EXPECT_TRUE(cells[i] == "visual:features" || cells[i] == "visual:phase") << "row " << i << ": " << cells[i];
    const nlohmann::json j = summary(air + "/visual");
    EXPECT_EQ(j["visual_odometry_lost_steps"].get<double>(), 0);
    std::printf("localize --odometry visual: %g steps by features, %g by phase, final odometry error %.2f m\n",
                j["visual_odometry_feature_steps"].get<double>(), j["visual_odometry_phase_steps"].get<double>(), j["odometry_final_error_m"].get<double>());
    EXPECT_LT(j["odometry_final_error_m"].get<double>(), 1.0);
    const auto folder = run_trnkit(common + air + "/folder");
    ASSERT_EQ(folder.code, 0) << folder.output;
    EXPECT_EQ(summary(air + "/folder")["odometry"], "folder");
    for (const std::string& c : sources(air + "/folder")) EXPECT_EQ(c, "folder");
}

}  // namespace
