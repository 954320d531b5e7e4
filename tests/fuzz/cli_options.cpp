#include "cli_options.hpp"

#include <sstream>

namespace trn::fuzz {
namespace {

// "  -b,--backend TEXT=cpu     Backend: ..." -> "-b,--backend TEXT=cpu" (the description follows
// after two or more spaces; continuation lines of a description start deeper than column 2).
bool entry_head(const std::string& line, std::string& head) {
    if (line.size() < 3 || line.compare(0, 2, "  ") != 0 || line[2] == ' ') return false;
    const auto gap = line.find("  ", 2);
    head = line.substr(2, gap == std::string::npos ? std::string::npos : gap - 2);
    while (!head.empty() && head.back() == ' ') head.pop_back();
    return !head.empty();
}

// "INT:INT in [1 - 1000000]=2000", "TEXT:{real,mono}=real", "FLOAT", "TEXT ..."
void describe_type(const std::string& type, CliOption& o) {
    for (const char* n : {"INT", "UINT", "FLOAT", "NUMBER", "DOUBLE"})
        if (type.rfind(n, 0) == 0) o.numeric = true;
    const auto open = type.find('{'), close = type.find('}');
    if (open == std::string::npos || close == std::string::npos || close < open) return;
    std::istringstream items(type.substr(open + 1, close - open - 1));
    for (std::string c; std::getline(items, c, ',');) o.choices.push_back(c);
}

}  // namespace

CliCommand parse_cli_help(const std::string& text, const std::vector<std::string>& path) {
    CliCommand cmd;
    cmd.path = path;
    std::istringstream in(text);
    std::string section, line, head;
    while (std::getline(in, line)) {
        if (!line.empty() && line[0] != ' ' && line.back() == ':') {
            section = line.substr(0, line.size() - 1);
            continue;
        }
        if (!entry_head(line, head)) continue;
        const auto space = head.find(' ');
        const std::string names = head.substr(0, space);
        CliOption o;
        o.takes_value = space != std::string::npos;
        describe_type(o.takes_value ? head.substr(space + 1) : std::string(), o);
        if (section == "Subcommands") {
            cmd.subcommands.push_back(names);
        } else if (section == "Positionals") {
            o.name = names;
            cmd.positionals.push_back(o);
        } else if (section == "Options") {
            std::istringstream parts(names);
            for (std::string n; std::getline(parts, n, ',');)
                if (o.name.empty() || n.rfind("--", 0) == 0) o.name = n;
            if (o.name != "--help" && o.name != "-h" && o.name.rfind("-", 0) == 0) cmd.options.push_back(o);
        }
    }
    return cmd;
}

}  // namespace trn::fuzz
