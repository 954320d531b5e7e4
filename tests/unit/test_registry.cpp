#include <gtest/gtest.h>

#include <cstdlib>

#include "trn/registry.hpp"

namespace trn {
namespace {

TEST(Registry, ListsCpuFamiliesAndEveryOtherFamilyByName) {
    const auto status = default_registry().status();
    std::vector<std::string> families;
    for (const auto& s : status) families.push_back(s.family);
    EXPECT_EQ(families, (std::vector<std::string>{"cpu-ref", "cpu", "opencl", "vulkan"}));
    for (const auto& s : status) {
        if (s.devices.empty()) {
            EXPECT_FALSE(s.why_none.empty()) << s.family << " has no devices and no reason";
        }
    }
    const auto names = default_registry().available();
    EXPECT_NE(std::find(names.begin(), names.end(), "cpu-ref"), names.end());
    EXPECT_NE(std::find(names.begin(), names.end(), "cpu"), names.end());
}

TEST(Registry, CreatesByNameIndexAndNameSubstring) {
    EXPECT_EQ(default_registry().create("cpu")->info().name, "cpu");
    EXPECT_EQ(default_registry().create("cpu:0")->info().name, "cpu");
    EXPECT_EQ(default_registry().create("cpu:OPTIMIZED")->info().name, "cpu");
    EXPECT_EQ(default_registry().create("cpu-ref")->info().name, "cpu-ref");
}

TEST(Registry, RefusesClearlyAndNeverFallsBack) {
    auto message = [](const char* spec) {
        try {
            default_registry().create(spec);
        } catch (const BackendUnavailable& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    EXPECT_NE(message("cuda").find("not built into this trnkit"), std::string::npos);
    EXPECT_NE(message("cpu:3").find("out of range"), std::string::npos);
    // An index too big for any integer is out of range too, not a std::stoi exception.
    EXPECT_NE(message("cpu:99999999999999999999").find("device index 99999999999999999999 out of range"), std::string::npos);
    EXPECT_NE(message("cpu:nosuch").find("no cpu device name or driver contains 'nosuch'"), std::string::npos);
}

// Device choice through the family's environment variable, on a registry of two real cpu backends.
TEST(Registry, EnvironmentVariablePicksTheDevice) {
    BackendRegistry r;
    r.add({"pair", "two devices",
           [](std::string&) {
               return std::vector<DeviceInfo>{{"pair:0", "pair", "first", "cpu", "", ""}, {"pair:1", "pair", "second", "cpu", "", ""}};
           },
           [](int index) { return default_registry().create(index == 0 ? "cpu-ref" : "cpu"); }, "TRN_TEST_PAIR_DEVICE"});
    ::setenv("TRN_TEST_PAIR_DEVICE", "second", 1);
    EXPECT_EQ(r.create("pair")->info().name, "cpu");
    EXPECT_EQ(r.create("pair:0")->info().name, "cpu-ref");  // an explicit device wins over the variable
    ::unsetenv("TRN_TEST_PAIR_DEVICE");
    EXPECT_EQ(r.create("pair")->info().name, "cpu-ref");
}

}  // namespace
}  // namespace trn
