// libFuzzer entry for one power-log parser, chosen at build time by TRN_FUZZ_FORMAT (a
// power_log_formats() name or "auto"). fuzz/replay_main.cpp links the same entry for gcc CI builds.
#include <cstddef>
#include <cstdint>

#include "fuzz_power_log_one.hpp"

#ifndef TRN_FUZZ_FORMAT
#error "define TRN_FUZZ_FORMAT to the parser under test"
#endif

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    trn::energy::fuzz::run_one(TRN_FUZZ_FORMAT, std::string_view(reinterpret_cast<const char*>(data), size));
    return 0;
}
