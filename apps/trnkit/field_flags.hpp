#pragma once
// The library's spec fields (trn::FieldError: "field: detail", other fields in the detail written
// `field`) spelled as the flags of `localize` and `demo`: only the CLI knows its flags.
#include <string>

#include "trn/field_error.hpp"

namespace trn::cli {

// "--flag: detail" with every `field` in the detail replaced by its flag.
std::string with_flags(const FieldError& error);
// A field's flag ("metres_per_pixel" -> "--mpp"); an unknown field comes back as it is.
std::string flag_of(const std::string& field);
// `field` marks in a library text (a note) replaced by flags.
std::string flags_in(std::string text);

}  // namespace trn::cli
