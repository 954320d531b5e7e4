#pragma once
// A small fork-join pool for the cpu backend. Workers sleep on a condition variable between jobs
// (no spinning: on a shared 2-core machine a spinning OpenMP runtime made 1080p Sobel 15x slower),
// the calling thread works too, chunks are handed out dynamically so a descheduled worker delays a
// job by at most one chunk, and a job allocates nothing.
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <thread>
#include <vector>

namespace trn::cpu {

class ThreadPool {
public:
    explicit ThreadPool(int threads);  // threads in all, the caller included (>= 1)
    ~ThreadPool();
    ThreadPool(const ThreadPool&) = delete;
    ThreadPool& operator=(const ThreadPool&) = delete;

    int threads() const { return static_cast<int>(workers_.size()) + 1; }

    // Calls body(begin, end) for consecutive ranges of at most `grain` covering [0, n).
    template <typename F>
    void parallel_for(std::int64_t n, std::int64_t grain, F&& body) {
        run(n, grain, [](void* ctx, std::int64_t b, std::int64_t e) { (*static_cast<F*>(ctx))(b, e); }, &body);
    }

private:
    using Fn = void (*)(void*, std::int64_t, std::int64_t);
    void run(std::int64_t n, std::int64_t grain, Fn fn, void* ctx);
    void work(std::uint32_t generation);  // claims and runs chunks of that job while any are left
    void worker_loop();

    std::vector<std::thread> workers_;
    std::mutex mutex_;
    std::condition_variable wake_, done_;
    bool stop_ = false;
    std::uint32_t generation_ = 0;
    // The current job. `claim_` packs (generation << 32 | next chunk) so a late worker can never
    // claim a chunk of a later job with the function of an earlier one.
    Fn fn_ = nullptr;
    void* ctx_ = nullptr;
    std::int64_t n_ = 0, grain_ = 1;
    std::atomic<std::uint32_t> chunks_{0};  // read before a claim, so atomic; the rest only after one
    std::atomic<std::uint64_t> claim_{0};
    std::atomic<std::uint32_t> finished_{0};
};

}  // namespace trn::cpu
