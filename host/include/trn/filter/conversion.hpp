#pragma once
// Similarity-to-probability conversion functions of the dissertation (eqs. 2.16-2.21): they turn a
// Pearson correlation x in [-1, 1] into an unnormalised particle probability.
//   linear        F(x) = (x + 1) / 2                                   (2.16)
//   softmax       F(x) = e^x                                           (2.17)
//   rectifying:d  piecewise linear with parameter d                    (2.18)
//   logistic:v    F(x, v) = L(x, v) / L(1, v), L = (1 + e^{-5x})^{-1/v}  (2.20, 2.21)
#include <string>
#include <string_view>
#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn::filter {

struct Conversion {
    enum class Kind { Linear, Softmax, Rectifying, Logistic };
    Kind kind = Kind::Logistic;
    double parameter = 0.2;  // d for rectifying, v for logistic; unused otherwise

    double operator()(double x) const;
    // "linear", "softmax", "rectifying:D", "logistic:V" (the parameter is required for the last two;
    // logistic needs v > 0). Throws trn::Error naming the text.
    static Conversion parse(std::string_view text);
    std::string to_string() const;
};

}  // namespace trn::filter
TRN_API_END
