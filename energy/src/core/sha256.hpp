#pragma once
// SHA-256 (FIPS 180-4) of a byte string as lowercase hex: the input hashes in reports'
// provenance, so a reader can tell which log produced which numbers.
#include <string>
#include <string_view>

namespace trn::energy {
std::string sha256_hex(std::string_view data);
}  // namespace trn::energy
