#pragma once
// Comparison and guard-band helpers shared by the conformance cases.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <iomanip>
#include <numbers>
#include <random>
#include <span>
#include <string>
#include <vector>

#include "trn/backend.hpp"

namespace trn::conformance {

inline constexpr int kGuard = 16;  // sentinel elements on each side of every output

// Scores for n particles with kGuard sentinel entries before and after.
class GuardedScores {
public:
    explicit GuardedScores(std::size_t n) : buf_(n + 2 * kGuard, sentinel()), n_(n) {}
    std::span<ParticleScore> out() { return {buf_.data() + kGuard, n_}; }
    std::span<const ParticleScore> scores() const { return {buf_.data() + kGuard, n_}; }
    // True when nothing outside out() was written.
    bool guards_intact() const {
        for (std::size_t i = 0; i < buf_.size(); ++i)
            if ((i < kGuard || i >= kGuard + n_) && std::memcmp(&buf_[i], &sentinel_value(), sizeof(ParticleScore)) != 0)
                return false;
        return true;
    }

private:
    static const ParticleScore& sentinel_value() {
        static const ParticleScore s{12345.0f, -777.0f, 999.0f, 0xDEADBEEFu, 0xFEEDFACEu};
        return s;
    }
    static ParticleScore sentinel() { return sentinel_value(); }
    std::vector<ParticleScore> buf_;
    std::size_t n_;
};

// Poses anywhere in (and `margin` of the map's size beyond) the map, any yaw, scales in [smin, smax).
inline std::vector<Pose> random_poses(std::mt19937& rng, int n, int map_w, int map_h, float margin, float smin, float smax) {
    std::uniform_real_distribution<float> ux(-margin * map_w, (1 + margin) * map_w), uy(-margin * map_h, (1 + margin) * map_h),
        yaw(-std::numbers::pi_v<float>, std::numbers::pi_v<float>), sc(smin, smax);
    std::vector<Pose> poses(n);
    for (Pose& p : poses) p = {ux(rng), uy(rng), yaw(rng), sc(rng)};
    return poses;
}

// A call that must throw trn::Error with `fragment` in its message (the same on every backend).
template <typename F>
void expect_error(F&& f, const std::string& fragment) {
    try {
        f();
        ADD_FAILURE() << "expected trn::Error containing '" << fragment << "'";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << "message was: " << e.what();
    }
}

// The same bits: every backend evaluates the exact integer definition of scoring.hpp.
inline bool same_bits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// Runs the same scoring on both backends and compares every particle for equality (scores bit for
// bit, counts, flags). `valid`: the map's no-data mask (empty: none). Returns the dut scores.
inline std::vector<ParticleScore> score_and_compare(Backend& dut, Backend& ref, GrayView map, GrayView valid,
                                                    const TemplateView& templ, std::span<const Pose> poses,
                                                    const ScoreOptions& options) {
    const ScoringPlan plan = make_scoring_plan(templ, options);
    GuardedScores got(poses.size()), want(poses.size());
    dut.score(dut.upload_map(map, valid), plan, poses, got.out());
    ref.score(ref.upload_map(map, valid), plan, poses, want.out());
    EXPECT_TRUE(got.guards_intact()) << dut.info().name << " wrote outside the score output";
    int reported = 0;
    for (std::size_t i = 0; i < poses.size(); ++i) {
        const ParticleScore &g = got.scores()[i], &w = want.scores()[i];
        const bool ok = g.valid_samples == w.valid_samples && g.flags == w.flags && std::isfinite(g.ncc) &&
                        std::isfinite(g.cc) && std::isfinite(g.ssd) && same_bits(g.ncc, w.ncc) && same_bits(g.cc, w.cc) &&
                        same_bits(g.ssd, w.ssd);
        if (!ok && reported++ < 5) {
            const Pose& p = poses[i];
            ADD_FAILURE() << std::setprecision(9) << "particle " << i << " pose (" << p.x << ", " << p.y << ", yaw " << p.yaw << ", scale " << p.scale
                          << ") map " << map.width << "x" << map.height << " template " << templ.width << "x" << templ.height
                          << "\n  " << dut.info().name << ": ncc " << g.ncc << " cc " << g.cc << " ssd " << g.ssd << " valid "
                          << g.valid_samples << " flags " << g.flags << "\n  cpu-ref: ncc " << w.ncc << " cc " << w.cc << " ssd "
                          << w.ssd << " valid " << w.valid_samples << " flags " << w.flags;
        }
    }
    if (reported > 5) ADD_FAILURE() << "... " << reported << " mismatching particles in all";
    return {got.scores().begin(), got.scores().end()};
}

inline std::vector<ParticleScore> score_and_compare(Backend& dut, Backend& ref, GrayView map, const TemplateView& templ,
                                                    std::span<const Pose> poses, const ScoreOptions& options) {
    return score_and_compare(dut, ref, map, GrayView{}, templ, poses, options);
}

}  // namespace trn::conformance
