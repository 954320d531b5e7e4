#include "sandboxed_run.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <stdexcept>

namespace trn::fuzz {
namespace {

constexpr std::size_t kCaptureCap = 64 * 1024;

void set_limit(int what, rlim_t value) {
    const rlimit r{value, value};
    setrlimit(what, &r);
}

// Child side: only async-signal-safe calls between fork and exec.
[[noreturn]] void exec_child(char* const* argv, char* const* envp, const char* cwd, int out_fd, int err_fd, const RunLimits& l) {
    setpgid(0, 0);
    const int in = open("/dev/null", O_RDONLY);
    if (in < 0 || dup2(in, 0) < 0 || dup2(out_fd, 1) < 0 || dup2(err_fd, 2) < 0 || chdir(cwd) != 0) _exit(126);
    signal(SIGXFSZ, SIG_IGN);  // a file-size limit must show up as a write error the program reports
    signal(SIGPIPE, SIG_DFL);
    set_limit(RLIMIT_CORE, 0);
    set_limit(RLIMIT_CPU, static_cast<rlim_t>(l.cpu_s));
    set_limit(RLIMIT_FSIZE, static_cast<rlim_t>(l.file_bytes));
    if (l.address_bytes) set_limit(RLIMIT_AS, static_cast<rlim_t>(l.address_bytes));
    execve(argv[0], argv, envp);
    _exit(127);
}

}  // namespace

RunResult run_sandboxed(const std::vector<std::string>& args, const std::string& cwd, const std::vector<std::string>& env,
                        const RunLimits& limits) {
    std::vector<char*> argv, envp;
    for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    for (const auto& e : env) envp.push_back(const_cast<char*>(e.c_str()));
    argv.push_back(nullptr), envp.push_back(nullptr);
    int out[2], err[2];
    if (pipe2(out, O_CLOEXEC) != 0 || pipe2(err, O_CLOEXEC) != 0) throw std::runtime_error("pipe: " + std::string(std::strerror(errno)));
    const auto start = std::chrono::steady_clock::now();
    const pid_t pid = fork();
    if (pid < 0) throw std::runtime_error("fork: " + std::string(std::strerror(errno)));
    if (pid == 0) exec_child(argv.data(), envp.data(), cwd.c_str(), out[1], err[1], limits);
    setpgid(pid, pid);  // also from this side, so the kill below cannot race the child's own call
    close(out[1]), close(err[1]);

    RunResult r;
    pollfd fds[2] = {{out[0], POLLIN, 0}, {err[0], POLLIN, 0}};
    std::string* sinks[2] = {&r.out, &r.err};
    int open_pipes = 2;
    const auto deadline = start + std::chrono::duration<double>(limits.timeout_s);
    while (open_pipes > 0) {
        const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now()).count();
        if (left <= 0) {
            r.timed_out = true;
            kill(-pid, SIGKILL);
            break;
        }
        if (poll(fds, 2, static_cast<int>(std::min<long long>(left, 200))) < 0 && errno != EINTR) break;
        for (int i = 0; i < 2; ++i) {
            if (fds[i].fd < 0 || !(fds[i].revents & (POLLIN | POLLHUP | POLLERR))) continue;
            char buf[8192];
            const ssize_t n = read(fds[i].fd, buf, sizeof buf);
            if (n <= 0) {
                close(fds[i].fd), fds[i].fd = -1, --open_pipes;
            } else if (sinks[i]->size() < kCaptureCap) {
                sinks[i]->append(buf, static_cast<std::size_t>(std::min<ssize_t>(n, static_cast<ssize_t>(kCaptureCap - sinks[i]->size()))));
            }
        }
    }
    for (auto& f : fds)
        if (f.fd >= 0) close(f.fd);
    // The pipes can close before the program ends (it closed them, or a grandchild holds them):
    // wait for the exit under the same deadline.
    int status = 0;
    rusage use{};
    while (true) {
        const pid_t w = wait4(pid, &status, r.timed_out ? 0 : WNOHANG, &use);
        if (w == pid) break;
        if (w < 0 && errno != EINTR) break;
        if (w == 0) {
            if (std::chrono::steady_clock::now() >= deadline) {
                r.timed_out = true;
                kill(-pid, SIGKILL);
            } else {
                usleep(10000);
            }
        }
    }
    kill(-pid, SIGKILL);  // leftovers of the group (a plotting child, say) go too
    r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    r.cpu_s = static_cast<double>(use.ru_utime.tv_sec + use.ru_stime.tv_sec) + 1e-6 * static_cast<double>(use.ru_utime.tv_usec + use.ru_stime.tv_usec);
    if (WIFEXITED(status)) r.exit_code = WEXITSTATUS(status);
    if (WIFSIGNALED(status)) r.signal = WTERMSIG(status);
    if (r.signal == SIGXCPU) r.timed_out = true;      // ran past its CPU seconds: the same verdict as a timeout
    if (r.timed_out && r.signal == SIGKILL) r.signal = 0;  // our own kill, not a crash
    return r;
}

std::string quoted_command_line(const std::vector<std::string>& argv) {
    std::string line;
    for (const auto& a : argv) {
        if (!line.empty()) line += ' ';
        const bool plain = !a.empty() && a.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-+=.,:/@%") ==
                                             std::string::npos;
        if (plain) {
            line += a;
            continue;
        }
        line += "$'";
        for (unsigned char c : a) {
            if (c == '\'' || c == '\\') {
                line += '\\', line += static_cast<char>(c);
            } else if (c < 0x20 || c >= 0x7f) {
                char hex[8];
                std::snprintf(hex, sizeof hex, "\\x%02x", c);
                line += hex;
            } else {
                line += static_cast<char>(c);
            }
        }
        line += '\'';
    }
    return line;
}

}  // namespace trn::fuzz
