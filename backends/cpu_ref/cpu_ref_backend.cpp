// cpu-ref: the test oracle. Written to be obviously correct, not fast: every sample is taken one
// by one exactly as scoring.hpp defines it and added to 64-bit integer sums; nothing is shared with
// the optimized paths except the contract itself (ScoringPlan's samples and quantized template,
// fixed_point.hpp's weight and bilinear formula, finalize_score).
#include "cpu_ref_backend.hpp"

#include <chrono>
#include <cmath>
#include <vector>

#include "trn/fixed_point.hpp"
#include "trn/impl/cell_mask.hpp"
#include "trn/impl/particle_sums.hpp"

namespace trn {
namespace {

class RefMap : public MapStorage {
public:
    // One byte per pixel, rows packed: the constructor's size and upload_map's estimate.
    static constexpr double bytes(std::int64_t width, std::int64_t height) { return double(width) * double(height); }
    RefMap(const Backend* owner, GrayView v, const CellMask* no_data)
        : MapStorage(owner, v.width, v.height, no_data != nullptr), pixels(static_cast<std::size_t>(bytes(v.width, v.height))) {
        for (int y = 0; y < v.height; ++y)
            for (int x = 0; x < v.width; ++x) pixels[std::size_t(y) * v.width + x] = v.at(x, y);
        if (no_data) mask = *no_data;
    }
    std::uint8_t at(int x, int y) const { return pixels[std::size_t(y) * width() + x]; }
    std::vector<std::uint8_t> pixels;
    CellMask mask;  // empty unless masked()
};

// Position and bilinear value exactly as scoring.hpp specifies; volatile stores keep the compiler
// from fusing multiply-adds so each product and sum is rounded to float on its own. `value` is the
// map value in 1/128 grey levels.
bool sample(const RefMap& m, const Affine& A, float du, float dv, std::int64_t& value) {
    volatile float t1 = A.a * du, t2 = A.b * dv, t3 = A.c * du, t4 = A.d * dv;
    volatile float sx = A.tx + t1, sy = A.ty + t3;
    const float px = sx + t2, py = sy + t4;
    if (!(px >= 0.0f && py >= 0.0f && px <= float(m.width() - 1) && py <= float(m.height() - 1))) return false;
    int x0 = static_cast<int>(std::floor(px)), y0 = static_cast<int>(std::floor(py));
    if (x0 > m.width() - 2) x0 = m.width() - 2;
    if (y0 > m.height() - 2) y0 = m.height() - 2;
    if (m.masked() && !m.mask.valid(x0, y0)) return false;  // the cell holds no-data
    const float fx = px - float(x0), fy = py - float(y0);  // exact (Sterbenz)
    value = fixed::bilinear(m.at(x0, y0), m.at(x0 + 1, y0), m.at(x0, y0 + 1), m.at(x0 + 1, y0 + 1), fixed::weight(fx),
                            fixed::weight(fy));
    return true;
}

// Adds the wall time of its scope to *target (when given): the CPU's own clock for PhaseTimes.
class Timer {
public:
    explicit Timer(double* target) : target_(target), start_(std::chrono::steady_clock::now()) {}
    ~Timer() {
        if (target_) *target_ += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start_).count();
    }

private:
    double* target_;
    std::chrono::steady_clock::time_point start_;
};

class CpuRefBackend final : public Backend {
public:
    CpuRefBackend() {
        info_ = {"cpu-ref", "cpu-ref", "naive C++ reference", "cpu", "trnkit", "exact integer sums, single thread"};
    }
    const DeviceInfo& info() const override { return info_; }

protected:
    MapHandle do_upload_map(GrayView map, const CellMask* mask, PhaseTimes* times) override {
        const Timer timer(times ? &times->upload_ms : nullptr);
        return std::make_shared<RefMap>(this, map, mask);
    }

    double do_map_bytes(std::int64_t width, std::int64_t height) const override { return RefMap::bytes(width, height); }

    void do_score(const MapStorage& storage, const ScoringPlan& plan, std::span<const Pose> poses,
                  std::span<ParticleScore> out, PhaseTimes* times) override {
        const Timer timer(times ? &times->execute_ms : nullptr);
        const RefMap& map = static_cast<const RefMap&>(storage);
        const std::size_t count = plan.sample_count();
        for (std::size_t p = 0; p < poses.size(); ++p) {
            const Affine A = pose_to_affine(poses[p]);
            ParticleSums sums;
            for (std::size_t k = 0; k < count; ++k) {
                const int u = plan.dense ? int(k % plan.width) : plan.points[k].u;
                const int v = plan.dense ? int(k / plan.width) : plan.points[k].v;
                std::int64_t i;
                if (!sample(map, A, float(u) - plan.cx, float(v) - plan.cy, i)) continue;
                const std::int64_t t = plan.quantized[k];
                sums.n += 1;
                sums.sj += i;
                sums.sjj += i * i;
                sums.sjt += i * t;
                sums.st += t;
                sums.stt += t * t;
            }
            out[p] = finalize_score(sums, plan);
        }
    }

    void do_sobel(GrayView src, Int16View gx, Int16View gy, PhaseTimes* times) override {
        const Timer timer(times ? &times->execute_ms : nullptr);
        const int w = src.width, h = src.height;
        // Reflect-101 index: -1 -> 1, w -> w-2; a 1-pixel-wide axis maps everything to 0.
        auto reflect = [](int i, int n) {
            if (n == 1) return 0;
            if (i < 0) return -i;
            if (i >= n) return 2 * n - 2 - i;
            return i;
        };
        static const int kx[3][3] = {{-1, 0, 1}, {-2, 0, 2}, {-1, 0, 1}};
        static const int ky[3][3] = {{-1, -2, -1}, {0, 0, 0}, {1, 2, 1}};
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                int sx = 0, sy = 0;
                for (int j = -1; j <= 1; ++j)
                    for (int i = -1; i <= 1; ++i) {
                        const int p = src.at(reflect(x + i, w), reflect(y + j, h));
                        sx += kx[j + 1][i + 1] * p;
                        sy += ky[j + 1][i + 1] * p;
                    }
                gx.at(x, y) = static_cast<std::int16_t>(sx);
                gy.at(x, y) = static_cast<std::int16_t>(sy);
            }
    }

private:
    DeviceInfo info_;
};

}  // namespace

std::unique_ptr<Backend> make_cpu_ref_backend() { return std::make_unique<CpuRefBackend>(); }

}  // namespace trn
