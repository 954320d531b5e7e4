// `--backend fastest` picks by a fixed preference order, never by which device won a timing race,
// so two runs on one machine score on the same backend.
#include <gtest/gtest.h>

#include "trn/filter/backend_choice.hpp"
#include "trn/registry.hpp"

namespace trn::filter {
namespace {

DeviceInfo device(const std::string& name, const std::string& family, const std::string& type) {
    DeviceInfo d;
    d.name = name, d.family = family, d.type = type;
    return d;
}

TEST(BackendChoice, GpuFirstThenCpuThenOtherDevicesAndTheOracleLast) {
    const std::vector<DeviceInfo> devices = {device("cpu-ref", "cpu-ref", "cpu"), device("opencl:0", "opencl", "cpu"),
                                             device("vulkan:0", "vulkan", "cpu"),  device("cpu", "cpu", "cpu"),
                                             device("vulkan:1", "vulkan", "gpu"),  device("opencl:1", "opencl", "gpu")};
    EXPECT_EQ(BackendRegistry::preferred_order(devices), (std::vector<std::string>{"opencl:1", "vulkan:1", "cpu", "opencl:0", "vulkan:0"}));
    // The same devices listed in another order give the same preference.
    std::vector<DeviceInfo> reversed(devices.rbegin(), devices.rend());
    EXPECT_EQ(BackendRegistry::preferred_order(reversed), BackendRegistry::preferred_order(devices));
    EXPECT_EQ(BackendRegistry::preferred_order({device("cpu-ref", "cpu-ref", "cpu")}), std::vector<std::string>{"cpu-ref"});
}

TEST(BackendChoice, FastestIsTheSameBackendEveryTime) {
    std::vector<BackendTiming> timings;
    const std::string first = create_fastest_backend({}, &timings)->info().name;
    ASSERT_FALSE(timings.empty());
    for (int i = 0; i < 2; ++i) EXPECT_EQ(create_fastest_backend({})->info().name, first);
    // The registry's own "fastest" follows the same order (without the timing batch).
    EXPECT_EQ(default_registry().create("fastest")->info().name, first);
}

}  // namespace
}  // namespace trn::filter
