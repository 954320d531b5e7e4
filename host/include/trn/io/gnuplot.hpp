#pragma once
// gnuplot for every trnkit figure, with no way for text from an input or an option to run as code.
//  - Labels enter a script only through gnuplot_string(): a string expression that cannot end
//    early (see there), and every terminal is `noenhanced` (gnuplot_png_terminal()).
//  - Scripts name their data and image files by plain basenames we choose; gnuplot runs in the
//    output folder, so no user path is ever pasted into a script.
//  - gnuplot is started without a shell (posix_spawn with an argv) by an absolute path resolved
//    before anything changes folder (set_gnuplot_program), never through a relative PATH entry.
//  - It runs in a private work folder (created 0700 beside the images, or under /tmp for a device
//    or FIFO target), so nothing in the output folder -- a planted `gnuplot`, a link named like its
//    log -- is run or written through. Only then are the images written to their targets and the
//    script, data and log (the sidecars) beside them, each by the one rule of atomic_file.hpp; a
//    sidecar never replaces a file that is not an earlier sidecar of the same plot (its script's
//    first line names them), and a device or FIFO target gets no sidecars.
#include <string>
#include <string_view>
#include <utility>
#include <vector>
#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn::io {

// A gnuplot string expression whose value is gnuplot_sanitized(text): single-quoted segments
// (gnuplot 5.4 expands nothing inside single quotes: no `command`, no \ escapes) joined with `.`
// to "\047" for an apostrophe and "\100" for an @. Not the doubled quote '': gnuplot's scanner
// splits a string at doubled quotes that open it or follow each other ('''x', 'a''''b'). Not "'":
// the @macro expander then loses track of the quotes and pastes a later @NAME (e.g. GPVAL_PWD, the
// output folder's name) into the line as code.
std::string gnuplot_string(std::string_view text);

// The text a label shows: every control character (C0 incl. NUL, newline, CR, tab; DEL; C1) and
// every byte that is not part of valid UTF-8 becomes '?' -- a line break would end the command
// and gnuplot would run the next line.
std::string gnuplot_sanitized(std::string_view text);

// True for a name gnuplot may be given: [A-Za-z0-9._-]+, not "." or "..", not starting with '-'.
bool is_plain_basename(std::string_view name);

// `name` with every character outside [A-Za-z0-9._-] replaced by '_' (and a leading '-' or '.' too),
// "plot" when nothing is left: a plain basename derived from a file name the user chose.
std::string plain_basename(std::string_view name);

// "set terminal pngcairo size W,H noenhanced" plus a font when given (a fixed font name of ours).
std::string gnuplot_png_terminal(int width, int height, std::string_view font = {});

// An image the user named (any path): gnuplot writes `name` (a plain basename) in its work folder,
// and those bytes are then written to `path` (a file of the sanitised name in `folder` is never
// touched). Data and script files are named after `name`.
struct PlotTarget {
    std::string folder;  // parent of path, "." when it has none
    std::string name;    // plain_basename(filename of path)
    std::string path;    // where the image ends up
};
PlotTarget plot_target(const std::string& path);

// One gnuplot run. Every name is a plain basename (checked before anything is written); the data
// files and the script go into a private work folder, gnuplot runs there with stdout/stderr in
// `log`. Afterwards each image must exist and not be empty; the sidecars are put into `folder` and
// the images written to their targets. Errors (a missing gnuplot, a failed script, no image, a
// sidecar name taken by someone else's file) are trn::Error naming the script and the log; on
// failure no image target is touched.
struct GnuplotJob {
    std::string folder;
    std::string script_name, script;
    std::vector<std::pair<std::string, std::string>> data;  // basename, bytes
    std::string log_name;
    std::vector<PlotTarget> images;  // each with .folder == folder
};
void run_gnuplot(const GnuplotJob& job);

// Whether `gnuplot --version` can be started and succeeds (no shell; the program above).
bool gnuplot_available();

// The gnuplot program: an absolute path. The CLI sets it from PATH at start-up (find_program; ""
// when PATH has none: plots then fail with "gnuplot not found on PATH"). Never set, the library
// looks in the system's default path (confstr(_CS_PATH), e.g. /bin:/usr/bin) -- it reads no
// environment. A relative path is refused.
void set_gnuplot_program(std::string absolute_path);
std::string gnuplot_program();

// The first absolute entry of `search_path` (a PATH-like list) holding an executable regular file
// `name`, "" when none. Relative and empty entries ("." or "::", which mean the current folder)
// are skipped: a program is never found in whatever folder the process happens to be in.
std::string find_program(std::string_view name, std::string_view search_path);

}  // namespace trn::io
TRN_API_END
