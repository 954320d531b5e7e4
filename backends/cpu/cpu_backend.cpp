// cpu: the fast CPU backend. Threads over particles (scoring) or rows (Sobel); inner loops are
// branch-free so the compiler vectorizes them; sums are float within a template row and double
// across rows, which keeps NCC within 1e-6 of the double reference on 640x480 templates.
#include "cpu_backend.hpp"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <thread>
#include <vector>

namespace trn {
namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

class CpuMap : public MapStorage {
public:
    CpuMap(const Backend* owner, GrayView v)
        : MapStorage(owner, v.width, v.height), stride(v.width), pixels(std::size_t(v.width) * v.height) {
        for (int y = 0; y < v.height; ++y) std::copy_n(v.row(y), v.width, pixels.data() + std::size_t(y) * v.width);
    }
    std::ptrdiff_t stride;
    std::vector<std::uint8_t> pixels;
};

// Row of samples: du/dv offsets from the template centre and centred template values.
struct SampleRow {
    const float* du;
    float dv;           // dense: one dv for the whole row
    const float* dvs;   // sparse: one dv per sample (nullptr for dense)
    const float* t;
    int count;
};

struct RowSums {
    float n = 0, sj = 0, sjj = 0, sjt = 0, st = 0, stt = 0;
};

// Samples one row. Checked = false when the whole patch is known to lie inside the map.
template <bool Checked>
RowSums sample_row(const CpuMap& m, const Affine& A, const SampleRow& row, float shift) {
    const float xmax = float(m.width() - 1), ymax = float(m.height() - 1);
    const int x0max = m.width() - 2, y0max = m.height() - 2;
    const std::uint8_t* px8 = m.pixels.data();
    const std::ptrdiff_t stride = m.stride;
    RowSums r;
    for (int k = 0; k < row.count; ++k) {
        const float dv = row.dvs ? row.dvs[k] : row.dv;
        // Same operation order as scoring.hpp: (t + a*du) + b*dv, no FMA (-ffp-contract=off).
        float px = (A.tx + A.a * row.du[k]) + A.b * dv;
        float py = (A.ty + A.c * row.du[k]) + A.d * dv;
        float valid = 1.0f;
        if constexpr (Checked) {
            valid = (px >= 0.0f && py >= 0.0f && px <= xmax && py <= ymax) ? 1.0f : 0.0f;
            px = std::clamp(px, 0.0f, xmax);
            py = std::clamp(py, 0.0f, ymax);
        }
        const int x0 = std::min(int(px), x0max), y0 = std::min(int(py), y0max);  // px >= 0: int() == floor
        const float fx = px - float(x0), fy = py - float(y0);
        const std::uint8_t* p = px8 + y0 * stride + x0;
        const float m00 = p[0], m10 = p[1], m01 = p[stride], m11 = p[stride + 1];
        const float top = m00 + fx * (m10 - m00), bot = m01 + fx * (m11 - m01);
        const float j = (top + fy * (bot - top)) - shift;
        const float t = row.t[k];
        r.n += valid;
        r.sj += valid * j;
        r.sjj += valid * j * j;
        r.sjt += valid * j * t;
        r.st += valid * t;
        r.stt += valid * t * t;
    }
    return r;
}

float centre_value(const CpuMap& m, float x, float y) {
    x = std::clamp(x, 0.0f, float(m.width() - 1));
    y = std::clamp(y, 0.0f, float(m.height() - 1));
    const int x0 = std::min(int(x), m.width() - 2), y0 = std::min(int(y), m.height() - 2);
    const float fx = x - float(x0), fy = y - float(y0);
    const std::uint8_t* p = m.pixels.data() + y0 * m.stride + x0;
    const float top = p[0] + fx * (p[1] - p[0]), bot = p[m.stride] + fx * (p[m.stride + 1] - p[m.stride]);
    return top + fy * (bot - top);
}

// True when every sample position of the template rectangle lies inside the map, so per-sample
// checks can be skipped. The mapped rectangle is convex, so its four corners decide; a one-pixel
// margin absorbs float rounding of the individual sample positions.
bool patch_inside(const CpuMap& m, const Affine& A, const ScoringPlan& plan) {
    const float hx = plan.cx, hy = plan.cy;
    for (float su : {-hx, hx})
        for (float sv : {-hy, hy}) {
            const float px = (A.tx + A.a * su) + A.b * sv, py = (A.ty + A.c * su) + A.d * sv;
            if (!(px >= 1.0f && py >= 1.0f && px <= float(m.width() - 2) && py <= float(m.height() - 2))) return false;
        }
    return true;
}

class CpuBackend final : public Backend {
public:
    CpuBackend() {
        const int threads = omp_get_max_threads();
        info_ = {"cpu", "cpu", "optimized C++ (OpenMP)", "cpu", "trnkit",
                 std::to_string(threads) + " threads, " + std::to_string(std::thread::hardware_concurrency()) +
                     " hardware threads"};
    }
    const DeviceInfo& info() const override { return info_; }

protected:
    MapHandle do_upload_map(GrayView map, PhaseTimes* times) override {
        const auto t0 = Clock::now();
        auto m = std::make_shared<CpuMap>(this, map);
        if (times) times->upload_ms = ms_since(t0);
        return m;
    }

    void do_score(const MapStorage& storage, const ScoringPlan& plan, std::span<const Pose> poses,
                  std::span<ParticleScore> out, PhaseTimes* times) override {
        const auto t0 = Clock::now();
        const CpuMap& map = static_cast<const CpuMap&>(storage);
        prepare_offsets(plan);
        const long n = static_cast<long>(poses.size());
#pragma omp parallel for schedule(dynamic, 4)
        for (long p = 0; p < n; ++p) out[p] = score_one(map, plan, poses[p]);
        if (times) times->execute_ms = ms_since(t0);
    }

    void do_sobel(GrayView src, Int16View gx, Int16View gy, PhaseTimes* times) override;

private:
    // du (and for sparse plans dv) per sample, cached across calls with the same template geometry
    // so steady-state calls allocate nothing.
    void prepare_offsets(const ScoringPlan& plan) {
        if (plan.dense) {
            du_.resize(plan.width);
            for (int u = 0; u < plan.width; ++u) du_[u] = float(u) - plan.cx;
        } else {
            du_.resize(plan.points.size());
            dv_.resize(plan.points.size());
            for (std::size_t k = 0; k < plan.points.size(); ++k) {
                du_[k] = float(plan.points[k].u) - plan.cx;
                dv_[k] = float(plan.points[k].v) - plan.cy;
            }
        }
    }

    ParticleScore score_one(const CpuMap& map, const ScoringPlan& plan, const Pose& pose) const {
        const Affine A = pose_to_affine(pose);
        ParticleSums sums;
        sums.shift = centre_value(map, pose.x, pose.y);
        const float shift = static_cast<float>(sums.shift);
        const bool inside = patch_inside(map, A, plan);
        auto add = [&](const SampleRow& row) {
            const RowSums r = inside ? sample_row<false>(map, A, row, shift) : sample_row<true>(map, A, row, shift);
            sums.n += r.n, sums.sj += r.sj, sums.sjj += r.sjj, sums.sjt += r.sjt, sums.st += r.st, sums.stt += r.stt;
        };
        if (plan.dense) {
            for (int v = 0; v < plan.height; ++v)
                add({du_.data(), float(v) - plan.cy, nullptr, plan.centered.data() + std::size_t(v) * plan.width, plan.width});
        } else {
            constexpr int kChunk = 512;  // float sums over short runs, double across them
            const int total = static_cast<int>(plan.points.size());
            for (int k = 0; k < total; k += kChunk)
                add({du_.data() + k, 0.0f, dv_.data() + k, plan.centered.data() + k, std::min(kChunk, total - k)});
        }
        return finalize_score(sums, plan);
    }

    DeviceInfo info_;
    std::vector<float> du_, dv_;
};

// Both gradients in one pass over the source: each output row reads three source rows.
void CpuBackend::do_sobel(GrayView src, Int16View gx, Int16View gy, PhaseTimes* times) {
    const auto t0 = Clock::now();
    const int w = src.width, h = src.height;
    auto reflect = [](int i, int n) { return n == 1 ? 0 : i < 0 ? -i : i >= n ? 2 * n - 2 - i : i; };
    const bool parallel = std::int64_t(w) * h >= 64 * 1024;
#pragma omp parallel for schedule(static) if (parallel)
    for (int y = 0; y < h; ++y) {
        const std::uint8_t* r0 = src.row(reflect(y - 1, h));
        const std::uint8_t* r1 = src.row(y);
        const std::uint8_t* r2 = src.row(reflect(y + 1, h));
        std::int16_t* ox = gx.row(y);
        std::int16_t* oy = gy.row(y);
        auto at = [&](int x) {  // one pixel with reflected columns (borders and tiny images)
            const int xl = reflect(x - 1, w), xr = reflect(x + 1, w);
            ox[x] = std::int16_t((r0[xr] - r0[xl]) + 2 * (r1[xr] - r1[xl]) + (r2[xr] - r2[xl]));
            oy[x] = std::int16_t((r2[xl] + 2 * r2[x] + r2[xr]) - (r0[xl] + 2 * r0[x] + r0[xr]));
        };
        at(0);
        for (int x = 1; x < w - 1; ++x) {
            const std::int16_t a0 = r0[x - 1], a1 = r0[x], a2 = r0[x + 1];
            const std::int16_t b0 = r1[x - 1], b2 = r1[x + 1];
            const std::int16_t c0 = r2[x - 1], c1 = r2[x], c2 = r2[x + 1];
            ox[x] = std::int16_t((a2 - a0) + 2 * (b2 - b0) + (c2 - c0));
            oy[x] = std::int16_t((c0 + 2 * c1 + c2) - (a0 + 2 * a1 + a2));
        }
        if (w > 1) at(w - 1);
    }
    if (times) times->execute_ms = ms_since(t0);
}

}  // namespace

std::unique_ptr<Backend> make_cpu_backend() { return std::make_unique<CpuBackend>(); }

}  // namespace trn
