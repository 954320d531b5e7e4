#pragma once
// Runs one program as the CLI fuzzer needs it: fork/exec with an argv (never a shell), in a given
// folder and environment, stdin from /dev/null, its own process group, resource limits, a wall-clock
// timeout that kills the whole group, and stdout/stderr captured (up to a cap).
#include <cstdint>
#include <string>
#include <vector>

namespace trn::fuzz {

struct RunLimits {
    double timeout_s = 20;             // wall clock; then SIGKILL to the process group
    long cpu_s = 25;                   // RLIMIT_CPU (SIGXCPU past it)
    std::uint64_t file_bytes = 64ull << 20;  // RLIMIT_FSIZE; SIGXFSZ is ignored so writes fail with EFBIG
    std::uint64_t address_bytes = 0;   // RLIMIT_AS; 0 = unlimited (sanitizer builds reserve terabytes)
};

struct RunResult {
    int exit_code = -1;    // when the program exited
    int signal = 0;        // when a signal ended it (SIGKILL after a timeout is reported as timed_out)
    bool timed_out = false;
    double wall_s = 0, cpu_s = 0;
    std::string out, err;  // captured, each cut at 64 KiB
};

RunResult run_sandboxed(const std::vector<std::string>& argv, const std::string& cwd, const std::vector<std::string>& env,
                        const RunLimits& limits);

// The argv as a shell-quoted line, for reports and reruns (it is never executed by us).
std::string quoted_command_line(const std::vector<std::string>& argv);

}  // namespace trn::fuzz
