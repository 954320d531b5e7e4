// Run reports (JSON round trip, CSV, hashes) and platform comparison on synthetic runs whose
// energies are known.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "sha256.hpp"
#include "synthetic_run.hpp"
#include "trn/error.hpp"
#include "trn/energy/compare.hpp"
#include "trn/energy/run_report.hpp"

namespace trn::energy {
namespace {

RunReport synthetic_report(const std::string& platform, double busy_w, double noise_w, int frames = 25) {
    const auto tl = test::make_timeline(frames, 0.05, 0.05);
    const double ref = tl.markers.rows.front().real_start_ns * 1e-9;
    const auto tr = test::sample_trace(tl.markers, test::TraceClock{-ref + 0.2, 0, ref}, 0, 0.2 + 5, 1e-3, 2.0, busy_w, noise_w);
    IntegrateRequest q;
    q.platform = platform, q.align = AlignMode::Offset, q.offset_s = -ref + 0.2;
    return integrate_run(tr, tl.markers, q);
}

TEST(Sha256, KnownVectors) {
    EXPECT_EQ(sha256_hex(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
    EXPECT_EQ(sha256_hex("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
    EXPECT_EQ(sha256_hex(std::string(1000, 'a')), "41edece42d63e8d9bf515a9ba6932e1c20cbc9f5a5d134645adb5db1b9737ea3");
}

TEST(RunReport, JsonRoundTripAndCsv) {
    const RunReport r = synthetic_report("A", 3.0, 0.05);
    const RunReport back = parse_run_report_json(run_report_json(r), "mem");
    ASSERT_EQ(back.frames.size(), r.frames.size());
    EXPECT_EQ(back.platform, "A");
    EXPECT_EQ(back.align_mode, "offset");
    for (std::size_t i = 0; i < r.frames.size(); ++i) {
        EXPECT_DOUBLE_EQ(back.frames[i].energy.net_j, r.frames[i].energy.net_j);
        EXPECT_EQ(back.frames[i].energy.samples, r.frames[i].energy.samples);
        EXPECT_DOUBLE_EQ(back.frames[i].exec_ms, r.frames[i].exec_ms);
    }
    const std::string csv = run_report_csv(r);
    EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), static_cast<long>(r.frames.size() + 1));
    EXPECT_THROW(parse_run_report_json("{\"x\":1}", "bad.json"), trn::Error);
    EXPECT_THROW(parse_run_report_json("not json", "bad.json"), trn::Error);
    auto j = nlohmann::json::parse(run_report_json(r));
    j["frames"][0].erase("net_j");
    try {
        parse_run_report_json(j.dump(), "cut.json");
        FAIL() << "missing field accepted";
    } catch (const trn::Error& e) {
        EXPECT_NE(std::string(e.what()).find("cut.json"), std::string::npos);
    }
}

TEST(Compare, TablesStatisticsAndProvenance) {
    // Platform B draws 1.5x the busy power of A: energy ratio A/B = 2/3 within noise.
    std::vector<RunInput> in = {{"a1.json", "h1", synthetic_report("A", 2.0, 0.3)},
                                {"a2.json", "h2", synthetic_report("A", 2.0, 0.3, 20)},
                                {"b.json", "h3", synthetic_report("B", 3.0, 0.3)},
                                {"c.json", "h4", synthetic_report("C", 2.0, 0.3)}};
    const Comparison c = compare_runs(in, CompareOptions{});
    ASSERT_EQ(c.platforms.size(), 3u);
    EXPECT_EQ(c.platforms[0].runs, 2u);
    EXPECT_EQ(c.platforms[0].energy.n, 45u);
    ASSERT_EQ(c.pairs.size(), 3u);
    const PairStats& ab = c.pairs[0];
    EXPECT_EQ(ab.a, "A");
    EXPECT_EQ(ab.b, "B");
    EXPECT_LT(ab.p_holm(), 1e-6);
    EXPECT_NEAR(ab.ratio.ratio, 2.0 / 3.0, 0.03);
    EXPECT_LT(ab.ratio.ci_low, ab.ratio.ratio);
    EXPECT_GT(ab.ratio.ci_high, ab.ratio.ratio);
    for (const auto& p : c.pairs) EXPECT_GE(p.p_holm(), p.t().p);
    for (const auto& p : c.platforms) ASSERT_TRUE(p.shapiro.has_value()) << p.shapiro_note;
    const std::string md = tables_markdown(c);
    for (const char* h : {"Table 1", "Table 2", "Table 3", "| A | B |", "Welch"}) EXPECT_NE(md.find(h), std::string::npos) << h;
    const auto j = nlohmann::json::parse(comparison_json(c));
    EXPECT_EQ(j["inputs"].size(), 4u);
    EXPECT_EQ(j["inputs"][0]["sha256"], "h1");
    EXPECT_EQ(j["platforms"].size(), 3u);
    EXPECT_EQ(j["pairs"].size(), 3u);
    const std::string t1 = energy_table_csv(c), t3 = ttest_table_csv(c);
    EXPECT_EQ(std::count(t1.begin(), t1.end(), '\n'), 4);
    EXPECT_EQ(std::count(t3.begin(), t3.end(), '\n'), 4);
    // Student's t is an option; one platform with one frame cannot be tested and says why.
    CompareOptions student;
    student.student = true;
    EXPECT_NE(tables_markdown(compare_runs(in, student)).find("Student"), std::string::npos);
    const Comparison tiny = compare_runs({{"t.json", "h", synthetic_report("T", 2.0, 0.3, 1)}, in[2]}, CompareOptions{});
    EXPECT_FALSE(tiny.platforms[0].shapiro.has_value());
    EXPECT_FALSE(tiny.pairs[0].note.empty());
    EXPECT_THROW(compare_runs({}, CompareOptions{}), trn::Error);
}

}  // namespace
}  // namespace trn::energy
