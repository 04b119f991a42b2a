// Output files written whole or not at all (STYLE.md: writers write to a temporary
// file and rename it). Every writer of TetLOD goes through this: meshes, collapse
// histories, PNGs, reports.
#pragma once

#include <cstdio>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "core/status.h"

namespace tetlod {

// A set of output files that one command writes together: a mesh and its collapse
// history, a TetGen .node/.ele pair. stage() writes a file's bytes to a new temporary
// file in its target's directory (so the rename is atomic); commit() renames the
// temporaries over the targets. Until commit() no target is touched, and the
// destructor removes the temporaries of a set that was not committed, so a command
// that fails anywhere before commit() leaves every output as it was.
//  - A target that is a symbolic link is written through it: the file it points to
//    is replaced, the link stays.
//  - A target that exists keeps its permission bits (a new one gets 0666 & ~umask),
//    and its owner and group where the writer may give them (as root; else the
//    group if the writer is in it).
//  - A target that exists and is not a regular file (a directory, a device such as
//    /dev/null, a FIFO) is an error at stage(), as is a target staged twice (a
//    history given the output mesh's path).
// commit() checks every target again, then renames in order; a rename can still fail
// between two others (the directory was made read-only meanwhile): the error then
// names the targets already replaced. No fsync: this protects against failures of
// the process, not of the machine.
class OutputFiles {
 public:
  OutputFiles() = default;
  OutputFiles(const OutputFiles&) = delete;
  OutputFiles& operator=(const OutputFiles&) = delete;
  ~OutputFiles();

  // Errors read "path: cannot write: reason".
  Status stage(const std::string& path, std::string_view contents);
  // For writers that stream: `write` writes to the open temporary and returns false
  // on a failed write.
  Status stage(const std::string& path, const std::function<bool(std::FILE*)>& write);
  Status commit();

 private:
  struct Staged {
    std::string path;       // as given, for messages
    std::string target;     // the file to replace: `path`, or what its link points to
    std::string temporary;  // in target's directory
    int slot = -1;          // where remove_output_temporaries() finds it, or -1
  };
  void discard();
  std::vector<Staged> staged_;
};

// Checks, before any work, that a file can be made at `path`: it is not a
// directory or a device, and the directory it goes in exists and is a directory the
// process may write in (a path through a symbolic link is left to stage()). With
// `make_directories`, `path` is a directory to be made with its parents: the nearest one that
// exists is checked. Errors read "path: cannot write: ...".
Status check_output_directory(const std::string& path, bool make_directories = false);

// Removes the temporaries of every OutputFiles in the process that has not
// committed them. Async-signal-safe (only unlink() and atomics): for a handler of SIGINT
// or SIGTERM, so that a run stopped by Ctrl-C or `timeout` leaves no temporary behind.
// Given the handler's `signal_number` while a commit() renames its files, it removes
// nothing and returns false: the handler is then to return, and commit() raises that
// signal again once all its files are in place (so a command's files change together).
bool remove_output_temporaries(int signal_number = 0);

// stage() and commit() of one file.
Status write_file_atomically(const std::string& path, std::string_view contents);

}  // namespace tetlod
