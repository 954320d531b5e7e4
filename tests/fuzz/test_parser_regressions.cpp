// Inputs the fuzzers turned up, kept as plain tests so they fail in any build (the fuzz replays
// only see some of them under a sanitizer).
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "trn/energy/compare.hpp"
#include "trn/energy/markers.hpp"
#include "trn/energy/parsers.hpp"
#include "trn/energy/run_report.hpp"
#include "trn/error.hpp"

namespace {

nlohmann::json corpus_report() {
    std::ifstream in(std::string(TRN_FUZZ_CORPUS_DIR) + "/run_report/run.json");
    return nlohmann::json::parse(in);
}

std::string refusal(const nlohmann::json& j) {
    try {
        trn::energy::parse_run_report_json(j.dump(), "r.json");
    } catch (const trn::Error& e) {
        return e.what();
    }
    return "accepted";
}

TEST(RunReportReading, TheCorpusReportReads) {
    const auto r = trn::energy::parse_run_report_json(corpus_report().dump(), "r.json");
    EXPECT_EQ(r.frames.size(), 2u);
    EXPECT_EQ(r.frames[1].energy.samples, 2u);
}

// nlohmann's get<int>/get<size_t> on these is a float-to-integer cast out of range (undefined
// behaviour: UBSan's float-cast-overflow aborts) or a silent wrap of a negative count.
TEST(RunReportReading, CountsAndIdsMustBeWholeNumbersInRange) {
    const struct {
        const char* where;
        nlohmann::json value;
    } cases[] = {
        {"/frames/0/id", 1e300},        {"/frames/0/id", -1e300},       {"/frames/0/id", 2147483648.0}, {"/frames/0/id", 0.5},
        {"/frames/0/samples", -1},      {"/frames/0/samples", 1e300},   {"/frames/0/samples", 2.5},     {"/config/min_samples", -3},
        {"/idle/segments", 1e19},       {"/inputs/log/samples", -1e300},
    };
    for (const auto& c : cases) {
        auto j = corpus_report();
        j[nlohmann::json::json_pointer(c.where)] = c.value;
        const std::string why = refusal(j);
        EXPECT_NE(why.find("must be a whole number"), std::string::npos) << c.where << " = " << c.value.dump() << ": " << why;
        EXPECT_NE(why.find("r.json"), std::string::npos) << why;
    }
}

TEST(RunReportReading, TheVersionFieldIsComparedWithoutACast) {
    auto j = corpus_report();
    j["trnkit_energy_run"] = 1e300;
    EXPECT_NE(refusal(j).find("not a run report"), std::string::npos);
    j["trnkit_energy_run"] = 1.0;
    EXPECT_EQ(refusal(j), "accepted");
}

// `energy integrate --markers /dev/full` read zeros for ever (found by the CLI fuzzer): the readers
// of marker files and run reports (and the power log `integrate` hashes) stop at a size limit.
TEST(EndlessInput, MarkerAndRunReportReadersStopAtASizeLimit) {
    try {
        trn::energy::read_markers("/dev/full");  // reads as endless zeros
        ADD_FAILURE() << "/dev/full read as markers";
    } catch (const trn::Error& e) {
        EXPECT_NE(std::string(e.what()).find("/dev/full: larger than 64 MiB"), std::string::npos) << e.what();
    }
    EXPECT_THROW(trn::energy::read_run_report("/dev/zero"), trn::Error);
    EXPECT_THROW(trn::energy::compare_files({"/dev/zero"}, {}), trn::Error);  // `energy compare /dev/zero` was OOM-killed
}

// Fuzz finding 15: `energy inspect /dev/zero` read the whole device into memory.
TEST(EndlessInput, PowerLogReaderStopsAtASizeLimit) {
    try {
        trn::energy::read_power_log("/dev/zero", "auto", {});
        ADD_FAILURE() << "/dev/zero read as a power log";
    } catch (const trn::Error& e) {
        EXPECT_NE(std::string(e.what()).find("/dev/zero: larger than 256 MiB"), std::string::npos) << e.what();
    }
}

}  // namespace
