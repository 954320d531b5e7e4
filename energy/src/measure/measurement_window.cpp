#include "trn/energy/measurement_window.hpp"

#include <thread>

#include "trn/error.hpp"
#include "trn/io/atomic_file.hpp"

namespace trn::energy {

MeasurementWindows::MeasurementWindows(std::map<std::string, std::string> meta) {
    // The header is space-separated key=value: keep every key and value one token.
    auto token = [](std::string s) {
        for (char& ch : s)
            if (ch == ' ' || ch == '=' || ch == ',' || ch == '\n' || ch == '\r' || ch == '\t') ch = '_';
        return s;
    };
    for (const auto& [k, v] : meta)
        if (!k.empty()) markers_.meta[token(k)] = token(v);
    markers_.meta["sampler"] = "windows";
}

void MeasurementWindows::begin(const char* kind, int id) {
    if (open_) throw Error(std::string("measurement window: cannot begin ") + kind + " while " + open_->kind + " " + std::to_string(open_->id) + " is open");
    const ClockPair now = now_both();
    FrameMarker m;
    m.kind = kind, m.id = id;
    m.mono_start_ns = now.mono_ns, m.real_start_ns = now.real_ns;
    // A wall clock stepped back below the previous window's end would make the file unreadable
    // (rows out of time order): refuse it here, where the program can still react.
    if (!markers_.rows.empty() && (m.real_start_ns < markers_.rows.back().real_end_ns || m.mono_start_ns < markers_.rows.back().mono_end_ns))
        throw Error("measurement window: the clock stepped back since the previous window (CLOCK_REALTIME adjusted?)");
    open_ = m;
}

void MeasurementWindows::end(const char* kind) {
    if (!open_ || open_->kind != kind) throw Error(std::string("measurement window: end_") + kind + " without begin_" + kind);
    const ClockPair now = now_both();
    open_->mono_end_ns = now.mono_ns, open_->real_end_ns = now.real_ns;
    if (open_->real_end_ns < open_->real_start_ns) throw Error("measurement window: CLOCK_REALTIME stepped back inside a window");
    markers_.rows.push_back(*open_);
    open_.reset();
}

int MeasurementWindows::begin_frame() {
    begin("frame", next_frame_);
    return next_frame_++;
}

void MeasurementWindows::end_frame(double write_ms, double exec_ms, double read_ms) {
    if (open_ && open_->kind == "frame") open_->write_ms = write_ms, open_->exec_ms = exec_ms, open_->read_ms = read_ms;
    end("frame");
}

void MeasurementWindows::begin_idle() { begin("idle", next_idle_++); }
void MeasurementWindows::end_idle() { end("idle"); }

void MeasurementWindows::idle_for(double seconds) {
    if (!(seconds >= 0) || seconds > 86400) throw Error("measurement window: idle_for(" + std::to_string(seconds) + "): expected 0..86400 s");
    begin_idle();
    std::this_thread::sleep_for(std::chrono::duration<double>(seconds));
    end_idle();
}

MeasurementWindows::Scope::~Scope() {
    // A destructor must not throw: a window that cannot be closed stays open, and save() says so.
    try {
        if (w_->open_) w_->end(w_->open_->kind == "frame" ? "frame" : "idle");
    } catch (const Error&) {
    }
}

MeasurementWindows::Scope MeasurementWindows::frame() {
    begin_frame();
    return Scope(*this);
}

void MeasurementWindows::save(const std::string& path) const {
    if (open_) throw Error(path + ": " + open_->kind + " window " + std::to_string(open_->id) + " is still open; end it before saving");
    io::write_file_atomic(path, format_markers(markers_));
}

void MeasurementWindows::save_minimal(const std::string& path, bool realtime) const {
    if (open_) throw Error(path + ": " + open_->kind + " window " + std::to_string(open_->id) + " is still open; end it before saving");
    if (frames() == 0) throw Error(path + ": no frame window to save");
    io::write_file_atomic(path, format_minimal_markers(markers_, realtime));
}

}  // namespace trn::energy
