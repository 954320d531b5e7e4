#pragma once
// What the CLI fuzzer knows beyond --help: per subcommand, the arguments that make a run short and
// reach real work (on the fixtures), which options legitimately scale the work (a timeout after
// one of them was fuzzed is "unbounded work", a finding, not a hang), and the nasty values.
#include <map>
#include <set>
#include <string>
#include <vector>

namespace trn::fuzz {

struct CommandPlan {
    std::vector<std::pair<std::string, std::string>> base;  // option -> value ("" for a flag; positional names too)
    std::set<std::string> work;     // options whose big values make a run long
    std::set<std::string> pinned;   // never dropped or changed (keep the run short, e.g. experiment --list-jobs)
    int weight = 1;                 // how often this subcommand is picked, relative
};

// Keyed by the command path joined with spaces ("energy integrate"). `fx` is the fixture folder,
// `t0`/`t1` a span inside the fixture power log.
std::map<std::string, CommandPlan> command_plans(const std::string& fx, const std::string& t0, const std::string& t1);

// Values to try, by kind; `fx` paths point at fixtures (files, a folder, a bad image, device stand-ins).
struct NastyValues {
    std::vector<std::string> numbers, texts, words, files;
    std::vector<std::string> all() const;
};
NastyValues nasty_values(const std::string& fx, bool long_run);

// Options whose value is a file the command writes (checked for silently ignored write errors).
bool is_output_option(const std::string& name);

}  // namespace trn::fuzz
