#include "core/io/file_access.h"

#include <fcntl.h>
#include <poll.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

namespace tetlod::io {
namespace {

std::string reason(int error_number) {
  return std::strerror(error_number);
}

}  // namespace

Status read_file(const std::string& path, std::string* contents, int pipe_wait_ms) {
  // Before opening: a device could be endless, and opening some blocks.
  struct stat before;
  if (stat(path.c_str(), &before) == 0 && (S_ISCHR(before.st_mode) || S_ISBLK(before.st_mode)))
    return Status::error(path + ": cannot read: it is a device, not a mesh file");
  // Opened without blocking (a named pipe no program writes to would block open()
  // for ever); a pipe is then given kPipeWriterSeconds for a writer to send data or
  // close it (Linux's poll() reports neither while no writer has come), then read,
  // blocking, to its end: a shell's <(...) is read, a pipe nobody opens is an error.
  const int fd = open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) return Status::error(path + ": cannot open: " + reason(errno));
  struct stat opened;
  if (fstat(fd, &opened) == 0 && S_ISFIFO(opened.st_mode)) {
    pollfd wait = {fd, POLLIN, 0};
    if (poll(&wait, 1, pipe_wait_ms) == 0) {
      close(fd);
      const std::string waited = pipe_wait_ms % 1000 == 0
                                     ? std::to_string(pipe_wait_ms / 1000) + " s"
                                     : std::to_string(pipe_wait_ms) + " ms";
      return Status::error(path + ": cannot read: it is a named pipe, and no program wrote to " +
                           "it within " + waited);
    }
  }
  const int flags = fcntl(fd, F_GETFL);
  FILE* file =
      flags < 0 || fcntl(fd, F_SETFL, flags & ~O_NONBLOCK) < 0 ? nullptr : fdopen(fd, "rb");
  if (!file) {
    const int error_number = errno;
    close(fd);
    return Status::error(path + ": cannot open: " + reason(error_number));
  }
  struct stat info;
  if (fstat(fileno(file), &info) != 0) {
    const int error_number = errno;
    std::fclose(file);
    return Status::error(path + ": cannot read: " + reason(error_number));
  }
  if (S_ISDIR(info.st_mode)) {
    std::fclose(file);
    return Status::error(path + ": cannot read: it is a directory");
  }
  contents->clear();
  if (S_ISREG(info.st_mode) && info.st_size > 0) {
    contents->resize(size_t(info.st_size));
    contents->resize(std::fread(contents->data(), 1, contents->size(), file));
  }
  // Whatever is left (a file that grew, or a pipe).
  char buffer[1 << 16];
  size_t got = 0;
  while ((got = std::fread(buffer, 1, sizeof(buffer), file)) > 0) {
    if (contents->size() + got > kMaxPipedBytes) {
      std::fclose(file);
      contents->clear();
      return Status::error(path + ": cannot read: more than " +
                           std::to_string(kMaxPipedBytes >> 30) +
                           " GiB through a pipe; give the file itself");
    }
    contents->append(buffer, got);
  }
  const bool failed = std::ferror(file);
  const int error_number = errno;
  std::fclose(file);
  if (failed) return Status::error(path + ": cannot read: " + reason(error_number));
  return Status();
}

}  // namespace tetlod::io
