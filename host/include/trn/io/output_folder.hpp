#pragma once
// Output folders of trnkit commands. A folder a command writes carries a marker file,
// ".trnkit-output": its first line names that command ("trnkit simulate"), the lines after a
// "# trnkit-output 2" line list the files the command wrote there. A command writes only into a
// folder that is absent, empty or marked as its own earlier output; any other non-empty folder is
// refused (its files are someone else's) unless `force` is given. Everything is checked before any
// work starts, so a bad --out costs nothing and touches nothing. Inside an opened output folder
// every write follows the output-folder rule of atomic_file.hpp (no links, no special files, no
// file the marker does not list is replaced, every file written is listed), and a rerun removes or
// replaces only listed files: files the command did not write stay.
#include <string>
#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn::io {

inline constexpr const char* kOutputMarker = ".trnkit-output";
inline constexpr const char* kStagingMarker = ".trnkit-staging";  // in a StagedFolder's staging folder only

// What a folder is to a command about to write there.
enum class FolderState { Absent, Empty, OwnOutput, Foreign };

// Throws trn::Error ("<option> <folder>: why") when `command` may not write into `folder`: a file
// is in the way, the folder (or the nearest existing folder above it) is not writable, or the
// folder is Foreign and `force` is false. Returns the folder's state otherwise.
FolderState check_output_folder(const std::string& folder, const std::string& command, bool force,
                                const std::string& option = "--out");

// What a rerun does with the files the previous run of the command listed in the marker.
enum class Rerun {
    Adds,              // they stay and may be replaced by name (experiment jobs add to one folder)
    ReplacesPrevious,  // they are removed first: the folder holds one run's files, never a mix
                       // (demo, localize, energy compare/bench). An exclusive lock on the folder
                       // is held until the process ends, so a second run into it waits.
};

// check_output_folder, then creates the folder (with parents), marks it as `command`'s output
// (a Foreign folder allowed by `force` is adopted: its other files stay, later runs need no
// --force) and registers it for this process (atomic_file.hpp). Call after every other check,
// right before the first write.
void open_output_folder(const std::string& folder, const std::string& command, bool force,
                        const std::string& option = "--out", Rerun rerun = Rerun::Adds);

// A folder built whole under a staging name next to its target ("<target>.partial-<pid>", marked
// by a ".trnkit-staging" file) and put in the target's place only by commit(): a failed or killed
// run leaves the earlier output as it was (and at most a staging folder, never a half-written
// target), and nothing the earlier run wrote survives into the new one, while what it did not
// write (a user's notes, localize's output folder) is moved into the new one. A target that is a
// symbolic link stays one: the folder it points to is replaced.
class StagedFolder {
public:
    // Checks the target (check_output_folder), removes staging folders of killed runs for the same
    // target (only marked ones whose process is gone), and creates an empty staging folder.
    StagedFolder(const std::string& target, std::string command, bool force, const std::string& option = "--out");
    ~StagedFolder();  // without commit() the staging folder and everything in it are removed
    StagedFolder(const StagedFolder&) = delete;
    StagedFolder& operator=(const StagedFolder&) = delete;

    const std::string& path() const { return staging_; }    // write the output here
    const std::string& target() const { return target_; }
    // Marks the staging folder and replaces the target by it (an atomic exchange where the file
    // system supports it); a Foreign target (allowed by force) keeps its other files, receives the
    // new ones and stays unmarked, so it is never replaced whole. Throws trn::Error naming the
    // target on failure.
    void commit();

private:
    std::string target_, staging_, command_;
    FolderState state_;
    int staging_fd_ = -1;
    bool committed_ = false;
};

}  // namespace trn::io
TRN_API_END
