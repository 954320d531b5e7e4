// The minimal marker format (frame,start_s,end_s on the log's clock) and a log's own start/end
// markers (PMT) as the frames of `integrate`: exact joules on known traces, refusals with file:line.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "trn/energy/run_report.hpp"
#include "trn/error.hpp"
#include "../common/shared_data.hpp"

namespace trn::energy {
namespace {
namespace fs = std::filesystem;

// 3 W from 0 to 10 s on a relative clock, 1 kHz, plus 2 W more in [1, 2) and [3, 3.5).
PowerTrace relative_trace() {
    PowerTrace tr;
    tr.source = "relative.log", tr.format = "trnkit";
    for (int i = 0; i <= 10000; ++i) {
        const double t = i * 1e-3;
        tr.t.push_back(t), tr.w.push_back(((t >= 1 && t < 2) || (t >= 3 && t < 3.5)) ? 5.0 : 3.0);
    }
    return tr;
}

std::string error_of(std::string_view text) {
    try {
        parse_markers(text, "m.csv");
    } catch (const Error& e) {
        return e.what();
    }
    return "(accepted)";
}

TEST(MinimalMarkers, IntegrateOnTheLogsOwnClock) {
    const MarkerFile m = parse_markers("# from my tool\nframe,start_s,end_s\n0,1.0,2.0\n1, 3.0 ,3.5\n\n", "m.csv");
    ASSERT_EQ(m.rows.size(), 2u);
    EXPECT_TRUE(on_log_clock(m));
    // A relative-time log needs no offset: the markers are on its clock, whatever --clock says.
    const RunReport r = integrate_run(relative_trace(), m, IntegrateRequest{});
    EXPECT_EQ(r.clock, "log");
    ASSERT_EQ(r.frames.size(), 2u);
    EXPECT_NEAR(r.frames[0].energy.gross_j, 5.0, 0.002);   // 5 W x 1 s (edges at samples)
    EXPECT_NEAR(r.frames[1].energy.gross_j, 2.5, 0.002);
    EXPECT_NEAR(r.idle_w, 3.0, 0.01);                      // from the gap between the frames
    EXPECT_NEAR(r.frames[0].energy.net_j, 2.0, 0.02);
    EXPECT_NEAR(r.frames[0].marker_ms, 1000, 1e-6);
    // --offset still applies: markers at -1 s land on the same frames.
    IntegrateRequest shifted;
    shifted.align = AlignMode::Offset, shifted.offset_s = 1.0;
    const RunReport s = integrate_run(relative_trace(), parse_markers("frame,start_s,end_s\n0,0,1\n1,2,2.5\n", "m.csv"), shifted);
    EXPECT_NEAR(s.frames[0].energy.gross_j, 5.0, 0.002);
    // The full format on CLOCK_REALTIME is still refused against a relative log.
    MarkerFile full = m;
    full.meta = {{"backend", "x"}};
    EXPECT_THROW(integrate_run(relative_trace(), full, IntegrateRequest{}), Error);
}

TEST(MinimalMarkers, WrittenAndReadExactly) {
    MarkerFile m;
    FrameMarker f;
    f.kind = "frame", f.id = 4, f.real_start_ns = 1733935225'009000001, f.real_end_ns = 1733935225'041000000, f.mono_start_ns = 5, f.mono_end_ns = 7;
    m.rows = {f};
    const std::string text = format_minimal_markers(m);
    EXPECT_NE(text.find("4,1733935225.009000001,1733935225.041000000\n"), std::string::npos) << text;
    EXPECT_NE(format_minimal_markers(m, false).find("4,0.000000005,0.000000007"), std::string::npos);
    const MarkerFile back = parse_markers(text, "m.csv");
    EXPECT_NEAR(static_cast<double>(back.rows[0].real_start_ns - f.real_start_ns), 0, 500);
}

TEST(MinimalMarkers, RefusedWithFileAndLine) {
    EXPECT_NE(error_of("frame,start_s,end_s\n0,1,2\n0,3,4\n").find("m.csv:3: frame id 0 repeats the row at line 2"), std::string::npos);
    EXPECT_NE(error_of("frame,start_s,end_s\n0,1,2\n1,1.5,4\n").find("m.csv:3: frame 1 starts before frame 0 (line 2)"), std::string::npos);
    EXPECT_NE(error_of("frame,start_s,end_s\n0,2,1\n").find("m.csv:2: end_s comes before start_s"), std::string::npos);
    EXPECT_NE(error_of("frame,start_s,end_s\n0,1,2,3\n").find("m.csv:2: expected 3 fields"), std::string::npos);
    EXPECT_NE(error_of("frame,start_s,end_s\n-1,1,2\n").find("m.csv:2: frame id"), std::string::npos);
    EXPECT_NE(error_of("frame,start_s,end_s\n0,nan,2\n").find("m.csv:2: start_s and end_s"), std::string::npos);
    EXPECT_NE(error_of("frame,start_s,end_s\n0,1e12,2e12\n").find("m.csv:2:"), std::string::npos);
    EXPECT_NE(error_of("frame,start_s,end_s\n").find("m.csv:1: no frame rows"), std::string::npos);
    EXPECT_NE(error_of("id,t0,t1\n0,1,2\n").find("or the minimal header 'frame,start_s,end_s'"), std::string::npos);
}

// A PMT dump: samples every 10 ms, 2 W idle and 6 W between the start/end markers.
std::string pmt_dump() {
    std::string s = "timestamp gpu_instant\n";
    char buf[80];
    for (int i = 0; i <= 400; ++i) {
        const double rel = i * 0.01;
        const bool busy = (rel >= 1.0 && rel < 1.5) || (rel >= 2.5 && rel < 3.0);
        std::snprintf(buf, sizeof buf, "%.3f %.3f\n", 1733935225.0 + rel, busy ? 6.0 : 2.0);
        s += buf;
        if (i == 100) s += "M 1.000 \"start\"\n";
        if (i == 150) s += "M 1.500 \"end\"\n";
        if (i == 250) s += "M 2.500 \"start\"\n";
        if (i == 300) s += "M 3.000 \"end\"\n";
    }
    return s;
}

TEST(LogMarkers, PmtStartEndMarkersAreTheFrames) {
    const fs::path log = fs::temp_directory_path() / ("trn_pmt_" + std::to_string(::getpid()) + ".log");
    std::ofstream(log) << pmt_dump();
    const RunReport r = integrate_files(log.string(), "auto", {}, "", IntegrateRequest{});
    ASSERT_EQ(r.frames.size(), 2u);
    EXPECT_EQ(r.clock, "log");
    EXPECT_EQ(r.markers_sha256, r.log_sha256);  // the frames came from the log itself
    EXPECT_NE(r.markers_path.find("its own start/end markers"), std::string::npos);
    for (const auto& f : r.frames) {
        EXPECT_EQ(f.energy.flag, "");
        EXPECT_NEAR(f.energy.duration(), 0.5, 0.011);       // marker placement within one sample
        EXPECT_NEAR(f.energy.gross_j, 3.0, 0.06);           // 6 W x 0.5 s, +- an edge
        EXPECT_NEAR(f.energy.net_j, 2.0, 0.08);             // minus 2 W idle from the gap
    }
    // A log without markers of its own needs a marker file, and says so.
    std::ofstream(log) << "timestamp gpu_instant\n1.0 2.0\n1.1 2.0\n1.2 2.0\n";
    try {
        integrate_files(log.string(), "auto", {}, "", IntegrateRequest{});
        FAIL();
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("no start/end markers of its own: give a marker file (--markers)"), std::string::npos) << e.what();
    }
    fs::remove(log);
}

TEST(LogMarkers, RealPmtDumpIntegratesWithoutAMarkerFile) {
    const std::string log = trn::test::shared_data("powerlogs/pmt/nlesc_ps3results_rtx4000ada_pmt-nvml.log");
    if (log.empty()) GTEST_SKIP() << "TRN_SHARED_DATA/powerlogs/pmt not found: real PMT dump unavailable";
    const RunReport r = integrate_files(log, "auto", {}, "", IntegrateRequest{});
    ASSERT_EQ(r.frames.size(), 4u);  // 8 M lines: 4 start/end pairs
    for (const auto& f : r.frames) {
        EXPECT_EQ(f.energy.flag, "");
        EXPECT_GT(f.energy.net_j, 0) << "the GPU draws more while its kernel runs";
        EXPECT_NEAR(f.energy.duration(), 1.9, 0.1);  // start/end 1.86..1.93 s apart in the dump
    }
}

}  // namespace
}  // namespace trn::energy
