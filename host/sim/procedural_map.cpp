// Procedural orthophoto: every pixel is shade(x, y) of a scene described by a few hashed rules
// (see procedural_map.hpp). Positions are in metres, so the resolution only changes sampling.
#include "trn/sim/procedural_map.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <string>
#include <thread>
#include <vector>

#include "random.hpp"
#include "trn/error.hpp"
#include "trn/limits.hpp"
#include "trn/detail/angles.hpp"

namespace trn::sim {
namespace {

using detail::hash;
using detail::unit;

// Smooth value noise on a hashed lattice with cell `cell_m` metres; values in [0, 1). The lattice
// over the region being generated is tabulated once, so a lookup is four loads, not four hashes.
class ValueNoise {
public:
    ValueNoise(std::uint64_t seed, double cell_m) : seed_(seed), inv_cell_(1.0 / cell_m) {}

    void tabulate(double x0, double y0, double x1, double y1) {
        ix0_ = static_cast<std::int64_t>(std::floor(x0 * inv_cell_)) - 1;
        iy0_ = static_cast<std::int64_t>(std::floor(y0 * inv_cell_)) - 1;
        nx_ = static_cast<std::int64_t>(std::floor(x1 * inv_cell_)) + 3 - ix0_;
        ny_ = static_cast<std::int64_t>(std::floor(y1 * inv_cell_)) + 3 - iy0_;
        table_.resize(static_cast<std::size_t>(nx_ * ny_));
        for (std::int64_t j = 0; j < ny_; ++j)
            for (std::int64_t i = 0; i < nx_; ++i) table_[j * nx_ + i] = static_cast<float>(lattice(ix0_ + i, iy0_ + j));
    }

    double at(double x, double y) const {
        const double gx = x * inv_cell_, gy = y * inv_cell_;
        const double fx0 = std::floor(gx), fy0 = std::floor(gy);
        const auto ix = static_cast<std::int64_t>(fx0), iy = static_cast<std::int64_t>(fy0);
        double fx = gx - fx0, fy = gy - fy0;
        fx = fx * fx * (3 - 2 * fx), fy = fy * fy * (3 - 2 * fy);
        double a, b, c, d;
        const std::int64_t ti = ix - ix0_, tj = iy - iy0_;
        if (ti >= 0 && tj >= 0 && ti + 1 < nx_ && tj + 1 < ny_) {
            const float* p = table_.data() + tj * nx_ + ti;
            a = p[0], b = p[1], c = p[nx_], d = p[nx_ + 1];
        } else {
            a = lattice(ix, iy), b = lattice(ix + 1, iy), c = lattice(ix, iy + 1), d = lattice(ix + 1, iy + 1);
        }
        const double top = a + fx * (b - a), bot = c + fx * (d - c);
        return top + fy * (bot - top);
    }

private:
    // Rounded to float like the table, so tabulated and direct lookups agree bit for bit.
    double lattice(std::int64_t i, std::int64_t j) const { return static_cast<float>(unit(hash(seed_, i, j))); }
    std::uint64_t seed_;
    double inv_cell_;
    std::int64_t ix0_ = 0, iy0_ = 0, nx_ = 0, ny_ = 0;
    std::vector<float> table_;
};

// The k-th of four 16-bit uniforms packed in one hash (cheaper than a hash per number).
inline double slice(std::uint64_t h, int k) { return static_cast<double>((h >> (16 * k)) & 0xFFFF) * (1.0 / 65536.0); }

enum class Land { Forest, Field, Meadow, Houses, Industrial, Park };

struct Rect {
    double x0, y0, x1, y1;
    bool contains(double x, double y) const { return x >= x0 && x < x1 && y >= y0 && y < y1; }
};

// True when the point lies in the shadow a box of `rect` casts along `dir` (unit, shadows fall
// that way) up to `length` metres: some t in [0, length] puts (x, y) - t*dir inside the box.
bool in_cast_shadow(const Rect& r, double x, double y, double dx, double dy, double length) {
    double t0 = 0, t1 = length;
    const double p[2] = {x, y}, d[2] = {dx, dy}, lo[2] = {r.x0, r.y0}, hi[2] = {r.x1, r.y1};
    for (int k = 0; k < 2; ++k) {
        if (std::abs(d[k]) < 1e-12) {
            if (p[k] < lo[k] || p[k] >= hi[k]) return false;
            continue;
        }
        // p - t d in [lo, hi]  <=>  t in [(p - hi)/d, (p - lo)/d] (swapped when d < 0)
        double a = (p[k] - hi[k]) / d[k], b = (p[k] - lo[k]) / d[k];
        if (a > b) std::swap(a, b);
        t0 = std::max(t0, a), t1 = std::min(t1, b);
        if (t0 > t1) return false;
    }
    return true;
}

class Scene {
public:
    // Generates positions within [x0, x1] x [y0, y1] metres (others work, just slower).
    Scene(const ProceduralMapOptions& o, double x0, double y0, double x1, double y1)
        : o_(o),
          urban_(o.style == TerrainStyle::Urban),
          seed_(detail::mix64(o.seed * 2 + (urban_ ? 1 : 0))),
          warp_x_(hash(seed_, 1), 450), warp_y_(hash(seed_, 2), 450),
          lakes_(hash(seed_, 3), urban_ ? 500 : 700), lakes_fine_(hash(seed_, 4), 120),
          mottle_(hash(seed_, 5), 14), grain_(hash(seed_, 6), 3.5), stands_(hash(seed_, 7), 60),
          river_wobble_(hash(seed_, 8), 300) {
        for (ValueNoise* n : {&warp_x_, &warp_y_, &lakes_, &lakes_fine_, &mottle_, &grain_, &stands_})
            n->tabulate(x0 - 10, y0 - 10, x1 + 10, y1 + 10);
        // mottle_ is also read at a third of the position (water) and grain_ at double (soil).
        make_lines(xs_, o.width_m, 11);
        make_lines(ys_, o.height_m, 12);
        tabulate_blocks();
        // The year sets the season and the sun; it never moves roads, blocks or rivers.
        const std::uint64_t y = hash(seed_, 20, o.year);
        const double shadow_azimuth = kPi * (0.55 + 0.9 * unit(y, 0));  // shadows fall north-ish
        sun_dx_ = std::sin(shadow_azimuth) * -1.0;
        sun_dy_ = std::cos(shadow_azimuth);  // azimuth measured from south, clockwise
        const double norm = std::hypot(sun_dx_, sun_dy_);
        sun_dx_ /= norm, sun_dy_ /= norm;
        sun_elevation_ = (30 + 30 * unit(y, 1)) * kPi / 180;
        shadow_per_metre_ = 1.0 / std::tan(sun_elevation_);
        gain_ = 0.92 + 0.16 * unit(y, 2);
        offset_ = -8 + 16 * unit(y, 3);
        vegetation_gain_ = 0.85 + 0.3 * unit(y, 4);
        river_y_ = o.height_m * (0.25 + 0.5 * unit(hash(seed_, 9)));
        river_phase_ = 2 * kPi * unit(hash(seed_, 10));
    }

    float shade(double x, double y) const {
        double v = shade_land(x, y);
        v = v * gain_ + offset_;
        v += 6.0 * (grain_.at(x, y) - 0.5) + 3.0 * (unit(hash(seed_, 30, std::llround(x * 8), std::llround(y * 8))) - 0.5);
        return static_cast<float>(std::clamp(v, 0.0, 255.0));
    }

private:
    void make_lines(std::vector<double>& lines, double extent, int salt) const {
        const double lo = urban_ ? 90 : 220, hi = urban_ ? 170 : 520;
        double p = -lo - 100;
        for (int i = 0; p < extent + hi + 100; ++i) {
            lines.push_back(p);
            p += lo + (hi - lo) * unit(hash(seed_, salt, i));
        }
    }
    // Per-block facts, tabulated once: looked up for every pixel.
    void tabulate_blocks() {
        const int nx = static_cast<int>(xs_.size()), ny = static_cast<int>(ys_.size());
        v_road_.resize(std::size_t(nx) * ny), h_road_.resize(std::size_t(nx) * ny);
        v_hedge_.resize(std::size_t(nx) * ny), h_hedge_.resize(std::size_t(nx) * ny), land_.resize(std::size_t(nx) * ny);
        for (int i = 0; i < nx; ++i)
            for (int j = 0; j < ny; ++j) {
                const std::size_t k = std::size_t(i) * ny + j;
                v_road_[k] = road_width_hashed(true, i, j);   // vertical line i, segment j
                h_road_[k] = road_width_hashed(false, j, i);  // horizontal line j, segment i
                v_hedge_[k] = hedge_hashed(true, i, j);
                h_hedge_[k] = hedge_hashed(false, j, i);
                land_[k] = land_hashed(i, j);
            }
    }
    std::size_t cell(int i, int j) const { return std::size_t(i) * ys_.size() + j; }
    double road_width(bool vertical, int line, int seg) const { return vertical ? v_road_[cell(line, seg)] : h_road_[cell(seg, line)]; }
    bool hedge(bool vertical, int line, int seg) const { return vertical ? v_hedge_[cell(line, seg)] : h_hedge_[cell(seg, line)]; }
    Land land(int bi, int bj) const { return land_[cell(bi, bj)]; }

    static int find(const std::vector<double>& lines, double p) {
        const auto it = std::upper_bound(lines.begin(), lines.end(), p);
        return std::clamp(static_cast<int>(it - lines.begin()) - 1, 0, static_cast<int>(lines.size()) - 2);
    }

    // Road width (metres) on segment `seg` of boundary line `line` (vertical when `vertical`); 0: none.
    double road_width_hashed(bool vertical, int line, int seg) const {
        const std::uint64_t h = hash(seed_, vertical ? 40 : 41, line, seg);
        const bool main_road = unit(hash(seed_, vertical ? 42 : 43, line)) < (urban_ ? 0.25 : 0.3);
        if (urban_) return main_road ? 14 : 8;
        if (main_road) return 8;
        return unit(h) < 0.3 ? 4.5 : 0.0;  // farm tracks on some field edges
    }
    bool hedge_hashed(bool vertical, int line, int seg) const { return !urban_ && unit(hash(seed_, vertical ? 44 : 45, line, seg)) < 0.35; }

    Land land_hashed(int bi, int bj) const {
        const double u = unit(hash(seed_, 50, bi, bj));
        if (urban_) {
            if (u < 0.58) return Land::Houses;
            if (u < 0.70) return Land::Industrial;
            if (u < 0.80) return Land::Park;
            if (u < 0.90) return Land::Field;
            return Land::Forest;
        }
        if (u < 0.45) return Land::Forest;
        if (u < 0.80) return Land::Field;
        if (u < 0.92) return Land::Meadow;
        return Land::Houses;
    }

    double shade_land(double x, double y) const {
        // Lakes: where large-scale noise peaks; a thin bright shore.
        const double lake = lakes_.at(x, y) + 0.15 * (lakes_fine_.at(x, y) - 0.5);
        const double level = urban_ ? 0.86 : 0.84;
        if (lake > level) return water(x, y, lake - level);
        if (lake > level - 0.012) return 150 + 20 * mottle_.at(x, y);

        // Gently curved road network: blocks between warped grid lines.
        const double amp = urban_ ? 10 : 35;
        const double wx = x + amp * (2 * warp_x_.at(x, y) - 1), wy = y + amp * (2 * warp_y_.at(x, y) - 1);
        const int bi = find(xs_, wx), bj = find(ys_, wy);
        const double lx = wx - xs_[bi], ly = wy - ys_[bj];
        const double bw = xs_[bi + 1] - xs_[bi], bh = ys_[bj + 1] - ys_[bj];
        const double dist[4] = {lx, bw - lx, ly, bh - ly};
        const double width[4] = {road_width(true, bi, bj), road_width(true, bi + 1, bj), road_width(false, bj, bi),
                                 road_width(false, bj + 1, bi)};
        for (int k = 0; k < 4; ++k)
            if (dist[k] < width[k] / 2) return road(x, y, width[k], dist[k]);

        // River: a meandering band (after roads, so roads bridge it).
        const double ry = river_y_ + 120 * std::sin(2 * kPi * x / 900 + river_phase_) + 80 * (river_wobble_.at(x, 0) - 0.5) * 2;
        const double river_half = urban_ ? 14 : 11;
        if (std::abs(y - ry) < river_half) return water(x, y, 0.05);
        if (std::abs(y - ry) < river_half + 4) return vegetation(trees(x, y, 4.0, 0.8, 75), 120);

        const bool hedges[4] = {hedge(true, bi, bj), hedge(true, bi + 1, bj), hedge(false, bj, bi), hedge(false, bj + 1, bi)};
        for (int k = 0; k < 4; ++k)
            if (hedges[k] && dist[k] < 3.5) {
                const double t = trees(x, y, 3.5, 0.85, 80);
                if (t >= 0) return vegetation(t, 0);
            }

        switch (land(bi, bj)) {
            case Land::Forest: return forest(x, y, bi, bj);
            case Land::Field: return field(x, y, bi, bj, lx, ly, bw, bh);
            case Land::Meadow: return meadow(x, y, 0.06);
            case Land::Park: return meadow(x, y, 0.35);
            case Land::Houses: return houses(x, y, bi, bj, lx, ly, bw, bh);
            case Land::Industrial: return industrial(x, y, bi, bj, lx, ly, bw, bh);
        }
        return 128;
    }

    double water(double x, double y, double depth) const {
        return 38 + 10 * mottle_.at(x * 0.3, y * 0.3) + 12 * std::max(0.0, 0.04 - depth) / 0.04;
    }

    double road(double x, double y, double w, double d) const {
        if (urban_ || w >= 8) {
            double v = 88 + 10 * mottle_.at(x, y);
            if (d < 0.8) v += 25;  // kerb / verge
            return v;
        }
        return 150 + 18 * mottle_.at(x, y) - (d > 0.9 && d < 1.6 ? 20 : 0);  // gravel track with wheel ruts
    }

    double vegetation(double value, double fallback) const { return value >= 0 ? value * vegetation_gain_ : fallback; }

    // Tree crowns on a jittered grid (cell metres, share of cells with a tree, base brightness):
    // a lit hemisphere per crown. Returns -1 where no crown covers the point.
    double trees(double x, double y, double cell, double density, double base) const {
        const auto cx = static_cast<std::int64_t>(std::floor(x / cell)), cy = static_cast<std::int64_t>(std::floor(y / cell));
        double best = -1, value = -1;
        for (std::int64_t j = cy - 1; j <= cy + 1; ++j)
            for (std::int64_t i = cx - 1; i <= cx + 1; ++i) {
                const std::uint64_t h = hash(seed_, 60, i, j);
                if (unit(h) >= density) continue;
                const std::uint64_t g = detail::mix64(h);
                const double px = (i + 0.15 + 0.7 * slice(g, 0)) * cell, py = (j + 0.15 + 0.7 * slice(g, 1)) * cell;
                const double r = cell * (0.45 + 0.3 * slice(g, 2));
                const double dx = x - px, dy = y - py, d2 = dx * dx + dy * dy;
                if (d2 >= r * r) continue;
                const double z = std::sqrt(r * r - d2);
                const double top = z + 2 * slice(g, 3);
                if (top <= best) continue;
                best = top;
                // Light comes from opposite the shadow direction.
                const double cos_e = std::cos(sun_elevation_), sin_e = std::sin(sun_elevation_);
                const double light = (-dx * sun_dx_ * cos_e - dy * sun_dy_ * cos_e + z * sin_e) / r;
                value = base * (0.5 + 0.75 * std::max(0.0, light)) + 25 * (slice(h, 0) - 0.5);
            }
        return value;
    }

    double forest(double x, double y, int bi, int bj) const {
        const std::uint64_t h = hash(seed_, 70, bi, bj);
        const bool cut = unit(h) < 0.2 && o_.year >= 2009 + static_cast<int>(12 * unit(h, 1));
        if (cut) {  // clear-cut: bright soil and young growth
            const double t = trees(x, y, 2.5, 0.25, 95);
            return t >= 0 ? vegetation(t, 0) : 135 + 30 * mottle_.at(x, y);
        }
        const double stand = stands_.at(x, y);
        const double t = trees(x, y, 4.0 + 1.5 * unit(h, 2), 0.92, 70 + 35 * stand);
        if (t >= 0) return vegetation(t, 0);
        // Gap: shaded forest floor, darker still where a neighbouring crown casts its shadow.
        const double shadowed = trees(x - 2.5 * sun_dx_, y - 2.5 * sun_dy_, 4.0 + 1.5 * unit(h, 2), 0.92, 1);
        return shadowed >= 0 ? 26 : 42;
    }

    double meadow(double x, double y, double tree_density) const {
        const double t = trees(x, y, 6.0, tree_density, 85);
        if (t >= 0) return vegetation(t, 0);
        const double shadowed = trees(x - 4 * sun_dx_, y - 4 * sun_dy_, 6.0, tree_density, 1);
        const double grass = (120 + 30 * mottle_.at(x, y)) * vegetation_gain_;
        return shadowed >= 0 ? grass * 0.55 : grass;
    }

    double field(double x, double y, int bi, int bj, double lx, double ly, double bw, double bh) const {
        const std::uint64_t hb = hash(seed_, 80, bi, bj);
        const bool along_x = bw >= bh;
        const int strips = 1 + static_cast<int>(3 * unit(hb));
        const double along = along_x ? lx : ly, extent = along_x ? bw : bh;
        const int k = std::min(strips - 1, static_cast<int>(along / (extent / strips)));
        const double edge = along - k * (extent / strips);
        if (k > 0 && edge < 1.2) return 105 + 15 * mottle_.at(x, y);  // strip boundary
        // Crops rotate every year.
        const std::uint64_t h = hash(seed_, 81, bi * 8 + k, bj, o_.year);
        const double kind = unit(h);
        const double base = 95 + 95 * unit(h, 1);
        if (kind < 0.2) return base + 25 * (mottle_.at(x, y) - 0.5) + 15 * (grain_.at(x * 2, y * 2) - 0.5);  // bare soil
        // Rows: parallel or across the strip, with tramlines every ~20 m.
        const double angle = (unit(h, 2) < 0.5 ? 0 : kPi / 2) + (unit(hb, 3) - 0.5) * 0.1;
        const double c = std::cos(angle), s = std::sin(angle);
        const double across = lx * c + ly * s;
        const double period = std::max(2.6 * o_.metres_per_pixel, 2.0 + 4.0 * unit(h, 3));
        const double amp = 10 + 18 * unit(h, 4);
        double v = base + amp * std::sin(2 * kPi * across / period) + 18 * (mottle_.at(x, y) - 0.5);
        const double tram = std::fmod(std::abs(across), 21.0);
        if (kind > 0.5 && tram < 1.6) v -= 22;
        return kind < 0.4 ? v * vegetation_gain_ : v;
    }

    // Houses stand in rows of lots along the block's long side: two rows (one per road) in a
    // village, more in town where the rows lie back to back. Row r faces its low edge when even.
    int house_rows(bool along_x, double bw, double bh) const {
        const double across = along_x ? bh : bw;
        return urban_ ? std::max(2, static_cast<int>(std::lround(across / 34))) : 2;
    }

    // The house on lot k of row `row` of a block, if one stands there this year.
    bool house(int bi, int bj, int row, int k, bool along_x, double bw, double bh, Rect& r, double& roof) const {
        const double extent = along_x ? bw : bh;
        const int rows = house_rows(along_x, bw, bh);
        if (row < 0 || row >= rows) return false;
        const double depth = (along_x ? bh : bw) / rows;
        const std::uint64_t hb = hash(seed_, 90, bi, bj);
        const double lot = 14 + 10 * unit(hb);
        if (k < 0 || (k + 1) * lot > extent) return false;
        const std::uint64_t h = hash(seed_, 91, bi * 64 + row, bj, k), g = detail::mix64(h);
        const int built = slice(h, 0) < 0.85 ? 1900 : 2000 + static_cast<int>(21 * slice(h, 1));
        const int demolished = slice(h, 2) < 0.04 ? 2005 + static_cast<int>(16 * slice(h, 3)) : 9999;
        if (o_.year < built || o_.year >= demolished || slice(g, 0) < (urban_ ? 0.05 : 0.2)) return false;
        const double w = std::min(lot - 3, 8 + 6 * slice(g, 1)), d = std::min(depth - 8, 8 + 5 * slice(g, 2));
        if (w < 4 || d < 4) return false;
        const double set_back = 4 + 3 * slice(g, 3);
        const double a0 = k * lot + (lot - w) / 2, a1 = a0 + w;
        const double b0 = row * depth + (row % 2 == 0 ? set_back : depth - set_back - d), b1 = b0 + d;
        r = along_x ? Rect{a0, b0, a1, b1} : Rect{b0, a0, b1, a1};
        roof = 70 + 120 * unit(detail::mix64(g));
        return true;
    }

    double houses(double x, double y, int bi, int bj, double lx, double ly, double bw, double bh) const {
        const bool along_x = bw >= bh;
        const std::uint64_t hb = hash(seed_, 90, bi, bj);
        const double lot = 14 + 10 * unit(hb);
        const double along = along_x ? lx : ly, across = along_x ? ly : lx;
        const int rows = house_rows(along_x, bw, bh);
        const int row = std::clamp(static_cast<int>(across / ((along_x ? bh : bw) / rows)), 0, rows - 1);
        const int k = static_cast<int>(std::floor(along / lot));
        bool shadow = false;
        for (int r = row - 1; r <= row + 1; ++r)
            for (int kk = k - 1; kk <= k + 1; ++kk) {
                Rect rect;
                double roof;
                if (!house(bi, bj, r, kk, along_x, bw, bh, rect, roof)) continue;
                if (rect.contains(lx, ly)) {
                    // Gable roof: the ridge runs along the long side; the half facing the sun is lit.
                    const bool ridge_x = (rect.x1 - rect.x0) >= (rect.y1 - rect.y0);
                    const double mid = ridge_x ? (rect.y0 + rect.y1) / 2 : (rect.x0 + rect.x1) / 2;
                    const double pos = ridge_x ? ly : lx, sun = ridge_x ? -sun_dy_ : -sun_dx_;
                    const bool lit = (pos < mid) == (sun < 0);
                    if (std::abs(pos - mid) < 0.35) return roof * 1.15;
                    return roof * (lit ? 1.1 : 0.72);
                }
                if (in_cast_shadow(rect, lx, ly, sun_dx_, sun_dy_, 6.5 * shadow_per_metre_)) shadow = true;
            }
        // Gardens: lawn, a few trees, a paved drive to the street in town.
        double ground = meadow(x, y, urban_ ? 0.05 : 0.08);
        if (urban_ && std::fmod(along, lot) < 3.0) ground = 115 + 10 * mottle_.at(x, y);
        return shadow ? ground * 0.5 : ground;
    }

    double industrial(double x, double y, int bi, int bj, double lx, double ly, double bw, double bh) const {
        const std::uint64_t h = hash(seed_, 95, bi, bj);
        const bool built = o_.year >= (unit(h) < 0.8 ? 1900 : 2005 + static_cast<int>(15 * unit(h, 1)));
        const Rect hall{12 + 10 * unit(h, 2), 12 + 10 * unit(h, 3), bw - 12 - 15 * unit(h, 4), bh - 12 - 15 * unit(h, 5)};
        if (built && hall.x1 > hall.x0 + 10 && hall.y1 > hall.y0 + 10) {
            if (hall.contains(lx, ly)) {
                double v = 165 + 45 * unit(h, 6);
                if (std::fmod(lx - hall.x0, 9.0) < 1.5 && std::fmod(ly - hall.y0, 12.0) < 1.5) v -= 60;  // roof vents
                return v;
            }
            const double v = 100 + 12 * mottle_.at(x, y);  // car park
            return in_cast_shadow(hall, lx, ly, sun_dx_, sun_dy_, 9 * shadow_per_metre_) ? v * 0.5 : v;
        }
        return meadow(x, y, 0.05);
    }

    ProceduralMapOptions o_;
    bool urban_;
    std::uint64_t seed_;
    ValueNoise warp_x_, warp_y_, lakes_, lakes_fine_, mottle_, grain_, stands_, river_wobble_;
    std::vector<double> xs_, ys_;
    std::vector<double> v_road_, h_road_;
    std::vector<char> v_hedge_, h_hedge_;
    std::vector<Land> land_;
    double sun_dx_ = 0, sun_dy_ = -1, sun_elevation_ = 0.8, shadow_per_metre_ = 1;
    double gain_ = 1, offset_ = 0, vegetation_gain_ = 1;
    double river_y_ = 0, river_phase_ = 0;
};

}  // namespace

TerrainStyle parse_terrain_style(std::string_view text) {
    if (text == "forest") return TerrainStyle::Forest;
    if (text == "urban") return TerrainStyle::Urban;
    throw Error("terrain style '" + std::string(text) + "': expected forest or urban");
}

const char* to_string(TerrainStyle style) { return style == TerrainStyle::Urban ? "urban" : "forest"; }

int ProceduralMapOptions::width_px() const { return static_cast<int>(std::lround(width_m / metres_per_pixel)); }
int ProceduralMapOptions::height_px() const { return static_cast<int>(std::lround(height_m / metres_per_pixel)); }

void ProceduralMapOptions::validate() const {
    if (!(metres_per_pixel >= 0.05 && metres_per_pixel <= 20))
        throw Error("procedural map: resolution " + std::to_string(metres_per_pixel) + " m/px must be in [0.05, 20]");
    char size[96];
    std::snprintf(size, sizeof size, "%g x %g m at %g m/px", width_m, height_m, metres_per_pixel);
    // Pixels in double first: width_px() would overflow int for absurd sizes.
    const double w = width_m / metres_per_pixel, h = height_m / metres_per_pixel;
    if (!(width_m > 0 && height_m > 0) || !(w >= 1.5 && h >= 1.5))
        throw Error(std::string("procedural map: ") + size + " is smaller than 2x2 pixels");
    constexpr double side = 1e18;  // keeps llround within int64; anything that large fails anyway
    limits::check_image(std::string("procedural map ") + size + ": image",
                        static_cast<std::int64_t>(std::llround(std::min(w, side))),
                        static_cast<std::int64_t>(std::llround(std::min(h, side))), limits::kMaxMapPixels,
                        limits::kGrayBytesPerPixel);
}

GrayImage generate_procedural_region(const ProceduralMapOptions& options, int x0, int y0, int w, int h) {
    options.validate();
    limits::check_image("procedural region", w, h, limits::kMaxMapPixels, limits::kGrayBytesPerPixel);
    const double mpp = options.metres_per_pixel;
    const Scene scene(options, x0 * mpp, y0 * mpp, (x0 + w) * mpp, (y0 + h) * mpp);
    GrayImage img{w, h, std::vector<std::uint8_t>(std::size_t(w) * h)};
    // Rows are independent: a few threads take interleaved bands of rows (no OpenMP: the library
    // does not link it).
    const int threads = std::clamp(static_cast<int>(std::thread::hardware_concurrency()), 1, std::max(1, h / 16));
    std::atomic<int> next_band{0};
    constexpr int kBand = 16;
    auto work = [&] {
        for (int b; (b = next_band.fetch_add(1)) * kBand < h;)
            for (int j = b * kBand; j < std::min(h, (b + 1) * kBand); ++j) {
                std::uint8_t* row = img.pixels.data() + std::size_t(j) * w;
                const double y = (y0 + j + 0.5) * mpp;
                for (int i = 0; i < w; ++i) row[i] = static_cast<std::uint8_t>(std::lround(scene.shade((x0 + i + 0.5) * mpp, y)));
            }
    };
    std::vector<std::thread> pool;
    for (int t = 1; t < threads; ++t) pool.emplace_back(work);
    work();
    for (std::thread& t : pool) t.join();
    return img;
}

Map generate_procedural_map(const ProceduralMapOptions& options) {
    options.validate();
    Map map;
    map.image = generate_procedural_region(options, 0, 0, options.width_px(), options.height_px());
    map.metres_per_pixel = options.metres_per_pixel;
    map.origin = options.origin;
    return map;
}

}  // namespace trn::sim
