#pragma once
// Runs the CUDA kernels' own source (kernels/cuda/*.cu) on the CPU, so that their arithmetic,
// indexing and reductions are checked against cpu-ref on a machine without a GPU. Not a CUDA
// implementation: just enough of the language for these kernels. Each thread of a block is an OS
// thread; __syncthreads and the warp shuffles are one barrier over the block's live threads (a
// thread that returns drops out of it), which is what these kernels need: every live thread of a
// block reaches the same barrier, and a shuffle's whole warp is live. Blocks run one after another,
// so a function's __shared__ array (a static here) is the block's own.
//
// Include this, then the .cu file, in a test source of its own.
#include <algorithm>
#include <barrier>
#include <cstdint>
#include <functional>
#include <optional>
#include <thread>
#include <vector>

#define __global__
#define __device__
#define __forceinline__ inline
#define __shared__ static

struct dim3 {
    unsigned int x = 1, y = 1, z = 1;
};
struct float2 {
    float x, y;
};
struct float4 {
    float x, y, z, w;
};
struct uint4 {
    unsigned int x, y, z, w;
};
inline uint4 make_uint4(unsigned int x, unsigned int y, unsigned int z, unsigned int w) { return {x, y, z, w}; }

namespace trn_emu {

inline dim3 block_idx, block_dim;
inline thread_local dim3 thread_idx;
inline std::optional<std::barrier<>> block_barrier;
inline std::vector<long long> shuffle_slots;

// Runs kernel(args) over grid x block, block after block.
template <typename Args>
void launch(void (*kernel)(Args), dim3 grid, dim3 block, const Args& args) {
    block_dim = block;
    const unsigned int threads = block.x * block.y;
    shuffle_slots.assign(threads, 0);
    for (unsigned int by = 0; by < grid.y; ++by)
        for (unsigned int bx = 0; bx < grid.x; ++bx) {
            block_idx = {bx, by, 0};
            block_barrier.emplace(static_cast<std::ptrdiff_t>(threads));
            std::vector<std::thread> pool;
            for (unsigned int t = 0; t < threads; ++t)
                pool.emplace_back([&, t] {
                    thread_idx = {t % block.x, t / block.x, 0};
                    kernel(args);
                    block_barrier->arrive_and_drop();
                });
            for (std::thread& th : pool) th.join();
        }
}

inline unsigned int linear_thread() { return thread_idx.y * block_dim.x + thread_idx.x; }

}  // namespace trn_emu

#define blockIdx (::trn_emu::block_idx)
#define blockDim (::trn_emu::block_dim)
#define threadIdx (::trn_emu::thread_idx)

inline void __syncthreads() { trn_emu::block_barrier->arrive_and_wait(); }

// Lane + offset of the same warp, or the thread's own value past the warp's end (CUDA's rule).
inline long long __shfl_down_sync(unsigned int, long long v, int offset) {
    const unsigned int me = trn_emu::linear_thread();
    trn_emu::shuffle_slots[me] = v;
    __syncthreads();
    const unsigned int lane = me % 32;
    const long long r = lane + unsigned(offset) < 32 ? trn_emu::shuffle_slots[me + unsigned(offset)] : v;
    __syncthreads();
    return r;
}

template <typename T>
T __ldg(const T* p) {
    return *p;
}
// The project builds with -ffp-contract=off, so these are single rounded operations, as on the GPU.
inline float __fmul_rn(float a, float b) { return a * b; }
inline float __fadd_rn(float a, float b) { return a + b; }
inline float __fsub_rn(float a, float b) { return a - b; }
inline int __float2int_rz(float f) { return static_cast<int>(f); }
using std::max;
using std::min;
