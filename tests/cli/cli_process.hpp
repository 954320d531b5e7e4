#pragma once
// Runs the trnkit executable as a user would (a real process) and keeps its exit code and output.
#include <sys/wait.h>

#include <cstdio>
#include <string>

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

inline CliResult run_trnkit(const std::string& args) {
    const std::string cmd = std::string(TRNKIT_EXE) + " " + args + " 2>&1";
    FILE* p = popen(cmd.c_str(), "r");
    CliResult r{-1, {}};
    if (!p) return r;
    char buf[4096];
    while (std::size_t n = std::fread(buf, 1, sizeof buf, p)) r.output.append(buf, n);
    const int status = pclose(p);
    r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return r;
}

}  // namespace trn::test
