// CLI argument fuzzer: runs the real trnkit binary (fork/exec, no shell) with random option/value
// combinations against every subcommand its --help lists, in a temporary sandbox, each run under a
// timeout and rlimits (CPU seconds, file size, address space). A run FAILS this test when it
//   - dies from a signal (a crash; SIGXCPU/timeout kills are judged as hangs below),
//   - hangs: runs past the timeout although no option that scales the work was fuzzed,
//   - writes outside the sandbox (seen by the write_watch LD_PRELOAD library),
//   - executes text from an argument (a file named PWNED appears),
//   - exits with a code nobody documented. Documented codes: 0 success, 1 trn::Error (one line
//     "trnkit: error: ..."), 2 unexpected error, and CLI11's parse errors (CLI::ExitCodes in
//     CLI/Error.hpp 2.x): 100 IncorrectConstruction, 101 BadNameString, 102 OptionAlreadyAdded,
//     103 FileError, 104 ConversionError, 105 ValidationError, 106 RequiredError, 107 RequiresError,
//     108 ExcludesError, 109 ExtrasError, 110 ConfigError, 111 InvalidError, 112 HorribleError,
//     113 OptionNotFound, 114 ArgumentMismatch, 127 BaseClass.
// Everything else is a FINDING, printed and written to --report, not a failure (yet): exit 2,
// an exit-1 message that is not one line, exit 0 although an output went to a full device or
// under a file, a run past the timeout after a work-size option was fuzzed, a writer that
// replaced a device path by a regular file.
//
// usage: trn_cli_fuzz --trnkit EXE [--watch LIB.so] [--seed N] [--cases N] [--seconds S]
//                     [--timeout S] [--no-as-limit] [--long] [--case K] [--report FILE] [--keep]
// The sequence of cases depends only on --seed (case K is the same with any --cases/--seconds);
// `--case K` reruns one case and prints its command line and output.
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <signal.h>
#include <sstream>

#include "cli_fixtures.hpp"
#include "cli_fuzz_plan.hpp"
#include "cli_options.hpp"
#include "sandboxed_run.hpp"
#include "../../fuzz/xorshift_rng.hpp"
#include "trn/io/atomic_file.hpp"

namespace fs = std::filesystem;
using namespace trn::fuzz;

namespace {

using Rng = XorshiftRng;

struct Settings {
    std::string trnkit, watch, report, corpus = TRN_FUZZ_CORPUS_DIR;
    std::uint64_t seed = 1;
    long cases = 1000000, only_case = -1;
    double seconds = 45, timeout = 20;
    bool as_limit = true, long_run = false, keep = false;
};

struct Case {
    std::vector<std::string> path;                          // subcommand path
    std::vector<std::pair<std::string, std::string>> args;  // option (or positional name) -> value
    std::set<std::string> fuzzed;                           // options whose value the fuzzer chose
    std::set<std::string> flags;                            // options that take no value
};

struct Finding {
    std::string kind, command, detail;
    int count = 0;
};

bool is_failure(const std::string& kind) { return kind.rfind("FAIL", 0) == 0; }

std::string join(const std::vector<std::string>& v) {
    std::string s;
    for (const auto& x : v) s += (s.empty() ? "" : " ") + x;
    return s;
}

// Every command reachable from `trnkit --help`, with its options.
std::vector<CliCommand> discover(const Settings& st, const std::vector<std::string>& env, const std::string& cwd, const RunLimits& limits) {
    std::vector<CliCommand> all;
    std::vector<std::vector<std::string>> todo = {{}};
    while (!todo.empty()) {
        const auto path = todo.back();
        todo.pop_back();
        std::vector<std::string> argv = {st.trnkit};
        argv.insert(argv.end(), path.begin(), path.end());
        argv.push_back("--help");
        const RunResult r = run_sandboxed(argv, cwd, env, limits);
        if (r.exit_code != 0) throw std::runtime_error(quoted_command_line(argv) + " failed: " + r.err);
        CliCommand c = parse_cli_help(r.out, path);
        for (const auto& sub : c.subcommands) {
            auto p = path;
            p.push_back(sub);
            todo.push_back(p);
        }
        all.push_back(c);
    }
    return all;
}

Case make_case(std::uint64_t seed, long index, const std::vector<CliCommand>& commands, const std::map<std::string, CommandPlan>& plans,
               const NastyValues& values) {
    Rng r{((seed * 0x9e3779b97f4a7c15ull) ^ (static_cast<std::uint64_t>(index + 1) * 0xd1b54a32d192ed03ull)) | 1};
    for (int i = 0; i < 4; ++i) r.next();
    // pick a command by weight; now and then one that needs a subcommand (a CLI11 error)
    std::vector<const CliCommand*> pool;
    for (const auto& c : commands) {
        const auto it = plans.find(join(c.path));
        const int w = !c.subcommands.empty() ? 0 : it == plans.end() ? 2 : it->second.weight;
        for (int k = 0; k < w; ++k) pool.push_back(&c);
    }
    const CliCommand& cmd = r.chance(3) ? commands[r.below(commands.size())] : *pool[r.below(pool.size())];
    Case c;
    c.path = cmd.path;
    const auto plan_it = plans.find(join(cmd.path));
    const CommandPlan plan = plan_it == plans.end() ? CommandPlan{} : plan_it->second;
    c.args = plan.base;
    for (const auto& o : cmd.options)
        if (!o.takes_value) c.flags.insert(o.name);
    const std::vector<std::string> all = values.all();
    const auto pick = [&](const std::vector<std::string>& v) { return v[r.below(v.size())]; };
    // Mostly values of the option's kind (a number for INT, a file for --map), so runs get past
    // the CLI11 type check and into trnkit's own validation; sometimes anything.
    const auto value_for = [&](const CliOption& o) {
        const bool path_like = o.name == "--map" || o.name == "--template" || o.name == "--poses" || o.name == "--markers" ||
                               o.name == "--dataset" || o.name == "--read" || o.name == "--sysfs-root" || is_output_option(o.name) ||
                               o.name.rfind("-", 0) != 0;
        if (!o.choices.empty() && r.chance(40)) return pick(o.choices);
        if (o.numeric && r.chance(80)) return pick(values.numbers);
        if (path_like && !o.numeric && r.chance(60)) return pick(values.files);
        if (!o.numeric && r.chance(30)) return pick(values.words);
        return pick(all);
    };
    const auto option_named = [&](const std::string& name) {
        for (const auto* list : {&cmd.options, &cmd.positionals})
            for (const auto& o : *list)
                if (o.name == name) return o;
        CliOption unknown;
        unknown.name = name, unknown.takes_value = true;
        return unknown;
    };
    const auto set = [&](const std::string& name, const std::string& value, bool replace) {
        if (plan.pinned.count(name)) return;
        c.fuzzed.insert(name);
        if (replace)
            for (auto& a : c.args)
                if (a.first == name) return void(a.second = value);
        c.args.emplace_back(name, value);
    };
    const int mutations = 1 + static_cast<int>(r.below(3));
    for (int m = 0; m < mutations; ++m) {
        const std::size_t what = r.below(100);
        if (what < 60 && !cmd.options.empty()) {
            const CliOption& o = cmd.options[r.below(cmd.options.size())];
            set(o.name, o.takes_value ? value_for(o) : "", true);
        } else if (what < 75 && !cmd.positionals.empty()) {
            const CliOption& p = cmd.positionals[r.below(cmd.positionals.size())];
            set(p.name, value_for(p), true);
        } else if (what < 81 && !c.args.empty()) {
            const std::size_t k = r.below(c.args.size());
            if (!plan.pinned.count(c.args[k].first)) c.fuzzed.insert(c.args[k].first), c.args.erase(c.args.begin() + static_cast<long>(k));
        } else if (what < 88) {
            set(r.chance(50) ? "--no-such-option" : "extra-positional", pick(all), false);
        } else if (what < 96 && !c.args.empty()) {
            const auto a = c.args[r.below(c.args.size())];
            set(a.first, a.first.rfind("-", 0) == 0 ? value_for(option_named(a.first)) : a.second, false);  // given twice
        } else if (!cmd.options.empty()) {
            const CliOption& o = cmd.options[r.below(cmd.options.size())];
            set(o.name + "=", o.takes_value ? value_for(o) : pick(all), true);  // "--flag=value", "--opt=" forms
        }
    }
    return c;
}

std::vector<std::string> to_argv(const Settings& st, const Case& c, Rng& r) {
    std::vector<std::string> argv = {st.trnkit};
    argv.insert(argv.end(), c.path.begin(), c.path.end());
    std::vector<std::string> positionals;
    for (const auto& [name, value] : c.args) {
        if (name.rfind("-", 0) != 0) {
            positionals.push_back(value);
        } else if (name.back() == '=') {
            argv.push_back(name + value);
        } else if (c.flags.count(name)) {
            argv.push_back(name);
        } else if (value.empty() && name.rfind("--", 0) == 0 && r.chance(70)) {
            argv.push_back(name);  // a flag, or an option left without its value
        } else if (name.rfind("--", 0) == 0 && (r.chance(40) || value.empty() || value[0] == '-')) {
            argv.push_back(name + "=" + value);
        } else {
            argv.push_back(name), argv.push_back(value);
        }
    }
    bool dashed = false;
    for (const auto& p : positionals) dashed = dashed || (!p.empty() && p[0] == '-');
    if (dashed) argv.push_back("--");
    argv.insert(argv.end(), positionals.begin(), positionals.end());
    return argv;
}

bool documented_exit(int code) { return code == 0 || code == 1 || code == 2 || (code >= 100 && code <= 114) || code == 127; }

// The error a program ends with is its last line (progress output may come before it).
std::string last_line(std::string s) {
    while (!s.empty() && s.back() == '\n') s.pop_back();
    const auto nl = s.rfind('\n');
    return nl == std::string::npos ? s : s.substr(nl + 1);
}

// Message text with the sandbox, numbers and quoted values blurred, so one bug is one finding.
std::string blur(std::string s, const std::string& root) {
    for (std::size_t p; (p = s.find(root)) != std::string::npos;) s.replace(p, root.size(), "SANDBOX");
    s = std::regex_replace(s, std::regex("'[^']*'"), "'…'");
    s = std::regex_replace(s, std::regex("[-+]?[0-9][0-9.e+-]*"), "N");
    return s.substr(0, 160);
}

bool is_symlink(const std::string& p) {
    struct stat st {};
    return lstat(p.c_str(), &st) == 0 && S_ISLNK(st.st_mode);
}

bool pwned(const Sandbox& s) {
    for (const auto& d : {s.run_dir, s.root, s.fx, s.root + "/home", s.root + "/tmp"})
        if (fs::exists(d + "/PWNED")) return true;
    return false;
}

// Judges one finished run; returns the (kind, detail) pairs it earned.
std::vector<std::pair<std::string, std::string>> judge(const Case& c, const std::vector<std::string>& argv, const RunResult& r,
                                                       const Sandbox& s, const std::map<std::string, CommandPlan>& plans) {
    std::vector<std::pair<std::string, std::string>> out;
    const auto plan_it = plans.find(join(c.path));
    bool work_fuzzed = false;
    for (const auto& f : c.fuzzed) {
        std::string name = f;
        if (!name.empty() && name.back() == '=') name.pop_back();
        work_fuzzed = work_fuzzed || (plan_it != plans.end() && plan_it->second.work.count(name));
    }
    if (r.signal) out.push_back({"FAIL crash", std::string("signal ") + strsignal(r.signal) + ": " + last_line(r.err)});
    if (r.timed_out)
        out.push_back({work_fuzzed ? "FINDING unbounded work" : "FAIL hang",
                       "ran past the limit (" + std::to_string(static_cast<int>(r.wall_s)) + " s wall, " +
                           std::to_string(static_cast<int>(r.cpu_s)) + " s CPU)"});
    std::ifstream watch(s.watch_log);
    for (std::string line; std::getline(watch, line);) out.push_back({"FAIL write outside the sandbox", line});
    if (pwned(s)) out.push_back({"FAIL executed argument text", "a file named PWNED appeared"});
    if (!r.signal && !r.timed_out) {
        if (!documented_exit(r.exit_code)) out.push_back({"FAIL undocumented exit code", std::to_string(r.exit_code) + ": " + last_line(r.err)});
        if (r.exit_code == 2) out.push_back({"FINDING exit 2 (unexpected error)", blur(last_line(r.err), s.root)});
        if (r.exit_code == 1) {
            // Progress lines may come first; the error itself is the last line, whole, and only once.
            std::string err = r.err;
            while (!err.empty() && err.back() == '\n') err.pop_back();
            const std::string last = last_line(err);
            const bool one_line = last.rfind("trnkit: error: ", 0) == 0 && err.find("trnkit: error: ") == err.size() - last.size();
            if (!one_line) out.push_back({"FINDING error is not one line", blur(r.err.substr(0, 200), s.root)});
        }
        if (r.exit_code == 0)
            for (const auto& [name, value] : c.args)
                if (is_output_option(name) && (value == s.fx + "/dev-full" || value.find("/below") != std::string::npos))
                    out.push_back({"FINDING exit 0 although the output could not be written", name + " " + value.substr(s.fx.size() + 1)});
    }
    for (const char* dev : {"dev-full", "dev-null"})
        if (!is_symlink(s.fx + "/" + dev))
            out.push_back({"FINDING writer replaced a device path by a regular file",
                           std::string("fx/") + dev + " (as root, --out /dev/null would replace the system's /dev/null)"});
    (void)argv;
    return out;
}

Settings parse_settings(int argc, char** argv) {
    Settings st;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        const auto next = [&]() -> std::string {
            if (i + 1 >= argc) throw std::runtime_error(a + " needs a value");
            return argv[++i];
        };
        if (a == "--trnkit") st.trnkit = next();
        else if (a == "--watch") st.watch = next();
        else if (a == "--report") st.report = next();
        else if (a == "--corpus") st.corpus = next();
        else if (a == "--seed") st.seed = std::stoull(next());
        else if (a == "--cases") st.cases = std::stol(next());
        else if (a == "--case") st.only_case = std::stol(next());
        else if (a == "--seconds") st.seconds = std::stod(next());
        else if (a == "--timeout") st.timeout = std::stod(next());
        else if (a == "--no-as-limit") st.as_limit = false;
        else if (a == "--long") st.long_run = true;
        else if (a == "--keep") st.keep = true;
        else throw std::runtime_error("unknown argument " + a);
    }
    if (st.trnkit.empty()) throw std::runtime_error("--trnkit EXE is required");
    st.trnkit = fs::absolute(st.trnkit).string();
    if (!st.watch.empty()) st.watch = fs::absolute(st.watch).string();
    return st;
}

std::vector<std::string> child_environment(const Settings& st, const std::string& root, const std::string& watch_log) {
    std::vector<std::string> env = {"PATH=/usr/local/bin:/usr/bin:/bin", "LC_ALL=C", "HOME=" + root + "/home", "TMPDIR=" + root + "/tmp",
                                    "XDG_CACHE_HOME=" + root + "/cache"};
    // In a sanitizer build a report must end the run by a signal (abort), not by exit code 1,
    // which would pass for a trn::Error; later options override the inherited ones.
    std::string asan = "detect_leaks=0:verify_asan_link_order=0:abort_on_error=1", ubsan = "halt_on_error=1:abort_on_error=1";
    for (const char* keep : {"OCL_ICD_VENDORS", "OCL_ICD_FILENAMES", "LD_LIBRARY_PATH", "VK_ICD_FILENAMES", "POCL_DEVICES"})
        if (const char* v = std::getenv(keep)) env.push_back(std::string(keep) + "=" + v);
    if (const char* v = std::getenv("ASAN_OPTIONS")) asan = std::string(v) + ":" + asan;
    if (const char* v = std::getenv("UBSAN_OPTIONS")) ubsan = std::string(v) + ":" + ubsan;
    env.push_back("ASAN_OPTIONS=" + asan);
    env.push_back("UBSAN_OPTIONS=" + ubsan);
    if (!st.watch.empty()) {
        env.push_back("LD_PRELOAD=" + st.watch);
        env.push_back("TRN_WATCH_ALLOW=" + root + ":/dev/null:/dev/dri:/dev/shm");
        env.push_back("TRN_WATCH_LOG=" + watch_log);
    }
    return env;
}

}  // namespace

int main(int argc, char** argv) try {
    const Settings st = parse_settings(argc, argv);
    RunLimits limits;
    limits.timeout_s = st.timeout;
    limits.cpu_s = static_cast<long>(st.timeout) + 5;
    if (st.as_limit) limits.address_bytes = 8ull << 30;

    // Fixtures are made without the watch (they write inside the sandbox by design).
    Settings setup = st;
    setup.watch.clear();
    const std::vector<std::string> setup_env = child_environment(setup, "/nonexistent-before-setup", "");
    Sandbox s = make_sandbox(st.trnkit, st.corpus, setup_env, limits);
    const std::vector<std::string> env = child_environment(st, s.root, s.watch_log);
    const std::vector<CliCommand> commands = discover(st, env, s.run_dir, limits);
    const auto plans = command_plans(s.fx, s.t0, s.t1);
    const auto values = nasty_values(s.fx, st.long_run);
    std::printf("cli fuzz: seed %llu, %zu commands, %zu values, sandbox %s, watch %s\n", static_cast<unsigned long long>(st.seed), commands.size(),
                values.all().size(), s.root.c_str(), st.watch.empty() ? "off" : "on");
    for (const auto& c : commands)
        if (c.subcommands.empty() && !plans.count(join(c.path))) std::printf("  note: no plan for '%s': fuzzed from no arguments\n", join(c.path).c_str());

    std::map<std::string, Finding> findings;  // by kind + command + blurred detail
    std::string fingerprint = fixture_fingerprint(s);
    const auto start = std::chrono::steady_clock::now();
    long ran = 0, failures = 0;
    std::map<int, long> exits;
    for (long k = st.only_case >= 0 ? st.only_case : 0; k < (st.only_case >= 0 ? st.only_case + 1 : st.cases); ++k) {
        if (st.only_case < 0 && std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() > st.seconds) break;
        const Case c = make_case(st.seed, k, commands, plans, values);
        Rng form{(st.seed ^ (static_cast<std::uint64_t>(k) * 0x2545f4914f6cdd1dull)) | 1};
        const auto args = to_argv(st, c, form);
        fs::remove_all(s.run_dir);
        fs::create_directories(s.run_dir);
        fs::remove(s.watch_log);
        const RunResult r = run_sandboxed(args, s.run_dir, env, limits);
        ++ran;
        ++exits[r.signal ? -r.signal : r.timed_out ? -1000 : r.exit_code];
        const std::string line = quoted_command_line(args);
        if (st.only_case >= 0)
            std::printf("case %ld: %s\nexit %d signal %d timed_out %d wall %.2f s\n--- stdout\n%s--- stderr\n%s", k, line.c_str(), r.exit_code, r.signal,
                        r.timed_out, r.wall_s, r.out.c_str(), r.err.c_str());
        for (const auto& [kind, detail] : judge(c, args, r, s, plans)) {
            Finding& f = findings[kind + "|" + join(c.path) + "|" + detail];
            if (f.count++ == 0) {
                f.kind = kind, f.command = line, f.detail = detail;
                std::printf("%s [case %ld]: %s\n    %s\n", kind.c_str(), k, line.c_str(), detail.c_str());
            }
            failures += is_failure(kind);
        }
        if (fixture_fingerprint(s) != fingerprint) {
            restore_fixtures(s);
            fingerprint = fixture_fingerprint(s);
        }
        std::fflush(stdout);
    }
    std::printf("\n%ld run(s) in %.0f s; outcomes:", ran,
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    for (const auto& [code, n] : exits)
        std::printf(" %s=%ld", code == -1000 ? "timeout" : code < 0 ? ("signal" + std::to_string(-code)).c_str() : ("exit" + std::to_string(code)).c_str(), n);
    std::printf("\n%zu distinct finding(s), %ld failing run(s)\n", findings.size(), failures);
    if (!st.report.empty()) {
        std::ostringstream md;
        md << "# trnkit CLI fuzz report (seed " << st.seed << ", " << ran << " runs)\n\n";
        for (const auto& [key, f] : findings)
            md << "- **" << f.kind << "** (" << f.count << "x) — " << f.detail << "\n  `" << f.command << "`\n";
        trn::io::write_file_atomic(st.report, md.str());
    }
    if (!st.keep) fs::remove_all(s.root);
    else std::printf("sandbox kept: %s\n", s.root.c_str());
    return failures ? 1 : 0;
} catch (const std::exception& e) {
    std::fprintf(stderr, "trn_cli_fuzz: %s\n", e.what());
    return 2;
}
