// Writes go through a temporary file that is renamed over the target.
#include <gtest/gtest.h>

#include <filesystem>

#include "core/io/mesh_io.h"
#include "core/test_io_helpers.h"
#include "core/test_meshes.h"

namespace tetlod {
namespace {

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

TEST(IoAtomicWrite, FailedRenameRemovesTheTemporaryFile) {
  // The target is a directory: the temporary file is written, rename() fails.
  const std::string dir = test::output_dir("atomic_rename");
  std::filesystem::create_directories(dir + "/m.vtu/inside");
  const Status status = write_mesh(dir + "/m.vtu", test::make_single_tet());
  ASSERT_FALSE(status.ok());
  EXPECT_EQ(status.message().rfind(dir + "/m.vtu: cannot write: cannot replace it", 0), 0u)
      << status.message();
  EXPECT_EQ(directory_entries(dir), std::vector<std::string>{"m.vtu"});
}

TEST(IoAtomicWrite, TetGenPairFailureLeavesNoTemporaryFile) {
  const std::string dir = test::output_dir("atomic_tetgen");
  std::filesystem::create_directories(dir + "/m.ele/inside");
  const Status status = write_mesh(dir + "/m.node", test::make_single_tet());
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.message().find("m.ele"), std::string::npos) << status.message();
  // The .node file was renamed first; its replacement is the documented limit of a
  // two-file write. No temporary file is left.
  for (const std::string& name : directory_entries(dir)) {
    EXPECT_EQ(name.find(".tmp"), std::string::npos) << name;
  }
}

TEST(IoAtomicWrite, ReadingADirectoryIsAnError) {
  const std::string dir = test::output_dir("atomic_read_dir");
  std::filesystem::create_directories(dir + "/d.mesh");
  TetMesh mesh;
  const Status status = read_mesh(dir + "/d.mesh", &mesh);
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.message().find("directory"), std::string::npos) << status.message();
}

}  // namespace
}  // namespace tetlod
