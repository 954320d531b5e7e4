#pragma once
// A gtest fixture for CLI tests that work in a fresh temporary folder: made before each test,
// removed after, with path(name) inside it and simulate(name, frames) for a small real dataset.
// `run` is the test file's way of running trnkit (so a file can point it at another build).
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <functional>
#include <string>

#include "cli_process.hpp"

namespace trn::test {

class TempFolderTest : public testing::Test {
protected:
    TempFolderTest(std::string prefix, std::function<CliResult(const std::string&)> run)
        : prefix_(std::move(prefix)), run_(std::move(run)) {}
    void SetUp() override {
        dir_ = std::filesystem::temp_directory_path() / (prefix_ + std::to_string(::getpid()));
        std::filesystem::remove_all(dir_);
        std::filesystem::create_directories(dir_);
    }
    void TearDown() override { std::filesystem::remove_all(dir_); }
    std::string path(const std::string& name) const { return (dir_ / name).string(); }
    // A small valid dataset in `name` (`frames` frames).
    void simulate(const std::string& name, int frames) {
        const CliResult r = run_("simulate --scenario FC-300 --size-m 900 --frames " + std::to_string(frames) + " --out " + path(name));
        ASSERT_EQ(r.code, 0) << r.output;
    }
    std::filesystem::path dir_;

private:
    std::string prefix_;
    std::function<CliResult(const std::string&)> run_;
};

}  // namespace trn::test
