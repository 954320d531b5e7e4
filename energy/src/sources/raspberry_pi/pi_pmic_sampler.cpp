// Live Raspberry Pi 5 PMIC power: `vcgencmd pmic_read_adc` run at every poll (pi_pmic.hpp).
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string>

#include "pi_pmic.hpp"
#include "text_input.hpp"
#include "trn/error.hpp"

namespace trn::energy::pmic {
namespace {

// Runs `program pmic_read_adc` with an empty environment and returns its standard output.
std::string run_vcgencmd(const std::string& program) {
    if (program.empty() || program.front() != '/') throw Error("pmic:vcgencmd: the program must be an absolute path, not '" + program + "'");
    int fd[2];
    if (pipe2(fd, O_CLOEXEC) != 0) throw Error("pmic:vcgencmd: pipe: " + std::string(std::strerror(errno)));
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_adddup2(&fa, fd[1], STDOUT_FILENO);
    std::string arg0 = program, arg1 = "pmic_read_adc";
    char* argv[] = {arg0.data(), arg1.data(), nullptr};
    char* envp[] = {nullptr};
    pid_t pid = 0;
    const int rc = posix_spawn(&pid, program.c_str(), &fa, nullptr, argv, envp);
    posix_spawn_file_actions_destroy(&fa);
    close(fd[1]);
    if (rc != 0) {
        close(fd[0]);
        throw Error("pmic:vcgencmd: cannot run '" + program + "' (" + std::strerror(rc) + ")");
    }
    std::string out;
    char buf[4096];
    for (;;) {
        const ssize_t n = read(fd[0], buf, sizeof buf);
        if (n > 0) out.append(buf, static_cast<std::size_t>(n));
        else if (n == 0 || errno != EINTR) break;
        if (out.size() > (1u << 20)) break;  // a PMIC dump is a few kB
    }
    close(fd[0]);
    int status = 0;
    while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
        throw Error("pmic:vcgencmd: '" + program + " pmic_read_adc' failed (" +
                    (WIFEXITED(status) ? "exit status " + std::to_string(WEXITSTATUS(status)) : std::string("killed by a signal")) + ")");
    return out;
}

class PmicSampler : public PowerSampler {
public:
    explicit PmicSampler(std::string program) : program_(std::move(program)) {
        trace_.source = "pmic:vcgencmd (" + program_ + ")";
        trace_.format = "pi5-pmic";
        trace_.kind = SampleKind::Instant;
        trace_.quantity = "sum of PMIC rails I x V (vcgencmd pmic_read_adc)";
    }
    std::string describe() const override { return trace_.source; }
    void poll(double t_s) override {
        if (!trace_.t.empty() && !(t_s > trace_.t.back())) throw Error(trace_.source + ": poll times must increase");
        const std::string out = run_vcgencmd(program_);
        Dump d;
        for (const auto& l : text::split_lines(out))
            if (const auto r = parse_line(l.text)) (r->current ? d.amps : d.volts)[r->rail] = r->value;
        const Sum s = sum(d);
        if (s.rails.empty())
            throw Error(trace_.source + ": 'pmic_read_adc' printed no rail with both a current and a voltage (not a Raspberry Pi 5?)");
        if (rails_.empty()) {
            rails_ = s.rails;
            std::string left;
            for (const auto& u : s.unpaired) left += (left.empty() ? "" : ", ") + u;
            trace_.notes.push_back("power = sum of I x V over the PMIC rails " + rails_ + (left.empty() ? "" : "; left out, without a partner reading: " + left) +
                                   "; " + kNotInSum);
        } else if (s.rails != rails_) {
            throw Error(trace_.source + ": the PMIC's rails changed between polls (" + rails_ + " then " + s.rails + ")");
        }
        trace_.t.push_back(t_s);
        trace_.w.push_back(s.w);
    }
    PowerTrace trace() const override { return trace_; }

private:
    std::string program_, rails_;
    PowerTrace trace_;
};

}  // namespace

std::unique_ptr<PowerSampler> make_sampler(const std::string& vcgencmd) { return std::make_unique<PmicSampler>(vcgencmd); }

}  // namespace trn::energy::pmic
