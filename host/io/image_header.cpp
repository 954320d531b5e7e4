// Header-only image size readers; see image_header.hpp. Each reads a few bytes at known offsets
// (JPEG: walks the segment list up to the first frame header) and never trusts a length blindly.
#include "trn/io/image_header.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstring>
#include <fstream>
#include <string_view>

#include "trn/error.hpp"
#include "trn/io/input_file.hpp"
#include "trn/limits.hpp"

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

// PNG: signature, then the IHDR chunk: length, "IHDR", width, height (big-endian), bit depth,
// colour type, compression, filter, interlace; then the chunks up to the first IDAT, for a tRNS
// (transparency) chunk.
std::optional<ImageSize> png_size(std::ifstream& f, std::uint64_t file_bytes) {
    unsigned char h[29];
    if (!read_at(f, 0, h, sizeof h) || std::string(reinterpret_cast<char*>(h + 12), 4) != "IHDR") return std::nullopt;
    ImageSize size{be32(h + 16), be32(h + 20), 2, 0, "PNG"};
    const int colour = h[25];
    size.bits_per_sample = h[24];
    size.channels = colour == 0 ? 1 : colour == 4 ? 2 : colour == 6 ? 4 : 3;  // grey, grey+alpha, RGBA; RGB and palette: 3
    size.alpha_possible = colour == 4 || colour == 6;
    size.interlaced = h[28] == 1;
    std::uint64_t at = 33;
    for (int chunks = 0; chunks < 10000 && at + 8 <= file_bytes; ++chunks) {
        unsigned char c[8];
        if (!read_at(f, at, c, 8)) break;
        const std::uint32_t length = be32(c);
        const std::string type(reinterpret_cast<char*>(c + 4), 4);
        if (type == "IDAT" || type == "IEND") break;
        if (type == "tRNS") {
            size.alpha_possible = true;
            if (colour == 3) size.channels = 4;  // a palette with transparency decodes as BGRA
        }
        at += 12 + std::uint64_t(length);
    }
    return size;
}

// A JPEG frame header (SOFn at `at`): length, precision, height, width, components (id, sampling
// HV, table). A progressive frame (SOF2, 6, 10, 14) is decoded by libjpeg into a buffer of every
// DCT coefficient of the image first, 2 bytes per coefficient: 2 B per pixel of each component at
// its sampling (4:2:0 colour: 3 B/px), on top of the 2 B/px of the grey output and its copy.
std::optional<ImageSize> jpeg_frame(std::ifstream& f, std::uint64_t at, unsigned char marker, std::uint32_t length) {
    unsigned char h[8 + 3 * 255];
    if (length < 8 || !read_at(f, at + 2, h, 8)) return std::nullopt;
    const std::uint32_t components = h[7];
    if (components == 0 || length < 8 + 3 * components || !read_at(f, at + 2, h, 8 + 3 * components)) return std::nullopt;
    ImageSize size{be16(h + 5), be16(h + 3), 2, 0, "JPEG"};
    size.channels = components == 1 ? 1 : 3, size.bits_per_sample = h[2] > 8 ? 16 : 8, size.alpha_possible = false;
    if ((marker & 0x03) == 0x02) {  // progressive
        unsigned h_max = 1, v_max = 1;
        for (std::uint32_t c = 0; c < components; ++c) h_max = std::max(h_max, unsigned(h[9 + 3 * c] >> 4)), v_max = std::max(v_max, unsigned(h[9 + 3 * c] & 15));
        double share = 0;  // of the full-size pixel count, summed over the components
        for (std::uint32_t c = 0; c < components; ++c) share += double(h[9 + 3 * c] >> 4) * double(h[9 + 3 * c] & 15) / (double(h_max) * v_max);
        size.decode_bytes_per_pixel += 2 * share;
        size.format = "progressive JPEG";
    }
    return size;
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
        if (sof) return jpeg_frame(f, at, m[1], length);
        at += 2 + length;
    }
    return std::nullopt;
}

// BMP: file header (14 bytes), then the info header: its size, then width and height (int32; a
// negative height is a top-down image), or int16 ones in the old 12-byte core header.
std::optional<ImageSize> bmp_size(std::ifstream& f) {
    unsigned char h[26];
    if (!read_at(f, 0, h, sizeof h)) return std::nullopt;
    if (le32(h + 14) == 12) return ImageSize{le16(h + 18), le16(h + 20), 2, 0, "BMP"};
    const auto w = static_cast<std::int32_t>(le32(h + 18)), ht = static_cast<std::int32_t>(le32(h + 22));
    return ImageSize{w < 0 ? -std::int64_t(w) : w, ht < 0 ? -std::int64_t(ht) : ht, 2, 0, "BMP"};
}

// PNM (P1..P6): "Pn", then width and height as decimal text, with whitespace and # comments
// between. PFM ("PF" colour, "Pf" grey) has the same layout; OpenCV decodes it into a float buffer
// (4 B per channel) before converting.
std::optional<ImageSize> pnm_size(std::ifstream& f, char kind) {
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
    if (kind == 'F') return ImageSize{values[0], values[1], 18, 0, "PFM"};  // float RGB, 8-bit RGB, grey, copy
    if (kind == 'f') return ImageSize{values[0], values[1], 8, 0, "PFM"};
    return ImageSize{values[0], values[1], 2, 0, "PNM"};
}

// TIFF: byte order, 42, offset of the first image directory; its entries (tag, type, count,
// value) hold ImageWidth (256) and ImageLength (257) as SHORT or LONG. OpenCV reads a TIFF one
// strip or tile at a time into a buffer of up to 1 GB (its MAX_TILE_SIZE): BitsPerSample (258),
// SamplesPerPixel (277), RowsPerStrip (278), TileWidth/TileLength (322/323) size it.
std::optional<ImageSize> tiff_size(std::ifstream& f, bool little) {
    auto u16 = [&](const unsigned char* p) { return little ? le16(p) : be16(p); };
    auto u32 = [&](const unsigned char* p) { return little ? le32(p) : be32(p); };
    unsigned char h[8];
    if (!read_at(f, 0, h, sizeof h)) return std::nullopt;
    const std::uint64_t ifd = u32(h + 4);
    unsigned char n[2];
    if (!read_at(f, ifd, n, 2)) return std::nullopt;
    std::int64_t width = -1, height = -1, bits = 8, samples = 1, rows_per_strip = -1, tile_w = -1, tile_h = -1;
    for (std::uint32_t i = 0, count = u16(n); i < count; ++i) {
        unsigned char e[12];
        if (!read_at(f, ifd + 2 + 12 * std::uint64_t(i), e, sizeof e)) return std::nullopt;
        const std::uint32_t tag = u16(e), type = u16(e + 2), values = u32(e + 4);
        const std::int64_t value = type == 3 ? u16(e + 8) : type == 4 ? u32(e + 8) : -1;  // SHORT / LONG
        if (tag == 256) width = value;
        else if (tag == 257) height = value;
        else if (tag == 258 && type == 3 && values <= 2) bits = value;  // more samples: an offset; 8 assumed below
        else if (tag == 258 && type == 3) {
            unsigned char b[2];
            if (read_at(f, u32(e + 8), b, 2)) bits = u16(b);
        } else if (tag == 277) samples = value;
        else if (tag == 278) rows_per_strip = value;
        else if (tag == 322) tile_w = value;
        else if (tag == 323) tile_h = value;
    }
    if (width < 0 || height < 0) return std::nullopt;
    ImageSize size{width, height, 2, 0, "TIFF"};
    size.channels = static_cast<int>(std::clamp<std::int64_t>(samples, 1, 4)), size.bits_per_sample = bits > 8 ? 16 : 8;
    size.alpha_possible = samples == 2 || samples >= 4;
    const std::int64_t bw = tile_w > 0 ? std::min(tile_w, width) : width;
    const std::int64_t bh = tile_h > 0 ? std::min(tile_h, height) : rows_per_strip > 0 ? std::min(rows_per_strip, height) : height;
    const double buffer = double(bw) * double(bh) * double(std::max<std::int64_t>(samples, 1)) * double(std::max<std::int64_t>(bits, 8)) / 8;
    size.decode_extra_bytes = static_cast<std::uint64_t>(std::min(buffer, double(std::uint64_t(1) << 30)));
    return size;
}

// Reads one text line (at most 512 bytes; a longer one is not a header this reader understands).
bool header_line(std::ifstream& f, std::string& line) {
    line.clear();
    for (int c; (c = f.get()) != EOF;) {
        if (c == '\n') return true;
        if (line.size() >= 512) return false;
        line += char(c);
    }
    return !line.empty();
}

bool parse_int(std::string_view s, std::int64_t& out) {
    while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
    while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
    if (s.empty() || s.size() > 12) return false;
    out = 0;
    for (char c : s) {
        if (c < '0' || c > '9') return false;
        out = out * 10 + (c - '0');
    }
    return true;
}

// Radiance HDR: "#?RADIANCE" (or "#?RGBE"), header lines up to an empty one, then the resolution
// "-Y 480 +X 640" (any signs, X and Y in either order). OpenCV decodes into float RGB (12 B/px),
// then converts: ~16 B/px in all (a real 8192x8192 file: 1.04 GB peak).
std::optional<ImageSize> hdr_size(std::ifstream& f) {
    f.clear();
    f.seekg(0);
    std::string line;
    for (int lines = 0;; ++lines) {
        if (lines > 256 || !header_line(f, line)) return std::nullopt;
        if (line.empty() || line == "\r") break;
    }
    if (!header_line(f, line)) return std::nullopt;
    char a[3] = {}, b[3] = {};
    char na[16] = {}, nb[16] = {};
    if (std::sscanf(line.c_str(), "%2s %15s %2s %15s", a, na, b, nb) != 4) return std::nullopt;
    std::int64_t va = 0, vb = 0;
    if (!parse_int(na, va) || !parse_int(nb, vb)) return std::nullopt;
    const auto axis = [](const char* t) { return (t[0] == '+' || t[0] == '-') ? t[1] : 0; };
    if (axis(a) == 'Y' && axis(b) == 'X') return ImageSize{vb, va, 16, 0, "Radiance HDR"};
    if (axis(a) == 'X' && axis(b) == 'Y') return ImageSize{va, vb, 16, 0, "Radiance HDR"};
    return std::nullopt;
}

// PAM (P7): "WIDTH n", "HEIGHT n", "DEPTH n", ... lines up to "ENDHDR"; decoded a row at a time.
std::optional<ImageSize> pam_size(std::ifstream& f) {
    f.clear();
    f.seekg(3);
    std::string line;
    std::int64_t width = -1, height = -1;
    for (int lines = 0; lines < 256 && header_line(f, line); ++lines) {
        if (line.rfind("ENDHDR", 0) == 0) break;
        std::int64_t v = 0;
        if (line.rfind("WIDTH", 0) == 0 && parse_int(std::string_view(line).substr(5), v)) width = v;
        if (line.rfind("HEIGHT", 0) == 0 && parse_int(std::string_view(line).substr(6), v)) height = v;
    }
    if (width < 0 || height < 0) return std::nullopt;
    return ImageSize{width, height, 2, 0, "PAM"};
}

// WebP: RIFF, size, "WEBP", then a "VP8 " (lossy: 14-bit sides after the start code 9D 01 2A),
// "VP8L" (lossless: 0x2F, then 14 bits each of width-1 and height-1) or "VP8X" (extended: 24-bit
// canvas width-1 and height-1) chunk. OpenCV reads the whole file into memory and decodes to
// BGR(A), then converts: 4 B/px + the file.
std::optional<ImageSize> webp_size(std::ifstream& f, std::uint64_t file_bytes) {
    unsigned char h[30];
    if (!read_at(f, 0, h, sizeof h) || std::memcmp(h + 8, "WEBP", 4) != 0) return std::nullopt;
    std::int64_t w = -1, ht = -1;
    if (std::memcmp(h + 12, "VP8 ", 4) == 0 && h[23] == 0x9D && h[24] == 0x01 && h[25] == 0x2A) {
        w = le16(h + 26) & 0x3FFF, ht = le16(h + 28) & 0x3FFF;
    } else if (std::memcmp(h + 12, "VP8L", 4) == 0 && h[20] == 0x2F) {
        const std::uint32_t bits = le32(h + 21);
        w = (bits & 0x3FFF) + 1, ht = ((bits >> 14) & 0x3FFF) + 1;
    } else if (std::memcmp(h + 12, "VP8X", 4) == 0) {
        w = (std::int64_t(h[24]) | std::int64_t(h[25]) << 8 | std::int64_t(h[26]) << 16) + 1;
        ht = (std::int64_t(h[27]) | std::int64_t(h[28]) << 8 | std::int64_t(h[29]) << 16) + 1;
    } else {
        return std::nullopt;
    }
    return ImageSize{w, ht, 6, file_bytes, "WebP"};
}

// JPEG 2000: a raw codestream (FF 4F FF 51: SIZ with Xsiz, Ysiz, XOsiz, YOsiz, ..., Csiz) or a JP2
// file, whose header box jp2h holds ihdr (height, width, components). OpenJPEG decodes every
// component into int32 before OpenCV converts: 4 B per component + 2.
std::optional<ImageSize> j2k_codestream_size(std::ifstream& f, std::uint64_t at) {
    unsigned char s[42];
    if (!read_at(f, at, s, sizeof s) || s[0] != 0xFF || s[1] != 0x4F || s[2] != 0xFF || s[3] != 0x51) return std::nullopt;
    const std::int64_t xs = be32(s + 8), ys = be32(s + 12), xo = be32(s + 16), yo = be32(s + 20);
    const std::int64_t components = be16(s + 40);
    if (xs < xo || ys < yo) return std::nullopt;
    return ImageSize{xs - xo, ys - yo, 4.0 * double(std::max<std::int64_t>(components, 1)) + 2, 0, "JPEG 2000"};
}

std::optional<ImageSize> jp2_size(std::ifstream& f) {
    std::uint64_t at = 0;
    for (int boxes = 0; boxes < 1000; ++boxes) {
        unsigned char b[8];
        if (!read_at(f, at, b, sizeof b)) return std::nullopt;
        std::uint64_t length = be32(b);
        std::uint64_t header = 8;
        if (length == 1) {
            unsigned char l[8];
            if (!read_at(f, at + 8, l, sizeof l)) return std::nullopt;
            length = std::uint64_t(be32(l)) << 32 | be32(l + 4), header = 16;
        }
        if (std::memcmp(b + 4, "jp2h", 4) == 0) {
            unsigned char i[22];
            if (!read_at(f, at + header, i, sizeof i) || std::memcmp(i + 4, "ihdr", 4) != 0) return std::nullopt;
            const std::int64_t components = be16(i + 16);
            return ImageSize{be32(i + 12), be32(i + 8), 4.0 * double(std::max<std::int64_t>(components, 1)) + 2, 0, "JPEG 2000"};
        }
        if (std::memcmp(b + 4, "jp2c", 4) == 0) return j2k_codestream_size(f, at + header);
        if (length < header) return std::nullopt;  // 0: "to the end of the file", no header box seen
        at += length;
    }
    return std::nullopt;
}

// Sun raster: magic 59 A6 6A 95, width, height, depth (big-endian 32-bit); decoded a row at a time.
std::optional<ImageSize> sun_size(std::ifstream& f) {
    unsigned char h[16];
    if (!read_at(f, 0, h, sizeof h)) return std::nullopt;
    return ImageSize{be32(h + 4), be32(h + 8), 2, 0, "Sun raster"};
}

std::optional<ImageSize> header_size(const std::string& path, std::uint64_t file_bytes) {
    std::ifstream f(path, std::ios::binary);
    if (!f) throw Error(io::quote_input(path, 512) + ": cannot open");
    std::array<unsigned char, 12> magic{};
    if (!read_at(f, 0, magic.data(), magic.size())) return std::nullopt;
    static constexpr unsigned char kPng[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
    static constexpr unsigned char kJp2[12] = {0, 0, 0, 0x0C, 'j', 'P', ' ', ' ', 0x0D, 0x0A, 0x87, 0x0A};
    if (std::equal(magic.begin(), magic.begin() + 8, kPng)) return png_size(f, file_bytes);
    if (magic[0] == 0xFF && magic[1] == 0xD8) return jpeg_size(f);
    if (magic[0] == 'B' && magic[1] == 'M') return bmp_size(f);
    if (magic[0] == 'P' && ((magic[1] >= '1' && magic[1] <= '6') || magic[1] == 'F' || magic[1] == 'f')) return pnm_size(f, char(magic[1]));
    if (magic[0] == 'P' && magic[1] == '7' && magic[2] == '\n') return pam_size(f);
    if (magic[0] == 'I' && magic[1] == 'I' && magic[2] == 42 && magic[3] == 0) return tiff_size(f, true);
    if (magic[0] == 'M' && magic[1] == 'M' && magic[2] == 0 && magic[3] == 42) return tiff_size(f, false);
    if (std::memcmp(magic.data(), "#?", 2) == 0) return hdr_size(f);
    if (std::memcmp(magic.data(), "RIFF", 4) == 0) return webp_size(f, file_bytes);
    if (std::equal(magic.begin(), magic.end(), kJp2)) return jp2_size(f);
    if (magic[0] == 0xFF && magic[1] == 0x4F && magic[2] == 0xFF && magic[3] == 0x51) return j2k_codestream_size(f, 0);
    if (magic[0] == 0x59 && magic[1] == 0xA6 && magic[2] == 0x6A && magic[3] == 0x95) return sun_size(f);
    return std::nullopt;
}

}  // namespace

std::optional<ImageSize> read_image_size(const std::string& path) {
    const io::FileIdentity file = io::check_input_file(path, io::kMaxImageFileBytes, "an image file");
    return header_size(path, file.size);
}

double validity_decode_bytes(const ImageSize& s) {
    const double px = double(s.width) * double(s.height);
    if (std::string_view(s.format) == "PNG") return px * (s.interlaced ? 5 : 1) + 4 * double(s.width);  // png_validity.cpp
    const double sample_bytes = s.bits_per_sample > 8 ? 2 : 1;
    return px * (s.channels * sample_bytes + (s.bits_per_sample > 8 ? s.channels : 0) + 1);
}

ImageSize check_image_file(const std::string& path) {
    const auto size = read_image_size(path);
    const std::string name = io::quote_input(path, 512);
    if (!size)
        throw Error(name + ": not a readable image (a damaged header, or not a format trnkit reads: PNG, JPEG, TIFF, BMP, PNM/PAM/PFM, "
                           "Radiance HDR, WebP, JPEG 2000, Sun raster)");
    const std::string what = name + ": image";
    const double bytes = double(size->width) * double(size->height) * size->decode_bytes_per_pixel + double(size->decode_extra_bytes);
    if (size->width > limits::kMaxImageSide || size->height > limits::kMaxImageSide ||
        double(size->width) * double(size->height) > double(limits::kMaxMapPixels))  // the side and pixel limits' own messages
        limits::check_image(what, size->width, size->height, limits::kMaxMapPixels, size->decode_bytes_per_pixel);
    if (bytes > kMaxImageDecodeBytes)
        throw Error(what + " " + std::to_string(size->width) + "x" + std::to_string(size->height) + " (" + size->format + ") needs ~" +
                    limits::format_bytes(bytes) + " to decode (limit " + limits::format_bytes(kMaxImageDecodeBytes) + " per image)");
    limits::check_image(what, size->width, size->height, limits::kMaxMapPixels, size->decode_bytes_per_pixel);
    limits::check_memory(what, bytes);
    return *size;
}

}  // namespace trn
