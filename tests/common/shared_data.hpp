#pragma once
// The real maps, flights and power logs of ../shared/data as the tests reach them: CTest sets
// TRN_SHARED_DATA where that folder exists (tests/CMakeLists.txt). One home for the variable, for the
// tests and the benchmarks (bench/inputs.cpp); a test that finds nothing skips visibly, naming what
// it missed.
#include <cstdlib>
#include <filesystem>
#include <string>

namespace trn::test {

// The folder, or an empty path when TRN_SHARED_DATA is unset or empty.
inline std::filesystem::path shared_data_dir() {
    const char* d = std::getenv("TRN_SHARED_DATA");
    return d && *d ? std::filesystem::path(d) : std::filesystem::path();
}

// The folder's `relative` (a file or folder) when it exists, else an empty string.
inline std::string shared_data(const std::string& relative) {
    const std::filesystem::path dir = shared_data_dir();
    if (dir.empty()) return "";
    const std::filesystem::path p = dir / relative;
    return std::filesystem::exists(p) ? p.string() : "";
}

}  // namespace trn::test
