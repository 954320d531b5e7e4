#include "results_store.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "trn/error.hpp"
#include "trn/io/atomic_file.hpp"

namespace trn::experiments {
namespace fs = std::filesystem;

std::string config_hash(const Json& config) {
    std::uint64_t h = 0xcbf29ce484222325ull;
    for (const unsigned char c : config.dump()) h = (h ^ c) * 0x100000001b3ull;
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

ResultsStore::ResultsStore(std::string path, const Json& config) : path_(std::move(path)), hash_(config_hash(config)), config_(config) {}

std::string ResultsStore::load() {
    lines_.clear();
    unreadable = other_config = repeated = 0;
    if (path_.empty() || !fs::exists(path_)) return "";
    std::ifstream in(path_, std::ios::binary);
    if (!in) throw Error(path_ + ": cannot read the results store (" + std::strerror(errno) + ")");
    std::map<std::string, std::size_t> other_hashes;
    std::string line;
    while (std::getline(in, line)) {
        if (line.empty()) continue;
        Json j;
        try {
            j = Json::parse(line);
        } catch (const std::exception&) {
            ++unreadable;
            continue;
        }
        if (!j.is_object() || !j.contains("job") || !j["job"].is_string() || !j.contains("config") || !j["config"].is_string() ||
            !j.contains("result") || !j.contains("params")) {
            ++unreadable;
            continue;
        }
        if (j["config"] != hash_) {
            ++other_config, ++other_hashes[j["config"].get<std::string>()];
            continue;
        }
        if (!lines_.emplace(j["job"].get<std::string>(), std::move(j)).second) ++repeated;
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

Json ResultsStore::output(const std::string& job) const {
    const Json& l = lines_.at(job);
    Json params = l.at("params");
    params["id"] = job;  // stored without it: the line's "job"
    Json o{{"params", params}, {"result", l.at("result")}, {"wall_s", l.value("wall_s", 0.0)}};
    o["backend_device"] = l.value("device", config_.value("backend", std::string("?")));
    o["git_commit"] = l.value("commit", std::string("?"));
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
    if (!fs::exists(config_file)) io::write_file_atomic(config_file, config_.dump(1) + "\n");

    Json p = params;
    const std::string job = p.at("id").get<std::string>();
    p.erase("id");
    Json line{{"job", job}, {"config", hash_}, {"commit", commit.substr(0, 12)}, {"params", p}, {"result", rounded(result)}};
    char wall[32];
    std::snprintf(wall, sizeof wall, "%.4g", wall_s);
    line["wall_s"] = std::strtod(wall, nullptr);
    (void)device;  // not kept: the configuration names the backend, the commit the code
    const std::string text = line.dump() + "\n";

    const int fd = ::open(path_.c_str(), O_WRONLY | O_APPEND | O_CREAT | O_CLOEXEC, 0644);
    if (fd < 0) throw Error(path_ + ": cannot open the results store for appending (" + std::strerror(errno) + ")");
    struct Closer {
        int fd;
        ~Closer() { ::close(fd); }  // also releases the lock
    } closer{fd};
    while (::flock(fd, LOCK_EX) != 0)
        if (errno != EINTR) throw Error(path_ + ": cannot lock the results store (" + std::strerror(errno) + ")");
    // A last line cut off by a killed writer is closed first, so it cannot swallow this one.
    struct stat st {};
    if (::fstat(fd, &st) == 0 && st.st_size > 0) {
        const int rd = ::open(path_.c_str(), O_RDONLY | O_CLOEXEC);
        char last = '\n';
        if (rd >= 0) {
            if (::pread(rd, &last, 1, st.st_size - 1) != 1) last = '\n';
            ::close(rd);
        }
        if (last != '\n') io::write_all(fd, "\n", path_);
    }
    io::write_all(fd, text, path_);
    if (::fsync(fd) != 0) throw Error(path_ + ": cannot flush the results store (" + std::strerror(errno) + ")");
}

}  // namespace trn::experiments
