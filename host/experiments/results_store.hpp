#pragma once
// The results store of a study (private to host/experiments): every finished job as one small
// JSON line in a file kept in the repository, results/<study>/<profile>[-quick].jsonl, so a sweep
// survives its output folder and is resumed and merged from it (trnkit experiment --resume).
//
// A line: {"job": id, "config": <hash>, "commit": <first 12 of the git commit>, "params": {...}
// (without the id), "result": {...}, "wall_s": s}; the result's reals rounded to 6 significant
// digits (the tables print at most 4), so a flight is ~0.55 kB (5760 conversion flights ~3.2 MB). The configuration itself is written once per hash beside the
// file, <folder>/configs/<hash>.json; the hash is FNV-1a 64 of its compact dump.
//
// Safety: a line is appended with one write() to a file opened O_APPEND under an exclusive flock
// and fsync'ed; a file whose last line was cut off (a writer killed mid-write, a full disk) gets a
// newline first, so the fragment stays one unreadable line and every later line reads. Reading
// ignores, and counts: lines that do not parse (the fragments), lines of another configuration
// (named by hash, e.g. another seed, quick vs full), and repeated jobs (the first line wins). Two
// runs of the same job in parallel both append; the first line is used. A link, FIFO or device at
// the store's name is refused (appending and reading: io::open_for_append, io::read_input_file).
//
// A line that parses but is not a line of the store is an Error naming file:line and the field
// (parse_store_line): the merge reads its fields by type, so it must not meet another type.
#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>

#include "study.hpp"

namespace trn::experiments {

// Largest store read: ~80 000 flights of ~0.55 kB (5760 conversion flights are 3.2 MB).
inline constexpr std::uint64_t kMaxResultsStoreBytes = std::uint64_t{64} << 20;

// One line of a store, its fields checked.
struct StoreLine {
    std::string job, config, commit;
    Json params, result;
    double wall_s = 0;
};

// Reads one line (without its newline); `where` names it ("results/x.jsonl:12"). nullopt when it is
// not JSON (a write cut off by a killed writer). Throws trn::Error "WHERE: field F ..." when it is
// JSON but not a store line: not an object; job, config or commit not a string; params or result
// not an object; wall_s not a number >= 0; a params value not a string, number or boolean; a result
// value not a number, boolean or null (or arrays and objects of them); nested deeper than 64.
std::optional<StoreLine> parse_store_line(std::string_view text, const std::string& where);

// The first difference in kind (number or null, boolean, array, object) between a result and the
// one of an earlier line, as "field result.K is an array where line N has a number"; "" when none.
// Keys only one of them has are not compared (a study's results may gain fields).
std::string result_kind_difference(const Json& result, const Json& earlier, std::size_t earlier_line);

// FNV-1a 64 of config.dump(), 16 hex digits.
std::string config_hash(const Json& config);

class ResultsStore {
public:
    // `path` "" : disabled (has() false, append() does nothing).
    ResultsStore(std::string path, const Json& config);

    const std::string& path() const { return path_; }
    bool enabled() const { return !path_.empty(); }
    const std::string& hash() const { return hash_; }

    // Reads the file (absent: empty). Returns a one-line note when lines were ignored, else "".
    std::string load();
    bool has(const std::string& job) const { return lines_.count(job) > 0; }
    // "path:line" of the job's line, for messages.
    std::string where(const std::string& job) const;
    // {"params", "result", "wall_s", "backend_device", "git_commit"} as a job file has them.
    Json output(const std::string& job) const;
    std::size_t size() const { return lines_.size(); }

    // Appends the job's line (creating the folder and the config file when needed); throws
    // trn::Error naming the file when it cannot be written. `device` is not kept (the backend is
    // in the configuration).
    void append(const Json& params, const Json& result, double wall_s, const std::string& device, const std::string& commit);

    std::size_t unreadable = 0, other_config = 0, repeated = 0;

private:
    std::string path_, hash_;
    Json config_;
    struct Kept {
        StoreLine line;
        std::size_t line_no;
    };
    std::map<std::string, Kept> lines_;
};

// The default store of a study: results/<study>/<profile>[-quick].jsonl.
std::string default_results_path(const std::string& study, const std::string& profile, bool quick);

}  // namespace trn::experiments
