// Automatic alignment on synthetic traces with a known clock offset and drift, the explicit and
// same-clock modes, and the +-1 sample sensitivity.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "../cli/cli_process.hpp"
#include "synthetic_run.hpp"
#include "trn/energy/align.hpp"
#include "trn/error.hpp"
#include "trn/energy/run_report.hpp"

namespace trn::energy {
namespace {

using test::make_timeline;
using test::sample_trace;
using test::TraceClock;

TEST(Align, RecoversOffsetOnRelativeClock) {
    const auto tl = make_timeline(30, 0.05, 0.08);
    const double ref = tl.markers.rows.front().real_start_ns * 1e-9;
    TraceClock c{-ref + 3.25, 0, ref};  // the run starts 3.25 s into a log with relative times
    const auto tr = sample_trace(tl.markers, c, 0, 3.25 + 6, 1e-3, 2.0, 3.0, 0.05);
    AlignOptions o;
    const Alignment a = align_auto(tr, tl.markers, o);
    EXPECT_NEAR(a.mapping.offset_s, c.offset, 0.5e-3);
    EXPECT_NEAR(a.mapping.drift, 0, 5e-5);
    EXPECT_NEAR(a.contrast_w, 3.0, 0.2);
    EXPECT_LT(a.residual_s, 1e-3);
}

TEST(Align, RecoversOffsetAndDrift) {
    const auto tl = make_timeline(60, 0.04, 0.06);
    const double ref = tl.markers.rows.front().real_start_ns * 1e-9;
    TraceClock c{-ref + 1.5, 400e-6, ref};  // logger clock runs 400 ppm fast
    const auto tr = sample_trace(tl.markers, c, 0, 1.5 + 8, 0.5e-3, 1.0, 4.0, 0.1);
    const Alignment a = align_auto(tr, tl.markers, AlignOptions{});
    EXPECT_NEAR(a.mapping.offset_s + a.mapping.drift * (a.mapping.ref_s - ref), c.offset, 0.5e-3);
    EXPECT_NEAR(a.mapping.drift, 400e-6, 15e-6);
    EXPECT_GE(a.window_offset_s.size(), 2u);
    EXPECT_FALSE(a.ambiguous) << a.confidence;
    EXPECT_LT(a.residual_s, 0.1e-3) << a.confidence;
    // With the estimate, every frame's energy matches the true busy energy within the bound.
    IntegrateRequest q;
    q.align = AlignMode::Auto;
    const RunReport r = integrate_run(tr, tl.markers, q);
    std::size_t k = 0;
    for (const auto& row : tl.markers.rows) {
        if (row.kind != "frame") continue;
        const auto& f = r.frames.at(k++).energy;
        const double true_len = (row.real_end_ns - row.real_start_ns) * 1e-9 * (1 + c.drift);
        ASSERT_TRUE(f.flag.empty()) << f.flag;
        EXPECT_NEAR(f.net_j, 4.0 * true_len, 4.0 * 1.5e-3 + 0.2 * true_len) << "frame " << f.id;
    }
    EXPECT_GT(r.shift.relative_plus, 0);
    EXPECT_GT(r.shift.relative_minus, 0);
    EXPECT_NEAR(r.shift.dt_s, 0.5e-3, 1e-9);
}

TEST(Align, SearchWindowAndRefusals) {
    const auto tl = make_timeline(10, 0.05, 0.05);
    const double ref = tl.markers.rows.front().real_start_ns * 1e-9;
    TraceClock c{-ref + 0.7, 0, ref};
    const auto tr = sample_trace(tl.markers, c, 0, 0.7 + 3.5, 1e-3, 2.0, 3.0);
    AlignOptions o;
    o.guess_s = c.offset + 0.02, o.search_s = 0.05;
    EXPECT_NEAR(align_auto(tr, tl.markers, o).mapping.offset_s, c.offset, 1e-3);
    // A trace shorter than the run cannot hold it.
    const auto short_tr = sample_trace(tl.markers, c, 0, 1.0, 1e-3, 2.0, 3.0);
    EXPECT_THROW(align_auto(short_tr, tl.markers, AlignOptions{}), trn::Error);
    MarkerFile idle_only;
    idle_only.rows.push_back(tl.markers.rows.front());
    EXPECT_THROW(align_auto(tr, idle_only, AlignOptions{}), trn::Error);
}

TEST(Align, ExplicitOffsetAndSameClock) {
    const auto tl = make_timeline(8, 0.1, 0.1);
    const double ref = tl.markers.rows.front().real_start_ns * 1e-9;
    TraceClock c{-ref + 0.25, 0, ref};
    const auto tr = sample_trace(tl.markers, c, 0, 0.25 + 3, 1e-3, 2.0, 3.0);
    IntegrateRequest q;
    q.align = AlignMode::Offset, q.offset_s = c.offset;
    const RunReport r = integrate_run(tr, tl.markers, q);
    ASSERT_EQ(r.frames.size(), 8u);
    for (const auto& f : r.frames) EXPECT_NEAR(f.energy.net_j, 3.0 * f.energy.duration(), 3.0 * 2e-3);
    EXPECT_NEAR(r.idle_w, 2.0, 0.02);  // idle rows include the ramps at frame edges
    // Same clock: a relative-time log cannot meet CLOCK_REALTIME markers.
    q.align = AlignMode::SameClock;
    EXPECT_THROW(integrate_run(tr, tl.markers, q), trn::Error);
    // A wall-clock log on the marker clock integrates as is.
    const auto wall = sample_trace(tl.markers, TraceClock{0, 0, ref}, ref - 0.1, ref + 3, 1e-3, 2.0, 3.0, 0, true);
    const RunReport same = integrate_run(wall, tl.markers, q);
    for (std::size_t i = 0; i < same.frames.size(); ++i) EXPECT_NEAR(same.frames[i].energy.net_j, r.frames[i].energy.net_j, 3.0 * 2e-3);
}

// A log on the marker clock itself: the estimate must be 0 offset and no drift, whatever the
// phase of the samples against the edges. (The old window fit reported up to -2.5 ms and
// 700 ppm here at 5 ms sampling, and 27 ppm at 1 ms.)
TEST(Align, ExactAlignmentIsRecoveredTightly) {
    const auto tl = make_timeline(30, 0.05, 0.08);
    const double ref = tl.markers.rows.front().real_start_ns * 1e-9;
    for (const double dt : {1e-3, 5e-3})
        for (const double phase : {0.0, 0.0007, 0.0029, 0.0041}) {
            const auto tr = sample_trace(tl.markers, TraceClock{0, 0, ref}, ref - 0.5 - phase, ref + 6.5, dt, 2.0, 3.0, 0, true);
            const Alignment a = align_auto(tr, tl.markers, AlignOptions{});
            EXPECT_NEAR(a.mapping.offset_s, 0, dt / 5) << "dt " << dt << " phase " << phase << ": " << a.confidence;
            EXPECT_NEAR(a.mapping.drift, 0, 20e-6) << "dt " << dt << " phase " << phase << ": " << a.confidence;
            EXPECT_FALSE(a.ambiguous) << a.confidence;
            EXPECT_TRUE(a.has_sync);
            EXPECT_LT(a.candidate_ratio, kAmbiguousRatio) << a.confidence;
        }
}

// Strictly periodic frames without a sync pattern: shifting by one frame period fits almost as
// well, so the estimate is flagged and integrate_run refuses it unless insisted on. The same
// run with a sync pattern is unambiguous although the frames alone are just as periodic.
TEST(Align, PeriodicRunWithoutSyncIsAmbiguous) {
    const auto bare = make_timeline(100, 0.01, 0.01, 0, 0.5, 0);
    const double ref = bare.markers.rows.front().real_start_ns * 1e-9;
    TraceClock c{-ref + 1.0, 0, ref};
    const auto tr = sample_trace(bare.markers, c, 0, 4.5, 1e-3, 2.0, 3.0, 0.05);
    const Alignment a = align_auto(tr, bare.markers, AlignOptions{});
    EXPECT_TRUE(a.ambiguous) << a.confidence;
    EXPECT_FALSE(a.has_sync);
    EXPECT_GE(a.candidate_ratio, kAmbiguousRatio) << a.confidence;
    EXPECT_NEAR(std::abs(a.second_offset_s - a.mapping.offset_s), 0.02, 1e-3) << a.confidence;  // one period away
    EXPECT_NE(a.confidence.find("AMBIGUOUS"), std::string::npos) << a.confidence;
    IntegrateRequest q;
    q.align = AlignMode::Auto;
    try {
        integrate_run(tr, bare.markers, q);
        ADD_FAILURE() << "an ambiguous alignment was accepted";
    } catch (const trn::Error& e) {
        EXPECT_NE(std::string(e.what()).find("ambiguous"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("`insist`"), std::string::npos) << e.what();  // the CLI names it --insist
    }
    q.insist = true;
    const RunReport r = integrate_run(tr, bare.markers, q);
    ASSERT_FALSE(r.warnings.empty());
    EXPECT_NE(r.warnings.front().find("AMBIGUOUS"), std::string::npos) << r.warnings.front();
    const RunReport back = parse_run_report_json(run_report_json(r), "r.json");
    EXPECT_TRUE(back.alignment.ambiguous);
    EXPECT_NEAR(back.alignment.candidate_ratio, a.candidate_ratio, 1e-12);

    const auto synced = make_timeline(100, 0.01, 0.01, 0.1, 0.5, 0);
    const auto tr2 = sample_trace(synced.markers, c, 0, 5.5, 1e-3, 2.0, 3.0, 0.05);
    const Alignment s = align_auto(tr2, synced.markers, AlignOptions{});
    EXPECT_FALSE(s.ambiguous) << s.confidence;
    EXPECT_TRUE(s.has_sync);
    EXPECT_LT(s.sync_ratio, kAmbiguousRatio) << s.confidence;
    EXPECT_NEAR(s.mapping.offset_s, c.offset, 0.6e-3) << s.confidence;  // edges on samples read half a sample early
}

// The CLI refuses the ambiguous estimate with one line and accepts it with --insist, saying so
// on stderr and in the report.
TEST(Align, CliRefusesAmbiguousUnlessInsisted) {
    namespace fs = std::filesystem;
    const fs::path dir = fs::temp_directory_path() / ("trn_align_cli_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    const auto tl = make_timeline(100, 0.01, 0.01, 0, 0.5, 0);
    const double ref = tl.markers.rows.front().real_start_ns * 1e-9;
    std::ofstream(dir / "m.csv") << format_markers(tl.markers);
    std::ofstream(dir / "p.log") << format_trnkit_power(sample_trace(tl.markers, TraceClock{-ref + 1.0, 0, ref}, 0, 4.5, 1e-3, 2.0, 3.0, 0.05));
    const std::string base = "energy integrate " + (dir / "p.log").string() + " --markers " + (dir / "m.csv").string() + " --align auto --json " +
                             (dir / "r.json").string();
    const auto refused = trn::test::run_trnkit(base);
    EXPECT_NE(refused.code, 0) << refused.output;
    EXPECT_NE(refused.output.find("ambiguous"), std::string::npos) << refused.output;
    EXPECT_FALSE(fs::exists(dir / "r.json"));
    const auto insisted = trn::test::run_trnkit(base + " --insist");
    EXPECT_EQ(insisted.code, 0) << insisted.output;
    EXPECT_NE(insisted.output.find("alignment confidence:"), std::string::npos) << insisted.output;
    EXPECT_NE(insisted.output.find("warning: AMBIGUOUS"), std::string::npos) << insisted.output;
    EXPECT_TRUE(read_run_report((dir / "r.json").string()).alignment.ambiguous);
    fs::remove_all(dir);
}

}  // namespace
}  // namespace trn::energy
