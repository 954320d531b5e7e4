// trn::load_validity (maps' no-data from alpha and --nodata levels) against its definition computed
// from cv::imread(IMREAD_UNCHANGED); the device kit's libpng reader runs the same cases.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>

#include "../common/validity_reference.hpp"

TEST(LoadValidity, EveryColourTypeAndTheRealMaps) {
    const std::string dir = testing::TempDir() + "/trn-validity-" + std::to_string(::getpid());
    std::filesystem::create_directories(dir);
    trn::test::check_validity_cases(dir);
    std::filesystem::remove_all(dir);
}
