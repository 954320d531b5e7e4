// trn_conformance --backend FAMILY[:DEVICE] [--require] [gtest flags]   (FAMILY cpu-ref: the oracle vs OpenCV)
// Registers every case for every selected device and every variant of its family (code paths
// chosen through BackendOptions: the cpu backend's portable loop, Vulkan's fallback paths, CUDA's
// one-warp blocks) and runs
// them against cpu-ref. A family with no device is reported "NOT AVAILABLE" by name and exits 77
// (ctest: skipped), or fails with --require. Base options come from the TRN_* variables as in the
// CLI (ctest sets TRN_VULKAN_VALIDATION=1).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <iostream>
#include <map>
#include <memory>

#include "backend_env.hpp"  // the TRN_* variables -> BackendOptions, as the CLI reads them
#include "cases.hpp"
#include "trn/registry.hpp"

namespace {

constexpr int kNotAvailable = 77;

// One set of options a family's devices are checked with; `name` ends the test-suite name.
struct Variant {
    std::string name;
    trn::BackendOptions options;
};

// The code paths each family has besides its default one, so that a machine that would always take
// the fast path (AVX2, subgroup arithmetic, unified memory, quad maps) checks the others as well.
std::vector<Variant> variants(const std::string& family, const trn::BackendOptions& base) {
    std::vector<Variant> out{{"", base}};
    if (family == "cpu") {
        Variant portable{"_portable", base};
        portable.options.cpu.simd = false;
        out.push_back(portable);
    } else if (family == "vulkan") {
        Variant fallbacks{"_fallbacks", base};  // shared-memory reduction, staging buffers, byte maps
        fallbacks.options.vulkan.subgroups = false;
        fallbacks.options.vulkan.force_staging = true;
        fallbacks.options.vulkan.quad_maps = false;
        out.push_back(fallbacks);
    } else if (family == "cuda") {
        Variant one_warp{"_one_warp", base};  // the NCC reduction without its shared-memory step
        one_warp.options.cuda.work_group = 32;
        out.push_back(one_warp);
    }
    return out;
}

std::string test_suite_name(const std::string& device) {
    std::string s = "conformance_" + device;
    std::replace(s.begin(), s.end(), ':', '_');
    std::replace(s.begin(), s.end(), '-', '_');
    return s;
}

class CaseTest : public testing::Test {
public:
    CaseTest(std::shared_ptr<trn::Backend> dut, std::shared_ptr<trn::Backend> ref, const trn::conformance::Case* c)
        : dut_(std::move(dut)), ref_(std::move(ref)), case_(c) {}
    void TestBody() override { case_->run(*dut_, *ref_); }

private:
    std::shared_ptr<trn::Backend> dut_, ref_;
    const trn::conformance::Case* case_;
};

class FailingTest : public testing::Test {
public:
    explicit FailingTest(std::string why) : why_(std::move(why)) {}
    void TestBody() override { FAIL() << why_; }

private:
    std::string why_;
};

}  // namespace

int main(int argc, char** argv) {
    std::string spec;
    bool require = false;
    std::vector<char*> rest = {argv[0]};
    for (int i = 1; i < argc; ++i) {
        if (!std::strcmp(argv[i], "--backend") && i + 1 < argc) spec = argv[++i];
        else if (!std::strcmp(argv[i], "--require")) require = true;
        else rest.push_back(argv[i]);
    }
    if (spec.empty()) {
        std::cerr << "usage: trn_conformance --backend FAMILY[:DEVICE] [--require] [gtest flags]\n";
        return 2;
    }
    const std::string family = spec.substr(0, spec.find(':'));
    if (family == "cpu-ref") {
        // The oracle every backend is compared with is itself checked against independent code
        // (OpenCV's warpAffine + matchTemplate, closed-form cases: test_cpu_ref_oracle.cpp, also
        // in trn_unit_tests), so a machine with only this binary (the device kit) checks it too.
        int gargc = static_cast<int>(rest.size());
        testing::InitGoogleTest(&gargc, rest.data());
        if (GTEST_FLAG_GET(filter) == "*") GTEST_FLAG_SET(filter, "CpuRefOracle.*");
        const int rc = RUN_ALL_TESTS();
        const auto* unit = testing::UnitTest::GetInstance();
        std::cout << "CONFORMANCE cpu-ref (oracle vs OpenCV): " << unit->successful_test_count() << " passed, "
                  << unit->failed_test_count() << " failed, " << unit->skipped_test_count() << " skipped\n";
        return rc;
    }

    const trn::BackendRegistry& registry = trn::default_registry();
    std::vector<trn::DeviceInfo> devices;
    std::string why = "not built into this trnkit";
    for (const trn::FamilyStatus& s : registry.status())
        if (s.family == family) {
            why = s.why_none;
            for (const trn::DeviceInfo& d : s.devices)
                if (spec == family || d.name == spec) devices.push_back(d);
            if (!s.devices.empty() && devices.empty()) why = "no device named " + spec;
        }
    if (devices.empty()) {
        std::cout << "CONFORMANCE " << spec << ": NOT AVAILABLE (" << why << ")\n";
        return require ? 1 : kNotAvailable;
    }

    static std::vector<trn::conformance::Case> cases;
    for (auto&& group : {trn::conformance::ncc_cases(), trn::conformance::sobel_cases(), trn::conformance::error_cases(),
                        trn::conformance::mask_cases()})
        cases.insert(cases.end(), group.begin(), group.end());

    const trn::BackendOptions base = trn::test::backend_options_from_environment();
    std::shared_ptr<trn::Backend> ref = registry.create("cpu-ref");
    std::vector<std::shared_ptr<trn::Backend>> owned;
    for (const trn::DeviceInfo& d : devices)
        for (const Variant& v : variants(family, base)) {
            const std::string suite = test_suite_name(d.name) + v.name, label = d.name + v.name;
            std::shared_ptr<trn::Backend> dut;
            try {
                dut = registry.create(d.name, v.options);
            } catch (const std::exception& e) {  // e.g. a device that cannot build the kernels: a failure, by name
                const std::string why = e.what();
                std::cout << "CONFORMANCE " << label << ": cannot create the backend: " << why << "\n";
                testing::RegisterTest(suite.c_str(), "create_backend", nullptr, label.c_str(), __FILE__, __LINE__,
                                      [why]() -> testing::Test* { return new FailingTest(why); });
                continue;
            }
            std::cout << "CONFORMANCE " << label << ": " << d.device << " [" << d.type << "] (" << d.driver << "), "
                      << cases.size() << " cases against cpu-ref; " << dut->info().details << "\n";
            // The registered factories live as long as gtest's UnitTest, a static that (with the
            // oracle's TEST()s in this binary) outlives libraries loaded later, such as a Vulkan
            // layer: they hold non-owning pointers, and main releases the backends before it returns.
            owned.push_back(dut);
            const std::shared_ptr<trn::Backend> dut_view(std::shared_ptr<void>{}, dut.get()), ref_view(std::shared_ptr<void>{}, ref.get());
            for (const auto& c : cases)
                testing::RegisterTest(suite.c_str(), c.name.c_str(), nullptr, label.c_str(), __FILE__, __LINE__,
                                      [dut_view, ref_view, &c]() -> testing::Test* { return new CaseTest(dut_view, ref_view, &c); });
        }
    int gargc = static_cast<int>(rest.size());
    testing::InitGoogleTest(&gargc, rest.data());
    if (GTEST_FLAG_GET(filter) == "*") GTEST_FLAG_SET(filter, "-CpuRefOracle.*");  // cpu-ref's own run has them
    const int rc = RUN_ALL_TESTS();
    owned.clear();
    ref.reset();
    const auto* unit = testing::UnitTest::GetInstance();
    std::cout << "CONFORMANCE " << spec << ": " << unit->successful_test_count() << " passed, " << unit->failed_test_count()
              << " failed, " << unit->skipped_test_count() << " skipped\n";
    return rc;
}
