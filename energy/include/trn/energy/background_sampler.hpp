#pragma once
// A sampler thread: polls a PowerSampler every period on one clock while the caller's thread does
// the work, so power and frame markers share the process's clock (no alignment step). The first
// poll happens in the constructor, so a source that cannot be read fails before any work.
#include <atomic>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <thread>

#include "trn/energy/power_sampler.hpp"
#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn::energy {

class BackgroundSampler {
public:
    // Throws trn::Error for a non-positive period or when the first poll fails.
    BackgroundSampler(PowerSampler& sampler, double period_s, SampleClock clock);
    ~BackgroundSampler();  // stops the thread; errors are dropped (call stop() to see them)
    BackgroundSampler(const BackgroundSampler&) = delete;
    BackgroundSampler& operator=(const BackgroundSampler&) = delete;

    // Polls once more, stops the thread and returns the trace (wall_clock set for Realtime);
    // rethrows an error the thread hit, naming the source. Call once.
    PowerTrace stop();
    // Polls that came later than one period after their due time (a loaded machine).
    std::size_t late_polls() const { return late_; }

private:
    void loop();
    PowerSampler& sampler_;
    double period_s_;
    SampleClock clock_;
    bool stop_ = false;                 // guarded by wake_mutex_
    std::mutex wake_mutex_;
    std::condition_variable wake_;      // stop() wakes the thread at once, even with a long period
    std::atomic<std::size_t> late_{0};
    std::exception_ptr error_;
    std::thread thread_;
};

}  // namespace trn::energy
TRN_API_END
