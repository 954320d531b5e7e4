#pragma once
// Writes a whole text file for a CLI command; a failure names the file.
#include <fstream>
#include <string>

#include "trn/error.hpp"

namespace trn::cli {

inline void write_text_file(const std::string& path, const std::string& text) {
    std::ofstream f(path, std::ios::binary);
    if (!f || !(f << text) || !f.flush()) throw Error(path + ": cannot write");
}

}  // namespace trn::cli
