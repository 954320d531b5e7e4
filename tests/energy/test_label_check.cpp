// Labels from outside (--platform, a marker file's header) are UTF-8 without control characters,
// checked when given (issue 45, class 4): they go into JSON, whose writer used to fail on them
// after the work was done.
#include <gtest/gtest.h>

#include <string>

#include "synthetic_run.hpp"
#include "trn/energy/label_check.hpp"
#include "trn/energy/markers.hpp"
#include "trn/energy/run_report.hpp"
#include "trn/error.hpp"

namespace trn::energy {
namespace {

std::string error_of(const std::string& value) {
    try {
        check_label(value, "--platform");
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

TEST(LabelCheck, Utf8IsTestedByteByByte) {
    EXPECT_EQ(first_invalid_utf8("jetson-nano"), std::nullopt);
    EXPECT_EQ(first_invalid_utf8("Vilnius \xC5\xAB \xE2\x80\x93 \xF0\x9F\x9A\x81"), std::nullopt);  // 2-, 3- and 4-byte forms
    EXPECT_EQ(first_invalid_utf8("ab\xFF"), 2u);
    EXPECT_EQ(first_invalid_utf8("a\xC5"), 1u);                 // cut short
    EXPECT_EQ(first_invalid_utf8("\xC0\xAF"), 0u);              // overlong '/'
    EXPECT_EQ(first_invalid_utf8("x\xED\xA0\x80"), 1u);         // a UTF-16 surrogate
    EXPECT_EQ(first_invalid_utf8("\xF4\x90\x80\x80"), 0u);      // above U+10FFFF
    EXPECT_EQ(first_invalid_utf8("\xE2\x28\xA1"), 0u);          // a continuation byte missing
}

TEST(LabelCheck, ALabelThatIsNotUtf8OrHoldsAControlCharacterIsRefusedNamingTheOption) {
    EXPECT_EQ(error_of("w7700 \xE2\x80\x93 rocm"), "");
    EXPECT_EQ(error_of("tx2\xFF"), "--platform 'tx2\\xff': byte 4 is not UTF-8 (labels go into JSON, CSV and plots); give it in UTF-8");
    EXPECT_NE(error_of("a\nb").find("--platform 'a\\x0ab' holds a control character"), std::string::npos) << error_of("a\nb");
}

TEST(LabelCheck, IntegrateRefusesSuchAPlatformBeforeAnyReport) {
    const auto tl = test::make_timeline(3, 0.2, 0.1);
    IntegrateRequest q;
    q.platform = "gpu\xC3";
    PowerTrace tr;
    tr.format = "trnkit", tr.wall_clock = true;
    for (double t = tl.t0 - 1; t < tl.t0 + 5; t += 0.01) tr.t.push_back(t), tr.w.push_back(5);
    try {
        integrate_run(tr, tl.markers, q);
        ADD_FAILURE() << "a platform label that is not UTF-8 was accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("platform 'gpu\\xc3': byte 4 is not UTF-8"), std::string::npos) << e.what();
    }
}

TEST(LabelCheck, AMarkerHeaderValueThatIsNotUtf8IsRefusedWithFileAndLine) {
    const std::string text = "# trnkit-frames v1 backend=cpu platform=tx2\xFE\n"
                             "kind,id,mono_start_ns,mono_end_ns,real_start_ns,real_end_ns,write_ms,exec_ms,read_ms\n";
    try {
        parse_markers(text, "m.csv");
        ADD_FAILURE() << "a marker header that is not UTF-8 was read";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("m.csv:1: header token 'platform=tx2\\xfe': byte 13 is not UTF-8"), std::string::npos) << e.what();
    }
}

// A run report edited by hand: JSON escapes let a platform carry an escape sequence to compare's
// terminal and a line break into its CSV tables.
TEST(LabelCheck, ARunReportsPlatformObeysTheSameRule) {
    const std::string good = run_report_json(test::report_with_energies("cpu-A", {0.010, 0.012, 0.011}, "la"));
    const std::string key = "\"platform\": \"cpu-A\"";
    ASSERT_NE(good.find(key), std::string::npos) << good.substr(0, 400);
    EXPECT_EQ(parse_run_report_json(good, "r.json").platform, "cpu-A");
    std::string bad = good;
    bad.replace(bad.find(key), key.size(), "\"platform\": \"cpu\\u001b[2J-A\"");
    try {
        parse_run_report_json(bad, "r.json");
        ADD_FAILURE() << "a report whose platform holds an escape sequence was read";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("r.json: platform 'cpu\\x1b[2J-A' holds a control character"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace trn::energy
