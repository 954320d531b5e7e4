// Header-only image size readers; see image_header.hpp. Each reads a few bytes at known offsets
// (JPEG: walks the segment list up to the first frame header) and never trusts a length blindly.
#include "trn/io/image_header.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <fstream>

#include "trn/error.hpp"

namespace trn {
namespace {

std::uint32_t be16(const unsigned char* p) { return std::uint32_t(p[0]) << 8 | p[1]; }
std::uint32_t be32(const unsigned char* p) { return be16(p) << 16 | be16(p + 2); }
std::uint32_t le16(const unsigned char* p) { return std::uint32_t(p[1]) << 8 | p[0]; }
std::uint32_t le32(const unsigned char* p) { return le16(p + 2) << 16 | le16(p); }

bool read_at(std::ifstream& f, std::uint64_t offset, unsigned char* out, std::size_t n) {
    f.clear();
    f.seekg(static_cast<std::streamoff>(offset));
    return f.read(reinterpret_cast<char*>(out), static_cast<std::streamsize>(n)) && f.gcount() == static_cast<std::streamsize>(n);
}

// PNG: signature, then the IHDR chunk: length, "IHDR", width, height (big-endian).
std::optional<ImageSize> png_size(std::ifstream& f) {
    unsigned char h[24];
    if (!read_at(f, 0, h, sizeof h) || std::string(reinterpret_cast<char*>(h + 12), 4) != "IHDR") return std::nullopt;
    return ImageSize{be32(h + 16), be32(h + 20)};
}

// JPEG: segments FF xx [length] until a start-of-frame (SOF0..SOF15 but DHT C4, JPG C8, DAC CC):
// length, precision, height, width.
std::optional<ImageSize> jpeg_size(std::ifstream& f) {
    std::uint64_t at = 2;
    for (int segments = 0; segments < 10000; ++segments) {
        unsigned char m[2];
        if (!read_at(f, at, m, 2) || m[0] != 0xFF) return std::nullopt;
        if (m[1] == 0xFF) {  // fill byte
            ++at;
            continue;
        }
        if (m[1] == 0x01 || (m[1] >= 0xD0 && m[1] <= 0xD7)) {  // no length
            at += 2;
            continue;
        }
        if (m[1] == 0xD9 || m[1] == 0xDA) return std::nullopt;  // end of image / scan before any frame
        unsigned char seg[7];
        if (!read_at(f, at + 2, seg, sizeof seg)) return std::nullopt;
        const std::uint32_t length = be16(seg);
        if (length < 2) return std::nullopt;
        const bool sof = m[1] >= 0xC0 && m[1] <= 0xCF && m[1] != 0xC4 && m[1] != 0xC8 && m[1] != 0xCC;
        if (sof) return length >= 7 ? std::optional<ImageSize>(ImageSize{be16(seg + 5), be16(seg + 3)}) : std::nullopt;
        at += 2 + length;
    }
    return std::nullopt;
}

// BMP: file header (14 bytes), then the info header: its size, then width and height (int32; a
// negative height is a top-down image), or int16 ones in the old 12-byte core header.
std::optional<ImageSize> bmp_size(std::ifstream& f) {
    unsigned char h[26];
    if (!read_at(f, 0, h, sizeof h)) return std::nullopt;
    if (le32(h + 14) == 12) return ImageSize{le16(h + 18), le16(h + 20)};
    const auto w = static_cast<std::int32_t>(le32(h + 18)), ht = static_cast<std::int32_t>(le32(h + 22));
    return ImageSize{w < 0 ? -std::int64_t(w) : w, ht < 0 ? -std::int64_t(ht) : ht};
}

// PNM (P1..P6): "Pn", then width and height as decimal text, with whitespace and # comments between.
std::optional<ImageSize> pnm_size(std::ifstream& f) {
    f.clear();
    f.seekg(2);
    std::int64_t values[2];
    for (std::int64_t& v : values) {
        int c = f.get();
        while (c != EOF && (std::isspace(c) || c == '#')) {
            if (c == '#')
                while (c != EOF && c != '\n') c = f.get();
            c = f.get();
        }
        if (c == EOF || !std::isdigit(c)) return std::nullopt;
        v = 0;
        for (; c != EOF && std::isdigit(c); c = f.get()) {
            v = v * 10 + (c - '0');
            if (v > (std::int64_t(1) << 40)) return std::nullopt;
        }
    }
    return ImageSize{values[0], values[1]};
}

// TIFF: byte order, 42, offset of the first image directory; its entries (tag, type, count,
// value) hold ImageWidth (256) and ImageLength (257) as SHORT or LONG.
std::optional<ImageSize> tiff_size(std::ifstream& f, bool little) {
    auto u16 = [&](const unsigned char* p) { return little ? le16(p) : be16(p); };
    auto u32 = [&](const unsigned char* p) { return little ? le32(p) : be32(p); };
    unsigned char h[8];
    if (!read_at(f, 0, h, sizeof h)) return std::nullopt;
    const std::uint64_t ifd = u32(h + 4);
    unsigned char n[2];
    if (!read_at(f, ifd, n, 2)) return std::nullopt;
    std::int64_t width = -1, height = -1;
    for (std::uint32_t i = 0, count = u16(n); i < count; ++i) {
        unsigned char e[12];
        if (!read_at(f, ifd + 2 + 12 * std::uint64_t(i), e, sizeof e)) return std::nullopt;
        const std::uint32_t tag = u16(e), type = u16(e + 2);
        if (tag != 256 && tag != 257) continue;
        const std::int64_t value = type == 3 ? u16(e + 8) : type == 4 ? u32(e + 8) : -1;  // SHORT / LONG
        (tag == 256 ? width : height) = value;
    }
    if (width < 0 || height < 0) return std::nullopt;
    return ImageSize{width, height};
}

}  // namespace

std::optional<ImageSize> read_image_size(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    if (!f) throw Error(path + ": cannot open");
    std::array<unsigned char, 8> magic{};
    if (!read_at(f, 0, magic.data(), magic.size())) return std::nullopt;
    static constexpr unsigned char kPng[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
    if (std::equal(magic.begin(), magic.end(), kPng)) return png_size(f);
    if (magic[0] == 0xFF && magic[1] == 0xD8) return jpeg_size(f);
    if (magic[0] == 'B' && magic[1] == 'M') return bmp_size(f);
    if (magic[0] == 'P' && magic[1] >= '1' && magic[1] <= '6') return pnm_size(f);
    if (magic[0] == 'I' && magic[1] == 'I' && magic[2] == 42 && magic[3] == 0) return tiff_size(f, true);
    if (magic[0] == 'M' && magic[1] == 'M' && magic[2] == 0 && magic[3] == 42) return tiff_size(f, false);
    return std::nullopt;
}

}  // namespace trn
