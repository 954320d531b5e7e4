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
// runs of the same job in parallel both append; the first line is used.
#include <cstddef>
#include <map>
#include <string>

#include "study.hpp"

namespace trn::experiments {

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
    std::map<std::string, Json> lines_;
};

// The default store of a study: results/<study>/<profile>[-quick].jsonl.
std::string default_results_path(const std::string& study, const std::string& profile, bool quick);

}  // namespace trn::experiments
