// run_energy_bench with fake sources and kernels that take a known time: the rows join frame
// time and joules correctly, the idle baseline comes out of the lead idle phase, and the power
// log and marker files it writes reproduce the rows through the ordinary integrate path.
#include <gtest/gtest.h>

#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <thread>

#include "trn/energy/energy_bench.hpp"
#include "trn/energy/parsers.hpp"
#include "trn/error.hpp"

namespace trn::energy {
namespace {
namespace fs = std::filesystem;

// A sampler whose power is 5 W while `busy` is set and 1 W otherwise: the kernel sets it, so
// the true energy of every frame is 5 W x its length (up to one sample period at each edge).
class StepSampler final : public PowerSampler {
public:
    std::atomic<bool> busy{false};
    StepSampler() { tr_.source = "step", tr_.format = "trnkit", tr_.quantity = "test"; }
    std::string describe() const override { return "step:test"; }
    void poll(double t) override { tr_.t.push_back(t), tr_.w.push_back(busy ? 5.0 : 1.0); }
    PowerTrace trace() const override { return tr_; }

private:
    PowerTrace tr_;
};

PhaseTimes sleep_ms(StepSampler* s, int ms) {
    if (s) s->busy = true;
    std::this_thread::sleep_for(std::chrono::milliseconds(ms));
    if (s) s->busy = false;
    PhaseTimes t;
    t.execute_ms = ms;
    return t;
}

BenchConfig small_config() {
    BenchConfig c;
    c.run.frames = 6, c.run.idle_s = 0.02, c.run.lead_idle_s = 0.1, c.run.sync_unit_s = 0;
    c.period_s = 0.002;
    c.platform = "testbox";
    return c;
}

TEST(EnergyBench, RowsJoinFrameTimeAndJoules) {
    StepSampler s;
    const std::vector<BenchTarget> targets = {{"slow", [&] { return sleep_ms(&s, 40); }, {{"backend", "slow"}, {"kernel", "sleep"}}},
                                              {"fast", [&] { return sleep_ms(&s, 16); }, {{"backend", "fast"}, {"kernel", "sleep"}}}};
    const BenchResult res = run_energy_bench(s, targets, small_config());
    ASSERT_EQ(res.rows.size(), 2u);
    for (const auto& r : res.rows) {
        SCOPED_TRACE(r.target);
        EXPECT_EQ(r.platform, "testbox");
        EXPECT_EQ(r.frames, 6u);
        EXPECT_GE(r.usable, 4u);  // a starved sampler thread (loaded machine) may leave a frame short
        EXPECT_NEAR(r.frames_per_s, 1000 / r.frame_ms, 1e-9);
        // Lead idle and gaps at 1 W; a gap's edges interpolate towards the 5 W of the frame before
        // it (one sample period, longer when the sampler thread is starved).
        EXPECT_GE(r.idle_w, 1.0 - 1e-9);
        EXPECT_LT(r.idle_w, 1.4);
        EXPECT_NEAR(r.busy_w, 5.0, 1.0);   // frames at 5 W, edges within a sample period (or a late one)
        // Net = gross - idle x frame time, frame by frame, so also on average.
        EXPECT_NEAR(r.net_j, r.gross_j - r.idle_w * r.frame_ms / 1000, 1e-9);
        EXPECT_NEAR(r.net_j, 4.0 * r.frame_ms / 1000, 0.25 * 4.0 * r.frame_ms / 1000);
        EXPECT_LE(r.gross_ci_low, r.gross_j);
        EXPECT_GE(r.gross_ci_high, r.gross_j);
        EXPECT_GT(r.bound_j, 0);  // 4 W steps at the edges are inside the bound
        EXPECT_EQ(r.run.platform, "testbox:" + r.target + "/sleep");
    }
    EXPECT_GT(res.rows[0].frame_ms, res.rows[1].frame_ms);
    EXPECT_GT(res.rows[0].gross_j, 2 * res.rows[1].gross_j);
    EXPECT_NE(bench_markdown(res).find("| testbox | slow | 6 (6) |"), std::string::npos) << bench_markdown(res);

    // The files a user gets reproduce the rows through the ordinary integrate path.
    const fs::path dir = fs::temp_directory_path() / ("trn_bench_lib_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    std::ofstream(dir / "power.log") << format_trnkit_power(res.trace);
    std::ofstream(dir / "markers.csv") << format_markers(res.rows[0].markers);
    IntegrateRequest q;
    q.realtime = false;
    const RunReport again = integrate_files((dir / "power.log").string(), "auto", {}, (dir / "markers.csv").string(), q);
    fs::remove_all(dir);
    ASSERT_EQ(again.frames.size(), res.rows[0].run.frames.size());
    for (std::size_t i = 0; i < again.frames.size(); ++i) EXPECT_DOUBLE_EQ(again.frames[i].energy.gross_j, res.rows[0].run.frames[i].energy.gross_j);
    EXPECT_EQ(again.log_sha256, res.rows[0].run.log_sha256);
    EXPECT_EQ(again.markers_sha256, res.rows[0].run.markers_sha256);
}

TEST(EnergyBench, FailuresNameTheBackendAndShortFramesAreWarned) {
    StepSampler s;
    EXPECT_THROW(run_energy_bench(s, {}, small_config()), Error);
    const std::vector<BenchTarget> broken = {{"opencl:7", [] () -> PhaseTimes { throw Error("device lost"); }, {}}};
    try {
        run_energy_bench(s, broken, small_config());
        FAIL();
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("backend opencl:7: device lost"), std::string::npos) << e.what();
    }
    BenchConfig c = small_config();
    c.period_s = 0.05;  // slower than the frames: none has 3 samples
    const BenchResult res = run_energy_bench(s, {{"quick", [] { return sleep_ms(nullptr, 1); }, {}}}, c);
    EXPECT_EQ(res.rows[0].usable, 0u);
    ASSERT_FALSE(res.warnings.empty());
    EXPECT_NE(res.warnings[0].find("quick: none of 6 frames is usable"), std::string::npos) << res.warnings[0];
}

}  // namespace
}  // namespace trn::energy
