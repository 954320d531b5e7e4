#pragma once
// The one way trnkit opens a file it reads (issue 23): a regular file only (a FIFO, device, socket
// or folder is refused without blocking on it), of at most a stated size, with errno failures as
// one-line trn::Error messages naming the path. Also the small helpers every reader shares for
// hostile content: a UTF-8 byte order mark, quoting input text in an error message (control
// characters escaped, length capped) and the nesting depth of a JSON text.
// The limits are listed for users in docs/RELIABILITY.md ("Hostile inputs and paths").
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn::io {

// Largest files each reader accepts, in bytes.
inline constexpr std::uint64_t kMaxTableFileBytes = std::uint64_t{256} << 20;  // metadata.csv, pose CSVs: ~1 M rows
inline constexpr std::uint64_t kMaxJsonFileBytes = std::uint64_t{64} << 20;    // flight.json, job files, run reports
inline constexpr std::uint64_t kMaxImageFileBytes = std::uint64_t{4} << 30;    // images and maps: 2^30 px of RGBA
// Deepest nesting of arrays and objects in any JSON trnkit reads (its own files nest 4 levels).
inline constexpr int kMaxJsonDepth = 64;
// Most characters of input text an error message quotes.
inline constexpr std::size_t kMaxQuotedChars = 80;

// What identifies one version of a file: a replaced or rewritten file differs in one of these.
struct FileIdentity {
    std::uint64_t device = 0, inode = 0, size = 0;
    std::int64_t mtime_ns = 0;
    bool operator==(const FileIdentity&) const = default;
};

// Checks that `path` (symlinks followed) is a regular file of at most max_bytes and returns its
// identity. Throws trn::Error "PATH: cannot open (Permission denied)", "PATH: is a FIFO, not a
// regular file", "PATH: 3.0 GB is larger than the 256 MB a ... may have". `what` names the kind of
// file in that last message ("a pose file"); empty: "an input file".
FileIdentity check_input_file(const std::string& path, std::uint64_t max_bytes, std::string_view what = {});

// The whole file, after the checks of check_input_file (made on the opened descriptor, so a file
// swapped in between cannot slip past them); `identity` receives what was read.
std::string read_input_file(const std::string& path, std::uint64_t max_bytes, std::string_view what = {},
                            FileIdentity* identity = nullptr);

// The identity of `path` now (symlinks followed); all zero when it cannot be stat'ed.
FileIdentity file_identity(const std::string& path);

// strerror for an errno value, thread-safe.
std::string errno_message(int error);

// `text` without a leading UTF-8 byte order mark (EF BB BF).
std::string_view strip_bom(std::string_view text);

// `text` as an error message may quote it: control characters and DEL as \n, \r, \t or \xHH,
// and at most max_chars bytes of it, then "... (N bytes)".
std::string quote_input(std::string_view text, std::size_t max_chars = kMaxQuotedChars);

// Throws trn::Error "SOURCE: JSON nested deeper than 64 levels (at byte N)" when arrays and
// objects nest deeper than max_depth outside strings; the parsers and dump() recurse per level.
void check_json_depth(std::string_view text, const std::string& source, int max_depth = kMaxJsonDepth);

}  // namespace trn::io
TRN_API_END
