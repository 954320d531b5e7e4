// No lost data, no silently cut files (issue 15): every trnkit writer, run as a user runs it (real
// processes, real files, a full device, a file-size limit, SIGKILL), must either finish its
// output or leave the earlier one as it was, and must say so with a non-zero exit.
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <thread>

#include <opencv2/imgcodecs.hpp>

#include "../common/test_images.hpp"
#include "../energy/synthetic_run.hpp"
#include "trn/energy/markers.hpp"
#include "trn/energy/parsers.hpp"
#include "temp_folder_test.hpp"
#include "trn/error.hpp"
#include "trn/io/atomic_file.hpp"
#include "trn/io/output_folder.hpp"

namespace {
namespace fs = std::filesystem;

using Result = trn::test::CliResult;

Result shell(const std::string& line) { return trn::test::run_shell(line); }

const std::string kExe = TRNKIT_EXE;
Result trnkit(const std::string& args) { return shell(kExe + " " + args + " 2>&1"); }
// stdout to a full device, stderr (the message) into the result.
Result trnkit_to_full_stdout(const std::string& args) { return shell(kExe + " " + args + " 2>&1 >/dev/full"); }

std::string slurp(const fs::path& p) {
    std::ifstream f(p, std::ios::binary);
    std::ostringstream ss;
    ss << f.rdbuf();
    return ss.str();
}

// Every regular file under a folder, by relative path, with its bytes.
std::map<std::string, std::string> snapshot(const fs::path& folder) {
    std::map<std::string, std::string> files;
    for (const auto& e : fs::recursive_directory_iterator(folder))
        if (e.is_regular_file()) files[fs::relative(e.path(), folder).string()] = slurp(e.path());
    return files;
}

// Names in a folder that start with `prefix` (staging folders, temporaries).
std::vector<std::string> names_starting(const fs::path& folder, const std::string& prefix) {
    std::vector<std::string> out;
    for (const auto& e : fs::directory_iterator(folder))
        if (e.path().filename().string().rfind(prefix, 0) == 0) out.push_back(e.path().filename().string());
    return out;
}

std::size_t count_frames(const fs::path& folder) { return names_starting(folder, "frame_").size(); }

const std::string kSimulate = "simulate --scenario FC-300 --size-m 900";

class Writers : public trn::test::TempFolderTest {
protected:
    Writers() : TempFolderTest("trnkit_writers_", trnkit) {}
    // Map, template and `n` poses for `trnkit score`.
    std::string score_inputs(int n) {
        cv::imwrite(path("map.png"), trn::test::textured_image(240, 200, 1).mat());
        cv::imwrite(path("templ.png"), trn::test::textured_image(240, 200, 1).mat()(cv::Rect(100, 80, 40, 30)));
        std::ofstream poses(path("poses.csv"));
        poses << "x,y,yaw,scale\n";
        for (int i = 0; i < n; ++i) poses << 60 + i % 100 << "," << 60 + i / 100 << ",0.1,1\n";
        return "score --backend cpu --map " + path("map.png") + " --template " + path("templ.png") + " --poses " + path("poses.csv");
    }
};

TEST_F(Writers, SimulateWithABadOptionLeavesTheEarlierDatasetByteIdentical) {
    simulate("flight", 6);
    const auto before = snapshot(path("flight"));
    ASSERT_GE(before.size(), 9u);  // map, metadata, flight.json, 6 frames
    const Result r = trnkit(kSimulate + " --frames 4 --noise -1 --out " + path("flight"));
    EXPECT_NE(r.code, 0) << r.output;
    EXPECT_EQ(snapshot(path("flight")), before) << r.output;
    EXPECT_TRUE(names_starting(dir_, "flight.partial").empty());
}

TEST_F(Writers, SimulateAgainWithFewerFramesLeavesNoStaleFrames) {
    simulate("flight", 8);
    ASSERT_EQ(count_frames(path("flight")), 8u);
    simulate("flight", 3);
    EXPECT_EQ(count_frames(path("flight")), 3u);
    const Result r = trnkit("simulate --read " + path("flight"));
    EXPECT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find(": 3 frames"), std::string::npos) << r.output;
    EXPECT_TRUE(names_starting(dir_, "flight.").empty());  // no staging or old copy left
}

TEST_F(Writers, SimulateKilledMidRunLeavesTheEarlierDatasetAndNoFolderThatReadsAsValid) {
    simulate("flight", 4);
    const auto before = snapshot(path("flight"));
    const std::size_t frames_before = count_frames(path("flight"));
    const pid_t pid = ::fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) {
        std::freopen("/dev/null", "w", stdout);
        std::freopen("/dev/null", "w", stderr);
        const std::string out = path("flight");
        ::execl(TRNKIT_EXE, TRNKIT_EXE, "simulate", "--scenario", "FC-300", "--size-m", "900", "--frames", "5000", "--out", out.c_str(),
                static_cast<char*>(nullptr));
        ::_exit(127);
    }
    // Kill it once it has written a few frames (wherever it writes them).
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    auto frames_written = [&] {
        std::size_t n = 0;
        for (const auto& e : fs::recursive_directory_iterator(dir_))
            if (e.path().filename().string().rfind("frame_", 0) == 0) ++n;
        return n;
    };
    while (frames_written() < frames_before + 3 && std::chrono::steady_clock::now() < deadline)
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    ::kill(pid, SIGKILL);
    int status = 0;
    ::waitpid(pid, &status, 0);
    ASSERT_TRUE(WIFSIGNALED(status)) << "simulate finished before it could be killed";
    EXPECT_EQ(snapshot(path("flight")), before);
    EXPECT_EQ(trnkit("simulate --read " + path("flight")).code, 0);
    // Whatever the killed run left beside it is not a dataset.
    for (const std::string& left : names_starting(dir_, "flight.")) {
        const Result r = trnkit("simulate --read " + path(left));
        EXPECT_NE(r.code, 0) << left << " reads as a valid dataset:\n" << r.output;
    }
}

TEST_F(Writers, SimulateRemovesTheStagingFolderOfAKilledRun) {
    const pid_t dead = ::fork();  // a process id that is surely not running any more
    if (dead == 0) ::_exit(0);
    ::waitpid(dead, nullptr, 0);
    const std::string left = path("flight.partial-" + std::to_string(dead));
    fs::create_directories(left);
    std::ofstream(left + "/.trnkit-staging") << "trnkit simulate: staging folder\n";  // what every staging folder carries
    std::ofstream(left + "/frame_000000.png") << "half a frame";
    fs::create_directories(path("flight.partial-notapid"));  // not a staging name: left alone
    simulate("flight", 2);
    EXPECT_FALSE(fs::exists(left));
    EXPECT_TRUE(fs::exists(path("flight.partial-notapid")));
}

TEST_F(Writers, ReadRefusesAMetadataFileWithFewerRowsThanFlightJsonDeclares) {
    simulate("flight", 5);
    std::string csv = slurp(path("flight/metadata.csv"));
    csv.erase(csv.rfind('\n', csv.size() - 2) + 1);  // drop the last row
    std::ofstream(path("flight/metadata.csv"), std::ios::binary | std::ios::trunc) << csv;
    const Result r = trnkit("simulate --read " + path("flight"));
    EXPECT_NE(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("4 rows, but flight.json declares 5"), std::string::npos) << r.output;
}

TEST_F(Writers, SimulateRefusesAForeignFolderUnlessForced) {
    fs::create_directories(path("mine"));
    std::ofstream(path("mine/notes.txt")) << "my notes\n";
    const Result refused = trnkit(kSimulate + " --frames 3 --out " + path("mine"));
    EXPECT_NE(refused.code, 0);
    EXPECT_NE(refused.output.find("--force"), std::string::npos) << refused.output;
    EXPECT_NE(refused.output.find(path("mine")), std::string::npos) << refused.output;
    EXPECT_FALSE(fs::exists(path("mine/metadata.csv")));
    const Result forced = trnkit(kSimulate + " --frames 3 --force --out " + path("mine"));
    ASSERT_EQ(forced.code, 0) << forced.output;
    EXPECT_EQ(slurp(path("mine/notes.txt")), "my notes\n");
    EXPECT_EQ(count_frames(path("mine")), 3u);
    EXPECT_EQ(trnkit("simulate --read " + path("mine")).code, 0);
    // Still not simulate's own folder: never replaced whole, so the next run asks again.
    EXPECT_NE(trnkit(kSimulate + " --frames 3 --out " + path("mine")).code, 0);
    EXPECT_EQ(slurp(path("mine/notes.txt")), "my notes\n");
}

TEST_F(Writers, ScoreToAFullDeviceFailsNamingIt) {
    const Result r = trnkit(score_inputs(5) + " -o /dev/full");
    EXPECT_NE(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("/dev/full"), std::string::npos) << r.output;
}

TEST_F(Writers, ScorePastAFileSizeLimitFailsAndLeavesTheEarlierFile) {
    const std::string score = score_inputs(400);  // ~25 KB of CSV, over the 1 KiB limit
    std::ofstream(path("scores.csv")) << "earlier\n";
    const Result r = shell("ulimit -f 1; exec " + kExe + " " + score + " -o " + path("scores.csv") + " 2>&1");
    EXPECT_NE(r.code, 0) << r.output;
    EXPECT_NE(r.output.find(path("scores.csv")), std::string::npos) << r.output;
    EXPECT_EQ(slurp(path("scores.csv")), "earlier\n");
    EXPECT_TRUE(names_starting(dir_, "scores.csv.").empty());  // no temporary left
    // Without the limit the same command writes the whole file.
    const Result ok = trnkit(score + " -o " + path("scores.csv"));
    ASSERT_EQ(ok.code, 0) << ok.output;
    const std::string csv = slurp(path("scores.csv"));
    EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 401);
}

TEST_F(Writers, ScoreToAFullStandardOutputFails) {
    const Result r = trnkit_to_full_stdout(score_inputs(5));
    EXPECT_NE(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("standard output"), std::string::npos) << r.output;
}

TEST_F(Writers, EnergyIntegrateToAFullStandardOutputFails) {
    using namespace trn::energy;
    const test::Timeline tl = test::make_timeline(6, 0.05, 0.05);
    std::ofstream(path("markers.csv")) << format_markers(tl.markers);
    const PowerTrace tr = test::sample_trace(tl.markers, test::TraceClock{}, tl.t0 - 0.2, tl.t0 + 2.5, 1e-3, 1.5, 2.0, 0, true);
    std::ofstream(path("power.log")) << format_trnkit_power(tr);
    const std::string cmd = "energy integrate " + path("power.log") + " --markers " + path("markers.csv");
    const Result ok = shell(kExe + " " + cmd + " 2>/dev/null");
    ASSERT_EQ(ok.code, 0) << ok.output;
    ASSERT_NE(ok.output.find("\"frames\""), std::string::npos) << ok.output;  // the JSON went to stdout
    const Result full = trnkit_to_full_stdout(cmd);
    EXPECT_NE(full.code, 0) << full.output;
    EXPECT_NE(full.output.find("standard output: write failed"), std::string::npos) << full.output;
}

TEST_F(Writers, LocalizeIntoAnExistingFileFailsBeforeTheRun) {
    simulate("flight", 4);
    std::ofstream(path("result")) << "a file\n";
    const Result r = trnkit("localize --dataset " + path("flight") + " --backend cpu --no-plots --out " + path("result"));
    EXPECT_NE(r.code, 0) << r.output;
    EXPECT_NE(r.output.find(path("result") + ": is a file, not a folder"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("localizing"), std::string::npos) << "the run started before the output was checked:\n" << r.output;
    EXPECT_EQ(slurp(path("result")), "a file\n");
}

TEST_F(Writers, LocalizeRefusesAFolderOfAnotherCommand) {
    simulate("flight", 4);
    const Result r = trnkit("localize --dataset " + path("flight") + " --backend cpu --no-plots --out " + path("flight"));
    EXPECT_NE(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("it is one of trnkit simulate"), std::string::npos) << r.output;
}

// The library pieces directly: what the commands above are built on.
TEST_F(Writers, WriteFileAtomicReplacesWholeOrNotAtAll) {
    trn::io::write_file_atomic(path("a.txt"), "first\n");
    trn::io::write_file_atomic(path("a.txt"), "second\n");
    EXPECT_EQ(slurp(path("a.txt")), "second\n");
    EXPECT_THROW(trn::io::write_file_atomic(path("no/such/folder/a.txt"), "x"), trn::Error);
    EXPECT_THROW(trn::io::write_file_atomic("/dev/full", "x"), trn::Error);
    fs::create_directories(path("d"));
    EXPECT_THROW(trn::io::write_file_atomic(path("d"), "x"), trn::Error);
    EXPECT_EQ(names_starting(dir_, "a.txt.").size(), 0u);
    // A link to a file stays a link; its target gets the new bytes.
    fs::create_symlink(path("a.txt"), path("link.txt"));
    trn::io::write_file_atomic(path("link.txt"), "third\n");
    EXPECT_TRUE(fs::is_symlink(path("link.txt")));
    EXPECT_EQ(slurp(path("a.txt")), "third\n");
}

TEST_F(Writers, OutputChecksNameTheOptionAndThePath) {
    fs::create_directories(path("d"));
    auto message = [](auto&& f) {
        try {
            f();
        } catch (const trn::Error& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    EXPECT_EQ(message([&] { trn::io::check_output_file(path("d"), "--csv"); }), "--csv " + path("d") + ": is a folder, not a file");
    EXPECT_NE(message([&] { trn::io::check_output_file(path("none/x.csv"), "--csv"); }).find("does not exist"), std::string::npos);
    EXPECT_EQ(message([&] { trn::io::check_output_file(path("x.csv")); }), "no error");
    EXPECT_EQ(message([&] { trn::io::check_output_file("/dev/null"); }), "no error");
    using trn::io::FolderState;
    EXPECT_EQ(trn::io::check_output_folder(path("new/deeper"), "demo", false), FolderState::Absent);
    EXPECT_EQ(trn::io::check_output_folder(path("d"), "demo", false), FolderState::Empty);
    trn::io::open_output_folder(path("d"), "demo", false);
    EXPECT_EQ(trn::io::check_output_folder(path("d"), "demo", false), FolderState::OwnOutput);
    EXPECT_NE(message([&] { trn::io::check_output_folder(path("d"), "localize", false); }).find("it is one of trnkit demo"), std::string::npos);
    EXPECT_EQ(trn::io::check_output_folder(path("d"), "localize", true), FolderState::Foreign);
    trn::io::open_output_folder(path("d"), "localize", true);  // --force adopts the folder
    EXPECT_EQ(trn::io::check_output_folder(path("d"), "localize", false), FolderState::OwnOutput);
}

// Several processes open one folder at once (experiment jobs on GNU parallel or Slurm): a marker
// another process is still writing is not someone else's file; anything else still is.
TEST_F(Writers, OutputFolderBeingMarkedByAnotherProcessIsEmpty) {
    using trn::io::FolderState;
    fs::create_directories(path("d"));
    std::ofstream(path("d/.trnkit-output.tmp-4242-0")) << "trnkit experiment sampling\n";
    EXPECT_EQ(trn::io::check_output_folder(path("d"), "experiment sampling", false), FolderState::Empty);
    trn::io::open_output_folder(path("d"), "experiment sampling", false);
    EXPECT_EQ(trn::io::check_output_folder(path("d"), "experiment sampling", false), FolderState::OwnOutput);
    fs::create_directories(path("e"));
    std::ofstream(path("e/.trnkit-output.tmp-4242-0")) << "x";
    std::ofstream(path("e/notes.txt")) << "x";
    EXPECT_THROW(trn::io::check_output_folder(path("e"), "experiment sampling", false), trn::Error);
}

}  // namespace
