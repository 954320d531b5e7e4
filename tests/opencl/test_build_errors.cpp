// Failures say what failed: a kernel that does not compile shows the device's build log, CL
// error codes are named in words, and a map too large for the device is a clear error.
#include <fstream>
#include <iterator>

#include "cl_api.hpp"
#include "opencl_test_support.hpp"
#include "program_cache.hpp"

namespace trn::test {
namespace {

struct Device {
    opencl::DeviceRef ref;
    opencl::ContextHandle context;
};

Device first_device() {
    std::string why;
    Device d{opencl::enumerate_devices(why).at(0), {}};
    cl_int err = CL_SUCCESS;
    d.context.reset(clCreateContext(nullptr, 1, &d.ref.device, nullptr, nullptr, &err));
    opencl::check(err, "clCreateContext");
    return d;
}

std::string read_text(const std::string& path) {
    std::ifstream in(path);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

TEST(OpenClBuildErrors, CompileFailureShowsTheBuildLog) {
    TRN_REQUIRE_OPENCL_DEVICE();
    const Device d = first_device();
    const std::string broken = "__kernel void broken(__global float* out) { out[0] = not_declared_anywhere; }\n";
    try {
        opencl::build_program(d.context.get(), d.ref, "broken.cl", broken, "no-hash", "-DX=1", {});
        FAIL() << "a kernel using an undeclared identifier must not build";
    } catch (const Error& e) {
        const std::string msg = e.what();
        EXPECT_NE(msg.find("broken.cl"), std::string::npos) << msg;
        EXPECT_NE(msg.find("CL_BUILD_PROGRAM_FAILURE"), std::string::npos) << msg;
        EXPECT_NE(msg.find("build log"), std::string::npos) << msg;
        EXPECT_NE(msg.find("not_declared_anywhere"), std::string::npos) << "the log names the bad identifier:\n" << msg;
        EXPECT_NE(msg.find(opencl::device_string(d.ref.device, CL_DEVICE_NAME)), std::string::npos) << msg;
    }
}

// The .cl files are complete OpenCL C on their own (with the .clh found beside them), with and
// without the build-time defines.
TEST(OpenClBuildErrors, KernelFilesBuildStandalone) {
    TRN_REQUIRE_OPENCL_DEVICE();
    const Device d = first_device();
    const std::string include = std::string("-I ") + TRN_KERNEL_DIR;
    for (const char* file : {"ncc_score.cl", "sobel3x3.cl"}) {
        const std::string source = read_text(std::string(TRN_KERNEL_DIR) + "/" + file);
        ASSERT_FALSE(source.empty()) << file;
        EXPECT_EQ(source.find("R\"("), std::string::npos) << file << " must not carry C++ raw-string wrapping";
        for (const std::string& options : {include, include + " -DTRN_WG_SIZE=32 -DTRN_TILE=8"})
            EXPECT_NO_THROW(opencl::build_program(d.context.get(), d.ref, file, source, "", options, {}))
                << file << " " << options;
    }
}

TEST(OpenClBuildErrors, ErrorCodesAreNamed) {
    EXPECT_STREQ(opencl::error_name(CL_OUT_OF_RESOURCES), "CL_OUT_OF_RESOURCES");
    EXPECT_STREQ(opencl::error_name(CL_MEM_OBJECT_ALLOCATION_FAILURE), "CL_MEM_OBJECT_ALLOCATION_FAILURE");
    EXPECT_STREQ(opencl::error_name(CL_INVALID_WORK_GROUP_SIZE), "CL_INVALID_WORK_GROUP_SIZE");
    EXPECT_STREQ(opencl::error_name(-12345), "unknown OpenCL error");
    try {
        opencl::check(CL_INVALID_KERNEL_ARGS, "clEnqueueNDRangeKernel(ncc_score_dense)");
        FAIL() << "check must throw on an error code";
    } catch (const Error& e) {
        EXPECT_STREQ(e.what(), "OpenCL clEnqueueNDRangeKernel(ncc_score_dense) failed: CL_INVALID_KERNEL_ARGS (-52)");
    }
    EXPECT_NO_THROW(opencl::check(CL_SUCCESS, "clFinish"));
}

TEST(OpenClBuildErrors, MapLargerThanTheDeviceCanHoldIsAClearError) {
    TRN_REQUIRE_OPENCL_DEVICE();
    const Device d = first_device();
    const auto max_alloc = opencl::device_value<cl_ulong>(d.ref.device, CL_DEVICE_MAX_MEM_ALLOC_SIZE);
    // The largest map every backend accepts (trn/limits.hpp: 2^30 pixels); only a device whose
    // largest buffer is smaller than that reaches the OpenCL-specific check.
    const int side = 32768;
    if (max_alloc >= cl_ulong(side) * side)
        GTEST_SKIP() << "this device can hold a " << side << "x" << side << " map (the largest trn::limits allows) in one buffer";
    auto b = default_registry().create("opencl:0", test::backend_options_from_environment());
    // The size check comes before any pixel is read, so one row of real pixels suffices as data.
    std::vector<std::uint8_t> row(side, 100);
    try {
        b->upload_map({row.data(), side, side, 0 + side});
        FAIL() << "a map larger than CL_DEVICE_MAX_MEM_ALLOC_SIZE must be refused";
    } catch (const Error& e) {
        const std::string msg = e.what();
        EXPECT_NE(msg.find("32768x32768"), std::string::npos) << msg;
        EXPECT_NE(msg.find("CL_DEVICE_MAX_MEM_ALLOC_SIZE"), std::string::npos) << msg;
        EXPECT_NE(msg.find("opencl:0"), std::string::npos) << msg;
    }
}

}  // namespace
}  // namespace trn::test
