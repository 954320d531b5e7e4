// `--backend fastest` (BackendRegistry::create_fastest) picks by a fixed preference order, never by
// which device won a timing race, so two runs on one machine score on the same backend; the timing
// batch runs only when a caller asks for the timings.
#include <gtest/gtest.h>

#include "trn/registry.hpp"

namespace trn {
namespace {

DeviceInfo device(const std::string& name, const std::string& family, const std::string& type) {
    DeviceInfo d;
    d.name = name, d.family = family, d.type = type;
    return d;
}

TEST(FastestBackend, GpuFirstThenCpuThenOtherDevicesAndTheOracleLast) {
    const std::vector<DeviceInfo> devices = {device("cpu-ref", "cpu-ref", "cpu"), device("opencl:0", "opencl", "cpu"),
                                             device("vulkan:0", "vulkan", "cpu"),  device("cpu", "cpu", "cpu"),
                                             device("vulkan:1", "vulkan", "gpu"),  device("opencl:1", "opencl", "gpu")};
    EXPECT_EQ(BackendRegistry::preferred_order(devices), (std::vector<std::string>{"opencl:1", "vulkan:1", "cpu", "opencl:0", "vulkan:0"}));
    // The same devices listed in another order give the same preference.
    std::vector<DeviceInfo> reversed(devices.rbegin(), devices.rend());
    EXPECT_EQ(BackendRegistry::preferred_order(reversed), BackendRegistry::preferred_order(devices));
    EXPECT_EQ(BackendRegistry::preferred_order({device("cpu-ref", "cpu-ref", "cpu")}), std::vector<std::string>{"cpu-ref"});
}

TEST(FastestBackend, FastestIsTheSameBackendEveryTime) {
    std::vector<BackendTiming> timings;
    const std::string first = default_registry().create_fastest({}, &timings)->info().name;
    ASSERT_FALSE(timings.empty());
    EXPECT_EQ(timings.front().name, first);  // the first candidate timed is the one chosen
    for (const BackendTiming& t : timings) EXPECT_GT(t.score_ms, 0) << t.name;
    for (int i = 0; i < 2; ++i) EXPECT_EQ(default_registry().create_fastest()->info().name, first);
    // "fastest" as a spec is the same choice (without the timing batch).
    EXPECT_EQ(default_registry().create("fastest")->info().name, first);
}

// Without timings nothing but the chosen backend is created (no other device is built or timed).
TEST(FastestBackend, TimesNothingUnlessAsked) {
    BackendRegistry r;
    int created = 0;
    auto family = [&](std::string name, std::string type) {
        return BackendFamily{name, "test",
                             [name, type](const BackendOptions&, std::string&) {
                                 return std::vector<DeviceInfo>{{name + ":0", name, "dev", type, "", ""}};
                             },
                             [&created](int, const BackendOptions&) {
                                 ++created;
                                 return default_registry().create("cpu-ref");
                             }};
    };
    r.add(family("opencl", "gpu"));
    r.add(family("vulkan", "gpu"));
    EXPECT_EQ(r.create_fastest()->info().name, "cpu-ref");
    EXPECT_EQ(created, 1);
    std::vector<BackendTiming> timings;
    r.create_fastest({}, &timings);
    EXPECT_EQ(created, 3);
    ASSERT_EQ(timings.size(), 2u);
    EXPECT_EQ(timings[0].name, "opencl:0");
    EXPECT_EQ(timings[1].name, "vulkan:0");
}

}  // namespace
}  // namespace trn
