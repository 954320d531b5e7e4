// Issue 14 item 3: exact scoring makes a localization run the same on every backend. One short
// simulated flight (20 frames) is localized with one seed on cpu-ref, cpu, OpenCL and Vulkan (real
// processes); summary.json minus the backend/device/timing fields and the per-step CSV minus its
// timing columns must be identical. A family without a device is skipped by name (NOT AVAILABLE).
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "../cli/cli_process.hpp"
#include "trn/error.hpp"
#include "trn/registry.hpp"

namespace {

using trn::test::run_trnkit;

const std::filesystem::path& work_dir() {
    static const std::filesystem::path d =
        std::filesystem::temp_directory_path() / ("trnkit_identical_flights_" + std::to_string(::getpid()));
    return d;
}

// Localizes the shared flight on `backend` into work_dir()/backend; returns the CLI output on failure.
std::string localize(const std::string& backend) {
    const std::string out = (work_dir() / backend).string();
    std::filesystem::remove_all(out);
    const auto r = run_trnkit("localize --dataset " + (work_dir() / "flight").string() + " --backend " + backend +
                              " --rate 50 --template-width 64 --max-particles 400 --min-particles 100 --seed 3 --no-plots --out " +
                              out);
    return r.code == 0 ? "" : r.output;
}

// summary.json without what legitimately differs between backends: which one ran, and timings.
nlohmann::json comparable_summary(const std::string& backend) {
    std::ifstream in(work_dir() / backend / "summary.json");
    nlohmann::json j = nlohmann::json::parse(in);
    for (const char* key : {"backend", "backend_requested", "device", "frames_per_second"}) j.erase(key);
    for (auto it = j.begin(); it != j.end();) it = it.key().ends_with("_ms") ? j.erase(it) : std::next(it);
    return j;
}

// The per-step CSV without its timing columns (score_ms, step_ms).
std::vector<std::string> comparable_rows(const std::string& backend) {
    std::ifstream in(work_dir() / backend / "localization.csv");
    std::vector<std::string> rows;
    std::vector<bool> keep;
    std::string line;
    while (std::getline(in, line)) {
        std::stringstream ss(line);
        std::string cell, row;
        for (std::size_t c = 0; std::getline(ss, cell, ','); ++c) {
            if (rows.empty()) keep.push_back(!cell.ends_with("_ms"));
            if (c < keep.size() && keep[c]) row += cell + ",";
        }
        rows.push_back(row);
    }
    return rows;
}

class IdenticalFlights : public testing::TestWithParam<const char*> {
protected:
    static void SetUpTestSuite() {
        std::filesystem::remove_all(work_dir());
        std::filesystem::create_directories(work_dir());
        const auto sim = run_trnkit("simulate --scenario FR-200 --seed 7 --frames 20 --out " + (work_dir() / "flight").string());
        if (sim.code != 0) {  // checked in SetUp: a failure here shows each test as SKIPPED, and ctest counts it so
            setup_failure_ = "simulate failed: " + sim.output;
            return;
        }
        reference_error_ = localize("cpu-ref");
    }
    void SetUp() override { ASSERT_EQ(setup_failure_, ""); }
    static inline std::string setup_failure_;
    static void TearDownTestSuite() { std::filesystem::remove_all(work_dir()); }
    static std::string reference_error_;
};
std::string IdenticalFlights::reference_error_;

TEST_P(IdenticalFlights, SameSummaryAndStepsAsCpuRef) {
    const std::string backend = GetParam();
    try {
        trn::default_registry().create(backend);
    } catch (const trn::BackendUnavailable& e) {
        GTEST_SKIP() << backend << " NOT AVAILABLE: " << e.what();
    }
    ASSERT_TRUE(std::filesystem::exists(work_dir() / "flight" / "metadata.csv")) << "the simulated flight is missing";
    ASSERT_EQ(reference_error_, "") << "cpu-ref run failed";
    ASSERT_EQ(localize(backend), "");
    const nlohmann::json want = comparable_summary("cpu-ref"), got = comparable_summary(backend);
    ASSERT_GT(want.at("steps").get<double>(), 10.0) << "the flight should have steps to compare";
    EXPECT_EQ(got, want) << "differences: " << nlohmann::json::diff(want, got).dump();
    const auto want_rows = comparable_rows("cpu-ref"), got_rows = comparable_rows(backend);
    ASSERT_EQ(got_rows.size(), want_rows.size());
    for (std::size_t i = 0; i < want_rows.size(); ++i) EXPECT_EQ(got_rows[i], want_rows[i]) << "localization.csv line " << i + 1;
}

INSTANTIATE_TEST_SUITE_P(EveryBackend, IdenticalFlights, testing::Values("cpu", "opencl", "vulkan"),
                         [](const testing::TestParamInfo<const char*>& i) { return std::string(i.param); });

}  // namespace
