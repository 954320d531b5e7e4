#pragma once
// The trnkit command tree as its own --help output describes it (CLI11 format): subcommands,
// options (and whether they take a value) and positionals. Deriving it from --help means a new
// option or subcommand is fuzzed without anyone editing the fuzzer.
#include <string>
#include <vector>

namespace trn::fuzz {

struct CliOption {
    std::string name;         // the long name when there is one ("--backend"), else the short one
    bool takes_value = false;
    bool numeric = false;               // INT, UINT, FLOAT ... in the help
    std::vector<std::string> choices;   // from "TEXT:{a,b}"
};

struct CliCommand {
    std::vector<std::string> path;          // {"energy", "integrate"}
    std::vector<CliOption> options;         // without --help
    std::vector<CliOption> positionals;     // in order (name without dashes)
    std::vector<std::string> subcommands;   // direct children
};

// Parses one --help text.
CliCommand parse_cli_help(const std::string& help_text, const std::vector<std::string>& path);

}  // namespace trn::fuzz
