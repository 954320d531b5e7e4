// The Vulkan layer under the backend: validation messages turn into errors, clear errors for a
// missing driver or validation layer, and the pipeline cache persisted on disk.
#include <filesystem>
#include <fstream>

#include "vk_context.hpp"
#include "vulkan_test_support.hpp"

namespace trn::test {
namespace {

std::filesystem::path fresh_temp_dir(const std::string& name) {
    const auto dir = std::filesystem::temp_directory_path() / (name + "-" + std::to_string(::getpid()));
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

TEST(VulkanValidation, AMessageFailsTheCallWithItsText) {
    TRN_REQUIRE_VULKAN();
    vk::Context ctx(std::make_unique<vk::Instance>(true), 0);
    ctx.throw_on_validation_messages("nothing yet");  // a clean device reports nothing
    VkFenceCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO;
    info.flags = 0x100;  // not a VkFenceCreateFlagBits value: the layer must object
    VkFence fence = VK_NULL_HANDLE;
    ASSERT_EQ(ctx.api().vkCreateFence(ctx.device(), &info, nullptr, &fence), VK_SUCCESS);
    ctx.api().vkDestroyFence(ctx.device(), fence, nullptr);
    try {
        ctx.throw_on_validation_messages("the bad fence");
        FAIL() << "no validation message was recorded";
    } catch (const Error& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("the bad fence"), std::string::npos) << what;
        EXPECT_NE(what.find("VUID-VkFenceCreateInfo-flags"), std::string::npos) << what;
    }
    ctx.throw_on_validation_messages("after the messages were taken");
}

TEST(VulkanValidation, MissingLayerIsAClearError) {
    TRN_REQUIRE_VULKAN();
    const auto empty = fresh_temp_dir("trn-no-layers");
    ScopedEnv layers("VK_LAYER_PATH", empty.c_str());
    try {
        vulkan_with([](auto& v) { v.validation = true; });
        FAIL() << "created a validated backend without the layer";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("vulkan-validationlayers"), std::string::npos) << e.what();
    }
    std::filesystem::remove_all(empty);
}

TEST(VulkanDriver, MissingIcdIsReportedNotFatal) {
    ScopedEnv icd("VK_ICD_FILENAMES", "/nonexistent/trnkit_icd.json");
    ScopedEnv drivers("VK_DRIVER_FILES", "/nonexistent/trnkit_icd.json");
    for (const FamilyStatus& f : default_registry().status()) {
        if (f.family != "vulkan") continue;
        EXPECT_TRUE(f.devices.empty());
        EXPECT_FALSE(f.why_none.empty());
        std::cout << "vulkan without a driver: " << f.why_none << "\n";
    }
    EXPECT_THROW(default_registry().create("vulkan", env_options()), BackendUnavailable);
}

TEST(VulkanPipelineCache, WrittenToDiskAndReused) {
    TRN_REQUIRE_VULKAN();
    const auto dir = fresh_temp_dir("trn-vk-cache");
    const auto with_cache = [&](auto& v) { v.pipeline_cache_dir = dir.string(); };
    const PaddedGray map = textured_image(120, 90, 61);
    const PaddedGray templ = textured_image(21, 17, 62);
    const std::vector<Pose> poses = random_poses(20, map.width, map.height, 63);
    std::vector<ParticleScore> first(poses.size()), second(poses.size());
    {
        auto dut = vulkan_with(with_cache);
        dut->score(dut->upload_map(map.view()), templ.view(), poses, {}, first, nullptr);
    }
    std::vector<std::filesystem::path> files;
    for (const auto& e : std::filesystem::directory_iterator(dir)) files.push_back(e.path());
    ASSERT_EQ(files.size(), 1u) << "expected one cache file in " << dir;
    EXPECT_EQ(files[0].extension(), ".bin");
    // A valid VkPipelineCache blob starts with its header (lavapipe stores nothing after it).
    std::ifstream in(files[0], std::ios::binary);
    std::uint32_t header[4] = {};
    ASSERT_TRUE(in.read(reinterpret_cast<char*>(header), sizeof header));
    EXPECT_GE(header[0], 32u) << "header length";
    EXPECT_EQ(header[1], std::uint32_t(VK_PIPELINE_CACHE_HEADER_VERSION_ONE));
    {
        auto dut = vulkan_with(with_cache);  // starts from the saved cache
        dut->score(dut->upload_map(map.view()), templ.view(), poses, {}, second, nullptr);
    }
    for (std::size_t i = 0; i < poses.size(); ++i) EXPECT_EQ(first[i].ncc, second[i].ncc) << i;
    std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace trn::test
