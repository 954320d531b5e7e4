// Issue 25 part 2 acceptance on real flight 1: localization without a compass (`--heading none`,
// uniform yaw prior, yaw turned by the folder's heading changes) against the same run with one.
// After convergence (the first step with yaw sd < 10 deg and a lock-monitor fix) the compass-less
// mean error must be at most 2x the compass run's mean error over the same frames: asserted with
// a margin on the mean over 5 seeds (<= 1.75x) and on at least 4 of the 5 seeds (<= 2x). Measured
// (docs/RESULTS.md, "Compass-less localization"): 1.11-1.79x, mean 1.36x. Skipped (visibly) without
// the shared data. Real flight 2 has no ground truth yet, so it is not checked here.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "real_air_fixture.hpp"

namespace trn::test {
namespace {

class RealFlightCompassless : public RealAirFolder {};

TEST_F(RealFlightCompassless, MeanErrorAfterConvergenceAtMostTwiceTheCompassRuns) {
    double ratio_sum = 0;
    int within = 0;
    for (int seed = 1; seed <= 5; ++seed) {
        const std::string with = dir_ + "/compass" + std::to_string(seed), without = dir_ + "/none" + std::to_string(seed);
        const auto a = localize("--map " + map(), seed, with);
        ASSERT_EQ(a.code, 0) << a.output;
        const auto b = localize("--map " + map() + " --heading none --max-particles 6000", seed, without);
        ASSERT_EQ(b.code, 0) << b.output;
        const nlohmann::json j = summary(without);
        ASSERT_TRUE(j["converged_from_frame"].is_number()) << "seed " << seed << ": never converged\n" << j.dump(2);
        const double from = j["converged_from_frame"], none = j["converged_mean_error_m"];
        double sum = 0;
        int n = 0;
        for (const auto& row : csv(with + "/localization.csv"))
            if (std::stod(row.at("frame")) >= from) sum += std::stod(row.at("error_m")), ++n;
        ASSERT_GT(n, 0);
        const double compass = sum / n, ratio = none / compass;
        std::cout << "seed " << seed << ": converged from frame " << from << ", mean error since: no compass " << none << " m, compass "
                  << compass << " m (x" << ratio << "); yaw error since " << j["converged_mean_yaw_error_deg"] << " deg, final yaw sd "
                  << j["final_yaw_sd_deg"] << " deg\n";
        EXPECT_LT(j["final_yaw_sd_deg"].get<double>(), 10.0) << seed;
        EXPECT_LT(j["converged_mean_yaw_error_deg"].get<double>(), 5.0) << seed;
        ratio_sum += ratio;
        within += ratio <= 2.0;
    }
    EXPECT_LE(ratio_sum / 5, 1.75) << "mean ratio over 5 seeds";
    EXPECT_GE(within, 4) << "seeds within the 2x target";
}

}  // namespace
}  // namespace trn::test
