#include "trn/io/output_folder.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <set>
#include <sstream>
#include <system_error>
#include <vector>

#include "trn/error.hpp"
#include "trn/io/atomic_file.hpp"

namespace trn::io {
namespace fs = std::filesystem;
namespace {

constexpr const char* kListLine =
    "# trnkit-output 2: the files below were written here by this command; a rerun replaces or removes only these";
constexpr const char* kUpgradedLine = "# marked by an older trnkit: unlisted files may still be replaced by name";

bool plain_name(const std::string& n) {
    return !n.empty() && n != "." && n != ".." && n.find('/') == std::string::npos && n.find('\0') == std::string::npos;
}

// A folder's marker as read (never through a link, never a special file, at most 64 MiB).
struct Marker {
    std::string command;  // "" when there is none
    bool listed = false;  // has the list (trnkit-output 2)
    bool upgraded = false;
    std::set<std::string> names;
};

Marker read_marker(const std::string& folder) {
    Marker m;
    const int fd = ::open((folder + "/" + kOutputMarker).c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) return m;
    struct stat st {};
    std::string text;
    if (::fstat(fd, &st) == 0 && S_ISREG(st.st_mode) && st.st_size <= (64 << 20)) {
        char buf[65536];
        ssize_t n;
        while ((n = ::read(fd, buf, sizeof buf)) > 0) text.append(buf, static_cast<std::size_t>(n));
    }
    ::close(fd);
    std::istringstream in(text);
    std::string line;
    if (!std::getline(in, line) || line.rfind("trnkit ", 0) != 0) return m;
    m.command = line.substr(7);
    while (std::getline(in, line)) {
        if (line == kListLine) m.listed = true;
        else if (line == kUpgradedLine) m.upgraded = true;
        else if (m.listed && line.rfind('#', 0) != 0 && plain_name(line)) m.names.insert(line);
    }
    return m;
}

std::string marker_text(const std::string& command, bool upgraded) {
    return "trnkit " + command + "\n" + kListLine + "\n" + (upgraded ? std::string(kUpgradedLine) + "\n" : "");
}

// The command named by a folder's marker ("" when it has none).
std::string marked_command(const std::string& folder) { return read_marker(folder).command; }

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
bool exchange_folders(const std::string& a, const std::string& b) {
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
        // Only a real folder that carries trnkit's staging marker: a user's "results.partial-2023"
        // is not ours to remove.
        const fs::file_status self = fs::symlink_status(it->path(), ec);
        const fs::file_status mark = fs::symlink_status(it->path() / kStagingMarker, ec);
        if (!fs::is_directory(self) || !fs::is_regular_file(mark)) continue;
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

void open_output_folder(const std::string& folder, const std::string& command, bool force, const std::string& option, Rerun rerun) {
    const FolderState state = check_output_folder(folder, command, force, option);
    if (state == FolderState::Absent) {
        std::error_code ec;
        fs::create_directories(folder, ec);
        if (ec) throw Error(option + " " + folder + ": cannot create folder (" + ec.message() + ")");
    }
    bool own = state == FolderState::OwnOutput;
    Marker m = read_marker(folder);
    // An older trnkit's marker lists nothing: its files may still be replaced by name (never removed).
    bool upgraded = own && (!m.listed || m.upgraded);
    int fd = output_registry::add(folder, own && m.listed ? m.names : std::set<std::string>{}, upgraded);
    if (rerun == Rerun::ReplacesPrevious) {
        while (::flock(fd, LOCK_EX) != 0 && errno == EINTR) {
        }
        m = read_marker(folder);  // an earlier run may have finished while we waited
        // A run started at the same time may have created the folder we found absent: once it has
        // finished, its marker makes the folder this command's own output, to be replaced.
        if (state == FolderState::Absent) own = check_output_folder(folder, command, force, option) == FolderState::OwnOutput;
        if (own && m.listed) {
            // Only the files the previous run listed, never a folder, and a link only as the link.
            for (const std::string& n : m.names) {
                if (n == kOutputMarker || n == kStagingMarker) continue;
                struct stat st {};
                if (::fstatat(fd, n.c_str(), &st, AT_SYMLINK_NOFOLLOW) == 0 && (S_ISREG(st.st_mode) || S_ISLNK(st.st_mode)))
                    ::unlinkat(fd, n.c_str(), 0);
            }
        }
        upgraded = own && (!m.listed || m.upgraded);
        output_registry::add(folder, {}, upgraded);
        write_file_atomic(folder + "/" + kOutputMarker, marker_text(command, upgraded), Destination::Derived);
    } else if (!(own && m.listed)) {
        write_file_atomic(folder + "/" + kOutputMarker, marker_text(command, upgraded), Destination::Derived);
    }
}

StagedFolder::StagedFolder(const std::string& target, std::string command, bool force, const std::string& option)
    : command_(std::move(command)) {
    state_ = check_output_folder(target, command_, force, option);
    target_ = without_trailing_separator(target);
    std::error_code ec;
    // The user's link to a folder stays a link: the folder it points to is the one replaced.
    if (fs::is_symlink(fs::symlink_status(target_, ec))) {
        const fs::path real = fs::canonical(target_, ec);
        if (ec) throw Error(option + " " + target + ": symbolic link to nothing usable (" + ec.message() + ")");
        target_ = real.string();
    }
    staging_ = target_ + ".partial-" + std::to_string(::getpid());
    remove_dead_stagings(target_);
    const fs::file_status left = fs::symlink_status(staging_, ec);
    if (fs::exists(left)) {
        // Only a dead run of this process id can have left one, and only if it is marked as ours.
        if (!fs::is_directory(left) || !fs::is_regular_file(fs::symlink_status(fs::path(staging_) / kStagingMarker, ec)))
            throw Error(option + " " + target + ": " + staging_ + " is in the way and is no staging folder of trnkit (move it away)");
        remove_tree(staging_);
    }
    fs::create_directories(fs::path(staging_).parent_path(), ec);
    if (!ec) fs::create_directory(staging_, ec);
    if (ec) throw Error(option + " " + target + ": cannot create the staging folder " + staging_ + " (" + ec.message() + ")");
    write_file_atomic(staging_ + "/" + kStagingMarker, "trnkit " + command_ + ": staging folder of " + target_ + ", process " +
                      std::to_string(::getpid()) + "\n", Destination::Derived);
    staging_fd_ = output_registry::add(staging_, {}, false);
    write_file_atomic(staging_ + "/" + kOutputMarker, marker_text(command_, false), Destination::Derived);
}

StagedFolder::~StagedFolder() {
    if (staging_fd_ >= 0) output_registry::drop(staging_fd_);
    if (!committed_) remove_tree(staging_);
}

void StagedFolder::commit() {
    if (committed_) throw Error(target_ + ": committed twice");
    output_registry::drop(staging_fd_);
    staging_fd_ = -1;
    std::error_code ec;
    std::vector<std::string> names;
    for (fs::directory_iterator it(staging_, ec), end; !ec && it != end; it.increment(ec)) names.push_back(it->path().filename().string());
    if (ec) throw Error(staging_ + ": cannot be listed (" + ec.message() + ")");
    if (state_ == FolderState::Foreign) {
        // Not ours to replace: move the new files in one by one; the folder's other files stay and
        // it stays unmarked.
        for (const std::string& n : names)
            if (n != kOutputMarker && n != kStagingMarker) rename_or_throw(staging_ + "/" + n, target_ + "/" + n, target_);
        committed_ = true;
        remove_tree(staging_);
        return;
    }
    const std::set<std::string> written(names.begin(), names.end());
    // What the earlier output holds that its command did not write (a user's notes, localize's
    // folder): moved into the new output, never removed. An older marker lists nothing: then all
    // but the names the new run writes and the frames (whose number changes) are kept.
    std::vector<std::string> keep;
    const bool had_target = fs::exists(fs::symlink_status(target_, ec));
    if (had_target) {
        const Marker old = read_marker(target_);
        for (fs::directory_iterator it(target_, ec), end; !ec && it != end; it.increment(ec)) {
            const std::string n = it->path().filename().string();
            if (n == kOutputMarker || n == kStagingMarker) continue;
            const bool was_ours = old.listed ? old.names.count(n) > 0 : (written.count(n) > 0 || n.rfind("frame_", 0) == 0);
            if (was_ours) continue;
            if (written.count(n))
                throw Error(target_ + "/" + n + ": was not written by trnkit " + command_ +
                            " and the new output has a file of that name; move it away (the earlier output is unchanged)");
            keep.push_back(n);
        }
        if (ec) throw Error(target_ + ": cannot be listed (" + ec.message() + ")");
    }
    ::unlink((staging_ + "/" + kStagingMarker).c_str());
    std::string old_output;  // where the earlier output is once the new one is in place
    if (!had_target) {
        rename_or_throw(staging_, target_, target_);
    } else if (exchange_folders(staging_, target_)) {
        old_output = staging_;
    } else {
        // No atomic exchange here: move the earlier output aside, put the new one in.
        old_output = target_ + ".old-" + std::to_string(::getpid());
        remove_tree(old_output);
        rename_or_throw(target_, old_output, target_);
        if (std::rename(staging_.c_str(), target_.c_str()) != 0) {
            const std::string why = std::strerror(errno);
            std::rename(old_output.c_str(), target_.c_str());
            throw Error(target_ + ": cannot replace (" + why + ")");
        }
    }
    committed_ = true;
    for (const std::string& n : keep)
        if (std::rename((old_output + "/" + n).c_str(), (target_ + "/" + n).c_str()) != 0)
            throw Error(target_ + ": the new output is in place, but " + old_output + "/" + n + " (not written by trnkit " + command_ +
                        ") could not be moved into it (" + std::strerror(errno) + "); the earlier output was left in " + old_output);
    if (!old_output.empty()) remove_tree(old_output);
}

}  // namespace trn::io
