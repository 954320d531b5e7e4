#pragma once
// Counts every heap allocation in the process (the bench binary replaces the global operator new),
// so a benchmark can report allocations per steady-state call; the issue asks for none.
#include <cstdint>

namespace trn::bench {

// Allocations made so far by any thread, through any form of operator new or new[].
std::uint64_t allocation_count();

}  // namespace trn::bench
