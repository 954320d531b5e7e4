// Fuzz entry: one line of a study's results store (host/experiments/results_store.cpp,
// parse_store_line) as `trnkit experiment --resume` reads it. A line is refused with trn::Error or
// read as a cut-off write (nullopt), never a crash or another exception; a line it accepts has the
// fields the merge reads, of their types, and written again as append() writes it reads back the same.
#include <cmath>
#include <optional>
#include <string>

#include "fuzz_check.hpp"
#include "results_store.hpp"
#include "trn/error.hpp"
#include "trn/io/outside_text.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    namespace ex = trn::experiments;
    using trn::fuzz::require;
    std::optional<ex::StoreLine> line;
    try {
        line = ex::parse_store_line(trn::fuzz::as_text(data, size), "fuzz.jsonl:1");
    } catch (const trn::Error&) {
        return 0;
    }
    if (!line) return 0;
    require(!line->job.empty(), "a line without a job accepted");
    require(line->params.is_object() && line->result.is_object(), "params or result that are no objects accepted");
    require(std::isfinite(line->wall_s) && line->wall_s >= 0, "a wall time that is not a number of seconds accepted");
    const ex::Json written{{"job", line->job},       {"config", line->config}, {"commit", line->commit},
                           {"params", line->params}, {"result", line->result}, {"wall_s", line->wall_s}};
    std::string text = trn::io::json_text(written);
    text.pop_back();  // the newline
    std::optional<ex::StoreLine> again;
    try {
        again = ex::parse_store_line(text, "round-trip.jsonl:1");
    } catch (const trn::Error& e) {
        std::fprintf(stderr, "%s\n", e.what());
        trn::fuzz::violation("a line written as append() writes it is refused");
    }
    require(again.has_value(), "a line written as append() writes it does not parse");
    require(again->job == line->job && again->config == line->config && again->params == line->params && again->result == line->result &&
                again->wall_s == line->wall_s,
            "parse -> write -> parse is not the same line");
    return 0;
}
