// Inputs the fuzzers turned up, kept as plain tests so they fail in any build (the fuzz replays
// only see some of them under a sanitizer).
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

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
        EXPECT_NE(std::string(e.what()).find("/dev/full: is a character device, not a regular file"), std::string::npos) << e.what();
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
        EXPECT_NE(std::string(e.what()).find("/dev/zero: is a character device, not a regular file"), std::string::npos) << e.what();
    }
}

// Issue 23: a FIFO given as a power log, marker file or run report is refused at once (before: the
// open() waited for a writer for ever; ctest's timeout fails this test on the old code).
TEST(EndlessInput, FifosAreRefusedNotWaitedOn) {
    const std::string fifo = testing::TempDir() + "/trn_fifo_" + std::to_string(::getpid());
    ::unlink(fifo.c_str());
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    for (int which = 0; which < 3; ++which) {
        try {
            if (which == 0) trn::energy::read_markers(fifo);
            if (which == 1) trn::energy::read_run_report(fifo);
            if (which == 2) trn::energy::read_power_log(fifo, "auto", {});
            ADD_FAILURE() << "a FIFO was read (" << which << ")";
        } catch (const trn::Error& e) {
            EXPECT_NE(std::string(e.what()).find(": is a FIFO, not a regular file"), std::string::npos) << e.what();
        }
    }
    ::unlink(fifo.c_str());
}

// Issue 23 finding 8: a UTF-8 byte order mark gave "expected '# trnkit-frames v1 ...'"; ESC and
// other control characters in the header (platform=...) reached the terminal and plots raw.
TEST(MarkerReading, ByteOrderMarkIsSkippedAndControlCharactersRefused) {
    const std::string frames = "# trnkit-frames v1 platform=tx2\n"
                               "kind,id,mono_start_ns,mono_end_ns,real_start_ns,real_end_ns,write_ms,exec_ms,read_ms\n"
                               "frame,0,100,200,100,200,0.1,0.2,0.3\n";
    EXPECT_EQ(trn::energy::parse_markers("\xEF\xBB\xBF" + frames, "bom.csv").rows.size(), 1u);
    EXPECT_EQ(trn::energy::parse_markers("\xEF\xBB\xBF" "frame,start_s,end_s\n0,1,2\n", "bom-minimal.csv").rows.size(), 1u);
    std::string hostile = frames;
    hostile.replace(hostile.find("tx2"), 3, "\x1b[2J\x07tx2");
    try {
        trn::energy::parse_markers(hostile, "esc.csv");
        ADD_FAILURE() << "an escape sequence in the header was accepted";
    } catch (const trn::Error& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("esc.csv:1: header token 'platform=\\x1b[2J\\x07tx2' holds a control character"), std::string::npos) << what;
        EXPECT_EQ(what.find('\x1b'), std::string::npos) << what;
    }
    // A 100 KB header token is quoted short.
    try {
        trn::energy::parse_markers("# trnkit-frames v1 " + std::string(100000, 'k') + "\n", "long.csv");
        ADD_FAILURE() << "accepted";
    } catch (const trn::Error& e) {
        EXPECT_LT(std::string(e.what()).size(), 300u);
    }
}

// Issue 23 finding 5: a run report nested 100000 deep overflowed the stack; now refused by depth.
TEST(RunReportReading, DeeplyNestedJsonIsRefused) {
    const std::string deep = "{\"trnkit_energy_run\": 1, \"x\": " + std::string(100000, '[') + std::string(100000, ']') + "}";
    try {
        trn::energy::parse_run_report_json(deep, "deep.json");
        ADD_FAILURE() << "accepted";
    } catch (const trn::Error& e) {
        EXPECT_NE(std::string(e.what()).find("deep.json: JSON nested deeper than 64 levels"), std::string::npos) << e.what();
    }
}

}  // namespace
