#pragma once
// Measurement windows inside someone else's program (as Zeus' begin_window/end_window): mark
// where each frame of work starts and ends, and where the program idles, then save the marks in
// the marker format `trnkit frames` writes. Run any power logger beside the program (`trnkit
// energy sample`, nvidia-smi, tegrastats, PMT, ...) and `trnkit energy integrate LOG --markers
// FILE` gives per-frame joules. Both clocks are recorded (CLOCK_MONOTONIC and CLOCK_REALTIME);
// save_minimal() writes the minimal format (frame,start_s,end_s) on one of them. One object is
// marked from one thread (windows are a sequence, not concurrent).
//
//   trn::energy::MeasurementWindows w({{"backend", "mine"}});
//   w.idle_for(1.0);                        // an idle baseline phase
//   for (...) { auto frame = w.frame(); work(); }   // or begin_frame() / end_frame()
//   w.save("markers.csv");                  // written whole (temporary name, then rename)
#include <map>
#include <optional>
#include <string>

#include "trn/energy/frame_runner.hpp"
#include "trn/energy/markers.hpp"
#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn::energy {

class MeasurementWindows {
public:
    // meta goes into the marker header (backend, kernel, ...: key=value, spaces and '=' replaced).
    explicit MeasurementWindows(std::map<std::string, std::string> meta = {});

    // Opens frame N (0, 1, ... in order) and returns N. Throws trn::Error while another window
    // is open: windows never overlap (their joules would be counted twice).
    int begin_frame();
    // Closes the open frame; phase times (ms) are optional, as the backend measured them.
    void end_frame(double write_ms = 0, double exec_ms = 0, double read_ms = 0);
    // An idle window (the baseline `integrate` subtracts): begin_idle/end_idle around a wait of
    // the program's own, or idle_for(seconds), which sleeps.
    void begin_idle();
    void end_idle();
    void idle_for(double seconds);

    // Closes a frame or idle window when it goes out of scope (an exception ends it too).
    class Scope {
    public:
        explicit Scope(MeasurementWindows& w) : w_(&w) {}
        ~Scope();
        Scope(const Scope&) = delete;
        Scope& operator=(const Scope&) = delete;

    private:
        MeasurementWindows* w_;
    };
    [[nodiscard]] Scope frame();  // begin_frame(); the frame ends with the Scope

    bool open() const { return open_.has_value(); }
    std::size_t frames() const { return next_frame_; }
    const MarkerFile& markers() const { return markers_; }

    // Writes every closed window in the trnkit-frames format (read_markers reads it back), or the
    // minimal format on CLOCK_REALTIME (realtime) or CLOCK_MONOTONIC seconds; atomically
    // (trn::io::write_file_atomic). Throws trn::Error naming the path on any write error, and
    // when a window is still open.
    void save(const std::string& path) const;
    void save_minimal(const std::string& path, bool realtime = true) const;

private:
    void begin(const char* kind, int id);
    void end(const char* kind);
    MarkerFile markers_;
    std::optional<FrameMarker> open_;
    int next_frame_ = 0, next_idle_ = 0;
};

}  // namespace trn::energy
TRN_API_END
