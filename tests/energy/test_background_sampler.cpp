// The sampler thread on a fake sysfs tree: it polls on the chosen clock while the caller works,
// and a source that fails mid-run is reported by stop(), naming the file.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <thread>

#include "trn/energy/background_sampler.hpp"
#include "trn/error.hpp"

namespace trn::energy {
namespace {
namespace fs = std::filesystem;

struct FakeHwmon {
    fs::path root = fs::temp_directory_path() / ("trn_bg_sysfs_" + std::to_string(::getpid()));
    fs::path chip = root / "class/hwmon/hwmon0";
    FakeHwmon() {
        fs::remove_all(root);
        fs::create_directories(chip);
        std::ofstream(chip / "name") << "ina226\n";
        std::ofstream(chip / "power1_input") << "2500000\n";  // 2.5 W
    }
    ~FakeHwmon() { fs::remove_all(root); }
};

TEST(BackgroundSampler, PollsOnTheMonotonicClockWhileTheCallerWorks) {
    FakeHwmon fake;
    SamplerOptions o;
    o.sysfs_root = fake.root.string();
    auto s = make_power_sampler("hwmon:ina226", o);
    const double before = clock_seconds(SampleClock::Monotonic);
    BackgroundSampler live(*s, 0.002, SampleClock::Monotonic);
    std::this_thread::sleep_for(std::chrono::milliseconds(60));
    const PowerTrace tr = live.stop();
    const double after = clock_seconds(SampleClock::Monotonic);
    EXPECT_GE(tr.size(), 10u);  // 30 due in 60 ms; a loaded machine may skip some
    EXPECT_FALSE(tr.wall_clock);
    EXPECT_GE(tr.t.front(), before);
    EXPECT_LE(tr.t.back(), after);
    EXPECT_GE(tr.t.back() - tr.t.front(), 0.06);
    for (std::size_t i = 0; i < tr.size(); ++i) {
        EXPECT_DOUBLE_EQ(tr.w[i], 2.5);
        if (i) {
            EXPECT_GT(tr.t[i], tr.t[i - 1]);
        }
    }
}

TEST(BackgroundSampler, StopsAtOnceWhateverThePeriod) {
    FakeHwmon fake;
    SamplerOptions o;
    o.sysfs_root = fake.root.string();
    auto s = make_power_sampler("hwmon:ina226", o);
    const auto start = std::chrono::steady_clock::now();
    BackgroundSampler live(*s, 30.0, SampleClock::Monotonic);  // a slow logger: one poll per 30 s
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    const PowerTrace tr = live.stop();
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 5.0) << "stop() waited for the period";
    ASSERT_EQ(tr.size(), 2u);  // the first poll and the one after the caller's work
    EXPECT_GE(tr.t[1] - tr.t[0], 0.02);
}

TEST(BackgroundSampler, ASourceFailingMidRunIsReportedByStop) {
    FakeHwmon fake;
    SamplerOptions o;
    o.sysfs_root = fake.root.string();
    auto s = make_power_sampler("hwmon:ina226", o);
    BackgroundSampler live(*s, 0.002, SampleClock::Realtime);
    std::ofstream(fake.chip / "power1_input") << "garbage\n";
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    try {
        live.stop();
        FAIL() << "stop() should rethrow the sampler's error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("power1_input"), std::string::npos) << e.what();
    }
    // The first poll happens in the constructor: a dead source fails before any work.
    EXPECT_THROW(BackgroundSampler(*s, 0.002, SampleClock::Realtime), Error);
    EXPECT_THROW(BackgroundSampler(*s, 0, SampleClock::Realtime), Error);
}

}  // namespace
}  // namespace trn::energy
