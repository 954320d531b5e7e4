// Tilt compensation (issue 12 item 4): a frame rendered by the simulator with roll / pitch, warped
// to nadir, must match the level frame rendered at the same place over its centred crop, and match
// it much better than the tilted frame itself does (which is shifted and skewed by the tilt).
#include <gtest/gtest.h>

#include <cmath>

#include "trn/error.hpp"
#include "trn/filter/nadir_warp.hpp"
#include "trn/sim/procedural_map.hpp"
#include "trn/sim/render.hpp"
#include "trn/detail/angles.hpp"

namespace {

using trn::kDeg;

// NCC of b against the centred crop of a with b's size.
double centred_ncc(const trn::GrayImage& a, const trn::GrayImage& b) {
    const int ox = (a.width - b.width) / 2, oy = (a.height - b.height) / 2;
    double sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0;
    const double n = double(b.width) * b.height;
    for (int y = 0; y < b.height; ++y)
        for (int x = 0; x < b.width; ++x) {
            const double va = a.pixels[std::size_t(y + oy) * a.width + x + ox], vb = b.pixels[std::size_t(y) * b.width + x];
            sa += va, sb += vb, saa += va * va, sbb += vb * vb, sab += va * vb;
        }
    return (sab - sa * sb / n) / std::sqrt((saa - sa * sa / n) * (sbb - sb * sb / n));
}

struct Scene {
    trn::sim::Map map = trn::sim::generate_procedural_map({trn::sim::TerrainStyle::Urban, 5, 2008, 600, 600, 0.5});
    trn::sim::Camera camera{320, 240, 60};
    trn::sim::RenderOptions render{0.0, true, 1};
    trn::GrayImage frame(double roll, double pitch) const {
        return trn::sim::render_frame(map, camera, {600, 600, 120, 0.7, roll * kDeg, pitch * kDeg}, render);
    }
};

}  // namespace

TEST(NadirWarp, TiltedFrameWarpedToNadirMatchesTheLevelFrame) {
    const Scene s;
    const trn::GrayImage level = s.frame(0, 0);
    for (const auto& [roll, pitch] : {std::pair{8.0, 0.0}, std::pair{0.0, -10.0}, std::pair{-6.0, 7.0}}) {
        const trn::GrayImage tilted = s.frame(roll, pitch);
        const trn::filter::NadirFrame n = trn::filter::warp_to_nadir(tilted.view(), s.camera.hfov_deg, roll * kDeg, pitch * kDeg);
        ASSERT_LT(n.image.width, tilted.width);  // cropped to what the tilted frame covers
        const double warped = centred_ncc(level, n.image);
        trn::GrayImage raw_crop;  // the tilted frame itself, same crop: what scoring without compensation sees
        raw_crop.width = n.image.width, raw_crop.height = n.image.height;
        for (int y = 0; y < raw_crop.height; ++y)
            for (int x = 0; x < raw_crop.width; ++x)
                raw_crop.pixels.push_back(tilted.pixels[std::size_t(y + (tilted.height - raw_crop.height) / 2) * tilted.width + x +
                                                        (tilted.width - raw_crop.width) / 2]);
        const double uncompensated = centred_ncc(level, raw_crop);
        std::cout << "roll " << roll << " pitch " << pitch << ": kept " << n.kept_fraction << " of the width, NCC with the level frame "
                  << warped << " (uncompensated " << uncompensated << ")\n";
        EXPECT_GT(warped, 0.95);
        EXPECT_LT(uncompensated, warped - 0.2);
    }
}

TEST(NadirWarp, LevelFrameIsUnchangedAndTheDefaultLimitKeepsHalfTheFrame) {
    const Scene s;
    const trn::GrayImage level = s.frame(0, 0);
    const trn::filter::NadirFrame same = trn::filter::warp_to_nadir(level.view(), 60, 0, 0);
    EXPECT_EQ(same.image.width, level.width);
    EXPECT_EQ(same.image.pixels, level.pixels);
    // The figures behind kDefaultMaxTiltDeg (60-degree 4:3 lens): at 10 degrees the level crop keeps
    // over half the width, at 15 only about a third (pitch; roll tilts along the long side and keeps more).
    for (double deg : {10.0, 15.0, 20.0})
        std::cout << deg << " deg: the crop keeps " << trn::filter::warp_to_nadir(level.view(), 60, 0, deg * kDeg).kept_fraction
                  << " of the width (pitch), " << trn::filter::warp_to_nadir(level.view(), 60, deg * kDeg, 0).kept_fraction << " (roll)\n";
    const double limit = trn::filter::kDefaultMaxTiltDeg * kDeg;
    EXPECT_GT(trn::filter::warp_to_nadir(level.view(), 60, 0, limit).kept_fraction, 0.5);
    EXPECT_GT(trn::filter::warp_to_nadir(level.view(), 60, limit, 0).kept_fraction, 0.6);
    EXPECT_LT(trn::filter::warp_to_nadir(level.view(), 60, 0, 15 * kDeg).kept_fraction, 0.4);
    EXPECT_THROW(trn::filter::warp_to_nadir(level.view(), 60, 0, 40 * kDeg), trn::Error);
}
