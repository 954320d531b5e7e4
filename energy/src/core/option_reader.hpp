#pragma once
// Reads a parser's key=value options, and refuses keys the parser does not know (a typo must
// not silently become a default) and numbers outside their stated range (option_ranges.hpp).
#include <cmath>
#include <cstdio>
#include <optional>
#include <set>
#include <string>

#include "option_ranges.hpp"
#include "text_input.hpp"
#include "trn/energy/parsers.hpp"

namespace trn::energy {

class OptionReader {
public:
    OptionReader(const ParseOptions& options, std::string parser, std::set<std::string> known)
        : options_(options), parser_(std::move(parser)), known_(std::move(known)) {
        for (const auto& [key, value] : options_)
            if (!known_.count(key)) {
                std::string list;
                for (const auto& k : known_) list += (list.empty() ? "" : ", ") + k;
                throw Error(parser_ + ": unknown option '" + key + "' (known: " + (list.empty() ? "none" : list) + ")");
            }
    }
    std::optional<std::string> text(const std::string& key) const {
        const auto it = options_.find(key);
        if (it == options_.end()) return std::nullopt;
        return it->second;
    }
    std::string text(const std::string& key, const std::string& fallback) const { return text(key).value_or(fallback); }
    std::optional<double> number(const std::string& key) const {
        const auto v = text(key);
        if (!v) return std::nullopt;
        const auto n = text::to_number(*v);
        if (!n) throw Error(parser_ + ": option " + key + "='" + *v + "' is not a finite number");
        const OptionRange* r = option_range(key);
        if (!r) throw Error(parser_ + ": option " + key + " has no stated range (a defect: add it to option_ranges.hpp)");
        if (*n < r->min || *n > r->max || (r->whole && *n != std::trunc(*n)))
            throw Error(parser_ + ": option " + key + "=" + *v + " is outside " + (r->whole ? "the whole numbers " : "") + shown(r->min) + ".." +
                        shown(r->max) + " " + std::string(r->unit));
        return n;
    }
    double number(const std::string& key, double fallback) const { return number(key).value_or(fallback); }

private:
    static std::string shown(double v) {
        char buf[32];
        std::snprintf(buf, sizeof buf, "%g", v);
        return buf;
    }
    const ParseOptions& options_;
    std::string parser_;
    std::set<std::string> known_;
};

}  // namespace trn::energy
