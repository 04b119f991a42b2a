#include "core/io/file_access.h"

#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>

namespace tetlod::io {
namespace {

std::string reason(int error_number) {
  return std::strerror(error_number);
}

// Creates a new file named after `path` with a suffix no other writer uses ("x":
// fail if it exists). Permissions follow the umask, as for a plain fopen().
FILE* create_temporary(const std::string& path, std::string* temp_path) {
  static std::atomic<unsigned> counter{0};
  constexpr int kAttempts = 100;
  for (int attempt = 0; attempt < kAttempts; ++attempt) {
    *temp_path = path + ".tmp" + std::to_string(getpid()) + "-" + std::to_string(counter++);
    FILE* file = std::fopen(temp_path->c_str(), "wbx");
    if (file || errno != EEXIST) return file;
  }
  return nullptr;
}

}  // namespace

Status read_file(const std::string& path, std::string* contents) {
  FILE* file = std::fopen(path.c_str(), "rb");
  if (!file) return Status::error(path + ": cannot open: " + reason(errno));
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
  while ((got = std::fread(buffer, 1, sizeof(buffer), file)) > 0) contents->append(buffer, got);
  const bool failed = std::ferror(file);
  const int error_number = errno;
  std::fclose(file);
  if (failed) return Status::error(path + ": cannot read: " + reason(error_number));
  return Status();
}

Status write_files_atomically(const std::vector<OutputFile>& files) {
  std::vector<std::string> temp_paths;
  auto fail = [&](const std::string& path, const std::string& what, int error_number) {
    for (const std::string& temp : temp_paths) std::remove(temp.c_str());
    return Status::error(path + ": cannot write: " + what + reason(error_number));
  };
  for (const OutputFile& output : files) {
    std::string temp_path;
    FILE* file = create_temporary(output.path, &temp_path);
    if (!file) return fail(output.path, "", errno);
    temp_paths.push_back(temp_path);
    const size_t written = std::fwrite(output.contents.data(), 1, output.contents.size(), file);
    if (written != output.contents.size() || std::fflush(file) != 0 || std::ferror(file)) {
      const int error_number = errno;
      std::fclose(file);
      return fail(output.path, "", error_number);
    }
    if (std::fclose(file) != 0) return fail(output.path, "", errno);
  }
  for (size_t i = 0; i < files.size(); ++i) {
    if (std::rename(temp_paths[i].c_str(), files[i].path.c_str()) != 0) {
      const int error_number = errno;
      temp_paths.erase(temp_paths.begin(), temp_paths.begin() + long(i));
      return fail(files[i].path, "cannot replace it: ", error_number);
    }
  }
  return Status();
}

}  // namespace tetlod::io
