// Automatic alignment on synthetic traces with a known clock offset and drift, the explicit and
// same-clock modes, and the +-1 sample sensitivity.
#include <gtest/gtest.h>

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
    EXPECT_NEAR(a.mapping.drift, 400e-6, 60e-6);
    EXPECT_GE(a.window_offset_s.size(), 2u);
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

}  // namespace
}  // namespace trn::energy
