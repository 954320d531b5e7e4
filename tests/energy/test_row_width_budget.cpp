// The memory budget of a text log's rows (issue 45, class 5): a header claiming millions of
// columns is refused by its width, before any reader splits it into fields (a 240 MB header of
// 120 M columns used to end in std::bad_alloc, exit 2).
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>

#include "../cli/cli_process.hpp"
#include "log_checks.hpp"
#include "text_input.hpp"
#include "trn/energy/markers.hpp"
#include "trn/energy/run_summaries.hpp"

namespace trn::energy {
namespace {
namespace fs = std::filesystem;

// A header of `columns` names "p" under `sep`, then one row of as many zeros.
std::string wide_log(std::size_t columns, char sep) {
    std::string header = "time_s", row = "0";
    for (std::size_t i = 1; i < columns; ++i) header += sep, header += 'p', row += sep, row += '0';
    return header + "\n" + row + "\n";
}

TEST(RowWidthBudget, AHeaderWiderThanTheBudgetIsRefusedNamingItsLine) {
    const std::size_t over = text::kMaxFieldsPerRow + 1;
    for (const char sep : {',', ';', '\t', ' '}) {
        SCOPED_TRACE(std::string("separator code ") + std::to_string(int(sep)));
        const std::string e = test::error_of(wide_log(over, sep));
        EXPECT_NE(e.find("x.log:1: a row of " + std::to_string(over) + " fields, more than the 65536 a log row may have"), std::string::npos) << e;
        EXPECT_NE(e.find("GB of memory"), std::string::npos) << e;
    }
    // Named formats are held to it too, and a wide row further down is named by its line.
    const std::string later = "time_s,power_W\n0,1\n1,2\n" + wide_log(over, ',').substr(wide_log(over, ',').find('\n') + 1);
    const std::string e = test::error_of(later, "ina219-csv");
    EXPECT_NE(e.find("x.log:4: a row of "), std::string::npos) << e;
}

TEST(RowWidthBudget, RowsAtTheBudgetAreLeftToTheReaders) {
    const std::string e = test::error_of(wide_log(text::kMaxFieldsPerRow, ','));
    EXPECT_EQ(e.find("a row of"), std::string::npos) << e;  // refused or not, then for what the columns hold
    // JSON is parsed whole, never split in fields: a one-line array of many steps is not a wide row.
    std::string steps = "[";
    for (int i = 0; i < 25000; ++i)
        steps += std::string(i ? "," : "") + R"({"host":{"consumption":30000000.0,"timestamp":)" + std::to_string(1674730735 + i) + "},\"sockets\":[]}";
    steps += "]";
    ASSERT_GT(std::count(steps.begin(), steps.end(), ','), static_cast<long>(text::kMaxFieldsPerRow));
    EXPECT_EQ(test::error_of(steps), "");
}

TEST(RowWidthBudget, MarkerFilesAndCodeCarbonRunsToo) {
    const std::string wide = wide_log(text::kMaxFieldsPerRow + 5, ',');
    try {
        parse_markers("frame,start_s,end_s\n" + wide, "m.csv");
        ADD_FAILURE() << "a marker file with a row of 65541 fields was read";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("m.csv:2: a row of 65541 fields"), std::string::npos) << e.what();
    }
    try {
        parse_codecarbon_runs(wide, "emissions.csv");
        ADD_FAILURE() << "an emissions.csv with a row of 65541 fields was read";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("emissions.csv:1: a row of 65541 fields"), std::string::npos) << e.what();
    }
}

// The issue's file through the CLI: 240 MB, one header of 120 M columns, under a 3 GB address
// space. Refused with one line and exit 1, not std::bad_alloc (exit 2).
TEST(RowWidthBudget, A240MbHeaderOf120MColumnsIsRefusedByTheCli) {
    const fs::path log = fs::temp_directory_path() / ("trn_wide_header_" + std::to_string(::getpid()) + ".csv");
    {
        std::string header;
        header.reserve(240'000'002);
        for (std::size_t i = 0; i < 120'000'000; ++i) header += "p,";
        header.back() = '\n';
        std::ofstream(log, std::ios::binary) << header << "0\n";
    }
    const auto r = trn::test::run_shell(trn::test::limited(3000000, 60) + trn::test::trnkit_exe() + " energy inspect " + log.string() + " 2>&1");
    fs::remove(log);
    EXPECT_EQ(r.code, 1) << r.output.substr(0, 2000);
    EXPECT_NE(r.output.find(":1: a row of 120000000 fields, more than the 65536 a log row may have"), std::string::npos) << r.output.substr(0, 2000);
}

}  // namespace
}  // namespace trn::energy
