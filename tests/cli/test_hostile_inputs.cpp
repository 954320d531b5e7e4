// Hostile input files (issue 23, findings 5 and 8): every reader refuses, at once and in one line
// with exit 1, what would crash, hang, eat memory or print nonsense: deep JSON, FIFOs and devices
// in a dataset, image headers claiming huge images, errno paths, values no flight has, byte order
// marks, huge fields, and a dataset replaced while it is read. Each case runs the real trnkit
// (TRNKIT_EXE; TRNKIT_UNDER_TEST overrides it, to show an older build failing these tests) under
// `timeout` and a memory limit, so the old behaviour fails the test instead of hanging the suite.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "cli_process.hpp"
#include "../common/peak_rss.hpp"
#include "trn/error.hpp"
#include "trn/filter/flight_source.hpp"
#include "trn/io/image_header.hpp"
#include "trn/io/input_file.hpp"
#include "trn/sim/air_format.hpp"

namespace fs = std::filesystem;

namespace {

using Result = trn::test::CliResult;

// Runs `prefix trnkit args` in a shell with a 20 s timeout and a 3 GB address-space limit (under
// AddressSanitizer: no memory limit, 100 s; trn::test::limited).
Result run(const std::string& args, const std::string& prefix = "") {
    return trn::test::run_shell(trn::test::limited(3000000, 20) + prefix + " " + trn::test::trnkit_exe() + " " + args + " 2>&1");
}

std::string quoted(const std::string& s) { return "'" + s + "'"; }

class HostileInputs : public testing::Test {
protected:
    static void SetUpTestSuite() {
        root_ = fs::temp_directory_path() / ("trnkit_hostile_" + std::to_string(::getpid()));
        fs::remove_all(root_);
        fs::create_directories(root_);
        const Result r = run("simulate --scenario UL-200 --procedural urban --seed 7 --frames 20 --out " + quoted((root_ / "DS").string()));
        if (r.code != 0) setup_failure_ = "simulate failed: " + r.output;
    }
    static void TearDownTestSuite() { fs::remove_all(root_); }
    // Not in SetUpTestSuite: a failure there shows each test as SKIPPED, and ctest counts it so.
    void SetUp() override { ASSERT_EQ(setup_failure_, ""); }

    static std::string at(const std::string& name) { return (root_ / name).string(); }
    static std::string dataset_copy(const std::string& name) {
        const fs::path d = root_ / name;
        fs::remove_all(d);
        fs::copy(root_ / "DS", d, fs::copy_options::recursive);
        fs::remove_all(d / "localize");
        return d.string();
    }
    static std::string score_args(const std::string& poses) {
        return "score --map " + quoted(at("DS/map.png")) + " --template " + quoted(at("DS/frame_000000.png")) + " --poses " + quoted(poses);
    }
    // Refused with exit 1, one line holding `expect`.
    static void expect_refused(const Result& r, const std::string& expect, const std::string& what) {
        EXPECT_EQ(r.code, 1) << what << "\n" << r.output;
        EXPECT_NE(r.output.find(expect), std::string::npos) << what << "\nexpected: " << expect << "\ngot: " << r.output.substr(0, 2000);
    }

    static fs::path root_;
    static inline std::string setup_failure_;
};
fs::path HostileInputs::root_;

// Finding 5: a flight.json whose seed is a 100000-deep [[...]] segfaulted simulate --read and localize.
TEST_F(HostileInputs, DeeplyNestedJsonIsRefusedNotACrash) {
    const std::string d = dataset_copy("deep");
    std::ifstream in(d + "/flight.json");
    std::stringstream ss;
    ss << in.rdbuf();
    std::string text = ss.str();
    const auto seed = text.find("\"seed\": 7");
    ASSERT_NE(seed, std::string::npos);
    text.replace(seed, 9, "\"seed\": " + std::string(100000, '[') + std::string(100000, ']'));
    std::ofstream(d + "/flight.json") << text;
    expect_refused(run("simulate --read " + quoted(d)), "JSON nested deeper than 64 levels", "simulate --read");
    expect_refused(run("localize --backend cpu --dataset " + quoted(d) + " --out " + quoted(at("deep-out"))), "JSON nested deeper than 64",
                   "localize");
    // A job file and a run report go through the same check (library level).
    EXPECT_THROW(trn::io::check_json_depth("{\"a\":" + std::string(65, '[') + std::string(65, ']') + "}", "x.json"), trn::Error);
    EXPECT_NO_THROW(trn::io::check_json_depth("{\"a\": \"[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[\"}", "x.json"));
}

// Finding 5: a FIFO as metadata.csv or as a frame made localize wait for ever.
TEST_F(HostileInputs, FifoAsMetadataOrFrameIsRefusedNotWaitedOn) {
    const std::string a = dataset_copy("fifo-meta");
    fs::remove(a + "/metadata.csv");
    ASSERT_EQ(::mkfifo((a + "/metadata.csv").c_str(), 0644), 0);
    expect_refused(run("localize --backend cpu --dataset " + quoted(a) + " --out " + quoted(at("fifo-out1"))), "metadata.csv: is a FIFO",
                   "FIFO metadata.csv");
    expect_refused(run("simulate --read " + quoted(a)), "metadata.csv: is a FIFO", "simulate --read with a FIFO");
    const std::string b = dataset_copy("fifo-frame");
    fs::remove(b + "/frame_000000.png");
    ASSERT_EQ(::mkfifo((b + "/frame_000000.png").c_str(), 0644), 0);
    const Result r = run("localize --backend cpu --dataset " + quoted(b) + " --out " + quoted(at("fifo-out2")));
    EXPECT_NE(r.code, 124) << "hung on the FIFO frame\n" << r.output;  // a missing frame is counted, not waited on
    expect_refused(run("sobel " + quoted(b + "/frame_000000.png") + " --out " + quoted(at("fifo-sobel"))), "frame_000000.png: is a FIFO",
                   "sobel of a FIFO");
}

// Finding 5: /dev/zero as metadata.csv grew to 2+ GB, as --poses to 1.1 GB, before any check.
TEST_F(HostileInputs, DevicesAsMetadataOrPosesAreRefusedAtOnce) {
    const std::string d = dataset_copy("zero");
    fs::remove(d + "/metadata.csv");
    fs::create_symlink("/dev/zero", d + "/metadata.csv");
    expect_refused(run("simulate --read " + quoted(d)), "metadata.csv: is a character device, not a regular file", "/dev/zero metadata");
    expect_refused(run(score_args("/dev/zero")), "/dev/zero: is a character device", "score --poses /dev/zero");
    // A regular file past the limit is refused by its size, unread (sparse: no disk used).
    const std::string big = at("big.csv");
    { std::ofstream(big) << "x,y,yaw,scale\n"; }
    fs::resize_file(big, trn::io::kMaxTableFileBytes + 1);
    expect_refused(run(score_args(big)), "is larger than the 256 MiB a pose file may have", "huge pose file");
}

// Finding 5: a 153-byte .hdr or 120-byte .pfm claiming 32768x32768 made OpenCV allocate 12.9 GB.
TEST_F(HostileInputs, ImageHeadersClaimingHugeImagesAreRefusedBeforeDecoding) {
    std::ofstream(at("big.hdr"), std::ios::binary) << "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 32768 +X 32768\n" << std::string(100, '\x02');
    std::ofstream(at("big.pfm"), std::ios::binary) << "PF\n32768 32768\n-1.0\n" << std::string(100, '\0');
    std::ofstream(at("wide.pam"), std::ios::binary) << "P7\nWIDTH 70000\nHEIGHT 2\nDEPTH 1\nMAXVAL 255\nTUPLTYPE GRAYSCALE\nENDHDR\n";
    expect_refused(run("sobel " + quoted(at("big.hdr")) + " --out " + quoted(at("s1"))), "(Radiance HDR) needs ~17 GB to decode", "HDR");
    expect_refused(run("sobel " + quoted(at("big.pfm")) + " --out " + quoted(at("s2"))), "(PFM) needs ~19 GB to decode", "PFM");
    expect_refused(run("sobel " + quoted(at("wide.pam")) + " --out " + quoted(at("s3"))), "image 70000x2 is too large", "PAM");
    std::ofstream(at("text.png")) << "not an image";
    expect_refused(run("sobel " + quoted(at("text.png")) + " --out " + quoted(at("s4"))), "not a readable image (a damaged header, or not a format trnkit reads", "unknown format");
}

// Finding 5: EACCES and ENAMETOOLONG gave exit 2 "unexpected error".
TEST_F(HostileInputs, ErrnoPathsAreExitOneWithOneLine) {
    const std::string long_name = at(std::string(300, 'a') + ".png");
    Result r = run("sobel " + quoted(long_name) + " --out " + quoted(at("e1")));
    expect_refused(r, "File name too long", "ENAMETOOLONG");
    EXPECT_EQ(r.output.find("unexpected"), std::string::npos) << r.output;
    r = run(score_args(long_name));
    expect_refused(r, "File name too long", "ENAMETOOLONG --poses");
    // EACCES: a frame in a folder only its owner may enter, read by another user.
    fs::create_directories(at("locked"));
    fs::copy_file(at("DS/frame_000000.png"), at("locked/f.png"), fs::copy_options::overwrite_existing);
    ::chmod(at("locked").c_str(), 0700);
    ::chmod(root_.c_str(), 0755);
    std::string prefix;
    if (::geteuid() == 0) {
        if (std::system("command -v setpriv >/dev/null") != 0) GTEST_SKIP() << "root and no setpriv: cannot provoke EACCES";
        prefix = "setpriv --reuid=65534 --regid=65534 --clear-groups";
        if (run("--version", prefix).code != 0) GTEST_SKIP() << "trnkit cannot run as nobody here (build folder not readable)";
    }
    r = run("sobel " + quoted(at("locked/f.png")) + " --out /tmp/trnkit-hostile-eacces-" + std::to_string(::getpid()), prefix);
    expect_refused(r, "Permission denied", "EACCES");
    EXPECT_EQ(r.output.find("unexpected"), std::string::npos) << r.output;
}

// Finding 8: a yaw of 3e38 rad was accepted.
TEST_F(HostileInputs, PoseValuesNoMapHasAreRefused) {
    std::ofstream(at("yaw.csv")) << "x,y,yaw,scale\n100,100,3e38,1\n";
    expect_refused(run(score_args(at("yaw.csv"))), "yaw.csv:2: yaw 3e+38 is beyond 1000 rad", "yaw 3e38");
    std::ofstream(at("x.csv")) << "1e30,100,0,1\n";
    expect_refused(run(score_args(at("x.csv"))), "x.csv:1: x 1e+30 is beyond", "x 1e30");
}

// Finding 8: simulate --read accepted an altitude of -5 m that localize refuses: one check now.
TEST_F(HostileInputs, SimulateReadRefusesTheAltitudeLocalizeRefuses) {
    const std::string d = dataset_copy("altitude");
    std::ifstream in(d + "/metadata.csv");
    std::string header, first, rest, line;
    std::getline(in, header);
    std::getline(in, first);
    while (std::getline(in, line)) rest += line + "\n";
    in.close();
    // RelativeAltitude is the 4th column in the writer's order.
    std::size_t c = 0;
    for (int k = 0; k < 3; ++k) c = first.find(',', c) + 1;
    first.replace(c, first.find(',', c) - c, "-5");
    std::ofstream(d + "/metadata.csv") << header << "\n" << first << "\n" << rest;
    const std::string expect = "metadata.csv:2: RelativeAltitude -5 m is not a flight altitude";
    expect_refused(run("simulate --read " + quoted(d)), expect, "simulate --read");
    expect_refused(run("localize --backend cpu --dataset " + quoted(d) + " --out " + quoted(at("alt-out"))), expect, "localize");
}

// Finding 8: a UTF-8 byte order mark in a pose file gave a misleading "not a number"/"expected header".
TEST_F(HostileInputs, ByteOrderMarkInPoseFilesIsAccepted) {
    std::ofstream(at("bom.csv"), std::ios::binary) << "\xEF\xBB\xBFx,y,yaw,scale\n100,100,0,1\n";
    const Result r = run(score_args(at("bom.csv")));
    EXPECT_EQ(r.code, 0) << r.output;
}

// Finding 8: a 100 KB field came back as a 100 KB error line.
TEST_F(HostileInputs, ErrorMessagesQuoteAtMostAShortPieceOfTheInput) {
    std::ofstream(at("long.csv")) << "x,y,yaw,scale\n100," << std::string(100000, '9') << "x,0,1\n";
    Result r = run(score_args(at("long.csv")));
    expect_refused(r, "long.csv:2: line of 100009 bytes (at most 4096)", "100 KB line");
    EXPECT_LT(r.output.size(), 1000u) << r.output.size() << " bytes of error";
    std::ofstream(at("field.csv")) << "x,y,yaw,scale\n100," << std::string(3000, '9') << "x,0,1\n";
    r = run(score_args(at("field.csv")));
    expect_refused(r, "field.csv:2: field 2 '9999", "long field");
    EXPECT_LT(r.output.size(), 1000u) << r.output.size() << " bytes of error";
    EXPECT_NE(r.output.find("... (3001 bytes)"), std::string::npos) << r.output.substr(0, 400);
    // Control characters in a quoted field are escaped, never sent to the terminal raw.
    std::ofstream(at("esc.csv")) << "1,\x1b[31mred\r,0,1\n";
    const Result e = run(score_args(at("esc.csv")));
    EXPECT_EQ(e.output.find('\x1b'), std::string::npos) << e.output;
    EXPECT_NE(e.output.find("\\x1b[31mred"), std::string::npos) << e.output;
}

// Finding 8: localize reading a dataset while simulate replaced it exited 0 with a 28 m error.
// Here the rows' metadata.csv is replaced (renamed over, as simulate's swap does) mid-flight.
TEST_F(HostileInputs, DatasetReplacedWhileReadIsDetected) {
    const std::string d = dataset_copy("replaced");
    const trn::sim::FlightInfo info = trn::sim::read_flight_info(d + "/flight.json");
    trn::filter::AirFlightSource source(d, info.camera, info.metres_per_pixel, info.fps, 1);
    trn::filter::FlightSample s;
    ASSERT_TRUE(source.next(s));
    fs::copy_file(d + "/metadata.csv", d + "/metadata.new", fs::copy_options::overwrite_existing);
    fs::rename(d + "/metadata.new", d + "/metadata.csv");  // the same rows, but another file now
    try {
        while (source.next(s)) {
        }
        ADD_FAILURE() << "the replaced dataset was read to the end without an error";
    } catch (const trn::Error& e) {
        EXPECT_NE(std::string(e.what()).find("the dataset was replaced or changed while it was read"), std::string::npos) << e.what();
    }
    // Untouched, the same flight reads to its end.
    trn::filter::AirFlightSource again(d, info.camera, info.metres_per_pixel, info.fps, 1);
    std::size_t n = 0;
    while (again.next(s)) ++n;
    EXPECT_EQ(n, 20u);
}

}  // namespace
