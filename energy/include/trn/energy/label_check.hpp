#pragma once
// Labels given from outside (`--platform`, a marker file's key=value header) end up in JSON, CSV,
// Markdown tables and plot titles. They are checked when given, before any run or file removal:
// bytes that are not UTF-8 would make the JSON writer fail after the work was done (issue 45).
#include <optional>
#include <string>
#include <string_view>

#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn::energy {

// The offset of the first byte of `text` that is not part of valid UTF-8 (overlong forms,
// surrogates and code points above U+10FFFF included), or nullopt when all of it is.
std::optional<std::size_t> first_invalid_utf8(std::string_view text);

// Throws trn::Error "WHAT 'ab\xFF': byte 3 is not UTF-8 ..." or "... holds a control character"
// (a line break or tab would split a CSV row or a table cell).
void check_label(std::string_view value, const std::string& what);

}  // namespace trn::energy
TRN_API_END
