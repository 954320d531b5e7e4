#include "row_kernels.hpp"

namespace trn::cpu {

const RowKernels& row_kernels(bool simd) {
    static const RowKernels portable{"portable", sample_row_inside, sample_row_checked, nullptr, false};
#if defined(__x86_64__)
    static const RowKernels avx2{"AVX2", sample_row_inside_avx2, sample_row_checked_avx2, sample_row_tiles_avx2, true};
    if (simd && __builtin_cpu_supports("avx2")) return avx2;
#elif defined(__aarch64__)
    // Advanced SIMD (NEON) is part of every AArch64 processor: nothing to ask at run time.
    static const RowKernels neon{"NEON", sample_row_inside_neon, sample_row_checked_neon, nullptr, false};
    if (simd) return neon;
#endif
    return portable;
}

}  // namespace trn::cpu
