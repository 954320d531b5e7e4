#include <gtest/gtest.h>

#include <random>
#include <sstream>

#include "trn/error.hpp"
#include "trn/io/pose_csv.hpp"

namespace trn {
namespace {

std::string error_of(const std::string& text) {
    std::istringstream in(text);
    try {
        read_poses_csv(in, "poses.csv");
    } catch (const Error& e) {
        return e.what();
    }
    return "no error";
}

TEST(PoseCsv, ReadsHeaderCommentsAndBlankLines) {
    std::istringstream in("# poses\nx,y,yaw,scale\n1,2,0.5,1\n\n 3.5 , 4 ,-1, 2 \r\n");
    const auto poses = read_poses_csv(in, "mem");
    ASSERT_EQ(poses.size(), 2u);
    EXPECT_FLOAT_EQ(poses[1].x, 3.5f);
    EXPECT_FLOAT_EQ(poses[1].scale, 2.0f);
}

TEST(PoseCsv, ErrorsNameFileAndLine) {
    EXPECT_EQ(error_of("1,2,3\n"), "poses.csv:1: expected 4 fields x,y,yaw,scale, got 3");
    EXPECT_EQ(error_of("x,y,yaw,scale\n1,2,abc,1\n"), "poses.csv:2: field 3 'abc' is not a number");
    EXPECT_EQ(error_of("1,2,nan,1\n"), "poses.csv:1: field 3 is not finite");
    EXPECT_EQ(error_of("1,2,0,0\n"), "poses.csv:1: scale must be > 0");
    EXPECT_EQ(error_of("x,y,z,w\n"), "poses.csv:1: header must be x,y,yaw,scale");
}

// A small deterministic fuzz: random bytes and mutated valid lines never crash; they parse or throw Error.
TEST(PoseCsv, RandomInputParsesOrThrowsError) {
    std::mt19937 rng(5);
    const std::string alphabet = "0123456789.,-+eE naNinf\n\r#xyzaw";
    for (int i = 0; i < 3000; ++i) {
        std::string s;
        const int len = rng() % 80;
        for (int k = 0; k < len; ++k) s += alphabet[rng() % alphabet.size()];
        std::istringstream in(s);
        try {
            for (const Pose& p : read_poses_csv(in, "fuzz")) ASSERT_TRUE(std::isfinite(p.x) && p.scale > 0);
        } catch (const Error&) {
        }
    }
}

}  // namespace
}  // namespace trn
