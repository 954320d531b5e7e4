// A stand-in for trnkit that the CLI fuzzer must catch: it answers --help like CLI11 (one
// subcommand "boom" with one option) and dies from SIGSEGV on anything else. ctest expects the
// fuzzer to fail against it (fuzz_cli_catches_a_crash), so the fuzzer is shown able to fail.
#include <csignal>
#include <cstdio>
#include <cstring>

int main(int argc, char** argv) {
    const bool help = argc > 1 && std::strcmp(argv[argc - 1], "--help") == 0;
    if (help && argc == 2) return std::puts("Usage: fake [OPTIONS] SUBCOMMAND\n\nSubcommands:\n  boom                        crashes\n"), 0;
    if (help) return std::puts("Usage: fake boom [OPTIONS]\n\nOptions:\n  -h,--help                   help\n  --x INT                     x\n"), 0;
    std::raise(SIGSEGV);
    return 0;
}
