// The KLD bound (eq. 2.22) and the normal quantile it needs.
#include <gtest/gtest.h>

#include <cmath>

#include "trn/error.hpp"
#include "trn/filter/kld.hpp"

namespace trn::filter {
namespace {

TEST(Kld, NormalQuantileMatchesTables) {
    EXPECT_NEAR(normal_quantile(0.5), 0.0, 1e-12);
    EXPECT_NEAR(normal_quantile(0.9), 1.2815515655446004, 1e-10);
    EXPECT_NEAR(normal_quantile(0.975), 1.959963984540054, 1e-10);
    EXPECT_NEAR(normal_quantile(0.01), -2.3263478740408408, 1e-10);
    EXPECT_THROW(normal_quantile(1.0), Error);
    EXPECT_THROW(normal_quantile(0.0), Error);
}

TEST(Kld, BoundFollowsEquation222) {
    const double z = 1.2815515655446004;
    for (std::size_t k : {2u, 16u, 200u}) {
        const double k1 = k - 1.0, t = 2 / (9 * k1);
        const double expected = k1 / (2 * 0.05) * std::pow(1 - t + std::sqrt(t) * z, 3);
        EXPECT_NEAR(kld_bound(k, 0.05, 0.9), expected, 1e-9 * expected);
    }
    EXPECT_EQ(kld_bound(1, 0.05, 0.9), 0.0);
    // A converged cloud over ~16 bins of 5 m needs a couple of hundred particles (dissertation: ~150).
    EXPECT_GT(kld_bound(16, 0.05, 0.9), 150);
    EXPECT_LT(kld_bound(16, 0.05, 0.9), 300);
    EXPECT_LT(kld_bound(16, 0.05, 0.9), kld_bound(17, 0.05, 0.9));
}

}  // namespace
}  // namespace trn::filter
