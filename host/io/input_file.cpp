// Opening and checking input files; see trn/io/input_file.hpp.
#include "trn/io/input_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "trn/error.hpp"
#include "trn/limits.hpp"

namespace trn::io {
namespace {

struct Fd {
    int fd = -1;
    explicit Fd(int f) : fd(f) {}
    Fd(Fd&& o) noexcept : fd(o.fd) { o.fd = -1; }
    Fd(const Fd&) = delete;
    Fd& operator=(const Fd&) = delete;
    Fd& operator=(Fd&&) = delete;
    ~Fd() {
        if (fd >= 0) ::close(fd);
    }
};

const char* kind_of(mode_t mode) {
    if (S_ISDIR(mode)) return "a folder";
    if (S_ISFIFO(mode)) return "a FIFO";
    if (S_ISCHR(mode)) return "a character device";
    if (S_ISBLK(mode)) return "a block device";
    if (S_ISSOCK(mode)) return "a socket";
    return "not a regular file";
}

FileIdentity identity_of(const struct stat& st) {
    return {static_cast<std::uint64_t>(st.st_dev), static_cast<std::uint64_t>(st.st_ino), static_cast<std::uint64_t>(st.st_size),
            static_cast<std::int64_t>(st.st_mtim.tv_sec) * 1'000'000'000 + st.st_mtim.tv_nsec};
}

std::string size_text(std::uint64_t bytes) {
    const std::uint64_t mib = bytes >> 20;
    return mib >= 1024 && mib % 1024 == 0 ? std::to_string(mib >> 10) + " GiB" : std::to_string(mib) + " MiB";
}

// Checks an opened (or stat'ed) file: regular, at most max_bytes.
void check_stat(const std::string& path, const struct stat& st, std::uint64_t max_bytes, std::string_view what) {
    if (!S_ISREG(st.st_mode)) {
        const char* kind = kind_of(st.st_mode);
        throw Error(quote_input(path, 512) + ": is " + kind + (std::strcmp(kind, "not a regular file") ? ", not a regular file" : ""));
    }
    if (static_cast<std::uint64_t>(st.st_size) > max_bytes)
        throw Error(quote_input(path, 512) + ": " + limits::format_bytes(double(st.st_size)) + " is larger than the " + size_text(max_bytes) +
                    " " + (what.empty() ? std::string("an input file") : std::string(what)) + " may have");
}

// Opens without blocking (a FIFO with no writer would block open() for ever) and without
// becoming the controlling terminal.
int open_checked(const std::string& path) {
    const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
    if (fd < 0) {
        const int e = errno;
        if (e == ENOENT) throw Error(quote_input(path, 512) + ": no such file");
        throw Error(quote_input(path, 512) + ": cannot open (" + errno_message(e) + ")");
    }
    return fd;
}

}  // namespace

std::string errno_message(int error) {
    char buf[256];
#if defined(__GLIBC__) && defined(_GNU_SOURCE)
    return ::strerror_r(error, buf, sizeof buf);
#else
    return ::strerror_r(error, buf, sizeof buf) == 0 ? buf : "error " + std::to_string(error);
#endif
}

// Opens the file (open_checked) and checks what fstat says of it (check_stat), filling `st`.
static Fd open_and_check(const std::string& path, std::uint64_t max_bytes, std::string_view what, struct stat& st) {
    Fd f{open_checked(path)};
    if (::fstat(f.fd, &st) != 0) {
        const int e = errno;
        throw Error(quote_input(path, 512) + ": cannot read its status (" + errno_message(e) + ")");
    }
    check_stat(path, st, max_bytes, what);
    return f;
}

FileIdentity check_input_file(const std::string& path, std::uint64_t max_bytes, std::string_view what) {
    struct stat st {};
    open_and_check(path, max_bytes, what, st);
    return identity_of(st);
}

std::string read_input_file(const std::string& path, std::uint64_t max_bytes, std::string_view what, FileIdentity* identity) {
    struct stat st {};
    const Fd f = open_and_check(path, max_bytes, what, st);
    // A regular file: O_NONBLOCK has no effect on it. Read what is there, but never more than the
    // limit, should it grow while being read.
    std::string text;
    text.reserve(static_cast<std::size_t>(st.st_size));
    char buf[1 << 16];
    while (true) {
        const ssize_t n = ::read(f.fd, buf, sizeof buf);
        if (n < 0) {
            if (errno == EINTR) continue;
            const int e = errno;
            throw Error(quote_input(path, 512) + ": read error (" + errno_message(e) + ")");
        }
        if (n == 0) break;
        text.append(buf, static_cast<std::size_t>(n));
        if (text.size() > max_bytes)
            throw Error(quote_input(path, 512) + ": grew past the " + size_text(max_bytes) + " " +
                        (what.empty() ? std::string("an input file") : std::string(what)) + " may have while it was read");
    }
    if (identity) *identity = identity_of(st);
    return text;
}

FileIdentity file_identity(const std::string& path) {
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0) return {};
    return identity_of(st);
}

std::string_view strip_bom(std::string_view text) {
    if (text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);
    return text;
}

std::string quote_input(std::string_view text, std::size_t max_chars) {
    std::string out;
    const std::size_t n = text.size() > max_chars ? max_chars : text.size();
    out.reserve(n + 24);
    for (std::size_t i = 0; i < n; ++i) {
        const unsigned char c = static_cast<unsigned char>(text[i]);
        if (c == '\n') out += "\\n";
        else if (c == '\r') out += "\\r";
        else if (c == '\t') out += "\\t";
        else if (c < 0x20 || c == 0x7f) {
            static const char hex[] = "0123456789abcdef";
            out += "\\x";
            out += hex[c >> 4];
            out += hex[c & 15];
        } else out += char(c);
    }
    if (n < text.size()) out += "... (" + std::to_string(text.size()) + " bytes)";
    return out;
}

void check_json_depth(std::string_view text, const std::string& source, int max_depth) {
    int depth = 0;
    bool in_string = false;
    for (std::size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (in_string) {
            if (c == '\\') ++i;
            else if (c == '"') in_string = false;
            continue;
        }
        if (c == '"') in_string = true;
        else if (c == '[' || c == '{') {
            if (++depth > max_depth)
                throw Error(source + ": JSON nested deeper than " + std::to_string(max_depth) + " levels (at byte " + std::to_string(i) +
                            "); not a file trnkit reads");
        } else if (c == ']' || c == '}') {
            if (depth > 0) --depth;
        }
    }
}

}  // namespace trn::io
