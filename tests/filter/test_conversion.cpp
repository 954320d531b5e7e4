// The conversion functions must follow the dissertation's equations 2.16-2.21.
#include <gtest/gtest.h>

#include <cmath>

#include "trn/error.hpp"
#include "trn/filter/conversion.hpp"

namespace trn::filter {
namespace {

TEST(Conversion, LinearAndSoftmaxFollowEquations216And217) {
    const Conversion lin = Conversion::parse("linear"), soft = Conversion::parse("softmax");
    EXPECT_DOUBLE_EQ(lin(-0.1), 0.45);  // the dissertation's own example
    EXPECT_DOUBLE_EQ(lin(-1), 0.0);
    EXPECT_DOUBLE_EQ(lin(1), 1.0);
    EXPECT_DOUBLE_EQ(soft(0.5), std::exp(0.5));
}

TEST(Conversion, RectifyingCoversAllFourCasesOfEquation218) {
    const Conversion neg = Conversion::parse("rectifying:-0.2"), pos = Conversion::parse("rectifying:0.3");
    EXPECT_DOUBLE_EQ(neg(0.1), 0.0);                          // d < 0, x <= |d|
    EXPECT_DOUBLE_EQ(neg(0.5), 1.2 * (0.5 - 0.2) + 0.04);     // d < 0, x > |d|
    EXPECT_DOUBLE_EQ(pos(-0.5), 0.3 * 0.5);                   // d >= 0, x <= 0
    EXPECT_DOUBLE_EQ(pos(0.5), 0.5 * 0.7 + 0.3);              // d >= 0, x > 0
    EXPECT_DOUBLE_EQ(pos(0.0), 0.3);                          // d is the value at 0
    EXPECT_DOUBLE_EQ(Conversion::parse("rectifying:0")(-0.4), 0.0);  // Nakhmani's rectified NCC
}

TEST(Conversion, LogisticIsNormalisedToOneAtPerfectCorrelation) {
    for (double v : {0.05, 0.1, 0.2, 0.5, 1.0}) {
        const Conversion c = Conversion::parse("logistic:" + std::to_string(v));
        EXPECT_NEAR(c(1.0), 1.0, 1e-12);
        const double l = std::pow(1 + std::exp(-5 * 0.3), -1 / v), l1 = std::pow(1 + std::exp(-5.0), -1 / v);
        EXPECT_NEAR(c(0.3), l / l1, 1e-12);
        EXPECT_LT(c(-0.5), c(0.0));
        EXPECT_LT(c(0.0), c(0.5));
    }
    // Smaller v discriminates harder: a mediocre match keeps less of its probability.
    EXPECT_LT(Conversion::parse("logistic:0.05")(0.3), Conversion::parse("logistic:0.2")(0.3));
}

TEST(Conversion, ParseRejectsBadTextAndRoundTrips) {
    EXPECT_THROW(Conversion::parse("logistic"), Error);
    EXPECT_THROW(Conversion::parse("logistic:0"), Error);
    EXPECT_THROW(Conversion::parse("logistic:abc"), Error);
    EXPECT_THROW(Conversion::parse("linear:1"), Error);
    EXPECT_THROW(Conversion::parse("cosine"), Error);
    EXPECT_EQ(Conversion::parse("logistic:0.2").to_string(), "logistic:0.2");
    EXPECT_EQ(Conversion::parse("rectifying:-0.1").to_string(), "rectifying:-0.1");
}

}  // namespace
}  // namespace trn::filter
