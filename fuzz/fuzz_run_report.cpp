// Fuzz entry: run-report JSON of `trnkit energy integrate` as `energy compare` reads it
// (energy/src/core/run_report.cpp, parse_run_report_json). A refusal must be trn::Error; a report it
// accepts and can write again must read back to the same JSON.
#include <cstdio>
#include <string>

#include "fuzz_check.hpp"
#include "trn/energy/run_report.hpp"
#include "trn/error.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    namespace en = trn::energy;
    const std::string text(trn::fuzz::as_text(data, size));
    en::RunReport report;
    std::string written;
    try {
        report = en::parse_run_report_json(text, "fuzz.json");
        written = en::run_report_json(report);  // may refuse a non-finite number: JSON cannot hold it
    } catch (const trn::Error&) {
        return 0;
    }
    std::string again;
    try {
        again = en::run_report_json(en::parse_run_report_json(written, "round-trip.json"));
    } catch (const trn::Error& e) {
        std::fprintf(stderr, "%s\n", e.what());
        trn::fuzz::violation("a run report written by run_report_json is refused");
    }
    trn::fuzz::require(again == written, "parse -> write -> parse -> write is not stable");
    return 0;
}
