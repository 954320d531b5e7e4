#pragma once
// Kernel sources compiled into the library at build time (cmake/EmbedOpenCL.cmake generates the
// definitions from kernels/opencl/*.cl, with the shared .clh pasted in).
#include <string_view>

namespace trn::opencl {

struct EmbeddedKernel {
    std::string_view file;    // "ncc_score.cl"
    std::string_view source;  // complete OpenCL C text
    std::string_view sha256;  // of `source`: part of the program-cache key
};

EmbeddedKernel embedded_ncc_score();
EmbeddedKernel embedded_sobel3x3();

}  // namespace trn::opencl
