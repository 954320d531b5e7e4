#pragma once
// Files written completely or not at all. Every trnkit writer goes through here:
//  - the bytes go to a temporary name in the destination's own folder ("<name>.tmp-<pid>-<n>"),
//  - every write, the flush and the close are checked (a full disk or a file-size limit is an Error
//    naming the destination, never a silently cut file),
//  - rename() publishes the complete file; on any failure the temporary is removed and an earlier
//    file of that name is left as it was.
// A destination that exists and is not a regular file (/dev/full, /dev/stdout, a FIFO) cannot be
// replaced by a rename: it is written in place, with the same checks. A symbolic link to a regular
// file is followed, so the link stays and its target is replaced.
#include <sstream>
#include <string>
#include <string_view>
#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn::io {

class AtomicFile {
public:
    explicit AtomicFile(std::string path);  // the destination; nothing is opened until commit()
    ~AtomicFile();                          // an uncommitted file leaves no trace
    AtomicFile(const AtomicFile&) = delete;
    AtomicFile& operator=(const AtomicFile&) = delete;

    std::ostream& stream() { return buffer_; }  // text goes here first
    template <class T>
    AtomicFile& operator<<(const T& v) {
        buffer_ << v;
        return *this;
    }
    void commit();  // write the temporary, check, rename; throws trn::Error naming path()
    const std::string& path() const { return path_; }

private:
    std::string path_;
    std::ostringstream buffer_;
    bool committed_ = false;
};

// The whole file in one call (same rules as AtomicFile).
void write_file_atomic(const std::string& path, std::string_view bytes);

// Throws trn::Error ("<option> <path>: why") unless a file can be written at `path` by
// write_file_atomic: not a folder, its folder exists and is writable (or, for a special file such
// as /dev/null, the file itself is writable). For checking outputs before any work is done.
void check_output_file(const std::string& path, const std::string& option = "");

// A temporary name next to `path` (same folder, so rename() stays on one file system).
std::string temporary_sibling(const std::string& path);

// Writes `bytes` to an already-open descriptor, retrying short writes; throws naming `what` on error.
void write_all(int fd, std::string_view bytes, const std::string& what);

}  // namespace trn::io
TRN_API_END
