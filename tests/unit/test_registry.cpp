#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>

#include "trn/registry.hpp"

namespace trn {
namespace {

TEST(Registry, ListsCpuFamiliesAndEveryOtherFamilyByName) {
    const auto status = default_registry().status();
    std::vector<std::string> families;
    for (const auto& s : status) families.push_back(s.family);
    EXPECT_EQ(families, (std::vector<std::string>{"cpu-ref", "cpu", "opencl", "vulkan", "cuda"}));
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
    EXPECT_NE(message("metal").find("not built into this trnkit"), std::string::npos);
    // A family this build lists is refused with its reason: "built without CUDA (...)", or why the
    // driver offers no device (tests/cuda checks the reasons).
    const std::vector<std::string> names = default_registry().available();
    if (std::none_of(names.begin(), names.end(), [](const std::string& n) { return n.starts_with("cuda:"); })) {
        EXPECT_NE(message("cuda").find("backend 'cuda' is not available: "), std::string::npos) << message("cuda");
    }
    EXPECT_NE(message("cpu:3").find("out of range"), std::string::npos);
    // An index too big for any integer is out of range too, not a std::stoi exception.
    EXPECT_NE(message("cpu:99999999999999999999").find("device index 99999999999999999999 out of range"), std::string::npos);
    EXPECT_NE(message("cpu:nosuch").find("no cpu device name or driver contains 'nosuch'"), std::string::npos);
    // "opencl:" names no device (issue 23, finding 8): refused, not read as the first device.
    EXPECT_NE(message("cpu:").find("backend 'cpu:': empty device after ':'"), std::string::npos);
    EXPECT_NE(message("opencl:").find("empty device after ':'"), std::string::npos);
}

// Device choice through BackendOptions::default_device, on a registry of two real cpu backends;
// the library reads no environment variable (a variable of the old name changes nothing).
TEST(Registry, DefaultDeviceOptionPicksTheDevice) {
    BackendRegistry r;
    r.add({"pair", "two devices",
           [](const BackendOptions&, std::string&) {
               return std::vector<DeviceInfo>{{"pair:0", "pair", "first", "cpu", "", ""}, {"pair:1", "pair", "second", "cpu", "", ""}};
           },
           [](int index, const BackendOptions&) { return default_registry().create(index == 0 ? "cpu-ref" : "cpu"); }});
    BackendOptions second;
    second.default_device["pair"] = "second";
    EXPECT_EQ(r.create("pair", second)->info().name, "cpu");
    EXPECT_EQ(r.create("pair:0", second)->info().name, "cpu-ref");  // an explicit device wins over the option
    EXPECT_EQ(r.create("pair")->info().name, "cpu-ref");
    ::setenv("TRN_VULKAN_DEVICE", "99", 1);  // was read by the library before; now only the CLI reads it
    EXPECT_NO_THROW(r.create("pair"));
    ::unsetenv("TRN_VULKAN_DEVICE");
}

// Options reach the backend by value and are checked there, naming the field.
TEST(Registry, CpuOptionsAreCheckedAndUsed) {
    BackendOptions o;
    o.cpu.threads = 3;
    EXPECT_NE(default_registry().create("cpu", o)->info().details.find("3 threads"), std::string::npos);
    o.cpu.threads = -1;
    try {
        default_registry().create("cpu", o);
        ADD_FAILURE() << "cpu.threads = -1 accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("BackendOptions.cpu.threads = -1"), std::string::npos) << e.what();
    }
    o.cpu.threads = 1;
    o.cpu.simd = false;
    EXPECT_NE(default_registry().create("cpu", o)->info().details.find("inner loop portable"), std::string::npos);
}

}  // namespace
}  // namespace trn
