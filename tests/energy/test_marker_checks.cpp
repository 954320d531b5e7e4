// Marker files whose rows overlap (the same joules counted in two intervals) or repeat an id (a
// frame's energy paired with another frame's phase times) are refused, naming file:line.
#include <gtest/gtest.h>

#include "synthetic_run.hpp"
#include "trn/energy/markers.hpp"
#include "trn/error.hpp"

namespace trn::energy {
namespace {

std::string refusal(const MarkerFile& m) {
    try {
        parse_markers(format_markers(m), "m.csv");
    } catch (const trn::Error& e) {
        return e.what();
    }
    return "";
}

// Index of the row of `kind` with `id`; data rows start at line 3 of the file.
std::size_t row_of(const MarkerFile& m, const std::string& kind, int id) {
    for (std::size_t i = 0; i < m.rows.size(); ++i)
        if (m.rows[i].kind == kind && m.rows[i].id == id) return i;
    ADD_FAILURE() << kind << " " << id << " not found";
    return 0;
}

TEST(MarkerChecks, WellFormedRunParses) {
    const auto tl = test::make_timeline(5, 0.05, 0.05);
    EXPECT_EQ(refusal(tl.markers), "");
    EXPECT_EQ(parse_markers(format_markers(tl.markers), "m.csv").rows.size(), tl.markers.rows.size());
}

TEST(MarkerChecks, DuplicateFrameIdIsRefused) {
    auto m = test::make_timeline(5, 0.05, 0.05).markers;
    const std::size_t first = row_of(m, "frame", 2), second = row_of(m, "frame", 3);
    m.rows[second].id = 2;
    const std::string why = refusal(m);
    EXPECT_NE(why.find("m.csv:" + std::to_string(second + 3) + ": frame id 2 repeats the row at line " + std::to_string(first + 3)), std::string::npos)
        << why;
}

// Fuzz finding 12: an id beyond int kept its low 32 bits (4294967296 became frame 0).
TEST(MarkerChecks, FrameIdBeyondIntIsRefused) {
    std::string text = format_markers(test::make_timeline(5, 0.05, 0.05).markers);
    const std::size_t at = text.find("\nframe,2,");
    ASSERT_NE(at, std::string::npos) << text;
    text.replace(at, 9, "\nframe,4294967296,");
    try {
        parse_markers(text, "m.csv");
        ADD_FAILURE() << "id 4294967296 accepted";
    } catch (const trn::Error& e) {
        EXPECT_NE(std::string(e.what()).find("frame id 4294967296 is outside [0, 2^31-1]"), std::string::npos) << e.what();
    }
}

TEST(MarkerChecks, OverlappingFramesAreRefused) {
    auto m = test::make_timeline(5, 0.05, 0.05).markers;
    const std::size_t i = row_of(m, "frame", 3);
    // Frame 3 starts 10 ms before frame 2's idle gap (the row before it) ends, on both clocks.
    m.rows[i].mono_start_ns = m.rows[i - 1].mono_end_ns - 10'000'000, m.rows[i].real_start_ns = m.rows[i - 1].real_end_ns - 10'000'000;
    std::string why = refusal(m);
    EXPECT_NE(why.find("m.csv:" + std::to_string(i + 3) + ": frame 3 starts before idle"), std::string::npos) << why;
    EXPECT_NE(why.find("(line " + std::to_string(i + 2) + ") ends on CLOCK_MONOTONIC"), std::string::npos) << why;
    // Rows out of time order overlap too; a step back of the wall clock alone is named as such.
    m = test::make_timeline(5, 0.05, 0.05).markers;
    m.rows[i].real_start_ns -= 30'000'000;
    why = refusal(m);
    EXPECT_NE(why.find("ends on CLOCK_REALTIME"), std::string::npos) << why;
}

}  // namespace
}  // namespace trn::energy
