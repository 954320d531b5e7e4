// The program binary cache: a cold start builds from source and stores binaries, a warm start
// loads them and computes the very same results, damaged entries are rebuilt, and
// TRN_OPENCL_CACHE=0 leaves the disk alone.
#include <fstream>

#include "opencl_test_support.hpp"
#include "program_cache.hpp"

namespace trn::test {
namespace {

// Scores a small fixed problem; used to show cold- and warm-built programs agree bit for bit.
std::vector<ParticleScore> score_fixed_problem(Backend& b) {
    const int mw = 96, mh = 80;
    const auto map = textured_pixels(mw, mh, 7);
    const auto templ = textured_pixels(24, 18, 9);
    const MapHandle h = b.upload_map({map.data(), mw, mh, mw});
    std::vector<Pose> poses;
    for (int i = 0; i < 12; ++i) poses.push_back({20.0f + 4.5f * i, 30.0f + 2.0f * i, 0.1f * i, 0.8f + 0.05f * i});
    std::vector<ParticleScore> out(poses.size());
    b.score(h, TemplateView(GrayView{templ.data(), 24, 18, 24}), poses, ScoreOptions{}, out);
    return out;
}

void expect_same_scores(const std::vector<ParticleScore>& a, const std::vector<ParticleScore>& b) {
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
        EXPECT_EQ(a[i].ncc, b[i].ncc) << i;
        EXPECT_EQ(a[i].cc, b[i].cc) << i;
        EXPECT_EQ(a[i].ssd, b[i].ssd) << i;
        EXPECT_EQ(a[i].valid_samples, b[i].valid_samples) << i;
        EXPECT_EQ(a[i].flags, b[i].flags) << i;
    }
}

TEST(OpenClProgramCache, ColdBuildStoresBinariesAndWarmStartLoadsThem) {
    TRN_REQUIRE_OPENCL_DEVICE();
    TempDir tmp;
    ScopedEnv xdg("XDG_CACHE_HOME", tmp.path().string());
    ScopedEnv on("TRN_OPENCL_CACHE", std::nullopt);
    const auto dir = tmp.path() / "trnkit" / "opencl";

    auto cold = default_registry().create("opencl:0", test::backend_options_from_environment());
    EXPECT_NE(cold->info().details.find("built from source"), std::string::npos) << cold->info().details;
    const auto entries = files_with_extension(dir, ".bin");
    EXPECT_EQ(entries.size(), 2u) << "one entry each for ncc_score.cl and sobel3x3.cl in " << dir;
    EXPECT_TRUE(files_with_extension(dir, ".tmp").empty());

    auto warm = default_registry().create("opencl:0", test::backend_options_from_environment());
    EXPECT_NE(warm->info().details.find("loaded from the cache"), std::string::npos) << warm->info().details;
    expect_same_scores(score_fixed_problem(*cold), score_fixed_problem(*warm));

    // Both build times are now on record for `trnkit devices --verbose`.
    std::string listed;
    for (const FamilyStatus& f : default_registry().status(test::backend_options_from_environment()))
        if (f.family == "opencl") listed = f.devices.at(0).details;
    EXPECT_NE(listed.find("cold build"), std::string::npos) << listed;
    EXPECT_EQ(listed.find("not yet measured"), std::string::npos) << listed;
}

TEST(OpenClProgramCache, DamagedEntryIsRebuiltAndReplaced) {
    TRN_REQUIRE_OPENCL_DEVICE();
    TempDir tmp;
    ScopedEnv xdg("XDG_CACHE_HOME", tmp.path().string());
    ScopedEnv on("TRN_OPENCL_CACHE", std::nullopt);
    const auto dir = tmp.path() / "trnkit" / "opencl";
    const auto reference = score_fixed_problem(*default_registry().create("opencl:0", test::backend_options_from_environment()));

    for (const auto& entry : files_with_extension(dir, ".bin")) {
        std::ofstream f(entry, std::ios::binary | std::ios::trunc);
        f << "trnkit-opencl-binary v1\nthis is not a program binary";
    }
    auto rebuilt = default_registry().create("opencl:0", test::backend_options_from_environment());
    EXPECT_NE(rebuilt->info().details.find("built from source"), std::string::npos) << rebuilt->info().details;
    expect_same_scores(reference, score_fixed_problem(*rebuilt));
    auto warm = default_registry().create("opencl:0", test::backend_options_from_environment());
    EXPECT_NE(warm->info().details.find("loaded from the cache"), std::string::npos) << "the damaged entries were replaced";
}

TEST(OpenClProgramCache, KeyCoversSourceOptionsAndDevice) {
    TRN_REQUIRE_OPENCL_DEVICE();
    std::string why;
    const auto dev = opencl::enumerate_devices(why).at(0);
    const std::string key = opencl::program_cache_key(dev, "aaaa", "-DTRN_WG_SIZE=64");
    EXPECT_NE(key, opencl::program_cache_key(dev, "aaab", "-DTRN_WG_SIZE=64"));
    EXPECT_NE(key, opencl::program_cache_key(dev, "aaaa", "-DTRN_WG_SIZE=128"));
    for (cl_device_info what : {CL_DEVICE_NAME, CL_DRIVER_VERSION, CL_DEVICE_VERSION})
        EXPECT_NE(key.find(opencl::device_string(dev.device, what)), std::string::npos) << key;
    EXPECT_NE(key.find(opencl::platform_string(dev.platform, CL_PLATFORM_VERSION)), std::string::npos) << key;
    opencl::ProgramCacheSettings s{true, "/x"};
    EXPECT_NE(opencl::program_cache_path(s, "ncc_score.cl", key),
              opencl::program_cache_path(s, "ncc_score.cl", opencl::program_cache_key(dev, "aaab", "-DTRN_WG_SIZE=64")));
}

TEST(OpenClProgramCache, OffSwitchWritesNothing) {
    TRN_REQUIRE_OPENCL_DEVICE();
    TempDir tmp;
    ScopedEnv xdg("XDG_CACHE_HOME", tmp.path().string());
    ScopedEnv off("TRN_OPENCL_CACHE", std::string("0"));
    auto b = default_registry().create("opencl:0", test::backend_options_from_environment());
    EXPECT_NE(b->info().details.find("built from source"), std::string::npos);
    EXPECT_FALSE(std::filesystem::exists(tmp.path() / "trnkit")) << "TRN_OPENCL_CACHE=0 must not touch the disk";
    EXPECT_FALSE(opencl::program_cache_settings(test::backend_options_from_environment().opencl).enabled);
}

}  // namespace
}  // namespace trn::test
