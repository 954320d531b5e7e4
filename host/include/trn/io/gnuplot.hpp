#pragma once
// gnuplot for every trnkit figure, with no way for text from an input or an option to run as code.
//  - Labels enter a script only through gnuplot_string(): a string expression that cannot end
//    early (see there), and every terminal is `noenhanced` (gnuplot_png_terminal()).
//  - Scripts name their data and image files by plain basenames we choose; gnuplot runs in the
//    output folder, so no user path is ever pasted into a script.
//  - gnuplot is started without a shell (posix_spawnp with an argv; PATH is searched by the C
//    library), its output goes to a log file in that folder.
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

// An image the user named (any path): gnuplot writes `name` (a plain basename) in `folder`, which
// is then renamed to `path` when the two differ. Data and script files are named after `name`.
struct PlotTarget {
    std::string folder;  // parent of path, "." when it has none
    std::string name;    // plain_basename(filename of path)
    std::string path;    // where the image ends up
};
PlotTarget plot_target(const std::string& path);

// One gnuplot run. Every name is a plain basename inside `folder` (checked before anything is
// written); the data files and the script are written with write_file_atomic, then gnuplot runs
// in `folder` with stdout/stderr in `log`. Afterwards each image must exist and not be empty and is
// moved to its target path. Errors (a missing gnuplot, a failed script, no image) are trn::Error
// naming the script and the log; on failure the images of this run are removed.
struct GnuplotJob {
    std::string folder;
    std::string script_name, script;
    std::vector<std::pair<std::string, std::string>> data;  // basename, bytes
    std::string log_name;
    std::vector<PlotTarget> images;  // each with .folder == folder
};
void run_gnuplot(const GnuplotJob& job);

// Whether `gnuplot --version` can be started and succeeds (no shell; PATH searched by the C library).
bool gnuplot_available();

}  // namespace trn::io
TRN_API_END
