#pragma once
// Writes a whole text file for a CLI command: complete or not at all (trn::io::write_file_atomic);
// a failure names the file.
#include <string>

#include "trn/io/atomic_file.hpp"

namespace trn::cli {

inline void write_text_file(const std::string& path, const std::string& text) { io::write_file_atomic(path, text); }

}  // namespace trn::cli
