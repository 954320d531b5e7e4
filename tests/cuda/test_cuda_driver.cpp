// Loading the CUDA driver and the reasons the family gives when it cannot: no libcuda at all, a
// library whose cuInit fails (the toolkit's link stub stands in for a broken driver), and what the
// registry and create() say on a machine without an NVIDIA driver.
#include <gtest/gtest.h>
#include <dlfcn.h>

#include <algorithm>
#include <string>

#include "cu_api.hpp"
#include "trn/registry.hpp"

namespace trn::cuda {
namespace {

std::string unavailable(const std::string& library) {
    try {
        open_driver(library);
    } catch (const BackendUnavailable& e) {
        return e.what();
    }
    return "loaded";
}

bool driver_present() {
    void* lib = dlopen("libcuda.so.1", RTLD_NOW | RTLD_LOCAL);
    if (lib) dlclose(lib);
    return lib != nullptr;
}

TEST(CudaDriver, MissingLibrarySaysWhich) {
    const std::string why = unavailable("/nonexistent/libcuda.so.1");
    EXPECT_NE(why.find("the CUDA driver library /nonexistent/libcuda.so.1 could not be loaded ("), std::string::npos) << why;
    EXPECT_NE(why.find("No such file"), std::string::npos) << why;  // dlerror's own words
}

TEST(CudaDriver, FailingCuInitIsReportedWithItsError) {
    const std::string stub = TRN_CUDA_STUB_LIBRARY;
    if (stub.empty()) GTEST_SKIP() << "NOT AVAILABLE: no lib64/stubs/libcuda.so in this CUDA toolkit";
    // Every entry point resolves (the stub exports the whole API), then cuInit refuses.
    const std::string why = unavailable(stub);
    EXPECT_NE(why.find("cuInit failed: CUDA_ERROR_STUB_LIBRARY (34)"), std::string::npos) << why;
    EXPECT_NE(why.find(stub), std::string::npos) << why;
}

TEST(CudaDriver, FamilyIsListedWithItsDevicesOrTheReason) {
    for (const FamilyStatus& s : default_registry().status()) {
        if (s.family != "cuda") continue;
        if (!driver_present()) {
            EXPECT_TRUE(s.devices.empty());
            EXPECT_NE(s.why_none.find("libcuda.so.1 could not be loaded"), std::string::npos) << s.why_none;
            try {
                default_registry().create("cuda");
                ADD_FAILURE() << "cuda created without a driver";
            } catch (const BackendUnavailable& e) {
                EXPECT_NE(std::string(e.what()).find("backend 'cuda' is not available: the CUDA driver library libcuda.so.1"),
                          std::string::npos) << e.what();
            }
        } else {
            std::cout << "cuda: " << (s.devices.empty() ? "not available: " + s.why_none : std::to_string(s.devices.size()) + " device(s)") << "\n";
            for (const DeviceInfo& d : s.devices) {
                EXPECT_EQ(d.family, "cuda");
                EXPECT_EQ(d.type, "gpu");
                EXPECT_NE(d.details.find("code: "), std::string::npos) << d.details;
            }
        }
        return;
    }
    ADD_FAILURE() << "the registry has no cuda family";
}

TEST(CudaDriver, OptionIsCheckedByName) {
    BackendOptions o;
    o.cuda.work_group = 48;
    const std::vector<std::string> names = default_registry().available();
    if (std::find(names.begin(), names.end(), "cuda:0") == names.end())
        GTEST_SKIP() << "NOT AVAILABLE: no CUDA device here (the option's rule: CudaPlan.BlockSizeFromTheRuleOrTheOption)";
    try {
        default_registry().create("cuda", o);
        ADD_FAILURE() << "work_group 48 accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("48"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace trn::cuda
