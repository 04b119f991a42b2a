// Whole-file reads (internal to core/io; writes go through core/io/output_files.h).
#pragma once

#include <string>
#include <vector>

#include "core/status.h"

namespace tetlod::io {

// Reads the whole file. Errors read "path: cannot read: reason". A device (say
// /dev/zero) is refused, and what comes through a pipe is read up to
// kMaxPipedBytes, so that no input can make a read run without end; a named pipe
// that no program opens to write within kPipeWriterSeconds is an error, not a wait
// without end.
inline constexpr size_t kMaxPipedBytes = size_t(4) << 30;
// (`pipe_wait_ms` other than that: tests.)
inline constexpr int kPipeWriterSeconds = 10;
Status read_file(const std::string& path, std::string* contents,
                 int pipe_wait_ms = kPipeWriterSeconds * 1000);

}  // namespace tetlod::io
