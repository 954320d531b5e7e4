#pragma once
// Helpers for the Vulkan tests: the first Vulkan device (or a skip saying why there is none) and
// score / Sobel comparisons against the cpu-ref oracle.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "backend_env.hpp"  // the TRN_* variables -> BackendOptions, as the CLI reads them
#include "test_images.hpp"
#include "trn/registry.hpp"

namespace trn::test {

// Empty string when there is a Vulkan device, else why not (for GTEST_SKIP).
inline std::string vulkan_unavailable() {
    for (const FamilyStatus& f : default_registry().status())
        if (f.family == "vulkan") return f.devices.empty() ? "no Vulkan device: " + f.why_none : "";
    return "this build has no Vulkan family";
}

#define TRN_REQUIRE_VULKAN()                                                     \
    do {                                                                         \
        if (const std::string why = ::trn::test::vulkan_unavailable(); !why.empty()) \
            GTEST_SKIP() << why;                                                 \
    } while (0)

// The options ctest runs these tests with (TRN_VULKAN_VALIDATION=1: the validation layer on),
// read the way the CLI reads them; tests change single fields from there.
inline BackendOptions env_options() { return test::backend_options_from_environment(); }

// The Vulkan backend with env_options() changed by `change` (which picks its path).
template <typename Change>
std::unique_ptr<Backend> vulkan_with(Change change) {
    BackendOptions o = env_options();
    change(o.vulkan);
    return default_registry().create("vulkan", o);
}

// Sets an environment variable for the life of the object (for the Vulkan loader's own variables).
class ScopedEnv {
public:
    ScopedEnv(const char* name, const char* value) : name_(name) {
        if (const char* old = std::getenv(name)) old_ = old, had_ = true;
        setenv(name, value, 1);
    }
    ~ScopedEnv() { had_ ? setenv(name_, old_.c_str(), 1) : unsetenv(name_); }

private:
    const char* name_;
    std::string old_;
    bool had_ = false;
};

inline std::vector<Pose> random_poses(int n, int map_w, int map_h, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> x(-10.0f, map_w + 10.0f), y(-10.0f, map_h + 10.0f), yaw(-3.2f, 3.2f), s(0.7f, 1.5f);
    std::vector<Pose> poses(n);
    for (Pose& p : poses) p = {x(rng), y(rng), yaw(rng), s(rng)};
    return poses;
}

// Scores on both backends; checks the conformance rule: scores, counts and flags equal.
inline std::vector<ParticleScore> expect_scores_match(Backend& dut, Backend& ref, GrayView map, GrayView templ,
                                                      const std::vector<Pose>& poses, const ScoreOptions& options) {
    std::vector<ParticleScore> got(poses.size()), want(poses.size());
    dut.score(dut.upload_map(map), templ, poses, options, got);
    ref.score(ref.upload_map(map), templ, poses, options, want);
    int valid = 0;
    for (std::size_t i = 0; i < poses.size(); ++i) {
        SCOPED_TRACE("pose " + std::to_string(i));
        EXPECT_EQ(got[i].valid_samples, want[i].valid_samples);
        EXPECT_EQ(got[i].flags, want[i].flags);
        EXPECT_EQ(got[i].ncc, want[i].ncc);
        EXPECT_EQ(got[i].cc, want[i].cc);
        EXPECT_EQ(got[i].ssd, want[i].ssd);
        valid += want[i].valid();
    }
    EXPECT_GT(valid, 0) << "the case should have valid particles";
    return got;
}

}  // namespace trn::test
