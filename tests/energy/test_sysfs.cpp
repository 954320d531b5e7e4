// The sysfs sampler against a fake sysfs tree in a temp dir: ina3221 (V x I per channel), an
// ina226 with power1_input, and a RAPL zone whose energy counter wraps.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "trn/error.hpp"
#include "trn/energy/parsers.hpp"
#include "trn/energy/sysfs_sampler.hpp"

namespace trn::energy {
namespace {
namespace fs = std::filesystem;

void put(const fs::path& p, const std::string& v) {
    fs::create_directories(p.parent_path());
    std::ofstream(p) << v << "\n";
}

class FakeSysfs : public ::testing::Test {
protected:
    fs::path root = fs::temp_directory_path() / ("trn_fake_sysfs_" + std::to_string(::getpid()));
    fs::path ina3221 = root / "class/hwmon/hwmon0", ina226 = root / "class/hwmon/hwmon1", rapl = root / "class/powercap/intel-rapl:0";
    void SetUp() override {
        fs::remove_all(root);
        put(ina3221 / "name", "ina3221");
        put(ina3221 / "in1_input", "5000"), put(ina3221 / "curr1_input", "400");
        put(ina3221 / "in2_input", "3300"), put(ina3221 / "curr2_input", "100");
        put(ina226 / "name", "ina226");
        put(ina226 / "power1_input", "2500000"), put(ina226 / "in1_input", "12000"), put(ina226 / "curr1_input", "200");
        put(root / "class/hwmon/hwmon2/name", "coretemp");
        put(root / "class/hwmon/hwmon2/temp1_input", "40000");
        put(rapl / "name", "package-0");
        put(rapl / "energy_uj", "999000000"), put(rapl / "max_energy_range_uj", "1000000000");
    }
    void TearDown() override { fs::remove_all(root); }
};

TEST_F(FakeSysfs, ListsAndFindsSources) {
    const auto all = list_sysfs_sources(root.string());
    ASSERT_EQ(all.size(), 4u);  // ina3221 ch1, ch2, ina226, package-0; coretemp is not a power sensor
    EXPECT_EQ(find_sysfs_source("hwmon:ina3221:2", root.string()).channel, 2);
    EXPECT_EQ(find_sysfs_source("rapl:package-0", root.string()).kind, "rapl");
    EXPECT_EQ(find_sysfs_source("rapl:intel-rapl:0", root.string()).name, "package-0");
    EXPECT_THROW(find_sysfs_source("hwmon:ina219", root.string()), trn::Error);
    EXPECT_THROW(find_sysfs_source("gpio:1", root.string()), trn::Error);
}

TEST_F(FakeSysfs, HwmonVoltageTimesCurrentAndPower) {
    SysfsSampler ch2(find_sysfs_source("hwmon:ina3221:2", root.string()));
    ch2.poll(10.0);
    put(ina3221 / "curr2_input", "300");
    ch2.poll(10.01);
    EXPECT_DOUBLE_EQ(ch2.trace().w[0], 3.3 * 0.1);
    EXPECT_DOUBLE_EQ(ch2.trace().w[1], 3.3 * 0.3);
    SysfsSampler p(find_sysfs_source("hwmon:ina226", root.string()));
    p.poll(1), p.poll(2);
    EXPECT_DOUBLE_EQ(p.trace().w[0], 2.5);  // power1_input (uW) wins over V x I
    EXPECT_THROW(p.poll(2), trn::Error);          // time must move forward
    put(ina226 / "power1_input", "garbage");
    EXPECT_THROW(p.poll(3), trn::Error);
}

TEST_F(FakeSysfs, RaplCounterWrapsAtMaxRange) {
    SysfsSampler s(find_sysfs_source("rapl:package-0", root.string()));
    s.poll(100.0);                              // 999 J
    put(rapl / "energy_uj", "4000000");         // wrapped: 1 J to the top + 4 J
    s.poll(100.5);
    put(rapl / "energy_uj", "9000000");         // +5 J
    s.poll(101.5);
    ASSERT_EQ(s.trace().size(), 2u);
    EXPECT_EQ(s.wraps(), 1u);
    EXPECT_NEAR(s.trace().w[0], 5.0 / 0.5, 1e-9);
    EXPECT_NEAR(s.trace().w[1], 5.0 / 1.0, 1e-9);
    EXPECT_EQ(s.trace().kind, SampleKind::IntervalMean);
    // Written and read back as a trnkit power log, the energy is the counters' 10 J.
    const PowerTrace back = parse_power_log(format_trnkit_power(s.trace()), "sampled.log");
    ASSERT_TRUE(back.first_interval_start.has_value());
    EXPECT_DOUBLE_EQ(*back.first_interval_start, 100.0);
    EXPECT_TRUE(back.wall_clock);
    // A counter stepping back without a range is an error, not a wrap.
    fs::remove(rapl / "max_energy_range_uj");
    SysfsSampler no_range(find_sysfs_source("rapl:package-0", root.string()));
    no_range.poll(1);
    put(rapl / "energy_uj", "1");
    EXPECT_THROW(no_range.poll(2), trn::Error);
}

TEST_F(FakeSysfs, LiveSamplingLoop) {
    const PowerTrace tr = sample_sysfs(find_sysfs_source("hwmon:ina3221:1", root.string()), 0.01, 0.05);
    EXPECT_GE(tr.size(), 5u);
    EXPECT_TRUE(tr.wall_clock);
    for (double w : tr.w) EXPECT_DOUBLE_EQ(w, 2.0);
    EXPECT_THROW(sample_sysfs(find_sysfs_source("hwmon:ina3221:1", root.string()), 0, 1), trn::Error);
}

}  // namespace
}  // namespace trn::energy
