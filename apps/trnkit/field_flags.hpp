#pragma once
// The library's spec fields (trn::FieldError: "field: detail"; fields inside any library message
// written `field`) spelled as the CLI's flags: only the CLI knows its flags. main() maps every
// error message, commands map the warnings they print.
#include <string>

#include "trn/field_error.hpp"

namespace trn::cli {

// "--flag: detail" with every `field` in the detail replaced by its flag.
std::string with_flags(const FieldError& error);
// A field's flag ("metres_per_pixel" -> "--mpp"); an unknown field comes back as it is.
std::string flag_of(const std::string& field);
// `field` marks of known fields in a library text replaced by their flags (others left as they are).
std::string flags_in(std::string text);

}  // namespace trn::cli
