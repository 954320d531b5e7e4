// Replay driver for every fuzz entry when libFuzzer is not available (gcc CI builds): links one
// LLVMFuzzerTestOneInput and feeds it, in a fixed order,
//   1. every file of the seed folders/files named on the command line (folders searched recursively),
//   2. -runs=N deterministic mutations of them (bit flips, dictionary tokens, cuts, splices).
// Arguments follow libFuzzer's spelling so one ctest line reads like a libFuzzer run:
//   replay [-dict=FILE] [-runs=N] [-seed=N] [-max_len=N] SEED...
// A seed that does not exist is reported (the shared data may be absent) and skipped. Any crash or
// broken invariant aborts, which fails the test; the input that did it is saved in fuzz-crash-input
// (in the test's working folder) for a rerun: replay_binary -runs=0 fuzz-crash-input.
#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "xorshift_rng.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace {

using Rng = trn::fuzz::XorshiftRng;

std::string read_all(const std::filesystem::path& p) {
    std::ifstream f(p, std::ios::binary);
    std::ostringstream ss;
    ss << f.rdbuf();
    return ss.str();
}

// libFuzzer dictionary lines: [name=]"value" with \\, \" and \xNN escapes; '#' starts a comment.
std::vector<std::string> read_dictionary(const std::string& path) {
    std::ifstream f(path);
    if (!f) {
        std::fprintf(stderr, "replay: cannot open dictionary %s\n", path.c_str());
        std::exit(2);
    }
    std::vector<std::string> tokens;
    for (std::string line; std::getline(f, line);) {
        const auto q = line.find('"');
        if (line.empty() || line[0] == '#' || q == std::string::npos) continue;
        std::string t;
        for (std::size_t i = q + 1; i < line.size() && line[i] != '"'; ++i) {
            if (line[i] != '\\' || i + 1 >= line.size()) {
                t += line[i];
            } else if (line[i + 1] == 'x' && i + 3 < line.size()) {
                t += static_cast<char>(std::strtol(line.substr(i + 2, 2).c_str(), nullptr, 16)), i += 3;
            } else {
                t += line[++i];
            }
        }
        tokens.push_back(t);
    }
    return tokens;
}

std::string mutate(std::string s, const std::vector<std::string>& seeds, const std::vector<std::string>& tokens, Rng& r,
                   std::size_t max_len) {
    const int n = 1 + static_cast<int>(r.below(8));
    for (int k = 0; k < n; ++k) {
        const std::size_t pos = r.below(s.size() + 1);
        switch (r.below(7)) {
            case 0: if (!s.empty()) s[r.below(s.size())] ^= static_cast<char>(1u << r.below(8)); break;
            case 1: if (!tokens.empty()) s.insert(pos, tokens[r.below(tokens.size())]); break;
            case 2: s.erase(pos, r.below(16)); break;
            case 3: if (pos < s.size()) s.insert(r.below(s.size()), s.substr(pos, r.below(64))); break;
            case 4: s.resize(pos); break;
            case 5: {
                const std::string& o = seeds[r.below(seeds.size())];
                const std::size_t from = r.below(o.size() + 1);
                s.insert(pos, o.substr(from, r.below(256)));
                break;
            }
            default: if (!s.empty()) s[r.below(s.size())] = "0123456789.,-\n\""[r.below(15)]; break;
        }
    }
    if (s.size() > max_len) s.resize(max_len);
    return s;
}

// The input under test, written to fuzz-crash-input by the handler below when it crashes.
const std::string* g_current = nullptr;

void save_current_input() {
    if (g_current) {
        const int fd = ::open("fuzz-crash-input", O_WRONLY | O_CREAT | O_TRUNC, 0644);
        if (fd >= 0) {
            if (::write(fd, g_current->data(), g_current->size()) < 0) { /* nothing more a handler can do */ }
            ::close(fd);
        }
        static const char msg[] = "replay: the crashing input is in fuzz-crash-input\n";
        if (::write(2, msg, sizeof msg - 1) < 0) { /* as above */ }
        g_current = nullptr;
    }
}

extern "C" void save_crash_input(int sig) {
    save_current_input();
    std::signal(sig, SIG_DFL);
    std::raise(sig);
}

// Sanitizers end the process their own way, past any signal handler: there every input is saved
// before it runs (slower, and only in those builds).
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_UNDEFINED__)
constexpr bool kSaveEveryInput = true;
#else
constexpr bool kSaveEveryInput = false;
#endif

void feed(const std::string& s) {
    g_current = &s;
    if (kSaveEveryInput) {
        const int fd = ::open("fuzz-crash-input", O_WRONLY | O_CREAT | O_TRUNC, 0644);
        if (fd >= 0) {
            if (::write(fd, s.data(), s.size()) < 0) { /* best effort: the run itself matters more */ }
            ::close(fd);
        }
    }
    LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(s.data()), s.size());
    g_current = nullptr;
}

}  // namespace

int main(int argc, char** argv) {
    for (int sig : {SIGABRT, SIGSEGV, SIGBUS, SIGFPE, SIGILL}) std::signal(sig, save_crash_input);
    long runs = 20000;
    std::uint64_t seed = 0x9e3779b97f4a7c15ull;
    std::size_t max_len = 65536;
    std::vector<std::string> tokens, paths;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a.rfind("-dict=", 0) == 0) {
            const auto more = read_dictionary(a.substr(6));
            tokens.insert(tokens.end(), more.begin(), more.end());
        } else if (a.rfind("-runs=", 0) == 0) {
            runs = std::atol(a.c_str() + 6);
        } else if (a.rfind("-seed=", 0) == 0) {
            seed = std::strtoull(a.c_str() + 6, nullptr, 0) | 1;  // xorshift must not start at 0
        } else if (a.rfind("-max_len=", 0) == 0) {
            max_len = static_cast<std::size_t>(std::atol(a.c_str() + 9));
        } else if (!a.empty() && a[0] == '-') {
            std::fprintf(stderr, "replay: unknown option %s\n", a.c_str());
            return 2;
        } else {
            paths.push_back(a);
        }
    }
    std::vector<std::string> seeds = {"", "\n"};
    std::size_t files = 0;
    for (const auto& p : paths) {
        std::error_code ec;
        std::vector<std::filesystem::path> found;
        if (std::filesystem::is_regular_file(p, ec)) {
            found.push_back(p);
        } else if (std::filesystem::is_directory(p, ec)) {
            for (const auto& e : std::filesystem::recursive_directory_iterator(p, ec))
                if (e.is_regular_file()) found.push_back(e.path());
        } else {
            std::printf("replay: seed %s is absent, replaying without it\n", p.c_str());
        }
        std::sort(found.begin(), found.end());
        for (const auto& f : found) {
            const std::string text = read_all(f);
            feed(text);                            // every file whole, once
            seeds.push_back(text.substr(0, 4096));  // mutations work on the first 4 KiB
            ++files;
        }
    }
    Rng r{seed};
    for (long i = 0; i < runs; ++i) feed(mutate(seeds[r.below(seeds.size())], seeds, tokens, r, max_len));
    if (kSaveEveryInput) std::remove("fuzz-crash-input");  // nothing crashed
    std::printf("replayed %zu seed file(s) and %ld mutation(s), %zu dictionary token(s)\n", files, runs, tokens.size());
    return 0;
}
