// MeasurementWindows: frames and idle windows marked from a program's own code, saved in the
// trnkit-frames format and in the minimal format, read back by the ordinary marker reader.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <thread>

#include "trn/energy/measurement_window.hpp"
#include "trn/error.hpp"

namespace trn::energy {
namespace {
namespace fs = std::filesystem;

fs::path temp(const std::string& name) { return fs::temp_directory_path() / (name + "_" + std::to_string(::getpid())); }

TEST(MeasurementWindows, FramesAndIdleSavedAndReadBack) {
    MeasurementWindows w({{"backend", "my tracker"}, {"kernel", "match"}});
    w.idle_for(0.005);
    for (int k = 0; k < 3; ++k) {
        auto frame = w.frame();
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    EXPECT_EQ(w.begin_frame(), 3);
    w.end_frame(0.1, 2.0, 0.3);
    w.begin_idle();
    w.end_idle();
    const fs::path full = temp("trn_windows.csv"), minimal = temp("trn_windows_min.csv");
    w.save(full.string());
    const MarkerFile m = read_markers(full.string());
    ASSERT_EQ(m.rows.size(), 6u);
    EXPECT_EQ(m.meta.at("backend"), "my_tracker");  // one header token
    EXPECT_EQ(m.rows[0].kind, "idle");
    EXPECT_GE(m.rows[0].mono_end_ns - m.rows[0].mono_start_ns, 5'000'000);
    for (int k = 0; k < 4; ++k) {
        EXPECT_EQ(m.rows[1 + k].kind, "frame");
        EXPECT_EQ(m.rows[1 + k].id, k);
    }
    EXPECT_GE(m.rows[1].mono_end_ns - m.rows[1].mono_start_ns, 2'000'000);
    EXPECT_DOUBLE_EQ(m.rows[4].exec_ms, 2.0);
    EXPECT_EQ(m.rows[5].kind, "idle");
    EXPECT_EQ(m.rows[5].id, 1);

    w.save_minimal(minimal.string());  // CLOCK_REALTIME seconds
    const MarkerFile mm = read_markers(minimal.string());
    fs::remove(full), fs::remove(minimal);
    ASSERT_EQ(mm.rows.size(), 4u);  // frames only
    EXPECT_TRUE(on_log_clock(mm));
    for (int k = 0; k < 4; ++k) {
        EXPECT_EQ(mm.rows[k].id, k);
        EXPECT_NEAR(static_cast<double>(mm.rows[k].real_start_ns - m.rows[1 + k].real_start_ns), 0, 1000);  // 1 us: a double's UNIX seconds
        EXPECT_EQ(mm.rows[k].mono_start_ns, mm.rows[k].real_start_ns);  // one clock
    }
}

TEST(MeasurementWindows, MisuseAndWriteErrorsAreNamed) {
    MeasurementWindows w;
    EXPECT_THROW(w.end_frame(), Error);
    EXPECT_THROW(w.end_idle(), Error);
    w.begin_frame();
    EXPECT_THROW(w.begin_frame(), Error);  // windows never overlap
    EXPECT_THROW(w.begin_idle(), Error);
    EXPECT_THROW(w.end_idle(), Error);     // the open window is a frame
    const fs::path out = temp("trn_windows_open.csv");
    try {
        w.save(out.string());
        FAIL();
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("still open"), std::string::npos) << e.what();
    }
    EXPECT_FALSE(fs::exists(out));
    w.end_frame();
    EXPECT_THROW(w.idle_for(-1), Error);
    try {
        w.save("/nonexistent-dir/markers.csv");
        FAIL();
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("/nonexistent-dir/markers.csv"), std::string::npos) << e.what();
    }
    MeasurementWindows none;
    EXPECT_THROW(none.save_minimal(out.string()), Error);  // no frame to save
    EXPECT_FALSE(fs::exists(out));
}

}  // namespace
}  // namespace trn::energy
