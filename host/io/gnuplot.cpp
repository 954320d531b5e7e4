#include "trn/io/gnuplot.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <set>

#include "trn/error.hpp"
#include "trn/io/atomic_file.hpp"

extern char** environ;  // handed to gnuplot as it is; the library itself reads no variable

namespace trn::io {
namespace {
namespace fs = std::filesystem;

// Length of the valid UTF-8 sequence at s[i] (RFC 3629: no overlongs, surrogates or code
// points above U+10FFFF), 0 when there is none; `cp` gets its code point.
std::size_t utf8_sequence(std::string_view s, std::size_t i, char32_t& cp) {
    const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(s[k]); };
    const unsigned char c = byte(i);
    std::size_t len = 0;
    char32_t min = 0;
    if (c >= 0xC2 && c <= 0xDF) len = 2, min = 0x80, cp = c & 0x1F;
    else if (c >= 0xE0 && c <= 0xEF) len = 3, min = 0x800, cp = c & 0x0F;
    else if (c >= 0xF0 && c <= 0xF4) len = 4, min = 0x10000, cp = c & 0x07;
    else return 0;
    if (i + len > s.size()) return 0;
    for (std::size_t k = 1; k < len; ++k) {
        if ((byte(i + k) & 0xC0) != 0x80) return 0;
        cp = (cp << 6) | (byte(i + k) & 0x3F);
    }
    if (cp < min || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) return 0;
    return len;
}

bool plain_char(char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '.' || c == '_' || c == '-';
}

// A path as an error message shows it: on one line (the CLI prints errors as one line).
std::string shown(const std::string& path) { return gnuplot_sanitized(path); }

void check_name(const std::string& name, const std::string& role) {
    if (!is_plain_basename(name))
        throw Error("gnuplot: " + role + " '" + gnuplot_sanitized(name) + "' is not a plain file name ([A-Za-z0-9._-], no leading '-')");
}

// Starts gnuplot with `args` in `folder` (empty: inherited), stdin from /dev/null and stdout and
// stderr to `log` (a name inside folder, or a full path). Returns posix_spawnp's error or 0.
int spawn_gnuplot(const std::vector<std::string>& args, const std::string& folder, const std::string& log, pid_t& pid) {
    posix_spawn_file_actions_t actions;
    if (posix_spawn_file_actions_init(&actions) != 0) return errno;
    int rc = 0;
    if (!folder.empty()) rc = posix_spawn_file_actions_addchdir_np(&actions, folder.c_str());
    if (!rc) rc = posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
    if (!rc) rc = posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (!rc) rc = posix_spawn_file_actions_adddup2(&actions, 1, 2);
    std::vector<std::string> owned = args;
    std::vector<char*> argv;
    for (std::string& a : owned) argv.push_back(a.data());
    argv.push_back(nullptr);
    if (!rc) rc = posix_spawnp(&pid, argv[0], &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    return rc;
}

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
    for (const auto& [name, bytes] : job.data) write_file_atomic(dir + name, bytes);
    write_file_atomic(dir + job.script_name, job.script);

    const std::string script = shown(dir + job.script_name), log = shown(dir + job.log_name);
    auto remove_images = [&] {
        std::error_code ec;
        for (const PlotTarget& image : job.images) fs::remove(dir + image.name, ec);
    };
    pid_t pid = 0;
    // -d: no ~/.gnuplot or other init file, so a figure looks the same everywhere.
    const int rc = spawn_gnuplot({"gnuplot", "-d", job.script_name}, job.folder, job.log_name, pid);
    if (rc == ENOENT && fs::is_directory(job.folder))
        throw Error("gnuplot not found on PATH (install gnuplot-nox, see scripts/install-deps.sh); " + script + " was written");
    if (rc != 0) throw Error("gnuplot: cannot start it for " + script + " (" + std::strerror(rc) + ")");
    if (wait_for(pid) != 0) {
        remove_images();
        throw Error("gnuplot failed on " + script + " (see " + log + ")");
    }
    for (const PlotTarget& image : job.images) {
        const std::string made = dir + image.name;
        std::error_code ec;
        if (fs::file_size(made, ec) == 0 || ec) {
            remove_images();
            throw Error("gnuplot wrote no image " + shown(made) + " from " + script + " (see " + log + ")");
        }
    }
    for (const PlotTarget& image : job.images) {
        const std::string made = dir + image.name;
        if (made == image.path) continue;
        std::error_code ec;
        fs::rename(made, image.path, ec);
        if (ec) throw Error(shown(image.path) + ": cannot move the image there (" + ec.message() + ")");
    }
}

bool gnuplot_available() {
    pid_t pid = 0;
    return spawn_gnuplot({"gnuplot", "--version"}, "", "/dev/null", pid) == 0 && wait_for(pid) == 0;
}

}  // namespace trn::io
