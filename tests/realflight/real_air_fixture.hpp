#pragma once
// The 16 real frames as an AIR folder (`trnkit register --verify --air-out` from the committed
// poses), built once (see base()) and copied per test, so each test can take flight.json
// away, resize frames or tilt rows. Skipped (visibly) without the shared data.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "../cli/cli_process.hpp"
#include "../common/csv_rows.hpp"
#include "../common/shared_data.hpp"

namespace trn::test {

class RealAirFolder : public testing::Test {
protected:
    static std::string data() {
        return trn::test::shared_data_dir().string();
    }
    // Built once per trnkit executable and shared by the test processes (ctest runs each test in
    // its own): `register` takes ~15 s on a loaded machine. Keyed by the executable's time stamp so
    // a rebuilt trnkit builds it again; staged under a private name and renamed into place whole.
    static std::string base() {
        const auto stamp = std::filesystem::last_write_time(TRNKIT_EXE).time_since_epoch().count();
        return testing::TempDir() + "/trnkit_real_air_base_" + std::to_string(stamp);
    }
    static inline std::string setup_failure_;
    static void SetUpTestSuite() {
        if (data().empty() || !std::filesystem::exists(data() + "/realflight/frame_00000.png")) return;
        if (std::filesystem::exists(base() + "/metadata.csv")) return;
        const std::string partial = base() + ".partial-" + std::to_string(::getpid());
        std::filesystem::remove_all(partial);
        const auto r = run_trnkit("register --map " + data() + "/orthophoto.png --verify " + TRN_POSES_CSV + " --air-out " + partial + " " +
                                  data() + "/realflight/frame_000*.png");
        if (r.code != 0) {  // checked in SetUp: a failure here shows each test as SKIPPED, and ctest counts it so
            setup_failure_ = "register failed: " + r.output;
            return;
        }
        std::error_code ec;
        std::filesystem::rename(partial, base(), ec);  // another process may have won the race: then its copy is used
        std::filesystem::remove_all(partial, ec);
    }
    void SetUp() override {
        if (data().empty() || !std::filesystem::exists(data() + "/realflight/frame_00000.png"))
            GTEST_SKIP() << "TRN_SHARED_DATA/realflight not found: real flight unavailable";
        ASSERT_EQ(setup_failure_, "");
        ASSERT_TRUE(std::filesystem::exists(base() + "/metadata.csv")) << base() << ": the registered AIR folder is missing";
        std::string name = testing::UnitTest::GetInstance()->current_test_info()->name();
        std::replace(name.begin(), name.end(), '/', '_');  // a parameterised test's name has a slash
        dir_ = testing::TempDir() + "/real_air_" + name + "_" + std::to_string(::getpid());
        std::filesystem::remove_all(dir_);
        std::filesystem::copy(base(), dir_, std::filesystem::copy_options::recursive);
    }
    void TearDown() override {
        if (!dir_.empty()) std::filesystem::remove_all(dir_);
    }
    std::string map() const { return data() + "/orthophoto.png"; }
    // localize on cpu at one step per frame (the folder is written at 0.5 fps).
    CliResult localize(const std::string& extra, int seed, const std::string& out) const {
        return run_trnkit("localize --dataset " + dir_ + " --rate 0.5 --no-plots --backend cpu --init-radius-m 50 --seed " +
                          std::to_string(seed) + " --out " + out + " " + extra);
    }
    static nlohmann::json summary(const std::string& out) {
        std::ifstream in(out + "/summary.json");
        return nlohmann::json::parse(in);
    }
    // The per-step CSV as rows of named cells.
    static std::vector<std::map<std::string, std::string>> csv(const std::string& path) { return read_csv_rows(path); }
    std::string dir_;
};

// A number as the CLI's CSV prints it (10 significant digits), to compare a library run with it.
inline std::string ten_digits(double v) {
    std::ostringstream os;
    os.precision(10);
    os << v;
    return os.str();
}

}  // namespace trn::test
