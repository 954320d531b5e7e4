#include "thread_pool.hpp"

#include <algorithm>

namespace trn::cpu {

ThreadPool::ThreadPool(int threads) {
    for (int i = 1; i < std::max(threads, 1); ++i) workers_.emplace_back([this] { worker_loop(); });
}

ThreadPool::~ThreadPool() {
    {
        std::lock_guard lock(mutex_);
        stop_ = true;
    }
    wake_.notify_all();
    for (std::thread& t : workers_) t.join();
}

void ThreadPool::work(std::uint32_t generation) {
    std::uint64_t c = claim_.load(std::memory_order_acquire);
    for (;;) {
        if (std::uint32_t(c >> 32) != generation || std::uint32_t(c) >= chunks_.load(std::memory_order_acquire)) return;
        if (!claim_.compare_exchange_weak(c, c + 1, std::memory_order_acq_rel)) continue;
        const std::int64_t begin = std::int64_t(std::uint32_t(c)) * grain_;
        fn_(ctx_, begin, std::min(n_, begin + grain_));
        if (finished_.fetch_add(1, std::memory_order_acq_rel) + 1 == chunks_.load(std::memory_order_relaxed)) {
            std::lock_guard lock(mutex_);
            done_.notify_all();
        }
        c = claim_.load(std::memory_order_acquire);
    }
}

void ThreadPool::worker_loop() {
    std::uint32_t seen = 0;
    for (;;) {
        std::uint32_t generation;
        {
            std::unique_lock lock(mutex_);
            wake_.wait(lock, [&] { return stop_ || generation_ != seen; });
            if (stop_) return;
            seen = generation = generation_;
        }
        work(generation);
    }
}

void ThreadPool::run(std::int64_t n, std::int64_t grain, Fn fn, void* ctx) {
    if (n <= 0) return;
    grain = std::max<std::int64_t>(grain, 1);
    const std::int64_t chunks = (n + grain - 1) / grain;
    if (workers_.empty() || chunks == 1) {
        for (std::int64_t b = 0; b < n; b += grain) fn(ctx, b, std::min(n, b + grain));
        return;
    }
    std::uint32_t generation;
    {
        std::lock_guard lock(mutex_);
        generation = ++generation_;
        fn_ = fn, ctx_ = ctx, n_ = n, grain_ = grain;
        chunks_.store(static_cast<std::uint32_t>(chunks), std::memory_order_relaxed);
        finished_.store(0, std::memory_order_relaxed);
        claim_.store(std::uint64_t(generation) << 32, std::memory_order_release);
    }
    wake_.notify_all();
    work(generation);
    std::unique_lock lock(mutex_);
    done_.wait(lock, [&] { return finished_.load(std::memory_order_acquire) == chunks_.load(std::memory_order_relaxed); });
}

}  // namespace trn::cpu
