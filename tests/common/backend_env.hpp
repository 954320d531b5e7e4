#pragma once
// The TRN_* variables -> trn::BackendOptions for the test and benchmark mains, read as the trnkit CLI
// reads them (trn::backend_options_from_variables, the table in README.md), so that
// `TRN_OPENCL_DEVICE=1 ctest` and `TRN_VULKAN_VALIDATION=1 trn_bench` mean what they mean for the
// CLI. Only the getenv is here.
#include <cstdlib>

#include "trn/backend_option_text.hpp"

namespace trn::test {

inline BackendOptions backend_options_from_environment() {
    return backend_options_from_variables([](const char* name) { return std::getenv(name); });
}

}  // namespace trn::test
