// The pre-issue-14 cpu backend's dense NCC, for the bench's before/after ratio (old_cpu_ncc.hpp).
#include "old_cpu_ncc.hpp"

#include <algorithm>
#include <cmath>

namespace trn::bench::old_cpu {
namespace {

// Bilinear map value at the pose's centre: the shift that kept the old float sums small.
float centre_value(const std::uint8_t* m, int stride, int w, int h, float x, float y) {
    x = std::clamp(x, 0.0f, float(w - 1));
    y = std::clamp(y, 0.0f, float(h - 1));
    const int x0 = std::min(int(x), w - 2), y0 = std::min(int(y), h - 2);
    const float fx = x - float(x0), fy = y - float(y0);
    const std::uint8_t* p = m + std::ptrdiff_t(y0) * stride + x0;
    const float top = p[0] + fx * (p[1] - p[0]), bot = p[stride] + fx * (p[stride + 1] - p[stride]);
    return top + fy * (bot - top);
}

bool patch_inside(int w, int h, const Affine& A, const FloatPlan& plan) {
    for (float su : {-plan.cx, plan.cx})
        for (float sv : {-plan.cy, plan.cy}) {
            const float px = (A.tx + A.a * su) + A.b * sv, py = (A.ty + A.c * su) + A.d * sv;
            if (!(px >= 1.0f && py >= 1.0f && px <= float(w - 2) && py <= float(h - 2))) return false;
        }
    return true;
}

float score_one(const std::uint8_t* map, int w, int h, const FloatPlan& plan, const Pose& pose, bool avx2,
                std::vector<float>& ax, std::vector<float>& ay) {
    const Affine A = pose_to_affine(pose);
    const float shift = centre_value(map, w, w, h, pose.x, pose.y);
    const bool vector = avx2 && patch_inside(w, h, A, plan);
    ax.resize(plan.du.size()), ay.resize(plan.du.size());
    for (std::size_t k = 0; k < plan.du.size(); ++k) ax[k] = A.tx + A.a * plan.du[k], ay[k] = A.ty + A.c * plan.du[k];
    double n = 0, sj = 0, sjj = 0, sjt = 0, st = 0, stt = 0;
    for (int v = 0; v < plan.height; ++v) {
        const float dv = float(v) - plan.cy;
        const Row row{map, w, w, h, ax.data(), ay.data(), A.b * dv, A.d * dv, plan.centered.data() + std::size_t(v) * plan.width,
                      plan.width};
        const RowSums r = vector ? row_inside_avx2(row, shift) : row_checked(row, shift);
        n += r.n, sj += r.sj, sjj += r.sjj, sjt += r.sjt, st += r.st, stt += r.stt;
    }
    if (n < 1) return 0;
    const double var_j = sjj - sj * sj / n, var_t = stt - st * st / n;
    if (var_j <= 0 || var_t <= 0) return 0;
    return float(std::clamp((sjt - sj * st / n) / std::sqrt(var_j * var_t), -1.0, 1.0));
}

}  // namespace

FloatPlan make_float_plan(const cv::Mat& templ) {
    FloatPlan p;
    p.width = templ.cols, p.height = templ.rows;
    p.cx = (templ.cols - 1) * 0.5f, p.cy = (templ.rows - 1) * 0.5f;
    p.mean = cv::mean(templ)[0];
    p.centered.resize(templ.total());
    for (int y = 0; y < templ.rows; ++y)
        for (int x = 0; x < templ.cols; ++x)
            p.centered[std::size_t(y) * templ.cols + x] = float(templ.at<std::uint8_t>(y, x) - p.mean);
    p.du.resize(templ.cols);
    for (int u = 0; u < templ.cols; ++u) p.du[u] = float(u) - p.cx;
    return p;
}

RowSums row_checked(const Row& r, float shift) {
    const float xmax = float(r.width - 1), ymax = float(r.height - 1);
    RowSums s;
    for (int k = 0; k < r.count; ++k) {
        float px = r.ax[k] + r.bdv, py = r.ay[k] + r.ddv;
        const float valid = (px >= 0.0f && py >= 0.0f && px <= xmax && py <= ymax) ? 1.0f : 0.0f;
        px = std::clamp(px, 0.0f, xmax), py = std::clamp(py, 0.0f, ymax);
        const int x0 = std::min(int(px), r.width - 2), y0 = std::min(int(py), r.height - 2);
        const float fx = px - float(x0), fy = py - float(y0);
        const std::uint8_t* p = r.map + std::ptrdiff_t(y0) * r.stride + x0;
        const float top = p[0] + fx * (p[1] - p[0]), bot = p[r.stride] + fx * (p[r.stride + 1] - p[r.stride]);
        const float j = valid * (top + fy * (bot - top) - shift), t = valid * r.t[k];
        s.n += valid, s.sj += j, s.sjj += j * j, s.sjt += j * t, s.st += t, s.stt += t * t;
    }
    return s;
}

bool avx2_available() {
#if defined(__x86_64__)
    return __builtin_cpu_supports("avx2");
#else
    return false;
#endif
}

PackedMap pack_map(const cv::Mat& m) {
    PackedMap p;
    p.width = m.cols, p.height = m.rows;
    p.pixels.assign(m.total() + 16, 0);
    for (int y = 0; y < m.rows; ++y) std::copy_n(m.ptr<std::uint8_t>(y), m.cols, p.pixels.data() + std::size_t(y) * m.cols);
    return p;
}

void score(const PackedMap& map, const FloatPlan& plan, std::span<const Pose> poses, std::span<float> ncc) {
    const bool avx2 = avx2_available();
    const long n = static_cast<long>(poses.size());
#pragma omp parallel for schedule(dynamic, 2)
    for (long i = 0; i < n; ++i) {
        static thread_local std::vector<float> ax, ay;  // per-thread scratch that only grows, as the old backend's
        ncc[i] = score_one(map.pixels.data(), map.width, map.height, plan, poses[i], avx2, ax, ay);
    }
}

}  // namespace trn::bench::old_cpu
