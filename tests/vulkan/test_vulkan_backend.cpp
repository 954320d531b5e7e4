// Vulkan backend behaviour beyond the shared conformance cases: device listing, the staging and
// shared-memory paths (forced on lavapipe), timing, repeatability, map lifetime and options.
#include <opencv2/imgproc.hpp>

#include <cstring>
#include <functional>
#include <iostream>

#include "vulkan_test_support.hpp"

namespace trn::test {
namespace {

TEST(VulkanDevices, ListedWithNameDriverAndDetails) {
    TRN_REQUIRE_VULKAN();
    for (const FamilyStatus& f : default_registry().status()) {
        if (f.family != "vulkan") continue;
        for (std::size_t i = 0; i < f.devices.size(); ++i) {
            const DeviceInfo& d = f.devices[i];
            EXPECT_EQ(d.name, "vulkan:" + std::to_string(i));
            EXPECT_EQ(d.family, "vulkan");
            EXPECT_FALSE(d.device.empty());
            EXPECT_NE(d.driver.find("Vulkan 1."), std::string::npos) << d.driver;
            EXPECT_NE(d.details.find("subgroup size"), std::string::npos) << d.details;
        }
    }
    auto backend = default_registry().create("vulkan", env_options());
    std::cout << "vulkan device under test: " << backend->info().device << " (" << backend->info().driver << ")\n";
}

TEST(VulkanDevices, PickedByDefaultDeviceOptionAndName) {
    TRN_REQUIRE_VULKAN();
    BackendOptions o = env_options();
    const std::string first = default_registry().create("vulkan:0", o)->info().device;
    o.default_device["vulkan"] = "0";
    EXPECT_EQ(default_registry().create("vulkan", o)->info().device, first);
    EXPECT_EQ(default_registry().create("vulkan:" + first.substr(0, 4), o)->info().device, first);
    o.default_device["vulkan"] = "99";
    EXPECT_THROW(default_registry().create("vulkan", o), BackendUnavailable);
}

// Dense, random and explicit sampling against cpu-ref.
void scores_match_reference(Backend& dut) {
    auto ref = default_registry().create("cpu-ref");
    const PaddedGray map = textured_image(301, 207, 11, 3);
    const PaddedGray templ = textured_image(41, 29, 12, 2);
    const std::vector<Pose> poses = random_poses(150, map.width, map.height, 13);
    ScoreOptions options;
    options.min_valid_fraction = 0.5;
    expect_scores_match(dut, *ref, map.view(), templ.view(), poses, options);
    options.sampling = Sampling::random(0.3, 5);
    expect_scores_match(dut, *ref, map.view(), templ.view(), poses, options);
    options.sampling = Sampling::explicit_points({{0, 0}, {40, 28}, {20, 14}, {3, 27}, {39, 1}, {10, 10}});
    expect_scores_match(dut, *ref, map.view(), templ.view(), poses, options);
}

TEST(VulkanPaths, StagingBuffersMatchReference) {
    TRN_REQUIRE_VULKAN();
    auto dut = vulkan_with([](auto& v) { v.force_staging = true; });
    EXPECT_NE(dut->info().details.find("staging buffers"), std::string::npos);
    scores_match_reference(*dut);
}

TEST(VulkanPaths, SharedMemoryReductionMatchesReference) {
    TRN_REQUIRE_VULKAN();
    auto dut = vulkan_with([](auto& v) { v.subgroups = false; });
    EXPECT_NE(dut->info().details.find("shared-memory reduction"), std::string::npos);
    scores_match_reference(*dut);
}

TEST(VulkanPaths, OtherWorkGroupSizesMatchReference) {
    TRN_REQUIRE_VULKAN();
    for (std::uint32_t size : {1u, 8u, 128u}) {
        SCOPED_TRACE("work-group " + std::to_string(size));
        auto dut = vulkan_with([&](auto& v) { v.work_group = size; });
        EXPECT_NE(dut->info().details.find("work-group " + std::to_string(size) + " "), std::string::npos) << dut->info().details;
        scores_match_reference(*dut);
    }
}

TEST(VulkanPaths, ParticlesPerGroupMatchReference) {
    TRN_REQUIRE_VULKAN();
    // 150 poses: 3 and 16 leave a partly filled last group; 16 is more than a group of 8 invocations.
    for (std::uint32_t count : {1u, 3u, 16u}) {
        SCOPED_TRACE("particles per group " + std::to_string(count));
        auto dut = vulkan_with([&](auto& v) {
            v.work_group = 8;
            v.particles_per_group = count;
        });
        EXPECT_NE(dut->info().details.find(" for up to " + std::to_string(count) + " particle"), std::string::npos) << dut->info().details;
        scores_match_reference(*dut);
    }
}

// lavapipe ends an invocation's loops after 65535 iterations: with small groups (a 4-wide
// subgroup on aarch64, or a forced work_group) each item of a 640x480 template's group walked up
// to 307200 samples and came back with a fraction of its sums; now the group widens for such plans.
TEST(VulkanPaths, LargeTemplatesMatchReferenceInSmallGroups) {
    TRN_REQUIRE_VULKAN();
    auto ref = default_registry().create("cpu-ref");
    const PaddedGray map = textured_image(1200, 1000, 71), templ = textured_image(640, 480, 72);
    const std::vector<Pose> poses = {{600, 500, 0.3f, 0.8f}, {500, 400, 2.0f, 1.0f}, {700, 450, -1.2f, 1.1f}};
    for (std::uint32_t size : {1u, 4u})
        for (std::uint32_t count : {1u, 8u, 16u}) {
            SCOPED_TRACE("work-group " + std::to_string(size) + ", particles per group " + std::to_string(count));
            auto dut = vulkan_with([&](auto& v) {
                v.work_group = size;
                v.particles_per_group = count;
            });
            expect_scores_match(*dut, *ref, map.view(), templ.view(), poses, {});
        }
}

TEST(VulkanPaths, BatchesSmallerThanAGroupMatchReference) {
    TRN_REQUIRE_VULKAN();
    auto dut = vulkan_with([](auto& v) { v.particles_per_group = 8; });  // 1, 3 and 7 poses take the smaller groups
    auto ref = default_registry().create("cpu-ref");
    const PaddedGray map = textured_image(301, 207, 61);
    const PaddedGray templ = textured_image(41, 29, 62);
    for (int count : {1, 3, 7}) {
        SCOPED_TRACE(std::to_string(count) + " poses");
        std::vector<Pose> poses;
        for (int i = 0; i < count; ++i) poses.push_back({140.0f + 3 * i, 95.0f + 2 * i, 0.3f * i, 1.0f + 0.05f * i});
        expect_scores_match(*dut, *ref, map.view(), templ.view(), poses, {});
    }
}

TEST(VulkanPaths, BytesMapLayoutMatchesReference) {
    TRN_REQUIRE_VULKAN();
    auto dut = vulkan_with([](auto& v) { v.quad_maps = false; });
    scores_match_reference(*dut);
}

// A bad option is an error naming the field.
void expect_option_error(const std::function<void(BackendOptions::Vulkan&)>& change, const std::string& field) {
    try {
        vulkan_with(change);
        ADD_FAILURE() << field << " accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
    }
}

TEST(VulkanPaths, BadParticlesPerGroupIsAnError) {
    TRN_REQUIRE_VULKAN();
    expect_option_error([](auto& v) { v.particles_per_group = 17; }, "BackendOptions.vulkan.particles_per_group = 17");
}

TEST(VulkanPaths, BadWorkGroupSizeIsAnError) {
    TRN_REQUIRE_VULKAN();
    expect_option_error([](auto& v) { v.work_group = 48; }, "BackendOptions.vulkan.work_group = 48");
    expect_option_error([](auto& v) { v.work_group = 2048; }, "BackendOptions.vulkan.work_group = 2048");
}

TEST(VulkanSobel, StagingPathIsBitExactWithOpenCV) {
    TRN_REQUIRE_VULKAN();
    auto dut = vulkan_with([](auto& v) { v.force_staging = true; });
    for (auto [w, h] : {std::pair{1, 1}, {1, 9}, {9, 1}, {2, 2}, {77, 45}}) {
        SCOPED_TRACE(std::to_string(w) + "x" + std::to_string(h));
        const PaddedGray src = noise_image(w, h, 21, 2);
        std::vector<std::int16_t> gx(std::size_t(w + 3) * h), gy(std::size_t(w + 5) * h);
        dut->sobel(src.view(), {gx.data(), w, h, w + 3}, {gy.data(), w, h, w + 5});
        cv::Mat ex, ey;
        cv::Sobel(src.mat(), ex, CV_16S, 1, 0, 3, 1, 0, cv::BORDER_REFLECT_101);
        cv::Sobel(src.mat(), ey, CV_16S, 0, 1, 3, 1, 0, cv::BORDER_REFLECT_101);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                ASSERT_EQ(gx[y * (w + 3) + x], ex.at<std::int16_t>(y, x)) << x << "," << y;
                ASSERT_EQ(gy[y * (w + 5) + x], ey.at<std::int16_t>(y, x)) << x << "," << y;
            }
    }
}

TEST(VulkanTiming, PhaseTimesComeFromTheDevice) {
    TRN_REQUIRE_VULKAN();
    auto dut = default_registry().create("vulkan", env_options());
    const PaddedGray map = textured_image(400, 300, 31);
    const PaddedGray templ = textured_image(64, 48, 32);
    const std::vector<Pose> poses = random_poses(64, map.width, map.height, 33);
    std::vector<ParticleScore> out(poses.size());
    PhaseTimes t;
    dut->score(dut->upload_map(map.view()), templ.view(), poses, {}, out, &t);
    EXPECT_GT(t.execute_ms, 0.0);
    EXPECT_GE(t.upload_ms, 0.0);
    EXPECT_GE(t.download_ms, 0.0);
    std::vector<std::int16_t> gx(std::size_t(map.width) * map.height), gy(std::size_t(map.width) * map.height);
    dut->sobel(map.view(), {gx.data(), map.width, map.height, map.width}, {gy.data(), map.width, map.height, map.width}, &t);
    EXPECT_GT(t.execute_ms, 0.0);
}

TEST(VulkanScore, RepeatedCallsAreBitIdenticalAcrossGrowingBatches) {
    TRN_REQUIRE_VULKAN();
    auto dut = default_registry().create("vulkan", env_options());
    const PaddedGray map = textured_image(250, 250, 41);
    const PaddedGray templ = textured_image(33, 33, 42);
    const MapHandle handle = dut->upload_map(map.view());
    const std::vector<Pose> poses = random_poses(300, map.width, map.height, 43);
    std::vector<ParticleScore> first(poses.size()), small(10), again(poses.size());
    dut->score(handle, templ.view(), poses, {}, first, nullptr);
    dut->score(handle, templ.view(), std::span(poses).first(10), {}, small, nullptr);  // smaller batch in between
    dut->score(handle, templ.view(), poses, {}, again, nullptr);
    for (std::size_t i = 0; i < poses.size(); ++i) {
        EXPECT_EQ(std::memcmp(&first[i], &again[i], sizeof(ParticleScore)), 0) << i;
        if (i < small.size()) {
            EXPECT_EQ(std::memcmp(&first[i], &small[i], sizeof(ParticleScore)), 0) << i;
        }
    }
}

TEST(VulkanScore, MapOutlivesItsBackend) {
    TRN_REQUIRE_VULKAN();
    MapHandle handle;
    {
        auto dut = default_registry().create("vulkan", env_options());
        const PaddedGray map = textured_image(64, 64, 51);
        handle = dut->upload_map(map.view());
    }
    EXPECT_EQ(handle->width(), 64);
    handle.reset();  // releases device memory of a device whose backend object is gone
}

}  // namespace
}  // namespace trn::test
