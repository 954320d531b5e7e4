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

#include "trn/error.hpp"

namespace trn::io {
namespace {

std::string errno_text(int e) { return std::strerror(e); }
std::string errno_text() { return errno_text(errno); }

// The folder a temporary for `path` goes into ("." for a bare file name).
std::string folder_of(const std::string& path) {
    const std::filesystem::path p(path);
    return p.has_parent_path() ? p.parent_path().string() : ".";
}

// A symbolic link to a regular file is replaced through its target, so the link survives.
std::string resolve_link(const std::string& path) {
    struct stat link {}, target {};
    if (::lstat(path.c_str(), &link) != 0 || !S_ISLNK(link.st_mode)) return path;
    if (::stat(path.c_str(), &target) != 0 || !S_ISREG(target.st_mode)) return path;
    char* real = ::realpath(path.c_str(), nullptr);
    if (!real) return path;
    std::string resolved(real);
    std::free(real);
    return resolved;
}

// Devices and FIFOs are written where they are: renaming over /dev/full would replace the device.
void write_in_place(const std::string& path, std::string_view bytes) {
    const int fd = ::open(path.c_str(), O_WRONLY | O_CLOEXEC | O_NOCTTY);
    if (fd < 0) throw Error(path + ": cannot open for writing (" + errno_text() + ")");
    try {
        write_all(fd, bytes, path);
    } catch (...) {
        ::close(fd);
        throw;
    }
    if (::close(fd) != 0) throw Error(path + ": write failed on close (" + errno_text() + ")");
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

void check_output_file(const std::string& given, const std::string& option) {
    const std::string name = option.empty() ? given : option + " " + given;
    if (given.empty()) throw Error((option.empty() ? std::string("output file") : option) + ": empty file name");
    const std::string path = resolve_link(given);
    struct stat st {};
    if (::stat(path.c_str(), &st) == 0) {
        if (S_ISDIR(st.st_mode)) throw Error(name + ": is a folder, not a file");
        if (!S_ISREG(st.st_mode)) {
            if (::access(path.c_str(), W_OK) != 0) throw Error(name + ": not writable (" + errno_text() + ")");
            return;
        }
    } else if (errno != ENOENT) {
        throw Error(name + ": cannot be written (" + errno_text() + ")");
    }
    const std::string folder = folder_of(path);
    struct stat fs {};
    if (::stat(folder.c_str(), &fs) != 0) throw Error(name + ": folder " + folder + " does not exist (" + errno_text() + ")");
    if (!S_ISDIR(fs.st_mode)) throw Error(name + ": " + folder + " is not a folder");
    if (::access(folder.c_str(), W_OK | X_OK) != 0) throw Error(name + ": cannot write in " + folder + " (" + errno_text() + ")");
}

void write_file_atomic(const std::string& given, std::string_view bytes) {
    const std::string path = resolve_link(given);
    struct stat st {};
    if (::stat(path.c_str(), &st) == 0) {
        if (S_ISDIR(st.st_mode)) throw Error(given + ": is a folder, not a file");
        if (!S_ISREG(st.st_mode)) return write_in_place(given, bytes);
    }
    const std::string tmp = temporary_sibling(path);
    const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
    if (fd < 0) throw Error(given + ": cannot create (" + errno_text() + ")");
    try {
        write_all(fd, bytes, given);
    } catch (...) {
        ::close(fd);
        ::unlink(tmp.c_str());
        throw;
    }
    if (::close(fd) != 0) {
        const std::string why = errno_text();
        ::unlink(tmp.c_str());
        throw Error(given + ": write failed on close (" + why + ")");
    }
    if (std::rename(tmp.c_str(), path.c_str()) != 0) {
        const std::string why = errno_text();
        ::unlink(tmp.c_str());
        throw Error(given + ": cannot replace (" + why + ")");
    }
}

AtomicFile::AtomicFile(std::string path) : path_(std::move(path)) {}

AtomicFile::~AtomicFile() = default;

void AtomicFile::commit() {
    if (committed_) throw Error(path_ + ": committed twice");
    if (!buffer_) throw Error(path_ + ": formatting failed");
    write_file_atomic(path_, buffer_.view());
    committed_ = true;
}

}  // namespace trn::io
