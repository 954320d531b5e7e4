#include "trn/io/gnuplot.hpp"
#include "trn/io/outside_text.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <sys/stat.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <set>
#include <sstream>

#include "trn/error.hpp"
#include "trn/io/atomic_file.hpp"

extern char** environ;  // handed to gnuplot as it is; the library itself reads no variable

namespace trn::io {
namespace {
namespace fs = std::filesystem;

bool plain_char(char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '.' || c == '_' || c == '-';
}

// A path as an error message shows it: on one line (the CLI prints errors as one line).
std::string shown(const std::string& path) { return gnuplot_sanitized(path); }

void check_name(const std::string& name, const std::string& role) {
    if (!is_plain_basename(name))
        throw Error("gnuplot: " + role + " '" + gnuplot_sanitized(name) + "' is not a plain file name ([A-Za-z0-9._-], no leading '-')");
}

std::mutex& program_mutex() {
    static std::mutex m;
    return m;
}
struct Program {
    bool set = false;
    std::string path;
};
Program& program_state() {
    static Program p;
    return p;
}

// Starts gnuplot (by its absolute path) with `args` in `folder` (empty: inherited), stdin from
// /dev/null and stdout and stderr to `log` (a new file inside folder, or a full path). Returns
// posix_spawn's error or 0; ENOENT when there is no gnuplot.
int spawn_gnuplot(const std::vector<std::string>& args, const std::string& folder, const std::string& log, pid_t& pid) {
    const std::string program = gnuplot_program();
    if (program.empty()) return ENOENT;
    posix_spawn_file_actions_t actions;
    if (posix_spawn_file_actions_init(&actions) != 0) return errno;
    int rc = 0;
    if (!folder.empty()) rc = posix_spawn_file_actions_addchdir_np(&actions, folder.c_str());
    if (!rc) rc = posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
    const int log_flags = folder.empty() ? O_WRONLY : O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW;
    if (!rc) rc = posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), log_flags, 0644);
    if (!rc) rc = posix_spawn_file_actions_adddup2(&actions, 1, 2);
    std::vector<std::string> owned = args;
    std::vector<char*> argv;
    for (std::string& a : owned) argv.push_back(a.data());
    argv.push_back(nullptr);
    if (!rc) rc = posix_spawn(&pid, program.c_str(), &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    return rc;
}

std::string read_small_file(const std::string& path, std::size_t limit) {
    const int fd = ::open(path.c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) return {};
    struct stat st {};
    std::string text;
    if (::fstat(fd, &st) == 0 && S_ISREG(st.st_mode) && static_cast<std::size_t>(st.st_size) <= limit) {
        char buf[65536];
        ssize_t n;
        while ((n = ::read(fd, buf, sizeof buf)) > 0) text.append(buf, static_cast<std::size_t>(n));
    }
    ::close(fd);
    return text;
}

// The first line of every script: names the plot's sidecars, so a later plot of the same name
// knows which files beside it are its own to replace.
constexpr std::string_view kSidecarsLine = "# written by trnkit; files of this plot (the next plot of this name replaces them):";

std::set<std::string> earlier_sidecars(const std::string& folder, const std::string& script_name) {
    const std::string text = read_small_file(folder + "/" + script_name, 1 << 20);
    std::set<std::string> names;
    if (text.rfind(kSidecarsLine, 0) != 0) return names;
    std::istringstream line(text.substr(kSidecarsLine.size(), text.find('\n') - kSidecarsLine.size()));
    for (std::string n; line >> n;) names.insert(n);
    return names;
}

// A work folder only this run uses, removed when done (unless kept to show a failure).
struct WorkFolder {
    std::string path;
    bool keep = false;
    ~WorkFolder() {
        std::error_code ec;
        if (!path.empty() && !keep) fs::remove_all(path, ec);
    }
};

int wait_for(pid_t pid) {
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0)
        if (errno != EINTR) return -1;
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace

std::string gnuplot_sanitized(std::string_view text) {
    std::string out;
    out.reserve(text.size());
    for (std::size_t i = 0; i < text.size();) {
        const unsigned char c = static_cast<unsigned char>(text[i]);
        if (c < 0x80) {
            out += c < 0x20 || c == 0x7F ? '?' : static_cast<char>(c);
            ++i;
            continue;
        }
        char32_t cp = 0;
        const std::size_t len = utf8_sequence(text, i, cp);
        if (len == 0) {
            out += '?';  // one per byte that belongs to no valid sequence
            ++i;
        } else {
            if (cp <= 0x9F) out += '?';  // C1 control
            else out.append(text.substr(i, len));
            i += len;
        }
    }
    return out;
}

std::string gnuplot_string(std::string_view text) {
    const std::string clean = gnuplot_sanitized(text);
    std::string out;
    auto separate = [&] {
        if (!out.empty()) out += '.';
    };
    std::size_t start = 0;
    while (start <= clean.size()) {
        const std::size_t special = std::min(clean.find_first_of("'@", start), clean.size());
        if (special > start) {
            separate();
            out += '\'';
            out.append(clean, start, special - start);
            out += '\'';
        }
        if (special == clean.size()) break;
        separate();
        out += clean[special] == '\'' ? "\"\\047\"" : "\"\\100\"";  // octal escapes: no quote, no @ in the script
        start = special + 1;
    }
    return out.empty() ? "''" : out;
}

bool is_plain_basename(std::string_view name) {
    if (name.empty() || name == "." || name == ".." || name.front() == '-') return false;
    for (char c : name)
        if (!plain_char(c)) return false;
    return true;
}

std::string plain_basename(std::string_view name) {
    std::string out;
    for (char c : name) out += plain_char(c) ? c : '_';
    if (!out.empty() && (out.front() == '-' || out.front() == '.')) out.front() = '_';
    return out.empty() ? "plot" : out;
}

std::string gnuplot_png_terminal(int width, int height, std::string_view font) {
    std::string s = "set terminal pngcairo size " + std::to_string(width) + "," + std::to_string(height);
    if (!font.empty()) s += " font " + gnuplot_string(font);
    return s + " noenhanced\n";
}

PlotTarget plot_target(const std::string& path) {
    const fs::path p(path);
    const std::string file = p.filename().string();
    if (file.empty() || file == "." || file == "..") throw Error(shown(path) + ": not a file name for an image");
    const std::string folder = p.parent_path().string();
    return {folder.empty() ? "." : folder, plain_basename(file), path};
}

void run_gnuplot(const GnuplotJob& job) {
    if (job.folder.empty()) throw Error("gnuplot: no output folder");
    std::set<std::string> names;
    auto add = [&](const std::string& name, const std::string& role) {
        check_name(name, role);
        if (!names.insert(name).second) throw Error("gnuplot: file name '" + name + "' used twice in one plot");
    };
    add(job.script_name, "script");
    add(job.log_name, "log");
    for (const auto& [name, bytes] : job.data) add(name, "data file");
    for (const PlotTarget& image : job.images) {
        add(image.name, "image");
        if (image.folder != job.folder) throw Error("gnuplot: image " + shown(image.path) + " is not in " + shown(job.folder));
    }
    const std::string dir = job.folder + "/";
    // A device or FIFO as the image (--plot /dev/stdout): written in place, and nothing beside it.
    bool special = false;
    for (const PlotTarget& image : job.images) {
        struct stat st {};
        if (::stat(image.path.c_str(), &st) == 0 && !S_ISREG(st.st_mode) && !S_ISDIR(st.st_mode)) special = true;
    }
    std::vector<std::string> sidecars{job.script_name};
    for (const auto& [name, bytes] : job.data) sidecars.push_back(name);
    sidecars.push_back(job.log_name);
    if (!special && !output_registry::contains(job.folder)) {
        // Outside an output folder (whose marker says what is ours) a sidecar may replace only an
        // earlier sidecar of this plot, as its script names them.
        const std::set<std::string> ours = earlier_sidecars(job.folder, job.script_name);
        for (const std::string& n : sidecars) {
            struct stat st {};
            if (::lstat((dir + n).c_str(), &st) == 0 && !(ours.count(n) && S_ISREG(st.st_mode)))
                throw Error(shown(dir + n) + ": exists and is not a file of an earlier trnkit plot of this name; it is left as it is (move it away or choose another name for the plot)");
        }
    }
    std::string script(kSidecarsLine);
    for (const std::string& n : sidecars) script += " " + n;
    script += "\n" + job.script;

    static std::atomic<unsigned> counter{0};
    WorkFolder work;
    if (special) {
        std::string templ = std::string(P_tmpdir) + "/trnkit-plot-XXXXXX";
        if (!::mkdtemp(templ.data())) throw Error("gnuplot: cannot create a work folder in " + std::string(P_tmpdir) + " (" + std::strerror(errno) + ")");
        work.path = templ;
    } else {
        work.path = dir + ".trnkit-plot-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
        if (::mkdir(work.path.c_str(), 0700) != 0)
            throw Error(shown(job.folder) + ": cannot create gnuplot's work folder (" + std::strerror(errno) + ")");
    }
    const std::string in_work = work.path + "/";
    for (const auto& [name, bytes] : job.data) write_file_atomic(in_work + name, bytes, Destination::Derived);
    write_file_atomic(in_work + job.script_name, script, Destination::Derived);

    // The sidecars beside the images (the script and log also when gnuplot fails, to be read).
    auto publish_sidecars = [&] {
        if (special) return;
        for (const std::string& n : sidecars) {
            const std::string bytes = read_small_file(in_work + n, std::size_t(1) << 31);
            write_file_atomic(dir + n, bytes, Destination::Derived);
        }
    };
    const std::string script_shown = shown((special ? in_work : dir) + job.script_name);
    const std::string log_shown = shown((special ? in_work : dir) + job.log_name);
    pid_t pid = 0;
    // -d: no ~/.gnuplot or other init file, so a figure looks the same everywhere.
    const int rc = spawn_gnuplot({"gnuplot", "-d", job.script_name}, work.path, job.log_name, pid);
    if (rc == ENOENT && gnuplot_program().empty()) {
        std::error_code ec;
        fs::remove(in_work + job.log_name, ec);
        sidecars.pop_back();
        publish_sidecars();
        throw Error("gnuplot not found on PATH (install gnuplot-nox, see scripts/install-deps.sh); " + script_shown + " was written");
    }
    if (rc != 0) throw Error("gnuplot: cannot start " + shown(gnuplot_program()) + " for " + script_shown + " (" + std::strerror(rc) + ")");
    if (wait_for(pid) != 0) {
        work.keep = special;
        publish_sidecars();
        throw Error("gnuplot failed on " + script_shown + " (see " + log_shown + ")");
    }
    std::vector<std::string> images;
    for (const PlotTarget& image : job.images) {
        const std::string made = in_work + image.name;
        std::error_code ec;
        if (fs::file_size(made, ec) == 0 || ec) {
            work.keep = special;
            publish_sidecars();
            throw Error("gnuplot wrote no image " + shown(dir + image.name) + " from " + script_shown + " (see " + log_shown + ")");
        }
        images.push_back(read_small_file(made, std::size_t(1) << 31));
    }
    publish_sidecars();
    for (std::size_t i = 0; i < job.images.size(); ++i) write_file_atomic(job.images[i].path, images[i]);
}

bool gnuplot_available() {
    pid_t pid = 0;
    return spawn_gnuplot({"gnuplot", "--version"}, "", "/dev/null", pid) == 0 && wait_for(pid) == 0;
}

std::string find_program(std::string_view name, std::string_view search_path) {
    if (name.empty() || name.find('/') != std::string_view::npos) return "";
    std::size_t start = 0;
    while (start <= search_path.size()) {
        const std::size_t colon = std::min(search_path.find(':', start), search_path.size());
        const std::string_view entry = search_path.substr(start, colon - start);
        start = colon + 1;
        if (entry.empty() || entry.front() != '/') continue;  // "", ".", "bin": the current folder, never searched
        const std::string candidate = std::string(entry) + "/" + std::string(name);
        struct stat st {};
        if (::stat(candidate.c_str(), &st) == 0 && S_ISREG(st.st_mode) && ::access(candidate.c_str(), X_OK) == 0) return candidate;
    }
    return "";
}

void set_gnuplot_program(std::string absolute_path) {
    if (!absolute_path.empty() && absolute_path.front() != '/')
        throw Error("gnuplot program '" + gnuplot_sanitized(absolute_path) + "' is not an absolute path");
    std::lock_guard lock(program_mutex());
    program_state() = {true, std::move(absolute_path)};
}

std::string gnuplot_program() {
    std::lock_guard lock(program_mutex());
    Program& p = program_state();
    if (!p.set) {
        std::string system_path(256, '\0');
        const std::size_t n = ::confstr(_CS_PATH, system_path.data(), system_path.size());
        system_path.resize(n > 0 && n <= system_path.size() ? n - 1 : 0);
        p = {true, find_program("gnuplot", system_path.empty() ? "/usr/bin:/bin" : system_path)};
    }
    return p.path;
}

}  // namespace trn::io
