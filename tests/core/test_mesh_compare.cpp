// compare_meshes(): each material's volume and how far each material pair's surface
// moved between two meshes.
#include <gtest/gtest.h>

#include <algorithm>

#include "core/io/mesh_io.h"
#include "core/mesh_compare.h"
#include "core/test_meshes.h"

namespace tetlod {
namespace {

TetMesh box2() {
  TetMesh mesh;
  EXPECT_TRUE(read_mesh(std::string(TETLOD_SOURCE_DIR) + "/assets/box2.mesh", &mesh));
  return mesh;
}

// Against itself: every volume the same, every surface unmoved, nothing lost or new.
TEST(MeshCompare, AMeshAgainstItself) {
  const TetMesh mesh = box2();
  const MeshComparison c = compare_meshes(mesh, mesh);
  ASSERT_FALSE(c.volumes.empty());
  for (const MaterialVolumes& v : c.volumes) {
    EXPECT_GT(v.before, 0);
    EXPECT_EQ(v.before, v.after);
  }
  ASSERT_FALSE(c.pairs.empty());
  for (const PairDeviation& d : c.pairs) EXPECT_LE(d.distance, 1e-12);  // (rounding)
  EXPECT_TRUE(c.lost.empty());
  EXPECT_TRUE(c.added.empty());
}

// Moved by 0.25 along z: every surface moves by 0.25 (the top and bottom along their
// normal; the sides' ends stick out past the old top and bottom by as much).
TEST(MeshCompare, AShiftedMeshMovesEverySurfaceByTheShift) {
  const TetMesh mesh = box2();
  TetMesh moved = mesh;
  for (Vec3& p : moved.positions) p.z += 0.25;
  const MeshComparison c = compare_meshes(mesh, moved);
  for (const MaterialVolumes& v : c.volumes) EXPECT_NEAR(v.after, v.before, 1e-9 * v.before);
  for (const PairDeviation& d : c.pairs) EXPECT_NEAR(d.distance, 0.25, 1e-12);
}

// A material relabelled: it is lost and the new id is new, with their surfaces.
TEST(MeshCompare, ARelabelledMaterialIsLostAndNew) {
  const TetMesh mesh = box2();
  TetMesh relabelled = mesh;
  const int32_t from = *std::max_element(mesh.materials.begin(), mesh.materials.end());
  for (int32_t& m : relabelled.materials)
    if (m == from) m = from + 100;
  const MeshComparison c = compare_meshes(mesh, relabelled);
  bool lost = false, added = false;
  for (const MaterialVolumes& v : c.volumes) {
    lost |= v.material == from && v.before > 0 && v.after == 0;
    added |= v.material == from + 100 && v.before == 0 && v.after > 0;
  }
  EXPECT_TRUE(lost);
  EXPECT_TRUE(added);
  EXPECT_FALSE(c.lost.empty());
  EXPECT_EQ(c.lost.size(), c.added.size());
}

}  // namespace
}  // namespace tetlod
