// The NVML sampler against fake NVML libraries built by the tests (fake_nvml.cpp): board power,
// the total energy counter, and every failure named (library, symbol, call, device).
#include <gtest/gtest.h>

#include <dlfcn.h>

#include "trn/energy/nvml_sampler.hpp"
#include "trn/energy/parsers.hpp"
#include "trn/error.hpp"

namespace trn::energy {
namespace {

// The fake's control function, from the same library the sampler loads (dlopen shares it).
struct FakeControl {
    void* lib = dlopen(FAKE_NVML, RTLD_NOW | RTLD_LOCAL);
    void (*set)(int, unsigned, unsigned long long, int) = lib ? reinterpret_cast<void (*)(int, unsigned, unsigned long long, int)>(dlsym(lib, "fake_nvml_control")) : nullptr;
    FakeControl() { EXPECT_NE(set, nullptr) << dlerror(); }
    ~FakeControl() {
        if (set) set(0, 0, 0, 0);
        if (lib) dlclose(lib);
    }
};

std::string error_of(const std::function<void()>& f) {
    try {
        f();
    } catch (const Error& e) {
        return e.what();
    }
    return "(no error)";
}

TEST(NvmlSampler, BoardPowerInWatts) {
    FakeControl fake;
    fake.set(1, 42500, 0, 0);
    NvmlSampler s(parse_nvml_spec("nvml:0:power"), FAKE_NVML);
    EXPECT_FALSE(s.energy_counter());
    s.poll(1.0), s.poll(1.5);
    const PowerTrace tr = s.trace();
    ASSERT_EQ(tr.size(), 2u);
    EXPECT_DOUBLE_EQ(tr.w[0], 42.5);
    EXPECT_EQ(tr.kind, SampleKind::Instant);
    EXPECT_NE(s.describe().find("Fake GPU"), std::string::npos) << s.describe();
    EXPECT_THROW(s.poll(1.5), Error);  // time must move forward
}

TEST(NvmlSampler, EnergyCounterGivesIntervalMeansAndIsTheDefault) {
    FakeControl fake;
    fake.set(1, 0, 1000000, 0);
    NvmlSampler s(parse_nvml_spec("nvml"), FAKE_NVML);  // index 0, counter where the GPU has one
    EXPECT_TRUE(s.energy_counter());
    s.poll(10.0);
    fake.set(1, 0, 1000000 + 1500, 0);  // +1.5 J in 0.5 s
    s.poll(10.5);
    fake.set(1, 0, 1000000 + 1500 + 2000, 0);  // +2 J in 1 s
    s.poll(11.5);
    PowerTrace tr = s.trace();
    ASSERT_EQ(tr.size(), 2u);
    EXPECT_EQ(tr.kind, SampleKind::IntervalMean);
    EXPECT_NEAR(tr.w[0], 3.0, 1e-12);
    EXPECT_NEAR(tr.w[1], 2.0, 1e-12);
    ASSERT_TRUE(tr.first_interval_start);
    // Written and read back as a power log, the whole trace integrates to the counter's 3.5 J.
    tr.wall_clock = true;
    const PowerTrace back = parse_power_log(format_trnkit_power(tr), "nvml.log");
    EXPECT_NEAR(back.w[0] * 0.5 + back.w[1] * 1.0, 3.5, 1e-9);
    fake.set(1, 0, 5, 0);  // a counter that steps back is a fault, named
    const std::string why = error_of([&] { s.poll(12); });
    EXPECT_NE(why.find("stepped back"), std::string::npos) << why;
}

TEST(NvmlSampler, FailuresNameLibrarySymbolCallAndDevice) {
    std::string why = error_of([] { NvmlSampler(parse_nvml_spec("nvml:0"), "/nonexistent/libnvidia-ml.so.1"); });
    EXPECT_NE(why.find("nvml: cannot load '/nonexistent/libnvidia-ml.so.1'"), std::string::npos) << why;
    why = error_of([] { NvmlSampler(parse_nvml_spec("nvml:3"), FAKE_NVML); });
    EXPECT_NE(why.find("nvml:3: no such GPU"), std::string::npos) << why;
    why = error_of([] { NvmlSampler(parse_nvml_spec("nvml:0:energy"), FAKE_NVML_NO_ENERGY); });
    EXPECT_NE(why.find("does not export nvmlDeviceGetTotalEnergyConsumption"), std::string::npos) << why;
    {
        NvmlSampler power_only(parse_nvml_spec("nvml:0"), FAKE_NVML_NO_ENERGY);  // falls back to board power
        EXPECT_FALSE(power_only.energy_counter());
    }
    FakeControl fake;
    fake.set(1, 1000, 0, 999);
    why = error_of([] { NvmlSampler(parse_nvml_spec("nvml:0:power"), FAKE_NVML); });
    EXPECT_NE(why.find("nvmlDeviceGetPowerUsage"), std::string::npos) << why;
    EXPECT_NE(why.find("Fake failure"), std::string::npos) << why;  // nvmlErrorString's text
    why = error_of([] { make_power_sampler("nvml:0:joules", {}); });
    EXPECT_NE(why.find("power or energy"), std::string::npos) << why;
    why = error_of([] { make_power_sampler("gpu:0", {}); });
    EXPECT_NE(why.find("nvml:INDEX"), std::string::npos) << why;
    // A library that is not NVML at all: the missing entry point is named.
    why = error_of([] { NvmlSampler(parse_nvml_spec("nvml"), "libm.so.6"); });
    EXPECT_NE(why.find("does not export nvmlInit_v2"), std::string::npos) << why;
}

TEST(NvmlSampler, ListedWithItsReadings) {
    SamplerOptions o;
    o.sysfs_root = "/nonexistent-sysfs", o.nvml_library = FAKE_NVML;
    auto all = list_power_sources(o);
    ASSERT_EQ(all.size(), 1u);
    EXPECT_EQ(all[0], "nvml:0 Fake GPU (CPU-driven) (board power, energy counter)");
    o.nvml_library = "/nonexistent/libnvidia-ml.so.1";
    all = list_power_sources(o);
    ASSERT_EQ(all.size(), 1u);
    EXPECT_EQ(all[0].rfind("nvml: not available (nvml: cannot load", 0), 0u) << all[0];
}

}  // namespace
}  // namespace trn::energy
