#include "trn/energy/background_sampler.hpp"

#include <algorithm>
#include <chrono>

#include "trn/error.hpp"

namespace trn::energy {

BackgroundSampler::BackgroundSampler(PowerSampler& sampler, double period_s, SampleClock clock) : sampler_(sampler), period_s_(period_s), clock_(clock) {
    if (!(period_s > 0) || period_s > 60) throw Error(sampler.describe() + ": sampling period must be in (0, 60] s");
    sampler_.poll(clock_seconds(clock_));
    thread_ = std::thread([this] { loop(); });
}

BackgroundSampler::~BackgroundSampler() {
    {
        std::lock_guard lock(wake_mutex_);
        stop_ = true;
    }
    wake_.notify_all();
    if (thread_.joinable()) thread_.join();
}

void BackgroundSampler::loop() {
    using clock = std::chrono::steady_clock;
    const auto period = std::chrono::duration_cast<clock::duration>(std::chrono::duration<double>(period_s_));
    auto due = clock::now() + period;
    for (;;) {
        {
            std::unique_lock lock(wake_mutex_);
            if (wake_.wait_until(lock, due, [this] { return stop_; })) return;
        }
        try {
            sampler_.poll(clock_seconds(clock_));
        } catch (...) {
            error_ = std::current_exception();
            return;
        }
        due += period;
        // Behind by more than a period (the machine is loaded): skip the missed polls instead of
        // firing them back to back, and count it.
        if (const auto now = clock::now(); now > due) {
            ++late_;
            due = now + period;
        }
    }
}

PowerTrace BackgroundSampler::stop() {
    {
        std::lock_guard lock(wake_mutex_);
        stop_ = true;
    }
    wake_.notify_all();
    if (thread_.joinable()) thread_.join();
    if (error_) std::rethrow_exception(error_);
    // One more poll (the thread has ended), so the trace covers the caller's last marker with a
    // sample; the short wait keeps its time apart from the thread's last poll.
    std::this_thread::sleep_for(std::chrono::duration<double>(std::min(period_s_, 1e-3)));
    sampler_.poll(clock_seconds(clock_));
    PowerTrace tr = sampler_.trace();
    tr.wall_clock = clock_ == SampleClock::Realtime;
    if (late_) tr.notes.push_back(std::to_string(late_) + " poll(s) more than one period late (a loaded machine); those gaps are interpolated");
    return tr;
}

}  // namespace trn::energy
