#include "trn/filter/conversion.hpp"

#include <cmath>
#include <cstdlib>
#include <sstream>

#include "trn/error.hpp"

namespace trn::filter {
namespace {

double logistic_l(double x, double v) { return std::pow(1.0 + std::exp(-5.0 * x), -1.0 / v); }

double parse_parameter(std::string_view text, std::string_view whole) {
    const std::string s(text);
    char* end = nullptr;
    const double value = std::strtod(s.c_str(), &end);
    if (s.empty() || end != s.c_str() + s.size() || !std::isfinite(value))
        throw Error("conversion '" + std::string(whole) + "': parameter '" + s + "' is not a number");
    return value;
}

}  // namespace

double Conversion::operator()(double x) const {
    switch (kind) {
        case Kind::Linear: return (x + 1.0) / 2.0;
        case Kind::Softmax: return std::exp(x);
        case Kind::Rectifying: {
            const double d = parameter, ad = std::abs(d);
            if (d < 0) return x <= ad ? 0.0 : (1.0 + ad) * (x - ad) + d * d;
            return x <= 0 ? d * (1.0 + x) : x * (1.0 - d) + d;
        }
        case Kind::Logistic: return logistic_l(x, parameter) / logistic_l(1.0, parameter);
    }
    return 0;
}

Conversion Conversion::parse(std::string_view text) {
    const auto colon = text.find(':');
    const std::string_view name = text.substr(0, colon);
    const bool has_param = colon != std::string_view::npos;
    Conversion c;
    if (name == "linear" || name == "softmax") {
        if (has_param) throw Error("conversion '" + std::string(text) + "': " + std::string(name) + " takes no parameter");
        c.kind = name == "linear" ? Kind::Linear : Kind::Softmax;
        c.parameter = 0;
        return c;
    }
    if (name != "rectifying" && name != "logistic")
        throw Error("conversion '" + std::string(text) + "': unknown; expected linear, softmax, rectifying:D or logistic:V");
    if (!has_param) throw Error("conversion '" + std::string(text) + "': needs a parameter, e.g. " + std::string(name) + ":0.2");
    c.kind = name == "rectifying" ? Kind::Rectifying : Kind::Logistic;
    c.parameter = parse_parameter(text.substr(colon + 1), text);
    if (c.kind == Kind::Logistic && !(c.parameter > 0))
        throw Error("conversion '" + std::string(text) + "': logistic parameter v must be > 0");
    return c;
}

std::string Conversion::to_string() const {
    std::ostringstream s;
    switch (kind) {
        case Kind::Linear: return "linear";
        case Kind::Softmax: return "softmax";
        case Kind::Rectifying: s << "rectifying:" << parameter; break;
        case Kind::Logistic: s << "logistic:" << parameter; break;
    }
    return s.str();
}

}  // namespace trn::filter
