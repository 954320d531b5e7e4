/* LD_PRELOAD library for the CLI fuzzer: records every file-system change that SUCCEEDED outside
 * the allowed folders, so the fuzzer can fail a run that wrote outside its temporary folder.
 *   TRN_WATCH_ALLOW  colon-separated path prefixes where changes are fine (the sandbox, /dev/)
 *   TRN_WATCH_LOG    file that gets one line "<call> <absolute path>" per change elsewhere
 * Only calls that go through the C library are seen (no raw syscalls), which covers
 * iostreams, stdio, OpenCV and std::filesystem. Failed calls wrote nothing and are not logged. */
#undef _FORTIFY_SOURCE /* the fortified open() wrappers would clash with ours */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <fcntl.h>
#include <limits.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <unistd.h>

#define REAL(name) ((__typeof__(&name))dlsym(RTLD_NEXT, #name))

/* Absolute, lexically normalised form of `path` as seen from directory fd `dirfd`. */
static void absolute(int dirfd, const char* path, char* out, size_t size) {
    char base[PATH_MAX] = "";
    if (path[0] != '/') {
        if (dirfd == AT_FDCWD) {
            if (!getcwd(base, sizeof base)) base[0] = 0;
        } else {
            char link[64];
            snprintf(link, sizeof link, "/proc/self/fd/%d", dirfd);
            const ssize_t n = readlink(link, base, sizeof base - 1);
            base[n > 0 ? n : 0] = 0;
        }
    }
    char joined[2 * PATH_MAX];
    snprintf(joined, sizeof joined, "%s/%s", base, path);
    /* collapse "//", "/./" and "/x/../" */
    size_t len = 0;
    out[0] = 0;
    for (char* save = NULL, *part = strtok_r(joined, "/", &save); part; part = strtok_r(NULL, "/", &save)) {
        if (strcmp(part, ".") == 0) continue;
        if (strcmp(part, "..") == 0) {
            while (len > 0 && out[len - 1] != '/') --len;
            if (len > 0) --len;
            out[len] = 0;
            continue;
        }
        const size_t n = strlen(part);
        if (len + n + 2 >= size) break;
        out[len++] = '/';
        memcpy(out + len, part, n + 1);
        len += n;
    }
    if (len == 0) strcpy(out, "/");
}

static int allowed(const char* abs) {
    const char* list = getenv("TRN_WATCH_ALLOW");
    if (!list) return 1;
    while (*list) {
        const char* end = strchr(list, ':');
        const size_t n = end ? (size_t)(end - list) : strlen(list);
        if (n > 0 && strncmp(abs, list, n) == 0 && (list[n - 1] == '/' || abs[n] == 0 || abs[n] == '/')) return 1;
        if (!end) break;
        list = end + 1;
    }
    return 0;
}

static void note(const char* call, int dirfd, const char* path) {
    const char* log = getenv("TRN_WATCH_LOG");
    if (!log || !path) return;
    char abs[PATH_MAX];
    absolute(dirfd, path, abs, sizeof abs);
    if (allowed(abs)) return;
    char line[PATH_MAX + 64];
    const int n = snprintf(line, sizeof line, "%s %s\n", call, abs);
    const int fd = (int)syscall(SYS_openat, AT_FDCWD, log, O_WRONLY | O_APPEND | O_CREAT | O_CLOEXEC, 0644);
    if (fd < 0) return;
    if (syscall(SYS_write, fd, line, (size_t)n) < 0) { /* nothing more to do */ }
    syscall(SYS_close, fd);
}

static int writes(int flags) { return (flags & O_ACCMODE) != O_RDONLY || (flags & (O_CREAT | O_TRUNC | O_APPEND)); }
static int mode_writes(const char* mode) { return mode && strpbrk(mode, "wa+") != NULL; }

#define OPEN_LIKE(name, ...)                                                             \
    int name(const char* path, int flags, ...) {                                         \
        mode_t mode = 0;                                                                 \
        if ((flags & O_CREAT) || (flags & O_TMPFILE) == O_TMPFILE) {                                       \
            va_list ap;                                                                  \
            va_start(ap, flags);                                                         \
            mode = va_arg(ap, mode_t);                                                   \
            va_end(ap);                                                                  \
        }                                                                                \
        const int fd = REAL(name)(path, flags, mode);                                    \
        if (fd >= 0 && writes(flags)) note(#name, AT_FDCWD, path);                       \
        return fd;                                                                       \
    }
OPEN_LIKE(open)
OPEN_LIKE(open64)

#define OPENAT_LIKE(name)                                                                \
    int name(int dirfd, const char* path, int flags, ...) {                              \
        mode_t mode = 0;                                                                 \
        if ((flags & O_CREAT) || (flags & O_TMPFILE) == O_TMPFILE) {                                       \
            va_list ap;                                                                  \
            va_start(ap, flags);                                                         \
            mode = va_arg(ap, mode_t);                                                   \
            va_end(ap);                                                                  \
        }                                                                                \
        const int fd = REAL(name)(dirfd, path, flags, mode);                             \
        if (fd >= 0 && writes(flags)) note(#name, dirfd, path);                          \
        return fd;                                                                       \
    }
OPENAT_LIKE(openat)
OPENAT_LIKE(openat64)

int creat(const char* path, mode_t mode) {
    const int fd = REAL(creat)(path, mode);
    if (fd >= 0) note("creat", AT_FDCWD, path);
    return fd;
}

FILE* fopen(const char* path, const char* mode) {
    FILE* f = REAL(fopen)(path, mode);
    if (f && mode_writes(mode)) note("fopen", AT_FDCWD, path);
    return f;
}

FILE* fopen64(const char* path, const char* mode) {
    FILE* f = REAL(fopen64)(path, mode);
    if (f && mode_writes(mode)) note("fopen64", AT_FDCWD, path);
    return f;
}

int mkdir(const char* path, mode_t mode) {
    const int r = REAL(mkdir)(path, mode);
    if (r == 0) note("mkdir", AT_FDCWD, path);
    return r;
}

int mkdirat(int dirfd, const char* path, mode_t mode) {
    const int r = REAL(mkdirat)(dirfd, path, mode);
    if (r == 0) note("mkdirat", dirfd, path);
    return r;
}

int rename(const char* from, const char* to) {
    const int r = REAL(rename)(from, to);
    if (r == 0) note("rename-from", AT_FDCWD, from), note("rename", AT_FDCWD, to);
    return r;
}

int renameat(int fromfd, const char* from, int tofd, const char* to) {
    const int r = REAL(renameat)(fromfd, from, tofd, to);
    if (r == 0) note("renameat-from", fromfd, from), note("renameat", tofd, to);
    return r;
}

int renameat2(int fromfd, const char* from, int tofd, const char* to, unsigned int flags) {
    const int r = REAL(renameat2)(fromfd, from, tofd, to, flags);
    if (r == 0) note("renameat2-from", fromfd, from), note("renameat2", tofd, to);
    return r;
}

int unlink(const char* path) {
    const int r = REAL(unlink)(path);
    if (r == 0) note("unlink", AT_FDCWD, path);
    return r;
}

int unlinkat(int dirfd, const char* path, int flags) {
    const int r = REAL(unlinkat)(dirfd, path, flags);
    if (r == 0) note("unlinkat", dirfd, path);
    return r;
}

int rmdir(const char* path) {
    const int r = REAL(rmdir)(path);
    if (r == 0) note("rmdir", AT_FDCWD, path);
    return r;
}

int truncate(const char* path, off_t length) {
    const int r = REAL(truncate)(path, length);
    if (r == 0) note("truncate", AT_FDCWD, path);
    return r;
}

int symlink(const char* target, const char* path) {
    const int r = REAL(symlink)(target, path);
    if (r == 0) note("symlink", AT_FDCWD, path);
    return r;
}

int link(const char* from, const char* to) {
    const int r = REAL(link)(from, to);
    if (r == 0) note("link", AT_FDCWD, to);
    return r;
}
