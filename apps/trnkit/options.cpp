#include "options.hpp"

#include <sstream>

#include "trn/parse_number.hpp"

namespace trn::cli {
namespace {

std::string number_text(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
}

}  // namespace

CLI::Validator whole_in(std::uint64_t lo, std::uint64_t hi) {
    const std::string range = "[" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
    return CLI::Validator(
        [lo, hi, range](std::string& text) -> std::string {
            const auto v = parse_whole_number(text);
            if (!v) return "'" + text + "' is not a whole number in " + range + " (decimal digits only, no sign)";
            if (*v < lo || *v > hi) return "'" + text + "' is outside " + range;
            text = std::to_string(*v);
            return {};
        },
        "in " + range);
}

CLI::Validator template_width_option() {
    const CLI::Validator pixels = whole_in(8, kMaxTemplateWidth);
    return CLI::Validator(
        [pixels](std::string& text) -> std::string {
            if (text == "full") {
                text = "0";
                return {};
            }
            std::string why = pixels(text);
            return why.empty() ? why : why + " or 'full'";
        },
        "full or in [8, " + std::to_string(kMaxTemplateWidth) + "]");
}

CLI::Validator any_seed() { return whole_in(0, std::numeric_limits<std::uint64_t>::max()); }

CLI::Validator real_in(double lo, double hi, Open open) {
    const bool lo_open = open == Open::low || open == Open::both, hi_open = open == Open::high || open == Open::both;
    const std::string range = (lo_open ? "(" : "[") + number_text(lo) + ", " + number_text(hi) + (hi_open ? ")" : "]");
    return CLI::Validator(
        [=](std::string& text) -> std::string {
            const auto v = parse_finite_real(text);
            if (!v) return "'" + text + "' is not a finite number";
            if (*v < lo || *v > hi || (lo_open && *v == lo) || (hi_open && *v == hi)) return "'" + text + "' is outside " + range;
            return {};
        },
        "in " + range);
}

}  // namespace trn::cli
