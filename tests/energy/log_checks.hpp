#pragma once
// What the power-log tests ask of a small log written for them: its refusal, whether a list of
// notes mentions a phrase, and the whole log's joules.
#include <string>
#include <vector>

#include "trn/energy/integrate.hpp"
#include "trn/energy/parsers.hpp"
#include "trn/error.hpp"

namespace trn::energy::test {

// The error parsing `text` gives ("" when it reads).
inline std::string error_of(const std::string& text, const std::string& format = "auto", const ParseOptions& o = {}) {
    try {
        parse_power_log(text, "x.log", format, o);
    } catch (const trn::Error& e) {
        return e.what();
    }
    return "";
}

inline bool mentions(const std::vector<std::string>& list, const std::string& part) {
    for (const auto& s : list)
        if (s.find(part) != std::string::npos) return true;
    return false;
}

inline double joules(const PowerTrace& tr) {
    return integrate_interval(tr, tr.first_interval_start.value_or(tr.t.front()), tr.t.back()).energy_j;
}

}  // namespace trn::energy::test
