// kernels/cuda/ncc_score.cu run on the CPU (kernel_emulator.hpp) with the backend's own planning
// (cuda_plan.hpp), against cpu-ref bit for bit: dense, sparse and explicit samples, poses partly off
// the map and on its last row and column, a map with no-data, several block sizes. What this does
// not check is everything of the driver's: memory, copies, launches, the real GPU's arithmetic.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <memory>
#include <vector>

#include "cuda_plan.hpp"
#include "trn/impl/cell_mask.hpp"
#include "trn/impl/particle_sums.hpp"
#include "trn/registry.hpp"

#include "kernel_emulator.hpp"
#include "ncc_score.cu"

namespace trn::cuda {
namespace {

struct World {
    int w = 203, h = 151;
    std::vector<std::uint8_t> map, valid;
    World() : map(std::size_t(w) * h), valid(std::size_t(w) * h, 255) {
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x)
                map[std::size_t(y) * w + x] = std::uint8_t(128 + 90 * std::sin(x * 0.11) * std::cos(y * 0.07) + (x * 13 + y * 7) % 23);
        for (int y = 40; y < 70; ++y)  // a hole, and a ragged band of no-data at the right edge
            for (int x = 60; x < 95; ++x) valid[std::size_t(y) * w + x] = 0;
        for (int y = 0; y < h; ++y)
            for (int x = w - 1 - y % 9; x < w; ++x) valid[std::size_t(y) * w + x] = 0;
    }
    GrayView map_view() const { return {map.data(), w, h, w}; }
    GrayView valid_view() const { return {valid.data(), w, h, w}; }
};

std::vector<Pose> poses_for(const World& world) {
    std::vector<Pose> p;
    for (int i = 0; i < 9; ++i) p.push_back({30.0f + 17.3f * i, 25.0f + 11.7f * i, 0.37f * i - 1.2f, 0.7f + 0.11f * i});
    p.push_back({float(world.w - 1), float(world.h - 1), 0.0f, 1.0f});  // centre on the last pixel: a quarter on the map
    p.push_back({-40.0f, 20.0f, 0.5f, 1.0f});                            // entirely off the map
    p.push_back({100.0f, 75.0f, 3.14159f, 1.0f / 3.0f});
    return p;
}

// The sums the kernel writes, through the backend's planning, then finalize_score.
std::vector<ParticleScore> emulate(const World& world, const CellMask* mask, const ScoringPlan& plan, const std::vector<Pose>& poses,
                                   std::size_t block) {
    NccLaunch l = plan_ncc(plan, poses.size(), world.w, world.h, mask ? mask->words_per_row : 0, block, {});
    std::vector<float> affines, offsets;
    affines_of(poses.data(), poses.size(), affines);
    if (!plan.dense) sample_offsets(plan, offsets);
    std::vector<std::int64_t> sums(poses.size() * kSumsPerParticle, -1);
    l.args.map = reinterpret_cast<std::uintptr_t>(world.map.data());
    l.args.cells = mask ? reinterpret_cast<std::uintptr_t>(mask->words.data()) : 0;
    l.args.affines = reinterpret_cast<std::uintptr_t>(affines.data());
    l.args.quantized = reinterpret_cast<std::uintptr_t>(plan.quantized.data());
    l.args.offsets = plan.dense ? 0 : reinterpret_cast<std::uintptr_t>(offsets.data());
    l.args.sums = reinterpret_cast<std::uintptr_t>(sums.data());
    trn_emu::launch(plan.dense ? &ncc_score_dense : &ncc_score_sparse, dim3{unsigned(l.grid), 1, 1}, dim3{unsigned(l.block), 1, 1}, l.args);
    std::vector<ParticleScore> out;
    for (std::size_t i = 0; i < poses.size(); ++i) {
        const std::int64_t* s = sums.data() + i * kSumsPerParticle;
        out.push_back(finalize_score(ParticleSums{s[0], s[1], s[2], s[3], s[4], s[5]}, plan));
    }
    return out;
}

void expect_same_bits(const std::vector<ParticleScore>& got, const std::vector<ParticleScore>& want) {
    ASSERT_EQ(got.size(), want.size());
    int valid = 0;
    for (std::size_t i = 0; i < got.size(); ++i) {
        EXPECT_EQ(std::memcmp(&got[i].ncc, &want[i].ncc, sizeof(float)), 0) << "particle " << i << ": " << got[i].ncc << " vs " << want[i].ncc;
        EXPECT_EQ(std::memcmp(&got[i].cc, &want[i].cc, sizeof(float)), 0) << "particle " << i;
        EXPECT_EQ(std::memcmp(&got[i].ssd, &want[i].ssd, sizeof(float)), 0) << "particle " << i;
        EXPECT_EQ(got[i].valid_samples, want[i].valid_samples) << "particle " << i;
        EXPECT_EQ(got[i].flags, want[i].flags) << "particle " << i;
        valid += want[i].valid();
    }
    EXPECT_GE(valid, 5);  // the case is not all invalid particles
}

void check(const Sampling& sampling, bool masked) {
    const World world;
    std::vector<std::uint8_t> templ(41 * 29);
    for (int y = 0; y < 29; ++y)
        for (int x = 0; x < 41; ++x) templ[std::size_t(y) * 41 + x] = world.map[std::size_t(y + 50) * world.w + x + 120];
    ScoreOptions o;
    o.sampling = sampling;
    o.min_valid_fraction = 0.2;
    const ScoringPlan plan = make_scoring_plan(GrayView{templ.data(), 41, 29, 41}, o);
    const std::vector<Pose> poses = poses_for(world);
    const std::unique_ptr<Backend> ref = default_registry().create("cpu-ref");
    const MapHandle h = masked ? ref->upload_map(world.map_view(), world.valid_view()) : ref->upload_map(world.map_view());
    std::vector<ParticleScore> want(poses.size());
    ref->score(h, plan, poses, want);
    const CellMask mask = make_cell_mask(world.valid_view());
    for (std::size_t block : {32u, 64u, 256u}) {
        SCOPED_TRACE("block " + std::to_string(block));
        expect_same_bits(emulate(world, masked ? &mask : nullptr, plan, poses, block), want);
    }
}

TEST(EmulatedNcc, DenseMatchesCpuRefBits) { check(Sampling::dense(), false); }
TEST(EmulatedNcc, SparseMatchesCpuRefBits) { check(Sampling::random(0.3, 11), false); }
TEST(EmulatedNcc, ExplicitPointsMatchCpuRefBits) {
    check(Sampling::explicit_points({{0, 0}, {40, 28}, {20, 14}, {3, 25}, {39, 1}, {7, 7}, {8, 8}, {33, 2}, {1, 27}}), false);
}
TEST(EmulatedNcc, NoDataMaskMatchesCpuRefBits) {
    check(Sampling::dense(), true);
    check(Sampling::random(0.5, 3), true);
}

}  // namespace
}  // namespace trn::cuda
