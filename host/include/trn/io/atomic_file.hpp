#pragma once
// Files written completely or not at all, under one rule for what is already at the destination.
// Every trnkit writer goes through here (docs/RELIABILITY.md, "Hostile inputs and paths"):
//  - the folder is opened once and everything after is relative to it (openat, O_NOFOLLOW), so a
//    link planted in the folder, or swapped in while we write, is never followed by accident;
//  - the bytes go to a temporary name in that folder ("<name>.tmp-<pid>-<n>", created O_EXCL),
//    every write, the flush and the close are checked (a full disk or a file-size limit is an Error
//    naming the destination, never a silently cut file);
//  - rename() publishes the complete file; on any failure the temporary is removed and an earlier
//    file of that name is left as it was. A replaced file keeps its permission bits (and owner and
//    group where the process may set them); a file with more than one hard link is refused, since
//    a rename would split the links silently.
// What is already there decides the rest:
//  - the path the user named (Destination::Named): a symbolic link is followed (the link stays, its
//    target is replaced); a device, FIFO or socket (/dev/full, /dev/stdout) is written in place,
//    never unlinked or renamed over;
//  - a name trnkit chose itself (Destination::Derived), and every file inside an output folder this
//    process opened (output_folder.hpp): a symbolic link or a non-regular file is refused; inside
//    an output folder an existing file the folder's marker does not list (someone else's) is
//    refused too, and every file written there is added to the marker's list.
#include <set>
#include <sstream>
#include <string>
#include <string_view>
#include <utility>
#include <vector>
#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn::io {

// Who chose a destination's name (see above).
enum class Destination { Named, Derived };

class AtomicFile {
public:
    explicit AtomicFile(std::string path, Destination d = Destination::Named);  // nothing is opened until commit()
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
    Destination destination_;
    std::ostringstream buffer_;
    bool committed_ = false;
};

// The whole file in one call (same rules as AtomicFile).
void write_file_atomic(const std::string& path, std::string_view bytes, Destination d = Destination::Named);

// Throws trn::Error ("<option> <path>: why") unless a file can be written at `path` by
// write_file_atomic as a named destination: not a folder, no other hard link, its folder exists and
// is writable (or, for a special file such as /dev/null, the file itself is writable; a link is
// checked at its target). For checking outputs before any work is done.
void check_output_file(const std::string& path, const std::string& option = "");

// Throws trn::Error when the output `path` (an existing file) is one of the inputs (the same file,
// also under another name or through a link): "<option> <path>: is the same file as <input option>
// <input>". `inputs` are (option, path) pairs.
void check_output_is_not_input(const std::string& path, const std::string& option,
                               const std::vector<std::pair<std::string, std::string>>& inputs);

// A file that only grows, one whole record per append (the results store): opened for reading and
// appending (O_APPEND, created 0644 when absent) without following a symbolic link at the name and
// without blocking on a FIFO; a link, a non-regular file or a file with another hard link is
// refused, naming `what` ("the results store"). Returns the descriptor (the caller closes it).
// Appending, not replacing, is what lets parallel jobs share one file; hence not write_file_atomic.
int open_for_append(const std::string& path, const std::string& what);

// A temporary name next to `path` (same folder, so rename() stays on one file system).
std::string temporary_sibling(const std::string& path);

// Writes `bytes` to an already-open descriptor, retrying short writes; throws naming `what` on error.
void write_all(int fd, std::string_view bytes, const std::string& what);

// Output folders of this process (used by output_folder.hpp; not needed by writers). A registered
// folder is opened once (its descriptor stays open until it is dropped) and writes into it follow
// the output-folder rule above: `listed` are the names its marker lists (files this command wrote
// there), `any_replaceable` lets unlisted files be replaced by name (a marker of an older trnkit,
// which listed nothing). Registering a folder twice returns the first registration's descriptor.
namespace output_registry {
int add(const std::string& folder, std::set<std::string> listed, bool any_replaceable);
bool contains(const std::string& folder);  // whether `folder` is a registered output folder
void drop(int fd);  // closes the descriptor add() returned; later writes there follow the plain rules
}  // namespace output_registry

}  // namespace trn::io
TRN_API_END
