#pragma once
// Conformance cases in the spirit of ggml's test-backend-ops: each case runs one scenario on the
// backend under test and on cpu-ref (the oracle) and compares the two.
#include <functional>
#include <string>
#include <vector>

#include "trn/backend.hpp"

namespace trn::conformance {

struct Case {
    std::string name;
    std::function<void(Backend& dut, Backend& ref)> run;
};

std::vector<Case> ncc_cases();
std::vector<Case> sobel_cases();
std::vector<Case> error_cases();
std::vector<Case> mask_cases();

}  // namespace trn::conformance
