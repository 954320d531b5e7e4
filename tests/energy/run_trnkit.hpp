#pragma once
// Runs the trnkit CLI as a user would (a real process) and keeps its exit code and output.
#include <cstdio>
#include <string>
#include <sys/wait.h>

namespace trn::energy::test {

struct CliResult {
    int code = -1;
    std::string output;  // stdout and stderr together
};

inline CliResult run_trnkit(const std::string& args) {
    const std::string cmd = std::string(TRNKIT_EXE) + " " + args + " 2>&1";
    FILE* p = popen(cmd.c_str(), "r");
    CliResult r;
    if (!p) return r;
    char buf[4096];
    while (std::size_t n = std::fread(buf, 1, sizeof buf, p)) r.output.append(buf, n);
    const int status = pclose(p);
    r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return r;
}

}  // namespace trn::energy::test
