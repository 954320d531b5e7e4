#pragma once
// Labels that try to make gnuplot run a command. Each one creates `canary` if it gets out of its
// string: a line break followed by gnuplot's `system`, a quote that ends the string early (also
// the doubled-quote forms gnuplot's scanner splits), a trailing backslash (line continuation), a
// backquote command, `!` (shell escape), @macros (also after a quote), control characters and
// invalid UTF-8.
#include <string>
#include <vector>

namespace trn::test {

inline std::vector<std::string> injection_payloads(const std::string& canary) {
    const std::string touch = "touch " + canary;
    return {
        "\nsystem \"" + touch + "\"\n#",
        "\r\nsystem \"" + touch + "\"\r\n#",
        "it's \nsystem '" + touch + "'\n#",
        "'\nsystem \"" + touch + "\"\n#'",
        "''`" + touch + "`''",
        "a''''`" + touch + "`''''b",
        "'''`" + touch + "`'''",
        "\"; system(\"" + touch + "\") #",
        "back\\slash \\\nsystem \"" + touch + "\"\n#\\",
        "`" + touch + "`",
        "!" + touch,
        "\n!" + touch + "\n",
        "x; !" + touch,
        "@GPVAL_TERM @x @@ \nx = 'system(\"" + touch + "\")'\n@x",
        "it's @GPVAL_TERM @GPVAL_PWD @x",
        "brace { if (1) { system(\"" + touch + "\") } # }",
        "$(" + touch + ") ; " + touch,
        std::string("nul") + '\0' + "\nsystem \"" + touch + "\"\n#",
        "tab\there\x7f del \xc2\x85 c1 \x85 lone",
        "bad utf8 \xff\xfe \xc3( \xe2\x82 \xed\xa0\x80 \xc0\xaf\n!" + touch,
        "Jurevi\xc4\x8dius \xe2\x80\x93 \xc3\xbc \xf0\x9f\x9b\xb8",
    };
}

}  // namespace trn::test
