#pragma once
// The one rule for text from outside (a file or folder name, an EXIF field, an option such as
// --platform, a scenario from flight.json) entering a file trnkit writes (issue 45): every byte that
// is not part of a valid UTF-8 sequence is replaced, one replacement per byte, so no writer can fail
// on it after the work is done. JSON (json_text) and CSV cells carry U+FFFD; gnuplot labels carry
// '?' (gnuplot_sanitized, which also replaces control characters: plots are ASCII-safe).
// JSON text is made only by json_text: nlohmann's dump() throws on invalid UTF-8 (exit 2).
#include <cstddef>
#include <string>
#include <string_view>

#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn::io {

// Length of the valid UTF-8 sequence at s[i] (RFC 3629: no overlongs, surrogates or code points
// above U+10FFFF), 0 when there is none; `cp` gets its code point.
std::size_t utf8_sequence(std::string_view s, std::size_t i, char32_t& cp);

bool is_utf8(std::string_view text);

// `text` with each byte that belongs to no valid sequence replaced by U+FFFD (EF BF BD).
std::string utf8_replaced(std::string_view text);

// Every string and key of `j` passed through utf8_replaced (a copy only when one needs it).
template <class Json>
void replace_invalid_utf8(Json& j) {
    if (j.is_string()) {
        auto& s = j.template get_ref<std::string&>();
        if (!is_utf8(s)) s = utf8_replaced(s);
    } else if (j.is_array()) {
        for (auto& v : j) replace_invalid_utf8(v);
    } else if (j.is_object()) {
        bool bad_key = false;
        for (auto it = j.begin(); it != j.end(); ++it) {
            bad_key |= !is_utf8(it.key());
            replace_invalid_utf8(it.value());
        }
        if (bad_key) {
            Json fixed = Json::object();
            for (auto it = j.begin(); it != j.end(); ++it) fixed[utf8_replaced(it.key())] = std::move(it.value());
            j = std::move(fixed);
        }
    }
}

// The text of a JSON file trnkit writes (with a final newline): `indent` as dump() takes it, outside
// text made valid UTF-8 first, so this never throws on it. The only call of dump() in host/, apps/,
// capi/, python/ and energy/ (security.json_text_only).
template <class Json>
std::string json_text(Json j, int indent = -1) {
    replace_invalid_utf8(j);
    return j.dump(indent) + "\n";
}

// The same as one line without the newline: for a message, a comparison or a hash.
template <class Json>
std::string json_line(const Json& j) {
    std::string text = json_text(j);
    text.pop_back();
    return text;
}

}  // namespace trn::io
TRN_API_END
