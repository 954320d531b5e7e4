// Replay driver for the fuzz entries when libFuzzer is not available (gcc CI): feeds every file
// of the seed folders (argv[1..], searched recursively; the shared power logs by default), then a
// bounded number of deterministic mutations of them (TRN_FUZZ_ITERATIONS, default 20000).
// Any crash or broken invariant aborts, which fails the test.
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace {

struct Rng {
    std::uint64_t s;
    std::uint64_t next() {
        s ^= s << 13, s ^= s >> 7, s ^= s << 17;
        return s;
    }
    std::size_t below(std::size_t n) { return n ? static_cast<std::size_t>(next() % n) : 0; }
};

// Bytes that matter to the parsers: separators, signs, exponents, markers, special words.
const char* const kTokens[] = {",", "\n", "\r\n", " ", "\t", "-", "+", ".", "e", "E", "e308", "1e-320", "nan", "inf", "0x", "\"",
                               "#", ":", "M ", "start", "end", "mW", "mA", "W", "/", "(", ")", "9999999999999999999", "0", "-0",
                               "VDD_IN ", "POM_5V_IN ", "Timestamp: ", "power.draw", "2024/01/01 00:00:00.000", "# trnkit-power v1 kind=instant "};

void feed(const std::string& s) { LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(s.data()), s.size()); }

std::string mutate(std::string s, const std::vector<std::string>& seeds, Rng& r) {
    const int n = 1 + static_cast<int>(r.below(8));
    for (int k = 0; k < n; ++k) {
        const std::size_t pos = r.below(s.size() + 1);
        switch (r.below(7)) {
            case 0: if (!s.empty()) s[r.below(s.size())] ^= static_cast<char>(1u << r.below(8)); break;
            case 1: s.insert(pos, kTokens[r.below(std::size(kTokens))]); break;
            case 2: s.erase(pos, r.below(16)); break;
            case 3: if (pos < s.size()) s.insert(r.below(s.size()), s.substr(pos, r.below(64))); break;
            case 4: s.resize(pos); break;
            case 5: {
                const std::string& o = seeds[r.below(seeds.size())];
                const std::size_t from = r.below(o.size() + 1);
                s.insert(pos, o.substr(from, r.below(256)));
                break;
            }
            default: if (!s.empty()) s[r.below(s.size())] = static_cast<char>("0123456789.,-\n"[r.below(14)]); break;
        }
    }
    if (s.size() > 65536) s.resize(65536);
    return s;
}

}  // namespace

int main(int argc, char** argv) {
    std::vector<std::string> dirs(argv + 1, argv + argc);
    if (dirs.empty()) {
        const char* shared = std::getenv("TRN_SHARED_DATA");
        if (shared) dirs.push_back(std::string(shared) + "/powerlogs");
    }
    std::vector<std::string> seeds = {"", "\n", "t,p\n0,1\n1,2\n"};
    for (const auto& d : dirs) {
        std::error_code ec;
        if (!std::filesystem::is_directory(d, ec)) continue;
        std::vector<std::filesystem::path> files;
        for (const auto& e : std::filesystem::recursive_directory_iterator(d, ec))
            if (e.is_regular_file()) files.push_back(e.path());
        std::sort(files.begin(), files.end());
        for (const auto& p : files) {
            std::ifstream f(p, std::ios::binary);
            std::ostringstream ss;
            ss << f.rdbuf();
            feed(ss.str());  // every file whole, once
            std::string head = ss.str().substr(0, 4096);  // mutations work on the first 4 KiB
            seeds.push_back(head);
        }
    }
    const char* it = std::getenv("TRN_FUZZ_ITERATIONS");
    const long iterations = it ? std::atol(it) : 20000;
    Rng r{0x9e3779b97f4a7c15ull};
    for (long i = 0; i < iterations; ++i) feed(mutate(seeds[r.below(seeds.size())], seeds, r));
    std::printf("replayed %zu seed(s) and %ld mutation(s) from %zu folder(s)\n", seeds.size(), iterations, dirs.size());
    return 0;
}
