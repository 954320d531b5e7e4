#pragma once
// What a CUDA fat binary holds: one entry per cubin (machine code for one sm_XY) or PTX (for one
// compute_XY, compiled by the driver's JIT for that architecture and any newer one). Used to say in
// `trnkit devices` which code a device will run, and by the tests to check what the build embedded.
// No CUDA header or driver needed.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace trn::cuda {

struct FatbinEntry {
    enum class Kind { Cubin, Ptx };
    Kind kind = Kind::Cubin;
    int arch = 0;  // 87 for sm_87 / compute_87
};

// The entries of a fat binary as `nvcc -fatbin` writes it (a 16-byte header with magic 0xBA55ED50,
// then entries with their own headers). Throws trn::Error naming what is malformed.
std::vector<FatbinEntry> fatbin_entries(std::span<const unsigned char> bytes);

// The code the driver would use on a device of compute capability `arch` (10 * major + minor): the
// newest cubin of the same major version at or below its minor one (a cubin runs on its own major
// version at the same or a higher minor), else the newest PTX at or below it (JIT), else none.
struct CodeChoice {
    bool runs = false;
    std::string text;  // "sm_90 cubin", "PTX compute_75, compiled by the driver (JIT)", or why none
};
CodeChoice code_for_device(const std::vector<FatbinEntry>& entries, int arch);

// "sm_87, sm_90 + PTX compute_75"
std::string describe(const std::vector<FatbinEntry>& entries);

}  // namespace trn::cuda
