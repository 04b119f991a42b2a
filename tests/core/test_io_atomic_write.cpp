// Writes go through a temporary file that is renamed over the target.
#include <gtest/gtest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <thread>

#include "core/io/file_access.h"
#include "core/io/mesh_io.h"
#include "core/io/output_files.h"
#include "core/test_io_helpers.h"
#include "core/test_meshes.h"

namespace tetlod {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> directory_entries(const std::string& dir) {
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    names.push_back(entry.path().filename().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

TEST(IoAtomicWrite, MissingDirectoryFailsNamingThePathAndLeavesNothing) {
  const std::string dir = test::output_dir("atomic_missing");
  const TetMesh mesh = test::make_single_tet();
  for (const char* name : {"/no/such/dir/m.mesh", "/no/such/dir/m.msh", "/no/such/dir/m.node",
                           "/no/such/dir/m.vtk", "/no/such/dir/m.vtu"}) {
    const std::string path = dir + name;
    const Status status = write_mesh(path, mesh);
    ASSERT_FALSE(status.ok());
    EXPECT_NE(status.message().find("cannot write"), std::string::npos) << status.message();
    EXPECT_NE(status.message().find("No such file or directory"), std::string::npos)
        << status.message();
    EXPECT_EQ(status.message().find(dir), 0u) << status.message();
  }
  EXPECT_TRUE(directory_entries(dir).empty());
}

TEST(IoAtomicWrite, OverwritesAnExistingFile) {
  const std::string dir = test::output_dir("atomic_overwrite");
  const std::string path = dir + "/m.mesh";
  test::write_text(path, std::string(100000, 'x'));
  const TetMesh mesh = test::make_io_mesh();
  ASSERT_TRUE(write_mesh(path, mesh).ok());
  TetMesh read;
  ASSERT_TRUE(read_mesh(path, &read).ok());
  test::expect_same_mesh(mesh, read);
  EXPECT_EQ(directory_entries(dir), std::vector<std::string>{"m.mesh"});
}

TEST(IoAtomicWrite, ADirectoryIsNotReplaced) {
  // The target is a directory: refused before anything is written.
  const std::string dir = test::output_dir("atomic_rename");
  std::filesystem::create_directories(dir + "/m.vtu/inside");
  const Status status = write_mesh(dir + "/m.vtu", test::make_single_tet());
  ASSERT_FALSE(status.ok());
  EXPECT_EQ(status.message().rfind(dir + "/m.vtu: cannot write: it is a directory", 0), 0u)
      << status.message();
  EXPECT_EQ(directory_entries(dir), std::vector<std::string>{"m.vtu"});
}

TEST(IoAtomicWrite, TetGenPairFailureLeavesNoTemporaryFile) {
  const std::string dir = test::output_dir("atomic_tetgen");
  std::filesystem::create_directories(dir + "/m.ele/inside");
  const Status status = write_mesh(dir + "/m.node", test::make_single_tet());
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.message().find("m.ele"), std::string::npos) << status.message();
  // Both files are staged before either is renamed: no .node without its .ele, and
  // no temporary file left.
  EXPECT_EQ(directory_entries(dir), std::vector<std::string>{"m.ele"});
}

TEST(IoAtomicWrite, ReadingADirectoryIsAnError) {
  const std::string dir = test::output_dir("atomic_read_dir");
  std::filesystem::create_directories(dir + "/d.mesh");
  TetMesh mesh;
  const Status status = read_mesh(dir + "/d.mesh", &mesh);
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.message().find("directory"), std::string::npos) << status.message();
}

// A file that is replaced keeps its permission bits (a 0600 file does not become
// readable by everyone).
TEST(IoAtomicWrite, ReplacedFileKeepsItsPermissions) {
  const std::string dir = test::output_dir("atomic_mode");
  const std::string path = dir + "/m.mesh";
  for (const auto mode : {fs::perms::owner_read | fs::perms::owner_write,
                          fs::perms::owner_all | fs::perms::group_read}) {
    test::write_text(path, "old");
    fs::permissions(path, mode);
    ASSERT_TRUE(write_mesh(path, test::make_single_tet()).ok());
    EXPECT_EQ(fs::status(path).permissions(), mode);
    EXPECT_NE(test::read_text(path), "old");
  }
}

// A file that is replaced keeps its owner where the writer may give it: root, as
// TetLOD often runs in containers, does not take over a user's files (the setuid bit
// a chown would clear is restored with the mode).
TEST(IoAtomicWrite, ReplacedFileKeepsItsOwnerWhenRootWrites) {
  if (geteuid() != 0) GTEST_SKIP() << "needs root to give a file to another user";
  const std::string path = test::output_dir("atomic_owner") + "/m.mesh";
  test::write_text(path, "old");
  ASSERT_EQ(chown(path.c_str(), 4321, 8765), 0);
  ASSERT_EQ(chmod(path.c_str(), 0640), 0);
  ASSERT_TRUE(write_mesh(path, test::make_single_tet()).ok());
  struct stat info;
  ASSERT_EQ(stat(path.c_str(), &info), 0);
  EXPECT_EQ(info.st_uid, 4321u);
  EXPECT_EQ(info.st_gid, 8765u);
  EXPECT_EQ(info.st_mode & 07777, 0640u);
  EXPECT_NE(test::read_text(path), "old");
  // A new file is the writer's.
  const std::string fresh = test::output_dir("atomic_owner") + "/new.mesh";
  std::remove(fresh.c_str());
  ASSERT_TRUE(write_mesh(fresh, test::make_single_tet()).ok());
  ASSERT_EQ(stat(fresh.c_str(), &info), 0);
  EXPECT_EQ(info.st_uid, 0u);
}

// A symbolic link is written through: the file it points to is replaced (or made,
// for a dangling link), the link stays a link.
TEST(IoAtomicWrite, SymbolicLinksAreWrittenThrough) {
  const std::string dir = test::output_dir("atomic_link");
  test::write_text(dir + "/target.mesh", "old");
  fs::create_directories(dir + "/sub");
  fs::create_symlink("../target.mesh", dir + "/sub/link.mesh");
  fs::create_symlink("new.mesh", dir + "/dangling.mesh");
  const TetMesh mesh = test::make_single_tet();
  ASSERT_TRUE(write_mesh(dir + "/sub/link.mesh", mesh).ok());
  ASSERT_TRUE(write_mesh(dir + "/dangling.mesh", mesh).ok());
  EXPECT_TRUE(fs::is_symlink(dir + "/sub/link.mesh"));
  EXPECT_TRUE(fs::is_symlink(dir + "/dangling.mesh"));
  for (const char* name : {"/target.mesh", "/new.mesh"}) {
    TetMesh read;
    EXPECT_TRUE(read_mesh(dir + name, &read).ok()) << name;
    test::expect_same_mesh(mesh, read);
  }
  EXPECT_EQ(directory_entries(dir),
            (std::vector<std::string>{"dangling.mesh", "new.mesh", "sub", "target.mesh"}));
  EXPECT_EQ(directory_entries(dir + "/sub"), std::vector<std::string>{"link.mesh"});
  fs::create_symlink("loop.mesh", dir + "/loop.mesh");
  const Status loop = write_mesh(dir + "/loop.mesh", mesh);
  EXPECT_NE(loop.message().find("symbolic links"), std::string::npos) << loop.message();
}

// Nothing replaces a device or a FIFO (as root, a rename over /dev/null would).
TEST(IoAtomicWrite, ADeviceIsNotReplaced) {
  const std::string dir = test::output_dir("atomic_device");
  fs::create_symlink("/dev/null", dir + "/null.mesh");
  const Status status = write_mesh(dir + "/null.mesh", test::make_single_tet());
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.message().find("not a regular file"), std::string::npos) << status.message();
  EXPECT_TRUE(fs::is_character_file("/dev/null"));
  EXPECT_EQ(directory_entries(dir), std::vector<std::string>{"null.mesh"});
}

// A set of outputs: nothing is written until commit(); a set dropped before it
// leaves no file; the same file twice in one set is refused.
TEST(IoAtomicWrite, OutputFilesAreCommittedTogetherOrNotAtAll) {
  const std::string dir = test::output_dir("atomic_set");
  test::write_text(dir + "/a.txt", "old a");
  {
    OutputFiles files;
    ASSERT_TRUE(files.stage(dir + "/a.txt", "new a").ok());
    ASSERT_TRUE(files.stage(dir + "/b.txt", "new b").ok());
    EXPECT_EQ(test::read_text(dir + "/a.txt"), "old a");
    EXPECT_FALSE(fs::exists(dir + "/b.txt"));
    for (const char* again : {"/./a.txt", "/../atomic_set/b.txt"}) {
      const Status twice = files.stage(dir + again, "again");
      EXPECT_NE(twice.message().find("the same file as " + dir + "/"), std::string::npos)
          << twice.message();
    }
  }  // not committed
  EXPECT_EQ(directory_entries(dir), std::vector<std::string>{"a.txt"});
  EXPECT_EQ(test::read_text(dir + "/a.txt"), "old a");
  OutputFiles files;
  ASSERT_TRUE(files.stage(dir + "/a.txt", "new a").ok());
  ASSERT_TRUE(files.stage(dir + "/b.txt", "new b").ok());
  ASSERT_TRUE(files.commit().ok());
  EXPECT_EQ(test::read_text(dir + "/a.txt"), "new a");
  EXPECT_EQ(test::read_text(dir + "/b.txt"), "new b");
  EXPECT_EQ(directory_entries(dir), (std::vector<std::string>{"a.txt", "b.txt"}));
}

// A device is refused at once (/dev/zero never ends); a pipe is read.
TEST(IoAtomicWrite, ReadingADeviceIsAnErrorAndAPipeIsRead) {
  const std::string dir = test::output_dir("atomic_read_device");
  fs::create_symlink("/dev/zero", dir + "/zero.mesh");
  TetMesh mesh;
  const Status status = read_mesh(dir + "/zero.mesh", &mesh);
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.message().find(dir + "/zero.mesh: cannot read: it is a device"),
            std::string::npos)
      << status.message();

  const std::string fifo = dir + "/pipe.mesh";
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  const std::string medit =
      "MeshVersionFormatted 2\nDimension 3\nVertices\n4\n0 0 0 1\n"
      "1 0 0 1\n0 1 0 1\n0 0 1 1\nTetrahedra\n1\n1 2 3 4 7\nEnd\n";
  std::thread writer([&] {
    std::FILE* f = std::fopen(fifo.c_str(), "wb");
    if (!f) return;
    std::fwrite(medit.data(), 1, medit.size(), f);
    std::fclose(f);
  });
  const Status piped = read_mesh(fifo, &mesh);
  writer.join();
  ASSERT_TRUE(piped.ok()) << piped.message();
  EXPECT_EQ(mesh.tet_count(), 1u);
  EXPECT_EQ(mesh.materials[0], 7);
}

// A named pipe that no program opens to write is an error after a wait, not a read
// that never ends (it blocked in open(), found by a hostile-input test).
TEST(IoAtomicWrite, ANamedPipeNobodyWritesToIsAnError) {
  const std::string dir = test::output_dir("atomic_read_lonely_pipe");
  const std::string fifo = dir + "/lonely.mesh";
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  std::string contents;
  const auto start = std::chrono::steady_clock::now();
  const Status status = io::read_file(fifo, &contents, 200);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(status.message(),
            fifo + ": cannot read: it is a named pipe, and no program wrote to it within 200 ms");
  EXPECT_LT(seconds, 5);
}

// What a signal handler calls (app/main.cpp): the temporaries of every set not yet
// committed go; a committed file and the targets stay.
TEST(IoAtomicWrite, RemoveOutputTemporariesLeavesOnlyCommittedFiles) {
  const std::string dir = test::output_dir("atomic_signal");
  for (const auto& entry : fs::directory_iterator(dir)) fs::remove(entry.path());
  test::write_text(dir + "/old.txt", "old");
  {
    OutputFiles done;
    ASSERT_TRUE(done.stage(dir + "/done.txt", "done").ok());
    ASSERT_TRUE(done.commit().ok());
    OutputFiles first, second;
    ASSERT_TRUE(first.stage(dir + "/old.txt", "new").ok());
    ASSERT_TRUE(first.stage(dir + "/a.txt", "a").ok());
    ASSERT_TRUE(second.stage(dir + "/b.txt", "b").ok());
    EXPECT_EQ(directory_entries(dir).size(), 5u);  // done, old and three temporaries
    remove_output_temporaries();
    EXPECT_EQ(directory_entries(dir), (std::vector<std::string>{"done.txt", "old.txt"}));
    EXPECT_EQ(test::read_text(dir + "/old.txt"), "old");
  }  // the destructors find their temporaries gone: nothing to do
  EXPECT_EQ(directory_entries(dir), (std::vector<std::string>{"done.txt", "old.txt"}));
  // Committed and discarded sets leave nothing for a later call to remove.
  OutputFiles later;
  ASSERT_TRUE(later.stage(dir + "/c.txt", "c").ok());
  ASSERT_TRUE(later.commit().ok());
  remove_output_temporaries();
  EXPECT_EQ(test::read_text(dir + "/c.txt"), "c");
}

// Checked before any work: the directory an output goes in.
TEST(IoAtomicWrite, CheckOutputDirectory) {
  const std::string dir = test::output_dir("atomic_check_dir");
  test::write_text(dir + "/file", "x");
  EXPECT_TRUE(check_output_directory(dir + "/m.mesh").ok());
  EXPECT_TRUE(check_output_directory("m.mesh").ok());  // the working directory
  Status s = check_output_directory(dir + "/no/such/m.mesh");
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.message(),
            dir + "/no/such/m.mesh: cannot write: " + dir + "/no/such/: No such file or directory");
  s = check_output_directory(dir + "/file/m.mesh");
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.message(), dir + "/file/m.mesh: cannot write: " + dir + "/file/ is not a directory");
  fs::create_directories(dir + "/d.vtk");
  s = check_output_directory(dir + "/d.vtk");
  EXPECT_EQ(s.message(), dir + "/d.vtk: cannot write: it is a directory");
  s = check_output_directory("/dev/null");
  EXPECT_NE(s.message().find("it is not a regular file"), std::string::npos) << s.message();
  // A directory to be made: its nearest existing ancestor must be a directory.
  EXPECT_TRUE(check_output_directory(dir + "/new/deeper/report", true).ok());
  EXPECT_FALSE(fs::exists(dir + "/new"));
  s = check_output_directory(dir + "/file/report", true);
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.message().find("is not a directory"), std::string::npos) << s.message();
  if (geteuid() != 0) {  // root may write anywhere
    const std::string locked = dir + "/locked";
    fs::create_directories(locked);
    chmod(locked.c_str(), 0555);
    s = check_output_directory(locked + "/m.mesh");
    chmod(locked.c_str(), 0755);
    ASSERT_FALSE(s.ok());
    EXPECT_NE(s.message().find("Permission denied"), std::string::npos) << s.message();
  }
}

}  // namespace
}  // namespace tetlod
