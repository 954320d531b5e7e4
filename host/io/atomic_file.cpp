#include "trn/io/atomic_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>

#include "trn/error.hpp"

namespace trn::io {
namespace {

std::string errno_text() { return std::strerror(errno); }

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

void write_file_atomic(const std::string& path, std::string_view bytes) {
    const std::string tmp = temporary_sibling(path);
    const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
    if (fd < 0) throw Error(path + ": cannot create (" + errno_text() + ")");
    try {
        write_all(fd, bytes, path);
    } catch (...) {
        ::close(fd);
        ::unlink(tmp.c_str());
        throw;
    }
    if (::close(fd) != 0) {
        const std::string why = errno_text();
        ::unlink(tmp.c_str());
        throw Error(path + ": write failed on close (" + why + ")");
    }
    if (std::rename(tmp.c_str(), path.c_str()) != 0) {
        const std::string why = errno_text();
        ::unlink(tmp.c_str());
        throw Error(path + ": cannot replace (" + why + ")");
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
