#include "trn/io/atomic_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <memory>
#include <mutex>
#include <utility>

#include "trn/error.hpp"
#include "trn/io/output_folder.hpp"

namespace trn::io {
namespace {

std::string errno_text(int e) { return std::strerror(e); }
std::string errno_text() { return errno_text(errno); }

// "a/b/c" -> ("a/b", "c"); a bare name's folder is ".".
std::pair<std::string, std::string> split(const std::string& path) {
    const std::filesystem::path p(path);
    const std::string name = p.filename().string();
    if (name.empty() || name == "." || name == "..") throw Error(path + ": not a file name");
    return {p.has_parent_path() ? p.parent_path().string() : ".", name};
}

// An open folder descriptor, closed unless it belongs to the registry.
struct FolderFd {
    int fd = -1;
    bool owned = false;
    FolderFd() = default;
    FolderFd(int f, bool o) : fd(f), owned(o) {}
    FolderFd(FolderFd&& o) noexcept : fd(o.fd), owned(std::exchange(o.owned, false)) {}
    FolderFd& operator=(FolderFd&& o) noexcept {
        std::swap(fd, o.fd);
        std::swap(owned, o.owned);
        return *this;
    }
    ~FolderFd() {
        if (owned && fd >= 0) ::close(fd);
    }
};

struct Registered {
    dev_t dev;
    ino_t ino;
    int fd;
    std::string path;
    std::set<std::string> listed;
    bool any_replaceable;
};

std::mutex& registry_mutex() {
    static std::mutex m;
    return m;
}
std::vector<std::unique_ptr<Registered>>& registry() {
    static std::vector<std::unique_ptr<Registered>> r;
    return r;
}
Registered* find_registered(dev_t dev, ino_t ino) {
    for (auto& r : registry())
        if (r->dev == dev && r->ino == ino) return r.get();
    return nullptr;
}

// What the folder of a destination is: its descriptor and, for an output folder of this process,
// a copy of its registration (so the registry lock is not held while writing).
struct Where {
    FolderFd folder;
    bool output_folder = false;
    std::string output_path;
    bool listed = false, any_replaceable = false;
};

Where open_folder_of(const std::string& given, const std::string& folder, const std::string& name) {
    Where w;
    w.folder.fd = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (w.folder.fd < 0) throw Error(given + ": cannot create (folder " + folder + ": " + errno_text() + ")");
    w.folder.owned = true;
    struct stat st {};
    if (::fstat(w.folder.fd, &st) != 0) throw Error(given + ": cannot create (" + errno_text() + ")");
    std::lock_guard lock(registry_mutex());
    if (Registered* r = find_registered(st.st_dev, st.st_ino)) {
        w.folder = FolderFd(r->fd, false);  // the old descriptor is closed with the swapped-out value
        w.output_folder = true;
        w.output_path = r->path;
        w.listed = r->listed.count(name) > 0;
        w.any_replaceable = r->any_replaceable;
    }
    return w;
}

// Adds `name` to the marker of the registered folder `fd` (one appended line; several processes
// may add to one marker at once, as the jobs of `trnkit experiment` do).
void list_in_marker(int fd, const std::string& name, const std::string& given) {
    if (name == kOutputMarker || name.find('\n') != std::string::npos) return;
    {
        std::lock_guard lock(registry_mutex());
        for (auto& r : registry())
            if (r->fd == fd && !r->listed.insert(name).second) return;  // listed already
    }
    const int m = ::openat(fd, kOutputMarker, O_WRONLY | O_APPEND | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
    if (m < 0) throw Error(given + ": cannot list it in the folder's " + kOutputMarker + " (" + errno_text() + ")");
    struct stat st {};
    if (::fstat(m, &st) != 0 || !S_ISREG(st.st_mode) || st.st_nlink != 1) {
        ::close(m);
        throw Error(given + ": the folder's " + kOutputMarker + " is not a plain file");
    }
    try {
        write_all(m, name + "\n", given + ": listing it in " + kOutputMarker);
    } catch (...) {
        ::close(m);
        throw;
    }
    if (::close(m) != 0) throw Error(given + ": cannot list it in " + kOutputMarker + " (" + errno_text() + ")");
}

// Devices and FIFOs are written where they are: renaming over /dev/full would replace the device.
void write_in_place(int dirfd, const std::string& name, const std::string& given, std::string_view bytes) {
    const int fd = ::openat(dirfd, name.c_str(), O_WRONLY | O_CLOEXEC | O_NOCTTY | O_NOFOLLOW);
    if (fd < 0) throw Error(given + ": cannot open for writing (" + errno_text() + ")");
    struct stat st {};
    if (::fstat(fd, &st) == 0 && S_ISREG(st.st_mode)) {  // swapped for a file after we looked
        ::close(fd);
        throw Error(given + ": changed while being written");
    }
    try {
        write_all(fd, bytes, given);
    } catch (...) {
        ::close(fd);
        throw;
    }
    if (::close(fd) != 0) throw Error(given + ": write failed on close (" + errno_text() + ")");
}

void write_file(const std::string& given, std::string_view bytes, Destination d, int links_left) {
    if (given.empty()) throw Error("output file: empty file name");
    const auto [folder, name] = split(given);
    Where w = open_folder_of(given, folder, name);
    const int dfd = w.folder.fd;
    const bool derived = w.output_folder || d == Destination::Derived;
    const std::string where = w.output_folder ? " inside the output folder " + w.output_path : " where trnkit writes a file of its own";

    struct stat st {};
    bool exists = false;
    if (::fstatat(dfd, name.c_str(), &st, AT_SYMLINK_NOFOLLOW) == 0) {
        exists = true;
        if (S_ISLNK(st.st_mode)) {
            if (derived) throw Error(given + ": is a symbolic link" + where + "; trnkit does not write through it (remove it)");
            char* real = ::realpath(given.c_str(), nullptr);
            if (!real) throw Error(given + ": symbolic link to nothing usable (" + errno_text() + ")");
            const std::string target(real);
            std::free(real);
            if (links_left <= 0) throw Error(given + ": symbolic links keep changing");
            return write_file(target, bytes, Destination::Named, links_left - 1);
        }
        if (S_ISDIR(st.st_mode)) throw Error(given + ": is a folder, not a file");
        if (!S_ISREG(st.st_mode)) {
            if (derived) throw Error(given + ": is not a regular file (a device, FIFO or socket)" + where + "; it is left as it is");
            return write_in_place(dfd, name, given, bytes);
        }
        if (st.st_nlink > 1)
            throw Error(given + ": has " + std::to_string(st.st_nlink) +
                        " hard links; trnkit replaces a file by a new one, which would split them (remove the other links or write elsewhere)");
        if (w.output_folder && name != kOutputMarker && !w.listed && !w.any_replaceable)
            throw Error(given + ": exists and was not written here by trnkit (" + w.output_path + "/" + kOutputMarker +
                        " does not list it); it is left as it is (move it away)");
    } else if (errno != ENOENT) {
        throw Error(given + ": cannot be written (" + errno_text() + ")");
    }

    static std::atomic<unsigned> counter{0};
    const std::string tmp = name + ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
    const int fd = ::openat(dfd, tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
    if (fd < 0) throw Error(given + ": cannot create (" + errno_text() + ")");
    auto fail = [&](const std::string& what) {
        ::unlinkat(dfd, tmp.c_str(), 0);
        throw Error(given + ": " + what);
    };
    if (exists) {
        // The replacement keeps what the file was: its permission bits (0600 stays 0600) and, where
        // the process may set them, owner and group. Never set-id bits.
        if (st.st_uid != ::geteuid() || st.st_gid != ::getegid())
            if (::fchown(fd, st.st_uid, st.st_gid) != 0) {
                // not ours to give away: the new file is the writer's
            }
        if (::fchmod(fd, st.st_mode & 0777) != 0) {
            const std::string why = errno_text();
            ::close(fd);
            fail("cannot keep its permissions (" + why + ")");
        }
    }
    try {
        write_all(fd, bytes, given);
    } catch (...) {
        ::close(fd);
        ::unlinkat(dfd, tmp.c_str(), 0);
        throw;
    }
    if (::close(fd) != 0) fail("write failed on close (" + errno_text() + ")");
    if (w.output_folder && !w.listed) {
        try {
            list_in_marker(dfd, name, given);
        } catch (...) {
            ::unlinkat(dfd, tmp.c_str(), 0);
            throw;
        }
    }
    if (::renameat(dfd, tmp.c_str(), dfd, name.c_str()) != 0) fail("cannot replace (" + errno_text() + ")");
}

}  // namespace

std::string temporary_sibling(const std::string& path) {
    static std::atomic<unsigned> counter{0};
    return path + ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
}

void write_all(int fd, std::string_view bytes, const std::string& what) {
    const char* p = bytes.data();
    std::size_t left = bytes.size();
    while (left) {
        const ssize_t n = ::write(fd, p, left);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) throw Error(what + ": write failed (" + (n < 0 ? errno_text() : std::string("no progress")) + ")");
        p += n;
        left -= static_cast<std::size_t>(n);
    }
}

int open_for_append(const std::string& path, const std::string& what) {
    const int fd = ::open(path.c_str(), O_RDWR | O_APPEND | O_CREAT | O_NOFOLLOW | O_NONBLOCK | O_NOCTTY | O_CLOEXEC, 0644);
    if (fd < 0) {
        const int e = errno;
        if (e == ELOOP) throw Error(path + ": is a symbolic link; trnkit does not append " + what + " through it (remove it)");
        throw Error(path + ": cannot open " + what + " for appending (" + errno_text(e) + ")");
    }
    struct stat st {};
    std::string why;
    if (::fstat(fd, &st) != 0) why = "cannot read its status (" + errno_text() + ")";
    else if (!S_ISREG(st.st_mode)) why = "is not a regular file (a device, FIFO or socket); it is left as it is";
    else if (st.st_nlink > 1) why = "has " + std::to_string(st.st_nlink) + " hard links; trnkit appends only to a file of its own";
    else if (::fcntl(fd, F_SETFL, O_APPEND) != 0) why = "cannot be opened for appending (" + errno_text() + ")";
    if (!why.empty()) {
        ::close(fd);
        throw Error(path + ": " + why);
    }
    return fd;
}

void check_output_file(const std::string& given, const std::string& option) {
    const std::string name = option.empty() ? given : option + " " + given;
    if (given.empty()) throw Error((option.empty() ? std::string("output file") : option) + ": empty file name");
    std::string path = given;
    struct stat st {};
    if (::lstat(given.c_str(), &st) == 0 && S_ISLNK(st.st_mode)) {
        char* real = ::realpath(given.c_str(), nullptr);
        if (!real) throw Error(name + ": symbolic link to nothing usable (" + errno_text() + ")");
        path = real;
        std::free(real);
    }
    if (::lstat(path.c_str(), &st) == 0) {
        if (S_ISDIR(st.st_mode)) throw Error(name + ": is a folder, not a file");
        if (!S_ISREG(st.st_mode)) {
            if (::access(path.c_str(), W_OK) != 0) throw Error(name + ": not writable (" + errno_text() + ")");
            return;
        }
        if (st.st_nlink > 1)
            throw Error(name + ": has " + std::to_string(st.st_nlink) +
                        " hard links; trnkit replaces a file by a new one, which would split them (remove the other links or write elsewhere)");
    } else if (errno != ENOENT) {
        throw Error(name + ": cannot be written (" + errno_text() + ")");
    }
    const std::filesystem::path p(path);
    const std::string folder = p.has_parent_path() ? p.parent_path().string() : ".";
    struct stat fs {};
    if (::stat(folder.c_str(), &fs) != 0) throw Error(name + ": folder " + folder + " does not exist (" + errno_text() + ")");
    if (!S_ISDIR(fs.st_mode)) throw Error(name + ": " + folder + " is not a folder");
    if (::access(folder.c_str(), W_OK | X_OK) != 0) throw Error(name + ": cannot write in " + folder + " (" + errno_text() + ")");
}

void check_output_is_not_input(const std::string& path, const std::string& option,
                               const std::vector<std::pair<std::string, std::string>>& inputs) {
    struct stat out {};
    if (path.empty() || ::stat(path.c_str(), &out) != 0 || !S_ISREG(out.st_mode)) return;  // a new file or a device
    for (const auto& [input_option, input] : inputs) {
        struct stat in {};
        if (!input.empty() && ::stat(input.c_str(), &in) == 0 && in.st_dev == out.st_dev && in.st_ino == out.st_ino)
            throw Error((option.empty() ? "" : option + " ") + path + ": is the same file as " +
                        (input_option.empty() ? "" : input_option + " ") + input + " (it would be overwritten while it is read)");
    }
}

void write_file_atomic(const std::string& given, std::string_view bytes, Destination d) { write_file(given, bytes, d, 8); }

AtomicFile::AtomicFile(std::string path, Destination d) : path_(std::move(path)), destination_(d) {}

AtomicFile::~AtomicFile() = default;

void AtomicFile::commit() {
    if (committed_) throw Error(path_ + ": committed twice");
    if (!buffer_) throw Error(path_ + ": formatting failed");
    write_file_atomic(path_, buffer_.view(), destination_);
    committed_ = true;
}

namespace output_registry {

int add(const std::string& folder, std::set<std::string> listed, bool any_replaceable) {
    const int fd = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0) throw Error(folder + ": cannot open the output folder (" + errno_text() + ")");
    struct stat st {};
    if (::fstat(fd, &st) != 0) {
        const std::string why = errno_text();
        ::close(fd);
        throw Error(folder + ": cannot open the output folder (" + why + ")");
    }
    std::lock_guard lock(registry_mutex());
    if (Registered* r = find_registered(st.st_dev, st.st_ino)) {
        ::close(fd);
        r->listed = std::move(listed);
        r->any_replaceable = any_replaceable;
        return r->fd;
    }
    registry().push_back(std::make_unique<Registered>(Registered{st.st_dev, st.st_ino, fd, folder, std::move(listed), any_replaceable}));
    return fd;
}

bool contains(const std::string& folder) {
    struct stat st {};
    if (::stat(folder.c_str(), &st) != 0) return false;
    std::lock_guard lock(registry_mutex());
    return find_registered(st.st_dev, st.st_ino) != nullptr;
}

void drop(int fd) {
    std::lock_guard lock(registry_mutex());
    auto& r = registry();
    for (auto it = r.begin(); it != r.end(); ++it)
        if ((*it)->fd == fd) {
            ::close((*it)->fd);
            r.erase(it);
            return;
        }
}

}  // namespace output_registry

}  // namespace trn::io
