// Checks the write watch the CLI fuzzer relies on: with it preloaded, real programs (coreutils
// touch, mkdir, mv) that change files outside the allowed folder are logged, changes inside are not,
// and failed attempts are not.
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "sandboxed_run.hpp"

namespace fs = std::filesystem;

int main(int argc, char** argv) {
    if (argc != 2) return std::fprintf(stderr, "usage: %s write_watch.so\n", argv[0]), 2;
    const fs::path base = fs::temp_directory_path() / ("trn-watch-selftest-" + std::to_string(::getpid()));
    const fs::path allowed = base / "allowed", outside = base / "outside", log = base / "writes.log";
    fs::create_directories(allowed), fs::create_directories(outside);
    const std::vector<std::string> env = {"PATH=/usr/bin:/bin", "LD_PRELOAD=" + fs::absolute(argv[1]).string(),
                                          "TRN_WATCH_ALLOW=" + allowed.string(), "TRN_WATCH_LOG=" + log.string()};
    const auto run = [&](std::vector<std::string> args) { trn::fuzz::run_sandboxed(args, allowed.string(), env, {}); };
    run({"/usr/bin/touch", "inside.txt", (outside / "touched.txt").string()});
    run({"/bin/mkdir", "sub", (outside / "made").string()});
    run({"/bin/mv", "inside.txt", "../outside/moved.txt"});
    run({"/usr/bin/touch", (outside / "no/such/folder/x").string()});  // fails: nothing written
    std::ifstream in(log);
    std::stringstream ss;
    ss << in.rdbuf();
    const std::string got = ss.str();
    std::printf("watch log:\n%s", got.c_str());
    int bad = 0;
    for (const char* want : {"/outside/touched.txt", "/outside/made", "/outside/moved.txt"})
        if (got.find(want) == std::string::npos) std::printf("MISSING: a change of %s was not seen\n", want), ++bad;
    for (const char* unwanted : {"inside.txt\n", "/allowed/sub", "no/such/folder"})
        if (got.find(unwanted) != std::string::npos) std::printf("WRONG: %s was reported\n", unwanted), ++bad;
    fs::remove_all(base);
    return bad ? 1 : 0;
}
