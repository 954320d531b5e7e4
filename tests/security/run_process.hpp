#pragma once
// Runs a program as a user would, but with an argv (no shell between), so arguments may hold
// newlines, quotes and backquotes exactly as an attacker would pass them.
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

extern char** environ;

namespace trn::test {

struct ProcessResult {
    int code = -1;
    std::string output;  // stdout and stderr together
};

inline ProcessResult run_process(std::vector<std::string> argv, const std::string& output_file) {
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 1, output_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_adddup2(&actions, 1, 2);
    std::vector<char*> args;
    for (std::string& a : argv) args.push_back(a.data());
    args.push_back(nullptr);
    ProcessResult r;
    pid_t pid = 0;
    if (posix_spawn(&pid, args[0], &actions, nullptr, args.data(), environ) == 0) {
        int status = 0;
        if (waitpid(pid, &status, 0) == pid && WIFEXITED(status)) r.code = WEXITSTATUS(status);
    }
    posix_spawn_file_actions_destroy(&actions);
    std::ifstream f(output_file);
    std::ostringstream ss;
    ss << f.rdbuf();
    r.output = ss.str();
    return r;
}

}  // namespace trn::test
