#pragma once
// The allocation counter of trn_vulkan_alloc_tests: that binary replaces the global operator new
// (counting_new.cpp), so every allocation through new / new[] in the process is counted, including
// those inside libtrnkit.
#include <cstdint>

namespace trn::test {

// Allocations through any form of operator new so far, by any thread.
std::uint64_t operator_new_calls();

}  // namespace trn::test
