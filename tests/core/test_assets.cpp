// The bundled models: Table I metrics against the independent computation, and a
// round trip of each model through every format.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <filesystem>
#include <string>
#include <tuple>
#include <vector>

#include "core/adjacency.h"
#include "core/io/mesh_io.h"
#include "core/mesh_stats.h"
#include "mesh_stats_reference.h"

namespace tetlod {
namespace {

namespace fs = std::filesystem;

std::string asset(const std::string& name) {
  return std::string(TETLOD_SOURCE_DIR) + "/assets/" + name;
}

// Order-independent description of a mesh: per tet, its material and corner positions.
std::vector<std::tuple<int32_t, std::array<double, 12>>> canonical(const TetMesh& mesh) {
  std::vector<std::tuple<int32_t, std::array<double, 12>>> out;
  for (size_t t = 0; t < mesh.tet_count(); ++t) {
    std::array<std::array<double, 3>, 4> corners;
    for (int c = 0; c < 4; ++c) {
      const Vec3& p = mesh.positions[mesh.tets[t][c]];
      corners[c] = {p.x, p.y, p.z};
    }
    std::sort(corners.begin(), corners.end());
    std::array<double, 12> flat;
    for (int c = 0; c < 4; ++c)
      for (int k = 0; k < 3; ++k) flat[3 * c + k] = corners[c][k];
    out.push_back({mesh.materials[t], flat});
  }
  std::sort(out.begin(), out.end());
  return out;
}

class Asset : public ::testing::TestWithParam<const char*> {};

TEST_P(Asset, StatsMatchTheIndependentComputation) {
  TetMesh mesh;
  ReadInfo info;
  const Status s = read_mesh(asset(GetParam()), &mesh, &info);
  ASSERT_TRUE(s) << s.message();
  EXPECT_EQ(info.validation.reoriented_tets, 0u);
  const MeshStats stats = compute_mesh_stats(mesh, build_vertex_tets(mesh));
  test::expect_stats_match_reference(mesh, stats);
}

TEST_P(Asset, RoundTripsThroughEveryFormat) {
  TetMesh mesh;
  ReadInfo info;
  ASSERT_TRUE(read_mesh(asset(GetParam()), &mesh, &info));
  const MeshStats stats = compute_mesh_stats(mesh, build_vertex_tets(mesh));
  const auto reference = canonical(mesh);
  const std::string dir = std::string(TETLOD_TEST_OUTPUT_DIR) + "/assets";
  fs::create_directories(dir);
  const std::string stem = dir + "/" + fs::path(GetParam()).stem().string();
  struct Target {
    std::string path;
    int gmsh_version;
  };
  for (const Target& target :
       {Target{stem + ".mesh", 41}, Target{stem + "_41.msh", 41}, Target{stem + "_22.msh", 22},
        Target{stem + ".node", 41}, Target{stem + ".vtk", 41}, Target{stem + ".vtu", 41}}) {
    WriteOptions options;
    options.gmsh_version = target.gmsh_version;
    Status s = write_mesh(target.path, mesh, options);
    ASSERT_TRUE(s) << s.message();
    TetMesh back;
    ReadInfo back_info;
    s = read_mesh(target.path, &back, &back_info);
    ASSERT_TRUE(s) << s.message();
    EXPECT_EQ(back_info.validation.reoriented_tets, 0u) << target.path;
    EXPECT_EQ(back.vertex_count(), mesh.vertex_count()) << target.path;
    EXPECT_EQ(back.tet_count(), mesh.tet_count()) << target.path;
    EXPECT_TRUE(canonical(back) == reference)
        << target.path << ": tets, positions or materials differ";
    const MeshStats back_stats = compute_mesh_stats(back, build_vertex_tets(back));
    EXPECT_EQ(back_stats.whole.edges, stats.whole.edges) << target.path;
    EXPECT_EQ(back_stats.whole.max_valence, stats.whole.max_valence) << target.path;
    EXPECT_DOUBLE_EQ(back_stats.whole.min_stretch, stats.whole.min_stretch) << target.path;
    EXPECT_DOUBLE_EQ(back_stats.whole.max_size, stats.whole.max_size) << target.path;
    ASSERT_EQ(back_stats.per_material.size(), stats.per_material.size()) << target.path;
    for (size_t m = 0; m < stats.per_material.size(); ++m) {
      EXPECT_EQ(back_stats.per_material[m].material, stats.per_material[m].material);
      EXPECT_EQ(back_stats.per_material[m].row.elements, stats.per_material[m].row.elements);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Bundled, Asset,
                         ::testing::Values("motor.mesh", "spheres.mesh", "box2.mesh"),
                         [](const ::testing::TestParamInfo<const char*>& param) {
                           return fs::path(param.param).stem().string();
                         });

}  // namespace
}  // namespace tetlod
