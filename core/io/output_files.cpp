#include "core/io/output_files.h"

#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <climits>
#include <csignal>
#include <cstdlib>
#include <cstring>

namespace tetlod {
namespace {

std::string reason(int error_number) {
  return std::strerror(error_number);
}

std::string directory_of(const std::string& path) {
  const size_t slash = path.rfind('/');
  if (slash == std::string::npos) return "";
  return path.substr(0, slash + 1);
}

// The file a write to `path` should replace: `path` itself, or, if it is a symbolic
// link (even to a file not there yet), the file at the end of the chain. False if
// the chain does not end (a loop).
bool resolve_links(const std::string& path, std::string* target) {
  *target = path;
  for (int hop = 0; hop < 40; ++hop) {
    struct stat info;
    if (lstat(target->c_str(), &info) != 0 || !S_ISLNK(info.st_mode)) return true;
    char buffer[PATH_MAX];
    const ssize_t length = readlink(target->c_str(), buffer, sizeof buffer - 1);
    if (length < 0) return true;  // let the write report what is wrong
    const std::string link(buffer, size_t(length));
    *target = !link.empty() && link[0] == '/' ? link : directory_of(*target) + link;
  }
  return false;
}

// The permission bits and owner of a file being replaced.
struct Keep {
  mode_t mode;
  uid_t owner;
  gid_t group;
};

// What is wrong with replacing an existing `target` by a new file, or "" if nothing
// (it does not exist, or it is a regular file). `keep`, if given, gets the
// permission bits and owner of a regular file there, and stays untouched if there is
// none.
std::string unreplaceable(const std::string& target, Keep* keep) {
  struct stat info;
  if (stat(target.c_str(), &info) != 0) return "";
  if (S_ISDIR(info.st_mode)) return "it is a directory";
  if (!S_ISREG(info.st_mode)) return "it is not a regular file (a device, FIFO or socket)";
  if (keep) *keep = {info.st_mode & 07777, info.st_uid, info.st_gid};
  return "";
}

constexpr mode_t kNoMode = ~mode_t(0);

// The temporaries that may exist now, for remove_output_temporaries(), which a
// signal handler calls: fixed slots (no allocation, no locks), each a path buffer
// and a state. A slot is claimed (kFree -> kClaimed) by the thread that writes its
// path, then published (kLive); the handler only reads kLive slots; the owner frees
// its slot by index (kFree). The buffers are never freed, so a handler racing a
// thread that frees and claims a slot reads a path, at worst a newer one of this
// process's temporaries. A temporary that finds no free slot (more than kSlots at
// once) is only not removed on a signal.
constexpr int kSlots = 256;
enum SlotState : int { kFree = 0, kClaimed = 1, kLive = 2 };
struct LiveSlot {
  std::atomic<int> state{kFree};
  char path[PATH_MAX];
};
LiveSlot live_temporaries[kSlots];

// A commit's renames, once begun, are all made before a signal ends the process (a signal
// between two of them left a new .node beside an old .ele): while one runs,
// remove_output_temporaries() only notes the signal, and commit() raises it again after
// its last rename. Lock-free atomics: read and written from a signal handler.
std::atomic<int> commits_running{0};
std::atomic<int> deferred_signal{0};

// Publishes `temporary` (before the file is made); its slot, or -1.
int add_live(const std::string& temporary) {
  if (temporary.size() >= PATH_MAX) return -1;
  for (int i = 0; i < kSlots; ++i) {
    int expected = kFree;
    if (!live_temporaries[i].state.compare_exchange_strong(expected, kClaimed)) continue;
    std::memcpy(live_temporaries[i].path, temporary.c_str(), temporary.size() + 1);
    live_temporaries[i].state.store(kLive);
    return i;
  }
  return -1;
}

void remove_live(int slot) {
  if (slot >= 0) live_temporaries[slot].state.store(kFree);
}

// Creates a new file next to `target` with a name no other writer uses ("x": fail
// if it exists).
FILE* create_temporary(const std::string& target, std::string* temp_path, int* slot) {
  static std::atomic<unsigned> counter{0};
  constexpr int kAttempts = 100;
  for (int attempt = 0; attempt < kAttempts; ++attempt) {
    *temp_path = target + ".tmp" + std::to_string(getpid()) + "-" + std::to_string(counter++);
    // Published first, so that no signal finds the file made but not listed.
    *slot = add_live(*temp_path);
    FILE* file = std::fopen(temp_path->c_str(), "w+bx");  // read back by some writers
    if (file) return file;
    const int error_number = errno;
    remove_live(*slot);
    *slot = -1;
    errno = error_number;
    if (error_number != EEXIST) return nullptr;
  }
  return nullptr;
}

// `path` with its directory made absolute and free of links, "." and "..": two
// spellings of one file give the same string, whether the file exists or not.
std::string canonical(const std::string& path) {
  const std::string directory = directory_of(path);
  char buffer[PATH_MAX];
  if (!realpath(directory.empty() ? "." : directory.c_str(), buffer)) return path;
  return std::string(buffer) + "/" + path.substr(directory.size());
}

bool same_file(const std::string& a, const std::string& b) {
  return a == b || canonical(a) == canonical(b);
}

}  // namespace

OutputFiles::~OutputFiles() {
  discard();
}

void OutputFiles::discard() {
  for (const Staged& s : staged_) {
    std::remove(s.temporary.c_str());
    remove_live(s.slot);
  }
  staged_.clear();
}

Status check_output_directory(const std::string& path, bool make_directories) {
  struct stat info;
  if (!make_directories && lstat(path.c_str(), &info) == 0 && S_ISLNK(info.st_mode))
    return Status();
  // What is there already: a directory or a device is never replaced (stage()).
  if (!make_directories) {
    if (const std::string why = unreplaceable(path, nullptr); !why.empty())
      return Status::error(path + ": cannot write: " + why);
  }
  // The directory the file goes in, or for a directory to be made, the nearest one
  // that is there.
  std::string directory = make_directories ? path : directory_of(path);
  while (!directory.empty() && directory.size() > 1 && directory.back() == '/')
    directory.pop_back();
  if (directory.empty()) directory = ".";
  while (make_directories && directory != "." && directory != "/" &&
         stat(directory.c_str(), &info) != 0 && (errno == ENOENT || errno == ENOTDIR)) {
    const std::string parent = directory_of(directory);
    directory = parent.empty() ? "." : parent == "/" ? "/" : parent.substr(0, parent.size() - 1);
  }
  const std::string shown = directory + (directory.back() == '/' ? "" : "/");
  if (stat(directory.c_str(), &info) != 0) {
    return Status::error(path + ": cannot write: " + shown + ": " + reason(errno));
  }
  if (!S_ISDIR(info.st_mode))
    return Status::error(path + ": cannot write: " + shown + " is not a directory");
  if (access(directory.c_str(), W_OK | X_OK) != 0)
    return Status::error(path + ": cannot write in " + shown + ": " + reason(errno));
  return Status();
}

bool remove_output_temporaries(int signal_number) {
  if (signal_number != 0 && commits_running.load() > 0) {
    deferred_signal.store(signal_number);
    return false;
  }
  for (LiveSlot& slot : live_temporaries) {
    if (slot.state.load() == kLive) unlink(slot.path);
  }
  return true;
}

Status OutputFiles::stage(const std::string& path, std::string_view contents) {
  return stage(path, [&](std::FILE* file) {
    return std::fwrite(contents.data(), 1, contents.size(), file) == contents.size();
  });
}

Status OutputFiles::stage(const std::string& path, const std::function<bool(std::FILE*)>& write) {
  auto fail = [&](const std::string& what) {
    return Status::error(path + ": cannot write: " + what);
  };
  Staged staged;
  staged.path = path;
  if (!resolve_links(path, &staged.target)) return fail("too many levels of symbolic links");
  for (const Staged& other : staged_) {
    if (same_file(other.target, staged.target))
      return fail("the same file as " + other.path + ", written by the same command");
  }
  Keep keep{kNoMode, 0, 0};  // a new file: the umask's mode, the writer's owner
  if (const std::string why = unreplaceable(staged.target, &keep); !why.empty()) return fail(why);
  FILE* file = create_temporary(staged.target, &staged.temporary, &staged.slot);
  if (!file) return fail(reason(errno));
  // The old file's owner, where the writer may give it (root, or a group the writer
  // is in; else the new file is the writer's, as any editor's save makes it), then
  // its permissions, before any byte is written (a 0600 file's contents are never
  // readable by others, not even in the temporary).
  if (keep.mode != kNoMode && fchown(fileno(file), keep.owner, keep.group) != 0)
    (void)!fchown(fileno(file), static_cast<uid_t>(-1), keep.group);
  bool ok = keep.mode == kNoMode || fchmod(fileno(file), keep.mode) == 0;
  int error_number = ok ? 0 : errno;
  if (ok) {
    ok = write(file) && std::fflush(file) == 0 && !std::ferror(file);
    error_number = ok ? 0 : errno;
  }
  if (std::fclose(file) != 0 && ok) ok = false, error_number = errno;
  if (!ok) {
    std::remove(staged.temporary.c_str());
    remove_live(staged.slot);
    return fail(error_number != 0 ? reason(error_number) : "write failed");
  }
  staged_.push_back(std::move(staged));
  return Status();
}

Status OutputFiles::commit() {
  for (const Staged& s : staged_) {
    if (const std::string why = unreplaceable(s.target, nullptr); !why.empty()) {
      const Status status = Status::error(s.path + ": cannot write: " + why);
      discard();
      return status;
    }
  }
  // A signal that comes meanwhile is raised again at the end (see commits_running).
  ++commits_running;
  struct Finish {
    ~Finish() {
      if (--commits_running == 0) {
        if (const int signal_number = deferred_signal.exchange(0); signal_number != 0)
          std::raise(signal_number);
      }
    }
  } finish;
  std::string replaced;
  for (size_t i = 0; i < staged_.size(); ++i) {
    if (std::rename(staged_[i].temporary.c_str(), staged_[i].target.c_str()) != 0) {
      const int error_number = errno;
      std::string message =
          staged_[i].path + ": cannot write: cannot replace it: " + reason(error_number);
      if (!replaced.empty()) message += " (" + replaced + " already written)";
      staged_.erase(staged_.begin(), staged_.begin() + long(i));
      discard();
      return Status::error(message);
    }
    remove_live(staged_[i].slot);
    replaced += (replaced.empty() ? "" : ", ") + staged_[i].path;
  }
  staged_.clear();
  return Status();
}

Status write_file_atomically(const std::string& path, std::string_view contents) {
  OutputFiles files;
  if (Status s = files.stage(path, contents); !s) return s;
  return files.commit();
}

}  // namespace tetlod
