// Read speed of a ~1M-tet mesh in every format. Disabled in the default run (it
// writes ~200 MB); run it with
//   build/tests/tetlod_core_tests --gtest_also_run_disabled_tests --gtest_filter='*IoSpeed*'
// The target: a ~1M-tet ASCII .mesh reads in <= 1 s on one core (Release).
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <filesystem>

#include "core/io/mesh_io.h"
#include "core/test_io_helpers.h"
#include "core/test_meshes.h"

namespace tetlod {
namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

TEST(IoSpeed, DISABLED_ReadMillionTetMesh) {
  const std::string dir = test::output_dir("speed");
  // 55^3 cubes of six tets: 998,250 tets, 175,616 vertices; a spacing without a short
  // decimal form makes coordinates full-length numbers (17 digits), as in real files.
  const TetMesh mesh = test::make_grid_mesh(
      55, 55, 55, [](int i, int j, int k) { return (i / 10 + j / 10 + k / 10) % 7; }, 1.0 / 3.0);
  for (const char* name : {"big.mesh", "big.msh", "big.node", "big.vtk", "big.vtu"}) {
    const std::string path = dir + "/" + name;
    auto start = std::chrono::steady_clock::now();
    ASSERT_TRUE(write_mesh(path, mesh).ok());
    const double write_seconds = seconds_since(start);
    start = std::chrono::steady_clock::now();
    TetMesh read;
    const Status status = read_mesh(path, &read);
    const double read_seconds = seconds_since(start);
    ASSERT_TRUE(status.ok()) << status.message();
    ASSERT_EQ(read.tet_count(), mesh.tet_count());
    double megabytes = double(std::filesystem::file_size(path)) / 1e6;
    if (std::string(name) == "big.node")
      megabytes += double(std::filesystem::file_size(dir + "/big.ele")) / 1e6;
    std::printf("%-9s %6.1f MB  write %.3f s  read %.3f s (%.2f M tets/s)\n", name, megabytes,
                write_seconds, read_seconds, double(mesh.tet_count()) / read_seconds / 1e6);
    if (std::string(name) == "big.mesh") {
#ifdef NDEBUG
      EXPECT_LE(read_seconds, 1.0);
#endif
    }
    std::filesystem::remove(path);
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace tetlod
