// The energy JSON writers go through the one JSON text rule (trn/io/outside_text.hpp, issue 45 /
// 46): a log in a folder whose name is not UTF-8 (its path is in the run report, its notes and
// provenance) made nlohmann's dump() throw after the work was done, exit 2 and no run.json.
// Now every byte that is not UTF-8 becomes U+FFFD, as in localize's summary.json.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "../cli/cli_process.hpp"

namespace {

TEST(EnergyJsonText, ALogInAFolderWhoseNameIsNotUtf8IsReportedWithReplacementCharacters) {
    const std::string dir = testing::TempDir() + "/energy_json_text_" + std::to_string(::getpid()) + "_\xff\xfe";
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    {
        std::ofstream log(dir + "/power.csv");
        log << "time_s,power_W\n";
        for (int k = 0; k <= 40; ++k) log << k * 0.05 << "," << (k >= 10 && k < 20 ? 5.0 : 1.0) << "\n";
        std::ofstream(dir + "/markers.csv") << "frame,start_s,end_s\n1,0.5,1.0\n";
    }
    const std::string q = "'" + dir + "'";
    const auto r = trn::test::run_trnkit("energy integrate " + q + "/power.csv --markers " + q + "/markers.csv --platform box --json " + q +
                                         "/run.json --csv " + q + "/run.csv");
    EXPECT_EQ(r.code, 0) << r.output;
    std::ifstream in(dir + "/run.json");
    ASSERT_TRUE(in.good()) << "no run.json:\n" << r.output;
    std::stringstream text;
    text << in.rdbuf();
    EXPECT_NE(text.str().find("_\xEF\xBF\xBD\xEF\xBF\xBD/power.csv"), std::string::npos) << "the log's path with U+FFFD per byte\n" << text.str();
    EXPECT_EQ(text.str().find('\xff'), std::string::npos);
    std::filesystem::remove_all(dir);
}

}  // namespace
