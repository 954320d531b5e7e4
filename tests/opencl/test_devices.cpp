// Device listing and selection: every OpenCL device appears as opencl:<n>, CPU devices included,
// and can be picked by index, by name substring and through TRN_OPENCL_DEVICE.
#include <algorithm>

#include "opencl_test_support.hpp"

namespace trn::test {
namespace {

const FamilyStatus& opencl_status(const std::vector<FamilyStatus>& all) {
    const auto it = std::find_if(all.begin(), all.end(), [](const FamilyStatus& f) { return f.family == "opencl"; });
    if (it == all.end()) throw std::runtime_error("the default registry has no opencl family");
    return *it;
}

TEST(OpenClDevices, EveryDeviceIsListedWithRealDescription) {
    TRN_REQUIRE_OPENCL_DEVICE();
    std::string why;
    const auto refs = opencl::enumerate_devices(why);
    const auto all = default_registry().status();
    const FamilyStatus& s = opencl_status(all);
    ASSERT_EQ(s.devices.size(), refs.size()) << "every device of every platform must be listed, CPU devices included";
    for (std::size_t i = 0; i < s.devices.size(); ++i) {
        const DeviceInfo& d = s.devices[i];
        EXPECT_EQ(d.name, "opencl:" + std::to_string(i));
        EXPECT_EQ(d.family, "opencl");
        EXPECT_EQ(d.device, opencl::device_string(refs[i].device, CL_DEVICE_NAME));
        EXPECT_TRUE(d.type == "cpu" || d.type == "gpu" || d.type == "other") << d.type;
        EXPECT_NE(d.driver.find(opencl::device_string(refs[i].device, CL_DRIVER_VERSION)), std::string::npos) << d.driver;
        EXPECT_NE(d.details.find("compute units"), std::string::npos) << d.details;
        EXPECT_NE(d.details.find("program cache"), std::string::npos) << d.details;
    }
}

TEST(OpenClDevices, SelectedByIndexNameAndEnvironment) {
    TRN_REQUIRE_OPENCL_DEVICE();
    const auto all = default_registry().status();
    const DeviceInfo& last = opencl_status(all).devices.back();
    const std::string index = last.name.substr(last.name.find(':') + 1);

    EXPECT_EQ(default_registry().create(last.name, test::backend_options_from_environment())->info().device, last.device);
    // A lower-case piece of the device name picks it as well.
    std::string piece = last.device.substr(0, std::min<std::size_t>(6, last.device.size()));
    std::transform(piece.begin(), piece.end(), piece.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    EXPECT_EQ(default_registry().create("opencl:" + piece, test::backend_options_from_environment())->info().device.substr(0, piece.size()).size(), piece.size());
    {
        ScopedEnv env("TRN_OPENCL_DEVICE", index);
        EXPECT_EQ(default_registry().create("opencl", test::backend_options_from_environment())->info().name, last.name);
    }
    {
        ScopedEnv env("TRN_OPENCL_DEVICE", std::string("no-such-device-xyz"));
        EXPECT_THROW(default_registry().create("opencl", test::backend_options_from_environment()), BackendUnavailable);
    }
    EXPECT_THROW(default_registry().create("opencl:999", test::backend_options_from_environment()), BackendUnavailable);
}

}  // namespace
}  // namespace trn::test
