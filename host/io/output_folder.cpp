#include "trn/io/output_folder.hpp"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <system_error>
#include <vector>

#include "trn/error.hpp"
#include "trn/io/atomic_file.hpp"

namespace trn::io {
namespace fs = std::filesystem;
namespace {

std::string marker_line(const std::string& command) { return "trnkit " + command; }

// The command named by a folder's marker ("" when it has none).
std::string marked_command(const std::string& folder) {
    std::ifstream in(folder + "/" + kOutputMarker);
    std::string line;
    if (!in || !std::getline(in, line) || line.rfind("trnkit ", 0) != 0) return "";
    return line.substr(7);
}

// "/a/b/" and "/a/b/." -> "/a/b", so a sibling name can be appended.
std::string without_trailing_separator(const std::string& folder) {
    fs::path p = fs::absolute(folder).lexically_normal();
    if (p.filename().empty() && p != p.root_path()) p = p.parent_path();
    return p.string();
}

// Whether a folder holds anything besides markers being written right now: several processes may
// open one output folder at once (the jobs of `trnkit experiment` on GNU parallel or a Slurm array),
// and one that sees another's marker before its rename must not take the folder for someone else's.
bool has_entries(const std::string& folder, std::error_code& ec) {
    const std::string marker_temporary = std::string(kOutputMarker) + ".tmp-";
    for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec))
        if (it->path().filename().string().rfind(marker_temporary, 0) != 0) return true;
    return false;
}

void remove_tree(const std::string& path) {
    std::error_code ec;
    fs::remove_all(path, ec);
}

// Swaps two folders in one step (Linux renameat2); false when the file system cannot.
bool exchange(const std::string& a, const std::string& b) {
#ifdef RENAME_EXCHANGE
    if (::renameat2(AT_FDCWD, a.c_str(), AT_FDCWD, b.c_str(), RENAME_EXCHANGE) == 0) return true;
    if (errno != EINVAL && errno != ENOSYS && errno != ENOTSUP) throw Error(b + ": cannot replace (" + std::strerror(errno) + ")");
#endif
    return false;
}

// Staging folders of runs that were killed ("<target>.partial-<pid>" whose process is gone): each
// can hold a whole flight of frames, so the next run for the same target removes them.
void remove_dead_stagings(const std::string& target) {
    const fs::path t(target);
    const std::string prefix = t.filename().string() + ".partial-";
    std::error_code ec;
    std::vector<fs::path> dead;
    for (fs::directory_iterator it(t.parent_path(), ec), end; !ec && it != end; it.increment(ec)) {
        const std::string name = it->path().filename().string();
        if (name.rfind(prefix, 0) != 0) continue;
        const std::string digits = name.substr(prefix.size());
        if (digits.empty() || digits.size() > 9 || digits.find_first_not_of("0123456789") != std::string::npos) continue;
        const pid_t pid = static_cast<pid_t>(std::stol(digits));
        if (pid > 0 && ::kill(pid, 0) != 0 && errno == ESRCH) dead.push_back(it->path());
    }
    for (const fs::path& p : dead) remove_tree(p.string());
}

void rename_or_throw(const std::string& from, const std::string& to, const std::string& what) {
    if (std::rename(from.c_str(), to.c_str()) != 0) throw Error(what + ": cannot move " + from + " to " + to + " (" + std::strerror(errno) + ")");
}

}  // namespace

FolderState check_output_folder(const std::string& folder, const std::string& command, bool force, const std::string& option) {
    const std::string name = option.empty() ? folder : option + " " + folder;
    if (folder.empty()) throw Error((option.empty() ? std::string("output folder") : option) + ": empty folder name");
    std::error_code ec;
    const fs::file_status st = fs::status(folder, ec);
    if (ec && ec != std::errc::no_such_file_or_directory) throw Error(name + ": cannot be used (" + ec.message() + ")");
    if (fs::exists(st)) {
        if (!fs::is_directory(st)) throw Error(name + ": is a file, not a folder");
        if (::access(folder.c_str(), W_OK | X_OK) != 0) throw Error(name + ": not writable (" + std::strerror(errno) + ")");
        if (!has_entries(folder, ec)) {
            if (ec) throw Error(name + ": cannot be listed (" + ec.message() + ")");
            return FolderState::Empty;
        }
        const std::string owner = marked_command(folder);
        if (owner == command) return FolderState::OwnOutput;
        if (!force)
            throw Error(name + ": not empty and not an earlier output of trnkit " + command +
                        (owner.empty() ? std::string() : " (it is one of trnkit " + owner + ")") +
                        "; choose another folder, or --force to write into it");
        return FolderState::Foreign;
    }
    // Absent: it will be created inside the nearest folder above that exists.
    fs::path up = fs::absolute(folder).lexically_normal();
    if (up.filename().empty()) up = up.parent_path();
    do up = up.parent_path();
    while (!fs::exists(up, ec) && up != up.root_path());
    if (!fs::is_directory(up, ec)) throw Error(name + ": " + up.string() + " is not a folder");
    if (::access(up.c_str(), W_OK | X_OK) != 0)
        throw Error(name + ": cannot be created in " + up.string() + " (" + std::strerror(errno) + ")");
    return FolderState::Absent;
}

void open_output_folder(const std::string& folder, const std::string& command, bool force, const std::string& option) {
    const FolderState state = check_output_folder(folder, command, force, option);
    if (state == FolderState::Absent) {
        std::error_code ec;
        fs::create_directories(folder, ec);
        if (ec) throw Error(option + " " + folder + ": cannot create folder (" + ec.message() + ")");
    }
    write_file_atomic(folder + "/" + kOutputMarker, marker_line(command) + "\n");
}

StagedFolder::StagedFolder(const std::string& target, std::string command, bool force, const std::string& option)
    : command_(std::move(command)) {
    state_ = check_output_folder(target, command_, force, option);
    target_ = without_trailing_separator(target);
    staging_ = target_ + ".partial-" + std::to_string(::getpid());
    remove_dead_stagings(target_);
    remove_tree(staging_);  // only a dead run of this process id can have left one
    std::error_code ec;
    fs::create_directories(staging_, ec);
    if (ec) throw Error(option + " " + target + ": cannot create the staging folder " + staging_ + " (" + ec.message() + ")");
}

StagedFolder::~StagedFolder() {
    if (!committed_) remove_tree(staging_);
}

void StagedFolder::commit() {
    if (committed_) throw Error(target_ + ": committed twice");
    if (state_ == FolderState::Foreign) {
        // Not ours to replace: move the new files in one by one; the folder's other files stay.
        std::error_code ec;
        std::vector<std::string> names;
        for (fs::directory_iterator it(staging_, ec), end; !ec && it != end; it.increment(ec)) names.push_back(it->path().filename().string());
        if (ec) throw Error(staging_ + ": cannot be listed (" + ec.message() + ")");
        for (const std::string& n : names) rename_or_throw(staging_ + "/" + n, target_ + "/" + n, target_);
    } else {
        write_file_atomic(staging_ + "/" + kOutputMarker, marker_line(command_) + "\n");
        std::error_code ec;
        if (!fs::exists(target_, ec)) {
            rename_or_throw(staging_, target_, target_);
        } else if (exchange(staging_, target_)) {
            // staging_ now holds the earlier output.
        } else {
            // No atomic exchange here: move the earlier output aside, put the new one in, drop the old.
            const std::string old = target_ + ".old-" + std::to_string(::getpid());
            remove_tree(old);
            rename_or_throw(target_, old, target_);
            if (std::rename(staging_.c_str(), target_.c_str()) != 0) {
                const std::string why = std::strerror(errno);
                std::rename(old.c_str(), target_.c_str());
                throw Error(target_ + ": cannot replace (" + why + ")");
            }
            remove_tree(old);
        }
    }
    committed_ = true;
    remove_tree(staging_);
}

}  // namespace trn::io
