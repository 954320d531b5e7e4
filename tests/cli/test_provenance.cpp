// Every JSON file the tools write names the trnkit version and git commit that wrote it (issue 13
// item 6), and the readers still take files written before these fields existed. Real processes,
// small inputs (seconds). `energy bench` is checked in tests/energy/test_bench_cli.cpp (it needs
// the fake NVML library built there).
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "../energy/synthetic_run.hpp"
#include "cli_process.hpp"
#include "trn/build_info.hpp"
#include "trn/energy/markers.hpp"
#include "trn/energy/parsers.hpp"

namespace {
namespace fs = std::filesystem;
using nlohmann::json;
using trn::test::run_trnkit;

json read_json(const fs::path& p) {
    std::ifstream f(p);
    return json::parse(f);
}

void write_json(const fs::path& p, const json& j) { std::ofstream(p) << j.dump(1) << "\n"; }

// The fields as this build of the library reports them (not a hard-coded version).
void expect_provenance(const fs::path& file) {
    SCOPED_TRACE(file.string());
    ASSERT_TRUE(fs::exists(file));
    const json j = read_json(file);
    ASSERT_TRUE(j.contains("trnkit_version"));
    ASSERT_TRUE(j.contains("git_commit"));
    EXPECT_EQ(j["trnkit_version"], std::string(trn::build_info().version));
    EXPECT_EQ(j["git_commit"], std::string(trn::build_info().git_commit));
    EXPECT_FALSE(j["trnkit_version"].get<std::string>().empty());
}

// A file as written before the provenance fields: the same file without them.
void strip_provenance(const fs::path& file) {
    json j = read_json(file);
    j.erase("trnkit_version");
    j.erase("git_commit");
    write_json(file, j);
}

class Provenance : public testing::Test {
protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() / ("trnkit_provenance_" + std::to_string(::getpid()));
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }
    std::string path(const std::string& name) const { return (dir_ / name).string(); }
    void simulate(const std::string& name) {
        const auto r = run_trnkit("simulate --scenario FC-300 --size-m 900 --frames 4 --out " + path(name));
        ASSERT_EQ(r.code, 0) << r.output;
    }
    // A synthetic power log (busy at `busy_w`) and its markers; `energy integrate` of them as `platform`.
    void integrate(const std::string& platform, double busy_w) {
        using namespace trn::energy;
        const test::Timeline tl = test::make_timeline(8, 0.05, 0.05);
        std::ofstream(path("markers.csv")) << format_markers(tl.markers);
        const PowerTrace tr = test::sample_trace(tl.markers, test::TraceClock{}, tl.t0 - 0.2, tl.t0 + 2.5, 1e-3, 1.5, busy_w, 0, true);
        std::ofstream(path(platform + ".log")) << format_trnkit_power(tr);
        const auto r = run_trnkit("energy integrate " + path(platform + ".log") + " --markers " + path("markers.csv") + " --platform " + platform +
                                  " --json " + path(platform + ".json"));
        ASSERT_EQ(r.code, 0) << r.output;
    }
    fs::path dir_;
};

TEST_F(Provenance, SimulateFlightJsonAndAnOldOneStillReads) {
    simulate("flight");
    expect_provenance(path("flight") + "/flight.json");
    strip_provenance(path("flight") + "/flight.json");
    const auto r = run_trnkit("simulate --read " + path("flight"));
    EXPECT_EQ(r.code, 0) << r.output;
}

TEST_F(Provenance, LocalizeSummaryJson) {
    simulate("flight");
    const auto r = run_trnkit("localize --dataset " + path("flight") + " --backend cpu --no-plots --out " + path("result"));
    ASSERT_EQ(r.code, 0) << r.output;
    expect_provenance(path("result") + "/summary.json");
}

TEST_F(Provenance, EnergyRunReportsAndComparisonAndOldReportsStillRead) {
    integrate("alpha", 2.0);
    integrate("beta", 3.0);
    expect_provenance(path("alpha.json"));
    expect_provenance(path("beta.json"));
    strip_provenance(path("beta.json"));  // compare reads a report from before the fields
    const auto r = run_trnkit("energy compare " + path("alpha.json") + " " + path("beta.json") + " --no-plots -o " + path("cmp"));
    ASSERT_EQ(r.code, 0) << r.output;
    expect_provenance(path("cmp") + "/summary.json");
}

TEST_F(Provenance, ExperimentJobFile) {
    const auto r = run_trnkit("experiment sampling --quick --backend cpu --no-plots --out " + path("exp") + " --job kld-3 --no-merge");
    ASSERT_EQ(r.code, 0) << r.output;
    expect_provenance(path("exp") + "/jobs/kld-3.json");
}

}  // namespace
