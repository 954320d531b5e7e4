#pragma once
// Runs the trnkit executable as a user would (a real process) and keeps its exit code and output.
#include <sys/wait.h>

#include <cstdio>
#include <cstdlib>
#include <string>

#include "../common/peak_rss.hpp"  // kUnderAddressSanitizer

namespace trn::test {

struct CliResult {
    int code;
    std::string output;  // stdout and stderr together
};

// Runs a shell command line (tests use `ulimit`, redirections); the code is the exit status, or
// 128 + the signal that ended it.
inline CliResult run_shell(const std::string& line) {
    FILE* p = popen(line.c_str(), "r");
    CliResult r{-1, {}};
    if (!p) return r;
    char buf[4096];
    while (std::size_t n = std::fread(buf, 1, sizeof buf, p)) r.output.append(buf, n);
    const int status = pclose(p);
    r.code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
    return r;
}

// The trnkit under test: this build's, or TRNKIT_UNDER_TEST=/path/to/an/older/trnkit to show what a
// test catches there (a test program reads it, never the library).
inline std::string trnkit_exe() {
    const char* over = std::getenv("TRNKIT_UNDER_TEST");
    return over && *over ? over : TRNKIT_EXE;
}

// A shell prefix that runs what follows under an address-space limit of `kbytes` and a time limit.
// Under AddressSanitizer (whose shadow reserves terabytes of address space at start-up, so any
// ulimit -v aborts the run before main) the memory limit is left out and 5x the time is allowed:
// what the test checks (a refusal, an exit code) still runs. Every test that limits memory uses it.
inline std::string limited(long kbytes, int seconds) {
    if (kUnderAddressSanitizer) return "timeout " + std::to_string(5 * seconds) + " ";
    return "ulimit -v " + std::to_string(kbytes) + "; timeout " + std::to_string(seconds) + " ";
}

inline CliResult run_trnkit(const std::string& args) { return run_shell(trnkit_exe() + " " + args + " 2>&1"); }

}  // namespace trn::test
