// BackendOptions from NAME=VALUE text (trn/backend_option_text.hpp): every field by its own name,
// values checked, errors naming the option (never an environment variable or a CLI flag).
#include <gtest/gtest.h>

#include "trn/backend_option_text.hpp"

namespace trn {
namespace {

std::string refusal(std::string_view name, std::string_view value) {
    BackendOptions o;
    try {
        set_backend_option(o, name, value);
    } catch (const BackendOptionError& e) {
        EXPECT_EQ(e.name(), name);
        EXPECT_EQ(e.value(), value);
        return e.what();
    }
    return "accepted";
}

TEST(BackendOptionText, EveryFieldByItsName) {
    BackendOptions o;
    set_backend_option(o, "default_device.opencl", "pocl");
    set_backend_option(o, "default_device.vulkan=1");
    set_backend_option(o, "cpu.threads", "3");
    set_backend_option(o, "cpu.simd", "off");
    set_backend_option(o, "opencl.work_group", "64");
    set_backend_option(o, "opencl.program_cache_dir", "/var/cache/x");
    set_backend_option(o, "vulkan.work_group", "256");
    set_backend_option(o, "vulkan.particles_per_group", "4");
    set_backend_option(o, "vulkan.quad_maps", "0");
    set_backend_option(o, "vulkan.subgroups", "false");
    set_backend_option(o, "vulkan.force_staging", "on");
    set_backend_option(o, "vulkan.validation", "1");
    set_backend_option(o, "vulkan.pipeline_cache_dir=");
    set_backend_option(o, "cuda.work_group", "128");
    EXPECT_EQ(o.default_device.at("opencl"), "pocl");
    EXPECT_EQ(o.default_device.at("vulkan"), "1");
    EXPECT_EQ(o.cpu.threads, 3);
    EXPECT_FALSE(o.cpu.simd);
    EXPECT_EQ(o.opencl.work_group, 64u);
    EXPECT_EQ(o.opencl.program_cache_dir, "/var/cache/x");
    EXPECT_EQ(o.vulkan.work_group, 256u);
    EXPECT_EQ(o.vulkan.particles_per_group, 4u);
    EXPECT_FALSE(o.vulkan.quad_maps);
    EXPECT_FALSE(o.vulkan.subgroups);
    EXPECT_TRUE(o.vulkan.force_staging);
    EXPECT_TRUE(o.vulkan.validation);
    EXPECT_EQ(o.vulkan.pipeline_cache_dir, "");
    EXPECT_EQ(o.cuda.work_group, 128u);
    // Every listed name is taken (FAMILY stands for any family).
    for (const BackendOptionName& n : backend_option_names()) {
        const std::string value = n.values.starts_with("on|off") ? "on" : n.values.starts_with("1..") ? "1" : "x";
        EXPECT_NO_THROW(set_backend_option(o, n.name, value)) << n.name;
    }
}

TEST(BackendOptionText, RefusalsNameTheOption) {
    EXPECT_EQ(refusal("cpu.threads", "abc"), "cpu.threads='abc': expected a whole number from 1 to 4096");
    EXPECT_EQ(refusal("cpu.threads", "0"), "cpu.threads='0': expected a whole number from 1 to 4096");
    EXPECT_EQ(refusal("cpu.threads", "-1"), "cpu.threads='-1': expected a whole number from 1 to 4096");
    EXPECT_EQ(refusal("vulkan.particles_per_group", "17"), "vulkan.particles_per_group='17': expected a whole number from 1 to 16");
    EXPECT_EQ(refusal("opencl.work_group", "99999999999999999999"),
              "opencl.work_group='99999999999999999999': expected a whole number from 1 to 65536");
    EXPECT_EQ(refusal("cpu.simd", "maybe"), "cpu.simd='maybe': expected on or off (1 or 0, true or false)");
    EXPECT_NE(refusal("cpu.thread", "3").find("cpu.thread='3': unknown backend option (known: default_device.FAMILY, cpu.threads"),
              std::string::npos);
    EXPECT_NE(refusal("default_device.", "1").find("unknown backend option"), std::string::npos);
    BackendOptions o;
    EXPECT_THROW(set_backend_option(o, "cpu.threads"), Error);
    EXPECT_THROW(set_backend_option(o, "=3"), Error);
}

}  // namespace
}  // namespace trn
