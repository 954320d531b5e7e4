// The fat binaries embedded in this build hold the cubins and the PTX CMake asked nvcc for
// (cuda_build.hpp), read with trnkit's own reader (fatbin_contents.hpp), and the code a device of
// each architecture would run follows from them.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <vector>

#include "cuda_build.hpp"
#include "embedded_fatbins.hpp"
#include "fatbin_contents.hpp"
#include "trn/error.hpp"

namespace trn::cuda {
namespace {

std::vector<FatbinEntry> expected() {
    std::vector<FatbinEntry> e;
    for (int arch : build::kCubinArchs) e.push_back({FatbinEntry::Kind::Cubin, arch});
    e.push_back({FatbinEntry::Kind::Ptx, build::kPtxArch});
    return e;
}

bool same(const std::vector<FatbinEntry>& a, const std::vector<FatbinEntry>& b) {
    auto key = [](const FatbinEntry& e) { return std::pair(int(e.kind), e.arch); };
    std::vector<std::pair<int, int>> ka, kb;
    for (const auto& e : a) ka.push_back(key(e));
    for (const auto& e : b) kb.push_back(key(e));
    std::sort(ka.begin(), ka.end());
    std::sort(kb.begin(), kb.end());
    return ka == kb;
}

TEST(CudaFatbin, EmbeddedImagesHoldTheArchitecturesAskedFor) {
    for (const EmbeddedFatbin& f : {embedded_ncc_score(), embedded_sobel3x3()}) {
        SCOPED_TRACE(f.file);
        EXPECT_EQ(reinterpret_cast<std::uintptr_t>(f.bytes.data()) % 64, 0u);
        const std::vector<FatbinEntry> entries = fatbin_entries(f.bytes);
        EXPECT_TRUE(same(entries, expected())) << describe(entries);
    }
    std::cout << "embedded (CUDA " << build::kToolkitVersion << "): " << describe(fatbin_entries(embedded_ncc_score().bytes))
              << (*build::kArchsLeftOut ? std::string("; left out (nvcc cannot target): ") + build::kArchsLeftOut : std::string())
              << "\n";
}

TEST(CudaFatbin, CodeChoicePerDevice) {
    const std::vector<FatbinEntry> e = {{FatbinEntry::Kind::Cubin, 87}, {FatbinEntry::Kind::Cubin, 90}, {FatbinEntry::Kind::Ptx, 75}};
    EXPECT_EQ(code_for_device(e, 90).text, "sm_90 cubin");  // H100 / H200
    EXPECT_EQ(code_for_device(e, 87).text, "sm_87 cubin");  // Orin
    EXPECT_EQ(code_for_device(e, 89).text, "sm_87 cubin");  // same major version, newer minor
    EXPECT_EQ(code_for_device(e, 86).text, "PTX compute_75, compiled by the driver (JIT)");  // older minor: no cubin
    EXPECT_EQ(code_for_device(e, 120).text, "PTX compute_75, compiled by the driver (JIT)");
    const CodeChoice xavier = code_for_device(e, 72);
    EXPECT_FALSE(xavier.runs);
    EXPECT_NE(xavier.text.find("no code for sm_72 in this build (sm_87, sm_90 + PTX compute_75)"), std::string::npos) << xavier.text;
    EXPECT_NE(xavier.text.find("CUDA 12"), std::string::npos);
    EXPECT_TRUE(code_for_device(e, 75).runs);
}

TEST(CudaFatbin, MalformedImagesAreRefused) {
    const unsigned char junk[32] = {1, 2, 3};
    EXPECT_THROW(fatbin_entries(junk), Error);
    std::vector<unsigned char> image(embedded_ncc_score().bytes.begin(), embedded_ncc_score().bytes.end());
    image.resize(100);  // cut inside the first entry
    try {
        fatbin_entries(image);
        ADD_FAILURE() << "a truncated fat binary was read";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("fat binary:"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace trn::cuda
