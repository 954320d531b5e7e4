#include "results_store.hpp"

#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "trn/error.hpp"
#include "trn/io/atomic_file.hpp"
#include "trn/io/outside_text.hpp"
#include "trn/io/input_file.hpp"

namespace trn::experiments {
namespace fs = std::filesystem;

std::string config_hash(const Json& config) {
    std::uint64_t h = 0xcbf29ce484222325ull;
    for (const unsigned char c : io::json_line(config)) h = (h ^ c) * 0x100000001b3ull;
    char text[17];
    std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(h));
    return text;
}

std::string default_results_path(const std::string& study, const std::string& profile, bool quick) {
    return "results/" + study + "/" + profile + (quick ? "-quick" : "") + ".jsonl";
}

namespace {

// Reals to 6 significant digits (integers, booleans, strings and nulls as they are).
Json rounded(const Json& j) {
    if (j.is_object()) {
        Json out = Json::object();
        for (auto it = j.begin(); it != j.end(); ++it) out[it.key()] = rounded(it.value());
        return out;
    }
    if (j.is_array()) {
        Json out = Json::array();
        for (const Json& v : j) out.push_back(rounded(v));
        return out;
    }
    if (j.is_number_float()) {
        const double v = j.get<double>();
        if (!std::isfinite(v)) return nullptr;
        char text[32];
        std::snprintf(text, sizeof text, "%.6g", v);
        return std::strtod(text, nullptr);
    }
    return j;
}

std::string folder_of(const std::string& path) {
    const fs::path p(path);
    return p.has_parent_path() ? p.parent_path().string() : std::string(".");
}

}  // namespace

namespace {

const char* type_name(const Json& v) {
    if (v.is_null()) return "null";
    if (v.is_boolean()) return "a boolean";
    if (v.is_number()) return "a number";
    if (v.is_string()) return "a string";
    if (v.is_array()) return "an array";
    return "an object";
}

// What the merge reads a value as: a number (null is a number that was not finite), a boolean, an
// array or an object.
const char* kind_name(const Json& v) { return v.is_null() ? "a number" : type_name(v); }

std::string field_error(const std::string& where, const std::string& field, const Json& v, const char* wanted) {
    return where + ": field " + field + " is " + type_name(v) + ", not " + wanted + " (not a line of a results store)";
}

// A result holds numbers, booleans and nulls, in arrays and objects.
void check_result_values(const Json& v, const std::string& field, const std::string& where) {
    if (v.is_object()) {
        for (auto it = v.begin(); it != v.end(); ++it) check_result_values(it.value(), field + "." + io::quote_input(it.key(), 40), where);
    } else if (v.is_array()) {
        for (std::size_t i = 0; i < v.size(); ++i) check_result_values(v[i], field + "[" + std::to_string(i) + "]", where);
    } else if (v.is_string() || v.is_binary() || v.is_discarded()) {
        throw Error(field_error(where, field, v, "a number, boolean or null"));
    }
}

std::string kind_difference(const Json& a, const Json& b, const std::string& field, std::size_t earlier_line) {
    if (std::string(kind_name(a)) != kind_name(b))
        return "field " + field + " is " + kind_name(a) + " where line " + std::to_string(earlier_line) + " has " + kind_name(b);
    if (a.is_object()) {
        for (auto it = a.begin(); it != a.end(); ++it)
            if (b.contains(it.key()))
                if (std::string d = kind_difference(it.value(), b.at(it.key()), field + "." + io::quote_input(it.key(), 40), earlier_line);
                    !d.empty())
                    return d;
    } else if (a.is_array() && !b.empty()) {
        for (std::size_t i = 0; i < a.size(); ++i)
            if (std::string d = kind_difference(a[i], b[0], field + "[" + std::to_string(i) + "]", earlier_line); !d.empty()) return d;
    }
    return "";
}

}  // namespace

std::optional<StoreLine> parse_store_line(std::string_view text, const std::string& where) {
    io::check_json_depth(text, where);  // the parser recurses per level: 100 000 levels overflow the stack
    Json j = Json::parse(text.begin(), text.end(), nullptr, false);
    if (j.is_discarded()) return std::nullopt;
    if (!j.is_object()) throw Error(where + ": is " + type_name(j) + ", not a JSON object (not a line of a results store)");
    auto string_field = [&](const char* key, bool required) -> std::string {
        if (!j.contains(key)) {
            if (required) throw Error(where + ": field " + key + " is missing (not a line of a results store)");
            return "";
        }
        const Json& v = j.at(key);
        if (!v.is_string()) throw Error(field_error(where, key, v, "a string"));
        return v.get<std::string>();
    };
    StoreLine line;
    line.job = string_field("job", true);
    if (line.job.empty()) throw Error(where + ": field job is empty");
    line.config = string_field("config", true);
    line.commit = string_field("commit", false);
    for (const char* key : {"params", "result"}) {
        if (!j.contains(key)) throw Error(where + ": field " + key + " is missing (not a line of a results store)");
        if (!j.at(key).is_object()) throw Error(field_error(where, key, j.at(key), "an object"));
    }
    check_result_values(j.at("result"), "result", where);
    if (j.contains("wall_s")) {
        const Json& w = j.at("wall_s");
        if (!w.is_number() || !std::isfinite(w.get<double>()) || w.get<double>() < 0)
            throw Error(where + ": field wall_s is " + (w.is_number() ? io::quote_input(io::json_line(w)) : std::string(type_name(w))) +
                        ", not a number of seconds >= 0");
        line.wall_s = w.get<double>();
    }
    line.params = std::move(j.at("params"));
    line.result = std::move(j.at("result"));
    return line;
}

std::string result_kind_difference(const Json& result, const Json& earlier, std::size_t earlier_line) {
    return kind_difference(result, earlier, "result", earlier_line);
}

ResultsStore::ResultsStore(std::string path, const Json& config) : path_(std::move(path)), hash_(config_hash(config)), config_(config) {}

std::string ResultsStore::load() {
    lines_.clear();
    unreadable = other_config = repeated = 0;
    if (path_.empty()) return "";
    struct stat st {};
    if (::lstat(path_.c_str(), &st) != 0) {
        if (errno == ENOENT) return "";  // no job stored yet
    } else if (S_ISLNK(st.st_mode)) {
        // Refused before any job runs: append() would refuse it after the first (open_for_append).
        throw Error(io::quote_input(path_, 512) + ": is a symbolic link; trnkit does not append the results store through it (remove it)");
    }
    // Regular files only, of a bounded size: a FIFO would hang the run, /dev/zero never end.
    const std::string text = io::read_input_file(path_, kMaxResultsStoreBytes, "a results store");
    std::map<std::string, std::size_t> other_hashes;
    const Json* first_result = nullptr;
    std::size_t first_line = 0, line_no = 0;
    for (std::size_t begin = 0; begin < text.size();) {
        const std::size_t end = std::min(text.find('\n', begin), text.size());
        const std::string_view line(text.data() + begin, end - begin);
        begin = end + 1;
        ++line_no;
        if (line.empty()) continue;
        const std::string where = io::quote_input(path_, 512) + ":" + std::to_string(line_no);
        std::optional<StoreLine> l = parse_store_line(line, where);
        if (!l) {
            ++unreadable;
            continue;
        }
        if (l->config != hash_) {
            ++other_config, ++other_hashes[l->config];
            continue;
        }
        if (first_result) {
            if (const std::string d = result_kind_difference(l->result, *first_result, first_line); !d.empty()) throw Error(where + ": " + d);
        }
        const std::string job = l->job;
        const auto [it, added] = lines_.emplace(job, Kept{std::move(*l), line_no});
        if (!added) ++repeated;
        if (!first_result) first_result = &it->second.line.result, first_line = line_no;
    }
    if (!unreadable && !other_config && !repeated) return "";
    std::string note = path_ + ":";
    if (other_config) {
        // Appended piece by piece: `"literal" + std::string` trips GCC 12's -Wrestrict false positive on aarch64 (GCC PR 105651).
        note.append(" ").append(std::to_string(other_config)).append(" line(s) of another configuration ignored (");
        bool first = true;
        for (const auto& [h, n] : other_hashes) note.append(first ? "" : ", ").append(h).append(" x").append(std::to_string(n)), first = false;
        note.append("; this run's is ").append(hash_).append(", each one's in ").append(folder_of(path_)).append("/configs/)");
    }
    if (unreadable) note.append(" ").append(std::to_string(unreadable)).append(" unreadable line(s) ignored (a cut-off write; their jobs run again)");
    if (repeated) note.append(" ").append(std::to_string(repeated)).append(" repeated job line(s) ignored (the first one is used)");
    return note;
}

std::string ResultsStore::where(const std::string& job) const {
    return io::quote_input(path_, 512) + ":" + std::to_string(lines_.at(job).line_no);
}

Json ResultsStore::output(const std::string& job) const {
    const StoreLine& l = lines_.at(job).line;
    Json params = l.params;
    params["id"] = job;  // stored without it: the line's "job"
    Json o{{"params", params}, {"result", l.result}, {"wall_s", l.wall_s}};
    o["backend_device"] = config_.value("backend", std::string("?"));
    o["git_commit"] = l.commit.empty() ? std::string("?") : l.commit;
    o["config"] = config_;
    return o;
}

void ResultsStore::append(const Json& params, const Json& result, double wall_s, const std::string& device, const std::string& commit) {
    if (path_.empty()) return;
    const std::string folder = folder_of(path_);
    std::error_code ec;
    fs::create_directories(folder + "/configs", ec);
    if (ec) throw Error(folder + "/configs: cannot create folder (" + ec.message() + ")");
    const std::string config_file = folder + "/configs/" + hash_ + ".json";
    // A name trnkit chose: anything there but a plain file (a planted link) is refused, not written through.
    if (!fs::is_regular_file(fs::symlink_status(config_file))) io::write_file_atomic(config_file, io::json_text(config_, 1), io::Destination::Derived);

    Json p = params;
    const std::string job = p.at("id").get<std::string>();
    p.erase("id");
    Json line{{"job", job}, {"config", hash_}, {"commit", commit.substr(0, 12)}, {"params", p}, {"result", rounded(result)}};
    char wall[32];
    std::snprintf(wall, sizeof wall, "%.4g", wall_s);
    line["wall_s"] = std::strtod(wall, nullptr);
    (void)device;  // not kept: the configuration names the backend, the commit the code
    const std::string text = io::json_text(line);

    const int fd = io::open_for_append(path_, "the results store");
    struct Closer {
        int fd;
        ~Closer() { ::close(fd); }  // also releases the lock
    } closer{fd};
    while (::flock(fd, LOCK_EX) != 0)
        if (errno != EINTR) throw Error(path_ + ": cannot lock the results store (" + std::strerror(errno) + ")");
    // A last line cut off by a killed writer is closed first, so it cannot swallow this one.
    struct stat st {};
    if (::fstat(fd, &st) == 0 && st.st_size > 0) {
        char last = '\n';
        if (::pread(fd, &last, 1, st.st_size - 1) != 1) last = '\n';
        if (last != '\n') io::write_all(fd, "\n", path_);
    }
    io::write_all(fd, text, path_);
    if (::fsync(fd) != 0) throw Error(path_ + ": cannot flush the results store (" + std::strerror(errno) + ")");
}

}  // namespace trn::experiments
