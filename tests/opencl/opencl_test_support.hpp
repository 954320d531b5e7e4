#pragma once
// Shared helpers of the OpenCL backend tests.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "backend_env.hpp"  // the TRN_* variables -> BackendOptions, as the CLI reads them
#include "../common/test_images.hpp"
#include "cl_devices.hpp"
#include "trn/registry.hpp"

namespace trn::test {

// The OpenCL devices, or a skip with the reason when this machine has none.
#define TRN_REQUIRE_OPENCL_DEVICE()                                                                        \
    do {                                                                                                   \
        std::string why_;                                                                                  \
        if (trn::opencl::enumerate_devices(why_).empty()) GTEST_SKIP() << "no OpenCL device: " << why_;  \
    } while (0)

// Sets an environment variable for the lifetime of the object, then restores it.
class ScopedEnv {
public:
    ScopedEnv(std::string name, const std::optional<std::string>& value) : name_(std::move(name)) {
        if (const char* old = std::getenv(name_.c_str())) old_ = old;
        if (value)
            ::setenv(name_.c_str(), value->c_str(), 1);
        else
            ::unsetenv(name_.c_str());
    }
    ~ScopedEnv() {
        if (old_)
            ::setenv(name_.c_str(), old_->c_str(), 1);
        else
            ::unsetenv(name_.c_str());
    }

private:
    std::string name_;
    std::optional<std::string> old_;
};

// A fresh, empty folder under the system temp folder, removed afterwards.
class TempDir {
public:
    TempDir() {
        std::random_device rd;
        path_ = std::filesystem::temp_directory_path() / ("trn_opencl_test_" + std::to_string(rd()));
        std::filesystem::create_directories(path_);
    }
    ~TempDir() {
        std::error_code ec;
        std::filesystem::remove_all(path_, ec);
    }
    const std::filesystem::path& path() const { return path_; }

private:
    std::filesystem::path path_;
};

inline std::vector<std::filesystem::path> files_with_extension(const std::filesystem::path& dir, const std::string& ext) {
    std::vector<std::filesystem::path> out;
    if (!std::filesystem::exists(dir)) return out;
    for (const auto& e : std::filesystem::directory_iterator(dir))
        if (e.path().extension() == ext) out.push_back(e.path());
    return out;
}

// The tests' texture (test_images.hpp) as a continuous w x h buffer.
inline std::vector<std::uint8_t> textured_pixels(int w, int h, std::uint32_t seed) { return textured_image(w, h, seed).buffer; }

}  // namespace trn::test
