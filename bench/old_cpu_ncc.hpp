#pragma once
// The cpu backend's dense NCC as it was before exact integer scoring (issue 14, commit d9a7914^):
// float bilinear values shifted by the pose's centre value, float sums per row, AVX2 rows with
// two gathers per 8 samples, particles split over the hardware threads. Kept only so that one
// bench-report run measures the integer backend against it ("old:cpu_float"); not a backend.
#include <cstdint>
#include <span>
#include <vector>

#include <opencv2/core.hpp>

#include "trn/scoring_plan.hpp"

namespace trn::bench::old_cpu {

// The centred float template of the old ScoringPlan (t - mean), row-major, and its geometry.
struct FloatPlan {
    int width = 0, height = 0;
    float cx = 0, cy = 0;
    double mean = 0;
    std::vector<float> centered;
    std::vector<float> du;  // u - cx per column
};

FloatPlan make_float_plan(const cv::Mat& templ_u8);

// The map as the old backend held it: rows packed (stride == width), 16 spare bytes at the end
// (a gather reads 4 bytes from any pixel).
struct PackedMap {
    int width = 0, height = 0;
    std::vector<std::uint8_t> pixels;
};
PackedMap pack_map(const cv::Mat& map_u8);

// NCC per pose (0 for a flat patch or where no sample is valid), computed as the old backend did.
void score(const PackedMap& map, const FloatPlan& plan, std::span<const Pose> poses, std::span<float> ncc);

// The old float row samplers (old_cpu_ncc.cpp: portable, old_cpu_ncc_avx2.cpp: AVX2).
struct RowSums {
    float n = 0, sj = 0, sjj = 0, sjt = 0, st = 0, stt = 0;
};
struct Row {
    const std::uint8_t* map;
    int stride, width, height;
    const float* ax;  // tx + a*du per sample
    const float* ay;
    float bdv, ddv;   // b*dv, d*dv of the row
    const float* t;   // centred template row
    int count;
};
RowSums row_checked(const Row& r, float shift);
RowSums row_inside_avx2(const Row& r, float shift);  // only where AVX2 is available
bool avx2_available();

}  // namespace trn::bench::old_cpu
