// Statistics checked against R 4.2 (Debian 12 r-base-core). Reference values were produced once
// with the R commands quoted next to them; the test itself needs no R.
#include <gtest/gtest.h>

#include <boost/math/distributions/normal.hpp>
#include <cmath>
#include <functional>
#include <vector>

#include "trn/error.hpp"
#include "trn/energy/stats.hpp"

using namespace trn::energy;

namespace {

std::vector<double> make(int n, const std::function<double(int)>& f) {
    std::vector<double> v;
    for (int i = 1; i <= n; ++i) v.push_back(f(i));
    return v;
}
double qnorm(double p) { return boost::math::quantile(boost::math::normal(), p); }

struct Ref {
    const char* name;
    std::vector<double> x;
    double w, p;
};

}  // namespace

// R: options(digits=15); r <- shapiro.test(x); sprintf("%.12f %.12g", r$statistic, r$p.value)
TEST(ShapiroWilk, MatchesR) {
    const std::vector<Ref> refs = {
        {"c(1,2,4)", {1, 2, 4}, 0.964285714286, 0.636886845029},
        {"c(2.1,3.4,1.9,5.6,4.0)", {2.1, 3.4, 1.9, 5.6, 4.0}, 0.931428977559, 0.606147205158},
        {"c(12.5,13.1,12.9,14.2,12.7,13.0,15.8,12.8)", {12.5, 13.1, 12.9, 14.2, 12.7, 13.0, 15.8, 12.8}, 0.747813271953, 0.00772578426648},
        {"log(1:11)", make(11, [](int i) { return std::log(i); }), 0.909827905727, 0.242751711523},
        {"sqrt(1:20)", make(20, [](int i) { return std::sqrt(i); }), 0.953052719142, 0.41581545242},
        {"((1:30*7919)%%1000)/1000", make(30, [](int i) { return ((i * 7919) % 1000) / 1000.0; }), 0.951335436894, 0.183552672665},
        {"sin(1:50)+(1:50)/25", make(50, [](int i) { return std::sin(i) + i / 25.0; }), 0.979113049806, 0.515190000181},
        {"exp(((1:100*37)%%101)/40)", make(100, [](int i) { return std::exp(((i * 37) % 101) / 40.0); }), 0.889254006309, 4.56806010151e-07},
        {"exp(((1:200*37)%%211)/60)", make(200, [](int i) { return std::exp(((i * 37) % 211) / 60.0); }), 0.838583950626, 1.24003982627e-13},
        {"qnorm(((1:500*263)%%501)/501)+0.1*cos(1:500)",
         make(500, [](int i) { return qnorm(((i * 263) % 501) / 501.0) + 0.1 * std::cos(i); }), 0.999282793914, 0.999684529334},
        {"qnorm(((1:5000*2731)%%5001)/5001)+0.02*sin(1:5000)^2",
         make(5000, [](int i) { return qnorm(((static_cast<long>(i) * 2731) % 5001) / 5001.0) + 0.02 * std::pow(std::sin(i), 2); }),
         0.999947679390, 0.99999985199},
    };
    for (const auto& r : refs) {
        const ShapiroWilk s = shapiro_wilk(r.x);
        EXPECT_NEAR(s.w, r.w, 1e-4) << r.name;
        EXPECT_NEAR(s.p, r.p, 1e-4) << r.name;
        EXPECT_NEAR(s.w, r.w, 1e-9) << r.name << " (tighter than required)";
    }
    EXPECT_THROW(shapiro_wilk(std::vector<double>{1, 2}), trn::Error);
    EXPECT_THROW(shapiro_wilk(std::vector<double>{3, 3, 3, 3}), trn::Error);
}

// R: a <- sqrt(1:20); b <- ((1:30*7919)%%1000)/1000*5; t.test(a,b); t.test(a,b,var.equal=TRUE)
TEST(TTests, MatchR) {
    const auto a = make(20, [](int i) { return std::sqrt(i); });
    const auto b = make(30, [](int i) { return ((i * 7919) % 1000) / 1000.0 * 5; });
    const TTest w = welch_t_test(a, b);
    EXPECT_NEAR(w.t, 1.037927094778, 1e-9);
    EXPECT_NEAR(w.df, 47.729775011577, 1e-8);
    EXPECT_NEAR(w.p, 0.304533764176, 1e-9);
    EXPECT_NEAR(w.ci_low, -0.338229886686, 1e-9);
    EXPECT_NEAR(w.ci_high, 1.059827667828, 1e-9);
    const TTest s = student_t_test(a, b);
    EXPECT_NEAR(s.t, 0.971094143107, 1e-9);
    EXPECT_EQ(s.df, 48);
    EXPECT_NEAR(s.p, 0.336369642943, 1e-9);
}

// R: p.adjust(c(0.01,0.04,0.03,0.005), "holm") -> 0.03 0.06 0.06 0.02
TEST(Holm, MatchesR) {
    const auto adj = holm_adjust(std::vector<double>{0.01, 0.04, 0.03, 0.005});
    const std::vector<double> want = {0.03, 0.06, 0.06, 0.02};
    for (std::size_t i = 0; i < 4; ++i) EXPECT_NEAR(adj[i], want[i], 1e-15);
}

TEST(Summary, QuantilesAndConfidenceInterval) {
    const std::vector<double> x = {1, 2, 3, 4, 10};
    const Summary s = summarize(x);
    EXPECT_DOUBLE_EQ(s.mean, 4);
    EXPECT_DOUBLE_EQ(s.median, 3);
    EXPECT_DOUBLE_EQ(s.q1, 2);
    EXPECT_DOUBLE_EQ(s.q3, 4);
    EXPECT_NEAR(s.sd, std::sqrt(12.5), 1e-12);
    // R: print(t.test(c(1,2,3,4,10))$conf.int, digits=10) -> -0.3899451654 8.3899451654
    EXPECT_NEAR(s.ci_low, -0.3899451654, 1e-9);
    EXPECT_NEAR(s.ci_high, 8.3899451654, 1e-9);
    const Ratio r = ratio_of_means(std::vector<double>{2, 2.2, 1.8}, std::vector<double>{1, 1.1, 0.9});
    EXPECT_NEAR(r.ratio, 2.0, 1e-12);
    EXPECT_LT(r.ci_low, 2.0);
    EXPECT_GT(r.ci_high, 2.0);
}
