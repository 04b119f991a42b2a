// compare_meshes(): each material's volume and how far each material pair's surface
// moved between two meshes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include "core/io/mesh_io.h"
#include "core/mesh_compare.h"
#include "core/test_meshes.h"
#include "core/validate.h"

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

// A fan of thin tets round one edge, materials 1 and 2 in turn: every interface
// triangle holds that edge, so a grid search near it reads them all (compare took
// minutes for 20,000 of them; a hostile-input test). Unchanged triangles are not
// searched: against itself every surface is at exactly 0.
TEST(MeshCompare, AFanAgainstItself) {
  TetMesh fan;
  constexpr int kTets = 2000;
  fan.positions = {{0, 0, -1}, {0, 0, 1}};
  for (int i = 0; i < kTets; ++i) {
    const double a = 2 * 3.14159265358979323846 * i / kTets;
    fan.positions.push_back({std::cos(a), std::sin(a), 0});
  }
  for (uint32_t i = 0; i < kTets; ++i) {
    fan.tets.push_back({0, 1, 2 + i, 2 + (i + 1) % kTets});
    fan.materials.push_back(1 + int32_t(i % 2));
  }
  ASSERT_TRUE(validate_mesh(&fan, "fan", {}, nullptr, nullptr).ok());  // (orients the tets)
  const MeshComparison c = compare_meshes(fan, fan);
  ASSERT_FALSE(c.pairs.empty());
  for (const PairDeviation& d : c.pairs) EXPECT_EQ(d.distance, 0);
}

// Far from the origin a mesh against itself has not moved, and one moved by a
// thousandth of its size moved by that (measured round the mesh: at 1e8, a surface
// against itself moved 3.7e-8).
TEST(MeshCompare, FarFromTheOriginAMeshAgainstItself) {
  TetMesh far = box2();
  for (Vec3& p : far.positions) p = p + Vec3{1e8, -3e8, 2e8};
  const MeshComparison c = compare_meshes(far, far);
  ASSERT_FALSE(c.pairs.empty());
  for (const PairDeviation& d : c.pairs) EXPECT_LE(d.distance, 1e-12);  // (as at the origin)
  for (const MaterialVolumes& v : c.volumes) EXPECT_EQ(v.before, v.after);
  TetMesh moved = far;
  for (Vec3& p : moved.positions) p.z += 1.0 / 1024;
  for (const PairDeviation& d : compare_meshes(far, moved).pairs)
    EXPECT_NEAR(d.distance, 1.0 / 1024, 1e-7);
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
  // Its pieces: 0 on the side without it.
  for (const MaterialPieces& p : c.pieces) {
    if (p.material == from) {
      EXPECT_TRUE(p.before > 0 && p.after == 0);
    }
    if (p.material == from + 100) {
      EXPECT_TRUE(p.before == 0 && p.after > 0);
    }
  }
}

// Topology: a 3 x 3 x 1 grid of material 1 with material 2 in the cube at a corner,
// against one with material 2 also in the opposite corner's cube. Material 2 is in 1
// piece, then 2; its interface with material 1 (three squares round the corner: a disk,
// V - E + F = 1) becomes two disks (2); its boundary likewise (1, then 2); material 1
// stays in one piece; on a mesh against itself nothing changes.
TEST(MeshCompare, PiecesAndEulerCharacteristics) {
  const auto grid = [](bool two) {
    return test::make_grid_mesh(3, 3, 1, [two](int i, int j, int) -> int32_t {
      return (i == 0 && j == 0) || (two && i == 2 && j == 2) ? 2 : 1;
    });
  };
  const TetMesh one = grid(false), two = grid(true);
  const MeshComparison same = compare_meshes(one, one);
  ASSERT_EQ(same.pieces.size(), 2u);
  for (const MaterialPieces& p : same.pieces) EXPECT_EQ(p.before, p.after);
  for (const PairEuler& e : same.euler) EXPECT_EQ(e.before, e.after);
  const MeshComparison c = compare_meshes(one, two);
  ASSERT_EQ(c.pieces.size(), 2u);
  EXPECT_EQ(c.pieces[0].material, 1);
  EXPECT_EQ(c.pieces[0].before, 1);
  EXPECT_EQ(c.pieces[0].after, 1);
  EXPECT_EQ(c.pieces[1].material, 2);
  EXPECT_EQ(c.pieces[1].before, 1);
  EXPECT_EQ(c.pieces[1].after, 2);
  std::map<MaterialPair, std::pair<long, long>> euler;
  for (const PairEuler& e : c.euler) euler[e.pair] = {e.before, e.after};
  EXPECT_EQ(euler[MaterialPair(1, 2)], std::make_pair(1L, 2L));
  EXPECT_EQ(euler[MaterialPair(2, kOutsideMaterial)], std::make_pair(1L, 2L));
  // Material 1's boundary: a sphere (2) with the corner's disk cut out (1), then two (0).
  EXPECT_EQ(euler[MaterialPair(1, kOutsideMaterial)], std::make_pair(1L, 0L));
}

// Materials numbered differently by another tool, with the same names: matched by
// name, renumbered, nothing lost or new.
TEST(MeshCompare, MaterialsNamedInBothFilesAreMatchedByName) {
  const TetMesh mesh = box2();
  std::vector<int32_t> ids(mesh.materials.begin(), mesh.materials.end());
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  ASSERT_EQ(ids.size(), 2u);
  const std::vector<MaterialName> before_names = {{ids[0], "iron"}, {ids[1], "air"}};
  // AFTER swaps the two ids.
  TetMesh after = mesh;
  for (int32_t& m : after.materials) m = m == ids[0] ? ids[1] : ids[0];
  std::vector<MaterialName> after_names = {{ids[0], "air"}, {ids[1], "iron"}};
  const MaterialMatch match = match_materials_by_name(before_names, after, after_names);
  EXPECT_EQ(match.why_by_id, "");
  ASSERT_EQ(match.renumbered.size(), 2u);
  EXPECT_EQ(match.renumbered[0], std::make_pair(ids[0], ids[1]));
  EXPECT_EQ(match.renumbered[1], std::make_pair(ids[1], ids[0]));
  renumber_materials(match, &after, &after_names);
  EXPECT_EQ(after.materials, mesh.materials);
  ASSERT_EQ(after_names.size(), 2u);
  EXPECT_EQ(after_names[0].material, ids[0]);
  EXPECT_EQ(after_names[0].name, "iron");
  const MeshComparison c = compare_meshes(mesh, after);
  EXPECT_TRUE(c.lost.empty());
  EXPECT_TRUE(c.added.empty());

  // Without the swap, nothing to renumber.
  EXPECT_TRUE(match_materials_by_name(before_names, mesh, before_names).renumbered.empty());
}

// Where names cannot say which is which, ids are used, and why is said.
TEST(MeshCompare, NamesThatCannotMatchLeaveTheIds) {
  const TetMesh mesh = box2();
  const int32_t a = mesh.materials.front();
  const std::vector<MaterialName> named = {{a, "iron"}};
  EXPECT_EQ(match_materials_by_name({}, mesh, named).why_by_id, "BEFORE does not name them");
  EXPECT_EQ(match_materials_by_name(named, mesh, {}).why_by_id, "AFTER does not name them");
  EXPECT_EQ(match_materials_by_name({}, mesh, {}).why_by_id, "neither file names them");
  const std::vector<MaterialName> twice = {{a, "iron"}, {a + 50, "iron"}};
  EXPECT_NE(match_materials_by_name(twice, mesh, named).why_by_id.find("names two materials"),
            std::string::npos);
  // AFTER's material named "iron" would take the id of AFTER's unnamed one.
  int32_t other = a;
  for (const int32_t m : mesh.materials)
    if (m != a) other = m;
  ASSERT_NE(other, a);
  const MaterialMatch match = match_materials_by_name(named, mesh, {{other, "iron"}});
  EXPECT_TRUE(match.renumbered.empty());
  EXPECT_NE(match.why_by_id.find("would both be"), std::string::npos) << match.why_by_id;
}

}  // namespace
}  // namespace tetlod
