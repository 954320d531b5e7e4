// cpu: the fast CPU backend. A thread pool over particles (scoring) or rows (Sobel); inner loops are
// branch-free so the compiler vectorizes them; sums are the exact integers of scoring.hpp, so
// scores equal cpu-ref's bit for bit.
#include "cpu_backend.hpp"
#include "ncc_rows.hpp"
#include "row_kernels.hpp"
#include "thread_pool.hpp"
#include "trn/impl/cell_mask.hpp"
#include "trn/impl/particle_sums.hpp"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <string>
#include <cmath>
#include <thread>
#include <vector>

namespace trn {
namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }
// More threads than this is a typing error, not a machine.
constexpr int kMaxThreads = 4096;

class CpuMap : public MapStorage {
public:
    // The map as vertical pixel pairs (cpu::MapPixels: twice the map's bytes), so that one 32-bit
    // read brings a sample's whole 2x2 cell; kPad spare bytes at the end for the last cell's read.
    static constexpr std::size_t kPad = 16;
    // Bytes of that layout for a width x height map: two per pixel of every row but the last. The
    // one definition: the constructor sizes `pairs` with it and upload_map's limit check quotes it.
    static constexpr double bytes(std::int64_t width, std::int64_t height) {
        return 2.0 * double(width) * double(height - 1) + double(kPad);
    }
    CpuMap(const Backend* owner, GrayView v, const CellMask* no_data)
        : MapStorage(owner, v.width, v.height, no_data != nullptr), pair_stride(2 * std::ptrdiff_t(v.width)),
          pairs(static_cast<std::size_t>(bytes(v.width, v.height)), 0) {
        for (int y = 0; y + 1 < v.height; ++y) {
            const std::uint8_t *top = v.row(y), *bottom = v.row(y + 1);
            std::uint8_t* out = pairs.data() + std::size_t(y) * std::size_t(pair_stride);
            for (int x = 0; x < v.width; ++x) out[2 * x] = top[x], out[2 * x + 1] = bottom[x];
        }
        if (no_data) {
            pack_cell_bits(*no_data);
            make_blocks(*no_data);
        }
    }
    cpu::MapPixels view() const {
        return {pairs.data(), pair_stride, width(), height(), masked() ? cell_bits.data() : nullptr, masked() ? &blocks : nullptr};
    }
    // True when every cell in columns [x_lo, x_hi] and rows [y_lo, y_hi] (clamped to the map) is
    // valid, judged by blocks of 8x8 cells: a particle there takes the unchecked (fast) samplers.
    bool cells_valid(int x_lo, int y_lo, int x_hi, int y_hi) const {
        if (!masked()) return true;
        return blocks.judge(std::max(x_lo, 0), std::max(y_lo, 0), std::min(x_hi, width() - 2), std::min(y_hi, height() - 2)) ==
               cpu::CellBlocks::kAllValid;
    }
    std::ptrdiff_t pair_stride;
    std::vector<std::uint8_t> pairs;
    // No-data, when masked(): cpu::MapPixels::cell_bits (the cell mask's bits with the rows packed
    // end to end, plus spare words), no larger than the CellMask that upload_map's check counts,
    // and the block tables (4 bytes per 64 cells, 1/16 byte per pixel, not counted by map_bytes).
    std::vector<std::uint32_t> cell_bits;
    cpu::CellBlocks blocks;

private:
    void pack_cell_bits(const CellMask& mask) {
        const std::size_t cells = std::size_t(mask.cells_x) * std::size_t(mask.cells_y);
        cell_bits.assign(cells / 32 + 2, 0u);
        std::size_t bit = 0;  // a word at a time; CellMask's bits past cells_x are 0
        for (int y = 0; y < mask.cells_y; ++y)
            for (int w = 0; w < mask.words_per_row; ++w) {
                const std::uint32_t word = mask.words[std::size_t(y) * mask.words_per_row + w];
                const unsigned shift = bit & 31;
                cell_bits[bit >> 5] |= word << shift;
                if (shift) cell_bits[(bit >> 5) + 1] |= word >> (32 - shift);
                bit += std::size_t(std::min(32, mask.cells_x - 32 * w));
            }
    }
    // Which 8x8-cell blocks hold an invalid and which a valid cell, as summed-area tables.
    void make_blocks(const CellMask& mask) {
        constexpr int k = cpu::CellBlocks::kShift;
        const int bx = (mask.cells_x + (1 << k) - 1) >> k, by = (mask.cells_y + (1 << k) - 1) >> k;
        std::vector<std::uint8_t> invalid(std::size_t(bx) * by, 0), valid(std::size_t(bx) * by, 0);
        static_assert(k >= 1 && k <= 5, "a block's row of cells lies in one mask word");
        constexpr int side = 1 << k, per_word = 32 / side;
        for (int y = 0; y < mask.cells_y; ++y)
            for (int x = 0; x < bx; ++x) {
                const std::uint32_t word = mask.words[std::size_t(y) * mask.words_per_row + (x / per_word)];
                const std::uint32_t bits = side == 32 ? word : (word >> (side * (x % per_word))) & ((1u << side) - 1u);
                const int n = std::min(side, mask.cells_x - side * x);
                const std::size_t b = std::size_t(y >> k) * bx + x;
                if (bits != (n == 32 ? 0xFFFFFFFFu : (1u << n) - 1u)) invalid[b] = 1;
                if (bits != 0) valid[b] = 1;
            }
        blocks.blocks_x = bx, blocks.blocks_y = by;
        const std::size_t w = std::size_t(bx) + 1;
        blocks.table.assign(w * (by + 1), {0, 0});
        for (int y = 0; y < by; ++y)
            for (int x = 0; x < bx; ++x) {
                const std::size_t b = std::size_t(y) * bx + x, at = (y + 1) * w + (x + 1);
                const auto &left = blocks.table[at - 1], &up = blocks.table[at - w], &corner = blocks.table[at - w - 1];
                // Wrapping uint16 sums: the differences judge() takes are exact below 2^16 blocks.
                blocks.table[at] = {std::uint16_t(invalid[b] + left.not_full + up.not_full - corner.not_full),
                                    std::uint16_t(valid[b] + left.with_valid + up.with_valid - corner.with_valid)};
            }
    }
};

// True when every sample position of the template rectangle lies inside the map and on valid
// cells, so per-sample checks can be skipped. The mapped rectangle is convex, so its four corners
// decide; a one-pixel margin absorbs float rounding of the individual sample positions.
bool patch_inside(const CpuMap& m, const Affine& A, const ScoringPlan& plan) {
    const float hx = plan.cx, hy = plan.cy;
    float x_lo = 1e30f, y_lo = 1e30f, x_hi = -1e30f, y_hi = -1e30f;
    for (float su : {-hx, hx})
        for (float sv : {-hy, hy}) {
            const float px = (A.tx + A.a * su) + A.b * sv, py = (A.ty + A.c * su) + A.d * sv;
            if (!(px >= 1.0f && py >= 1.0f && px <= float(m.width() - 2) && py <= float(m.height() - 2))) return false;
            x_lo = std::min(x_lo, px), y_lo = std::min(y_lo, py), x_hi = std::max(x_hi, px), y_hi = std::max(y_hi, py);
        }
    return m.cells_valid(int(x_lo) - 1, int(y_lo) - 1, int(x_hi) + 1, int(y_hi) + 1);
}

// Per-thread scratch that only grows, so steady-state calls allocate nothing.
struct Scratch {
    std::vector<float> ax, ay, bdv, ddv;
    std::vector<cpu::Tile> tiles;  // one band's
    void reserve(std::size_t n) {
        for (auto* v : {&ax, &ay, &bdv, &ddv})
            if (v->size() < n) v->resize(n);
    }
};

// Worker threads: the hardware threads unless options.threads says otherwise.
int thread_count(const BackendOptions::Cpu& options) {
    if (options.threads < 0 || options.threads > kMaxThreads)
        throw Error("BackendOptions.cpu.threads = " + std::to_string(options.threads) + ": expected 0 (the hardware threads) to " +
                    std::to_string(kMaxThreads));
    if (options.threads > 0) return options.threads;
    return static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

class CpuBackend final : public Backend {
public:
    // AVX2 or NEON when the processor has it, unless options.simd is off (to test and compare the portable path).
    explicit CpuBackend(const BackendOptions::Cpu& options) : kernels_(cpu::row_kernels(options.simd)), pool_(thread_count(options)) {
        info_ = {"cpu", "cpu", "optimized C++ (thread pool)", "cpu", "trnkit",
                 std::to_string(pool_.threads()) + " threads (TRN_CPU_THREADS), " + std::to_string(std::thread::hardware_concurrency()) +
                     " hardware threads, inner loop " + kernels_.name + " (TRN_CPU_SIMD=off forces portable)"};
    }
    const DeviceInfo& info() const override { return info_; }

protected:
    MapHandle do_upload_map(GrayView map, const CellMask* mask, PhaseTimes* times) override {
        const auto t0 = Clock::now();
        auto m = std::make_shared<CpuMap>(this, map, mask);
        if (times) times->upload_ms = ms_since(t0);
        return m;
    }

    double do_map_bytes(std::int64_t width, std::int64_t height) const override { return CpuMap::bytes(width, height); }

    void do_score(const MapStorage& storage, const ScoringPlan& plan, std::span<const Pose> poses,
                  std::span<ParticleScore> out, PhaseTimes* times) override {
        const auto t0 = Clock::now();
        const CpuMap& map = static_cast<const CpuMap&>(storage);
        prepare_offsets(plan);
        prepare_template_totals(plan);
        pool_.parallel_for(static_cast<std::int64_t>(poses.size()), 2, [&](std::int64_t begin, std::int64_t end) {
            for (std::int64_t p = begin; p < end; ++p) out[p] = score_one(map, plan, poses[p]);
        });
        if (times) times->execute_ms = ms_since(t0);
    }

    void do_sobel(GrayView src, Int16View gx, Int16View gy, PhaseTimes* times) override;

private:
    // Sum of T and T^2 over every sample, taken by particles whose samples are all inside the map,
    // and their prefix sums, for runs of a row (sample_row_clipped).
    void prepare_template_totals(const ScoringPlan& plan) {
        prefix_st_.resize(plan.quantized.size() + 1);
        prefix_stt_.resize(plan.quantized.size() + 1);
        st_ = 0, stt_ = 0;
        for (std::size_t k = 0; k < plan.quantized.size(); ++k) {
            prefix_st_[k] = st_, prefix_stt_[k] = stt_;
            const std::int64_t t = plan.quantized[k];
            st_ += t, stt_ += t * t;
        }
        prefix_st_.back() = st_, prefix_stt_.back() = stt_;
    }

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
        static thread_local Scratch scratch;
        const Affine A = pose_to_affine(pose);
        ParticleSums sums;
        const cpu::MapPixels pixels = map.view();
        const bool inside = patch_inside(map, A, plan);
        if (inside) sums.n = static_cast<std::int64_t>(plan.sample_count()), sums.st = st_, sums.stt = stt_;
        auto accumulate = [&](const cpu::RowSums& r) {
            sums.n += r.n, sums.sj += r.sj, sums.sjj += r.sjj, sums.sjt += r.sjt, sums.st += r.st, sums.stt += r.stt;
        };
        // Inside: every sample on the map and on a valid cell; else each is tested (SIMD: in lanes).
        auto add = [&](const cpu::RowInput& row) { accumulate(inside ? kernels_.inside(pixels, row) : kernels_.checked(pixels, row)); };
        const std::size_t count = du_.size();
        constexpr int kChunk = 512;  // sparse: samples per call of the row sampler
        const int total = static_cast<int>(count);
        if (!plan.dense && kernels_.sparse_from_affine) {  // positions computed in registers, nothing precomputed
            for (int k = 0; k < total; k += kChunk) {
                cpu::RowInput row{nullptr, nullptr, 0, 0, nullptr, nullptr, plan.quantized.data() + k, std::min(kChunk, total - k)};
                row.du = du_.data() + k, row.dv = dv_.data() + k;
                row.a = A.a, row.b = A.b, row.c = A.c, row.d = A.d, row.tx = A.tx, row.ty = A.ty;
                add(row);
            }
            return finalize_score(sums, plan);
        }
        scratch.reserve(count);
        // The row-invariant half of every position: tx + a*du and ty + c*du.
        for (std::size_t k = 0; k < count; ++k) {
            scratch.ax[k] = A.tx + A.a * du_[k];
            scratch.ay[k] = A.ty + A.c * du_[k];
        }
        if (plan.dense) {
            const cpu::TemplatePrefix prefix{prefix_st_.data(), prefix_stt_.data()};
            const int w = plan.width;
            // A patch near no-data: by tiles of kTileRows x kTileCols samples, each judged from
            // its corners (cpu::judge_tile), so only tiles over the no-data's edge or the map's
            // are tested sample by sample.
            const bool tiled = !inside && pixels.cell_bits;
            const int tile_cols = (w + cpu::kTileCols - 1) / cpu::kTileCols;
            if (tiled) scratch.tiles.resize(std::size_t(tile_cols));
            for (int v = 0; v < plan.height; ++v) {
                if (tiled && v % cpu::kTileRows == 0) {
                    const int v1 = std::min(v + cpu::kTileRows, plan.height) - 1;
                    const float dv0 = float(v) - plan.cy, dv1 = float(v1) - plan.cy;
                    const float bd0 = A.b * dv0, bd1 = A.b * dv1, dd0 = A.d * dv0, dd1 = A.d * dv1;
                    for (int i = 0; i < tile_cols; ++i) {
                        const int u0 = i * cpu::kTileCols, u1 = std::min(u0 + cpu::kTileCols, w) - 1;
                        const float px[4] = {scratch.ax[u0] + bd0, scratch.ax[u1] + bd0, scratch.ax[u0] + bd1, scratch.ax[u1] + bd1};
                        const float py[4] = {scratch.ay[u0] + dd0, scratch.ay[u1] + dd0, scratch.ay[u0] + dd1, scratch.ay[u1] + dd1};
                        scratch.tiles[i] = cpu::judge_tile(pixels, px, py);
                    }
                }
                const float dv = float(v) - plan.cy;
                const cpu::RowInput row{scratch.ax.data(), scratch.ay.data(), A.b * dv, A.d * dv, nullptr, nullptr,
                                        plan.quantized.data() + std::size_t(v) * w, w};
                if (inside)
                    add(row);
                else if (tiled)
                    accumulate(cpu::sample_row_tiles(pixels, row, kernels_, prefix, std::size_t(v) * w, scratch.tiles.data()));
                else  // over the map's edge: each row's run of samples on the map
                    accumulate(cpu::sample_row_clipped(pixels, row, kernels_, prefix, std::size_t(v) * w));
            }
        } else {
            for (std::size_t k = 0; k < count; ++k) {
                scratch.bdv[k] = A.b * dv_[k];
                scratch.ddv[k] = A.d * dv_[k];
            }
            for (int k = 0; k < total; k += kChunk)
                add({scratch.ax.data() + k, scratch.ay.data() + k, 0, 0, scratch.bdv.data() + k, scratch.ddv.data() + k,
                     plan.quantized.data() + k, std::min(kChunk, total - k)});
        }
        return finalize_score(sums, plan);
    }

    DeviceInfo info_;
    const cpu::RowKernels& kernels_;
    cpu::ThreadPool pool_;
    std::vector<float> du_, dv_;
    std::int64_t st_ = 0, stt_ = 0;
    std::vector<std::int64_t> prefix_st_, prefix_stt_;
};

// Interior pixels of one output row from three source rows; restrict lets the compiler vectorize
// (u8 pointers may otherwise alias the outputs).
void sobel_row_interior(const std::uint8_t* __restrict r0, const std::uint8_t* __restrict r1, const std::uint8_t* __restrict r2,
                        std::int16_t* __restrict ox, std::int16_t* __restrict oy, int w) {
    for (int x = 1; x < w - 1; ++x) {
        const std::int16_t a0 = r0[x - 1], a1 = r0[x], a2 = r0[x + 1];
        const std::int16_t b0 = r1[x - 1], b2 = r1[x + 1];
        const std::int16_t c0 = r2[x - 1], c1 = r2[x], c2 = r2[x + 1];
        ox[x] = std::int16_t((a2 - a0) + 2 * (b2 - b0) + (c2 - c0));
        oy[x] = std::int16_t((c0 + 2 * c1 + c2) - (a0 + 2 * a1 + a2));
    }
}

// Both gradients in one pass over the source: each output row reads three source rows.
void CpuBackend::do_sobel(GrayView src, Int16View gx, Int16View gy, PhaseTimes* times) {
    const auto t0 = Clock::now();
    const int w = src.width, h = src.height;
    auto reflect = [](int i, int n) { return n == 1 ? 0 : i < 0 ? -i : i >= n ? 2 * n - 2 - i : i; };
    // Rows in chunks of about 64K pixels: small images stay on the calling thread.
    const std::int64_t rows_per_chunk = std::max<std::int64_t>(1, (64 * 1024) / w);
    pool_.parallel_for(h, rows_per_chunk, [&](std::int64_t y0, std::int64_t y1) {
    for (int y = int(y0); y < int(y1); ++y) {
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
        sobel_row_interior(r0, r1, r2, ox, oy, w);
        if (w > 1) at(w - 1);
    }
    });
    if (times) times->execute_ms = ms_since(t0);
}

}  // namespace

std::unique_ptr<Backend> make_cpu_backend(const BackendOptions::Cpu& options) { return std::make_unique<CpuBackend>(options); }

}  // namespace trn
