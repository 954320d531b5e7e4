#pragma once
// The CUDA kernels as fat binaries, compiled by nvcc and embedded at build time
// (cmake/TrnCuda.cmake writes one cuda_fatbin_<name>.cpp per kernels/cuda/<name>.cu).
#include <span>

namespace trn::cuda {

struct EmbeddedFatbin {
    const char* file;                       // "ncc_score.cu"
    std::span<const unsigned char> bytes;   // the fatbin image, 64-byte aligned (cuModuleLoadDataEx's input)
};

EmbeddedFatbin embedded_ncc_score();
EmbeddedFatbin embedded_sobel3x3();

}  // namespace trn::cuda
