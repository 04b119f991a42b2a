// Whole-file reads and atomic writes (internal to core/io).
#pragma once

#include <string>
#include <vector>

#include "core/status.h"

namespace tetlod::io {

// Reads the whole file. Errors read "path: cannot read: reason".
Status read_file(const std::string& path, std::string* contents);

struct OutputFile {
  std::string path;
  std::string contents;
};

// Writes each file to a temporary file next to it (same directory, so rename() is
// atomic), checks every write, flush and close, then renames the temporaries over
// the targets. On failure every temporary is removed and the error names the path.
// Several files are renamed one after the other: a failure between two renames
// (rare: the directory became unwritable) can leave the first one replaced.
// No fsync: this protects against failures of the process, not of the machine.
Status write_files_atomically(const std::vector<OutputFile>& files);

}  // namespace tetlod::io
