#include "trn/energy/label_check.hpp"

#include <cstdio>

#include "trn/error.hpp"

namespace trn::energy {
namespace {

// `text` with every byte outside printable ASCII as \xHH, for an error message.
std::string escaped(std::string_view text) {
    std::string out;
    for (const unsigned char c : text.substr(0, 80)) {
        if (c >= 0x20 && c < 0x7f) {
            out += static_cast<char>(c);
        } else {
            char hex[8];
            std::snprintf(hex, sizeof hex, "\\x%02x", c);
            out += hex;
        }
    }
    return text.size() > 80 ? out + "..." : out;
}

}  // namespace

std::optional<std::size_t> first_invalid_utf8(std::string_view text) {
    std::size_t i = 0;
    while (i < text.size()) {
        const auto b = static_cast<unsigned char>(text[i]);
        std::size_t len = 0;
        unsigned cp = 0, min = 0;
        if (b < 0x80) len = 1, cp = b;
        else if ((b & 0xE0) == 0xC0) len = 2, cp = b & 0x1F, min = 0x80;
        else if ((b & 0xF0) == 0xE0) len = 3, cp = b & 0x0F, min = 0x800;
        else if ((b & 0xF8) == 0xF0) len = 4, cp = b & 0x07, min = 0x10000;
        else return i;
        if (i + len > text.size()) return i;
        for (std::size_t k = 1; k < len; ++k) {
            const auto c = static_cast<unsigned char>(text[i + k]);
            if ((c & 0xC0) != 0x80) return i;
            cp = (cp << 6) | (c & 0x3F);
        }
        if (cp < min || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) return i;
        i += len;
    }
    return std::nullopt;
}

void check_label(std::string_view value, const std::string& what) {
    if (const auto bad = first_invalid_utf8(value))
        throw Error(what + " '" + escaped(value) + "': byte " + std::to_string(*bad + 1) +
                    " is not UTF-8 (labels go into JSON, CSV and plots); give it in UTF-8");
    for (const unsigned char c : value)
        if (c < 0x20 || c == 0x7f)
            throw Error(what + " '" + escaped(value) + "' holds a control character (a line break or tab would split a CSV row or table cell)");
}

}  // namespace trn::energy
