// Statistics added for issue 16, checked against R 4.2.2 (Debian 12 r-base-core; the commands are
// quoted next to the values, which were produced once; the test itself needs no R): the
// Mann-Whitney U / Wilcoxon rank-sum test, p-values that underflow printed as bounds, Shapiro-Wilk
// above n = 5000 on a subsample, the bootstrap CI of a ratio, and what `compare` does with them:
// Welch and Student in one run, runs as the unit, and the note when normality is rejected.
#include <gtest/gtest.h>

#include <cstdio>

#include <boost/math/distributions/normal.hpp>
#include <cmath>
#include <functional>
#include <nlohmann/json.hpp>
#include <vector>

#include "synthetic_run.hpp"
#include "trn/energy/compare.hpp"
#include "trn/energy/stats.hpp"
#include "trn/error.hpp"

namespace trn::energy {
namespace {

std::vector<double> make(int from, int to, const std::function<double(int)>& f) {
    std::vector<double> v;
    for (int i = from; i <= to; ++i) v.push_back(f(i));
    return v;
}

struct MwRef {
    const char* r;
    std::vector<double> a, b;
    double w, p;
    bool exact;
};

// R: r <- suppressWarnings(wilcox.test(a, b)); sprintf("W=%.1f p=%.15g", r$statistic, r$p.value)
TEST(MannWhitney, MatchesR) {
    const std::vector<MwRef> refs = {
        {"sqrt(1:12), log(1:15)*2+0.3", make(1, 12, [](int i) { return std::sqrt(i); }), make(1, 15, [](int i) { return std::log(i) * 2 + 0.3; }), 31,
         0.00309436454274252, true},
        {"c(1,2,4), c(3,5,6,7)", {1, 2, 4}, {3, 5, 6, 7}, 1, 0.114285714285714, true},
        {"ties, n < 50", {1.83, 0.50, 1.62, 2.48, 1.68, 1.88, 1.55, 3.06, 1.30}, {0.878, 0.647, 0.598, 2.05, 1.06, 1.29, 1.06, 3.14, 1.29}, 58,
         0.132919458185319, false},
        {"sin(1:60)+0.3, cos(1:70)", make(1, 60, [](int i) { return std::sin(i) + 0.3; }), make(1, 70, [](int i) { return std::cos(i); }), 2679,
         0.00689904026110585, false},
        {"1:60, 101:160", make(1, 60, [](int i) { return i; }), make(101, 160, [](int i) { return i; }), 0, 3.55657097498477e-21, false},
        {"round(sin(1:80)*3), round(cos(1:40)*3)+1", make(1, 80, [](int i) { return std::nearbyint(std::sin(i) * 3); }),
         make(1, 40, [](int i) { return std::nearbyint(std::cos(i) * 3) + 1; }), 1207.5, 0.0275957184288019, false},
    };
    for (const auto& r : refs) {
        const RankTest t = mann_whitney_u(r.a, r.b);
        EXPECT_DOUBLE_EQ(t.w, r.w) << r.r;
        EXPECT_NEAR(t.p / r.p, 1.0, 1e-9) << r.r;
        EXPECT_EQ(t.exact, r.exact) << r.r;
    }
    // The swapped test has W' = na nb - W and the same p.
    const RankTest s = mann_whitney_u(refs[0].b, refs[0].a);
    EXPECT_DOUBLE_EQ(s.w, 12 * 15 - 31);
    EXPECT_NEAR(s.p, refs[0].p, 1e-15);
    EXPECT_THROW(mann_whitney_u(std::vector<double>{}, std::vector<double>{1}), trn::Error);
    EXPECT_DOUBLE_EQ(mann_whitney_u(std::vector<double>{2, 2}, std::vector<double>{2, 2, 2}).p, 1.0);
}

// R: t.test((1:1000)+1e6, 1:1000)$p.value -> 0 ; wilcox.test(1:5000, 10001:15000)$p.value -> 0
TEST(PValues, UnderflowIsPrintedAsABound) {
    const auto a = make(1, 1000, [](int i) { return i + 1e6; }), b = make(1, 1000, [](int i) { return i; });
    const TTest t = welch_t_test(a, b);
    EXPECT_EQ(t.p, 0.0);
    EXPECT_EQ(format_p(t.p), "< 1e-300");
    EXPECT_EQ(format_p(mann_whitney_u(make(1, 5000, [](int i) { return i; }), make(10001, 15000, [](int i) { return i; })).p), "< 1e-300");
    EXPECT_EQ(format_p(0.0123456), "0.0123");
    EXPECT_EQ(format_p(3.456e-7), "3.46e-07");
    EXPECT_EQ(format_p(2e-300), "2.00e-300");
}

TEST(Normality, AboveFiveThousandOnADocumentedSubsample) {
    const auto qn = [](double p) { return boost::math::quantile(boost::math::normal(), p); };
    const auto normal = make(1, 6000, [&](int i) { return qn(((static_cast<long>(i) * 2731) % 6001) / 6001.0); });
    const Normality n = normality_test(normal);
    EXPECT_EQ(n.n, 6000u);
    EXPECT_EQ(n.used, 5000u);
    EXPECT_TRUE(n.subsampled());
    EXPECT_GT(n.sw.p, 0.05);
    EXPECT_EQ(normality_test(normal).sw.w, n.sw.w) << "a fixed seed: the same data give the same result";
    const auto skewed = make(1, 6000, [](int i) { return std::exp(((i * 37) % 6007) / 1000.0); });
    EXPECT_LT(normality_test(skewed).sw.p, 1e-10);
    const auto small = make(1, 20, [](int i) { return std::sqrt(i); });
    EXPECT_FALSE(normality_test(small).subsampled());
    EXPECT_EQ(normality_test(small).sw.w, shapiro_wilk(small).w);
}

TEST(Bootstrap, RatioIntervalIsReproducibleAndFollowsTheData) {
    const auto a = make(1, 400, [](int i) { return 3.0 + 0.3 * std::sin(i * 1.3); });
    const auto b = make(1, 300, [](int i) { return 2.0 + 0.2 * std::cos(i * 0.7); });
    const BootstrapRatio r = bootstrap_ratio(a, b, 4000);
    EXPECT_EQ(r.resamples, 4000u);
    EXPECT_LT(r.ci_low, r.ratio);
    EXPECT_GT(r.ci_high, r.ratio);
    const BootstrapRatio again = bootstrap_ratio(a, b, 4000);
    EXPECT_EQ(again.ci_low, r.ci_low);
    EXPECT_EQ(again.ci_high, r.ci_high);
    // Symmetric, well-behaved data: the delta-method interval and the bootstrap agree closely.
    const Ratio d = ratio_of_means(a, b);
    EXPECT_NEAR(r.ci_low, d.ci_low, 0.1 * (d.ci_high - d.ci_low));
    EXPECT_NEAR(r.ci_high, d.ci_high, 0.1 * (d.ci_high - d.ci_low));
    // Skewed numerator with few values: the bootstrap interval is skewed too (longer above).
    const std::vector<double> s = {1, 1.1, 1.2, 1.1, 1.0, 1.3, 9.0, 1.2};
    const BootstrapRatio k = bootstrap_ratio(s, std::vector<double>{1, 1, 1.01, 0.99}, 4000);
    EXPECT_GT(k.ci_high - k.ratio, 1.5 * (k.ratio - k.ci_low));
    EXPECT_THROW(bootstrap_ratio(a, std::vector<double>{0, 0}, 4000), trn::Error);
}

RunReport report(const std::string& platform, const std::vector<double>& joules, const std::string& log_hash) {
    return test::report_with_energies(platform, joules, log_hash);
}

std::vector<double> around(double mean, int n, double spread, int phase) {
    return make(1, n, [&](int i) { return mean * (1 + spread * std::sin(i * 2.1 + phase)); });
}

TEST(CompareStatistics, WelchAndStudentInOneRunAndRankTestBeside) {
    std::vector<RunInput> in = {{"a.json", "1", report("A", around(0.010, 40, 0.1, 0), "la")}, {"b.json", "2", report("B", around(0.012, 30, 0.1, 1), "lb")}};
    CompareOptions o;
    o.both = true, o.bootstrap_resamples = 2000;
    const Comparison c = compare_runs(in, o);
    EXPECT_EQ(c.unit, "frames");
    ASSERT_EQ(c.pairs.size(), 1u);
    const PairStats& p = c.pairs[0];
    ASSERT_EQ(p.t_tests.size(), 2u);
    EXPECT_EQ(p.t_tests[0].test, "welch");
    EXPECT_EQ(p.t_tests[1].test, "student");
    const auto& a = c.platforms[0].energy_mj;
    const auto& b = c.platforms[1].energy_mj;
    EXPECT_EQ(p.t_tests[0].t.p, welch_t_test(a, b).p);
    EXPECT_EQ(p.t_tests[1].t.p, student_t_test(a, b).p);
    EXPECT_EQ(p.rank.p, mann_whitney_u(a, b).p);
    ASSERT_TRUE(p.bootstrap.has_value());
    EXPECT_LT(p.bootstrap->ci_low, p.ratio.ratio);
    const std::string md = tables_markdown(c);
    for (const char* h : {"| Welch |", "| Student |", "Table 4", "Mann-Whitney", "bootstrap"}) EXPECT_NE(md.find(h), std::string::npos) << h;
    const std::string summary = comparison_summary_text(c);
    EXPECT_NE(summary.find("Welch p(Holm)"), std::string::npos) << summary;
    EXPECT_NE(summary.find("Student p(Holm)"), std::string::npos) << summary;
    EXPECT_EQ(summary.find("| A |"), std::string::npos) << "the summary is not the tables";
    const auto j = nlohmann::json::parse(comparison_json(c));
    EXPECT_EQ(j["pairs"][0]["t_tests"].size(), 2u);
    EXPECT_EQ(j["config"]["test"], "welch+student");
}

TEST(CompareStatistics, SeveralRunsPerPlatformMakeTheRunTheUnit) {
    std::vector<RunInput> in;
    const double a_means[] = {0.010, 0.0104, 0.0098}, b_means[] = {0.011, 0.0113, 0.0109, 0.0112};
    for (int k = 0; k < 3; ++k) in.push_back({"a" + std::to_string(k), "ha" + std::to_string(k), report("A", around(a_means[k], 50, 0.05, k), "la" + std::to_string(k))});
    for (int k = 0; k < 4; ++k) in.push_back({"b" + std::to_string(k), "hb" + std::to_string(k), report("B", around(b_means[k], 50, 0.05, k), "lb" + std::to_string(k))});
    CompareOptions o;
    o.bootstrap_resamples = 1000;
    const Comparison c = compare_runs(in, o);
    EXPECT_EQ(c.unit, "runs");
    const PlatformStats& a = c.platforms[0];
    ASSERT_EQ(a.run_mean_mj.size(), 3u);
    EXPECT_EQ(a.energy.n, 150u);
    const PairStats& p = c.pairs[0];
    EXPECT_EQ(p.n_a, 3u);
    EXPECT_EQ(p.n_b, 4u);
    // The test is the t-test of the run means; frames pooled would claim far more certainty.
    EXPECT_DOUBLE_EQ(p.t().p, welch_t_test(a.run_mean_mj, c.platforms[1].run_mean_mj).p);
    EXPECT_GT(p.t().p, welch_t_test(a.energy_mj, c.platforms[1].energy_mj).p * 100);
    EXPECT_GT(a.run_means.sd, 0);
    EXPECT_GT(a.within_run_sd, 0);
    // The CI shown beside the mean is the run means' too, not the (narrower) pooled frames' one.
    const auto g4 = [](double v) { char b[32]; std::snprintf(b, sizeof b, "%.4g", v); return std::string(b); };
    const std::string run_ci = "[" + g4(a.run_means.ci_low) + ", " + g4(a.run_means.ci_high) + "]";
    const std::string frame_ci = "[" + g4(a.energy.ci_low) + ", " + g4(a.energy.ci_high) + "]";
    ASSERT_NE(run_ci, frame_ci);
    for (const std::string& text : {tables_markdown(c), comparison_summary_text(c)}) {
        EXPECT_NE(text.find(run_ci), std::string::npos) << text;
        EXPECT_EQ(text.find(frame_ci), std::string::npos) << text;
    }
    o.unit = TestUnit::Frames;
    const Comparison f = compare_runs(in, o);
    EXPECT_EQ(f.unit, "frames");
    EXPECT_EQ(f.pairs[0].n_a, 150u);
    bool warned = false;
    for (const auto& n : f.notes) warned = warned || n.find("between-run variation is not in the tests' error") != std::string::npos;
    EXPECT_TRUE(warned);
}

TEST(CompareStatistics, RejectedNormalitySaysSoAndTestsAboveFiveThousandFrames) {
    // A: heavily skewed energies (a few slow frames), 6000 of them; B: near-normal.
    const auto skewed = make(1, 6000, [](int i) { return 0.010 * (1 + std::exp(((i * 37) % 6007) / 1500.0) / 50); });
    std::vector<RunInput> in = {{"a.json", "1", report("A", skewed, "la")}, {"b.json", "2", report("B", around(0.012, 300, 0.1, 1), "lb")}};
    CompareOptions o;
    o.bootstrap_resamples = 200;
    const Comparison c = compare_runs(in, o);
    ASSERT_TRUE(c.platforms[0].shapiro.has_value()) << c.platforms[0].shapiro_note;
    EXPECT_EQ(c.platforms[0].shapiro_used, 5000u);
    EXPECT_TRUE(c.platforms[0].normality_rejected(0.05));
    EXPECT_TRUE(c.pairs[0].normality_rejected);
    std::string notes;
    for (const auto& n : c.notes) notes += n + "\n";
    EXPECT_NE(notes.find("A: Shapiro-Wilk rejects normality"), std::string::npos) << notes;
    EXPECT_NE(notes.find("subsample of 5000 of 6000"), std::string::npos) << notes;
    EXPECT_NE(tables_markdown(c).find("**rejected**"), std::string::npos);
    EXPECT_NE(comparison_summary_text(c).find("normality REJECTED"), std::string::npos);
}

}  // namespace
}  // namespace trn::energy
