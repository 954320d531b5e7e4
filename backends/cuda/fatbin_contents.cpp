// Fat binary listing and code choice; see fatbin_contents.hpp.
#include "fatbin_contents.hpp"

#include <cstring>

#include "trn/error.hpp"

namespace trn::cuda {
namespace {

constexpr std::uint32_t kMagic = 0xBA55ED50u;
constexpr std::size_t kHeaderBytes = 16;       // magic, version, header size, size of the entries
constexpr std::size_t kEntryHeaderBytes = 32;  // the part of an entry header we read
constexpr std::uint16_t kKindPtx = 1, kKindCubin = 2;

template <typename T>
T read_at(std::span<const unsigned char> bytes, std::size_t at) {
    T v;
    std::memcpy(&v, bytes.data() + at, sizeof v);  // little-endian, as nvcc writes it on every host we build on
    return v;
}

}  // namespace

std::vector<FatbinEntry> fatbin_entries(std::span<const unsigned char> bytes) {
    if (bytes.size() < kHeaderBytes || read_at<std::uint32_t>(bytes, 0) != kMagic)
        throw Error("fat binary: no fatbin header (magic 0xBA55ED50) in " + std::to_string(bytes.size()) + " bytes");
    const std::size_t header = read_at<std::uint16_t>(bytes, 6);
    const std::uint64_t size = read_at<std::uint64_t>(bytes, 8);
    if (header < kHeaderBytes || size > bytes.size() - header)
        throw Error("fat binary: header says " + std::to_string(size) + " bytes of entries after " + std::to_string(header) +
                    ", but the image has " + std::to_string(bytes.size()));
    std::vector<FatbinEntry> out;
    std::size_t at = header;
    const std::size_t end = header + std::size_t(size);
    while (at < end) {
        if (end - at < kEntryHeaderBytes) throw Error("fat binary: truncated entry header at byte " + std::to_string(at));
        const std::uint16_t kind = read_at<std::uint16_t>(bytes, at);
        const std::uint32_t entry_header = read_at<std::uint32_t>(bytes, at + 4);
        const std::uint64_t payload = read_at<std::uint64_t>(bytes, at + 8);
        const std::uint32_t arch = read_at<std::uint32_t>(bytes, at + 28);
        if (entry_header < kEntryHeaderBytes || entry_header > end - at || payload > end - at - entry_header)
            throw Error("fat binary: entry at byte " + std::to_string(at) + " runs past the end");
        if (kind == kKindPtx || kind == kKindCubin)
            out.push_back({kind == kKindPtx ? FatbinEntry::Kind::Ptx : FatbinEntry::Kind::Cubin, int(arch)});
        at += entry_header + std::size_t(payload);
    }
    return out;
}

CodeChoice code_for_device(const std::vector<FatbinEntry>& entries, int arch) {
    int cubin = 0, ptx = 0;
    for (const FatbinEntry& e : entries) {
        if (e.kind == FatbinEntry::Kind::Cubin && e.arch / 10 == arch / 10 && e.arch <= arch && e.arch > cubin) cubin = e.arch;
        if (e.kind == FatbinEntry::Kind::Ptx && e.arch <= arch && e.arch > ptx) ptx = e.arch;
    }
    if (cubin) return {true, "sm_" + std::to_string(cubin) + " cubin"};
    if (ptx) return {true, "PTX compute_" + std::to_string(ptx) + ", compiled by the driver (JIT)"};
    return {false, "no code for sm_" + std::to_string(arch) + " in this build (" + describe(entries) +
                       "); build trnkit with a CUDA toolkit that targets sm_" + std::to_string(arch) +
                       " (CUDA 12 for sm_50 to sm_72) and TRN_CUDA_ARCHS including " + std::to_string(arch)};
}

std::string describe(const std::vector<FatbinEntry>& entries) {
    std::string cubins, ptx;
    for (const FatbinEntry& e : entries) {
        std::string& list = e.kind == FatbinEntry::Kind::Cubin ? cubins : ptx;
        list += (list.empty() ? "" : ", ") + std::string(e.kind == FatbinEntry::Kind::Cubin ? "sm_" : "compute_") + std::to_string(e.arch);
    }
    if (cubins.empty() && ptx.empty()) return "no code";
    return cubins.empty() ? "PTX " + ptx : ptx.empty() ? cubins : cubins + " + PTX " + ptx;
}

}  // namespace trn::cuda
