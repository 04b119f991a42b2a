// Files Gmsh 4.8 wrote as analysts get them (tests/data/gmsh, made by its make.sh):
// partitioned meshes, second-order tets, tets next to prisms, physical surfaces and
// names. What is read is right, and what is not read is said in the reader's notes.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <map>
#include <string>

#include "core/io/mesh_io.h"
#include "core/test_io_helpers.h"

namespace tetlod {
namespace {

std::string gmsh_file(const std::string& name) {
  return test::data_path("gmsh/" + name);
}

// Whether one of the notes contains `text`.
bool has_note(const ReadInfo& info, const std::string& text) {
  for (const std::string& note : info.notes)
    if (note.find(text) != std::string::npos) return true;
  return false;
}

std::map<int32_t, size_t> tets_per_material(const TetMesh& mesh) {
  std::map<int32_t, size_t> count;
  for (int32_t m : mesh.materials) ++count[m];
  return count;
}

std::string all_notes(const ReadInfo& info) {
  std::string text;
  for (const std::string& note : info.notes) text += note + "\n";
  return text;
}

// A partitioned mesh's elements are in partition entities: their materials are the
// physical groups of the model volumes they are pieces of (they were the partition
// entities' own tags), as in the same mesh unpartitioned (here second-order).
TEST(IoGmshFiles, PartitionedMeshesKeepTheirPhysicalGroups) {
  TetMesh order2;
  ReadInfo order2_info;
  ASSERT_TRUE(read_mesh(gmsh_file("coax_order2.msh"), &order2, &order2_info).ok());
  for (const char* file : {"coax_part3.msh", "coax_part3_bin.msh"}) {
    SCOPED_TRACE(file);
    TetMesh mesh;
    ReadInfo info;
    const Status s = read_mesh(gmsh_file(file), &mesh, &info);
    ASSERT_TRUE(s.ok()) << s.message();
    // The same mesh (Gmsh's text and binary coordinates may differ in the last digit).
    EXPECT_EQ(tets_per_material(mesh), tets_per_material(order2));
    EXPECT_EQ(tets_per_material(mesh).size(), 4u);
    EXPECT_TRUE(has_note(info,
                         "volume groups are materials by their number (.msh, .inp, .vtk "
                         "and .vtu outputs keep their names): "
                         "'inner_conductor' = 1, 'dielectric_inner' = 2, "
                         "'dielectric_outer' = 3, 'shield' = 4"))
        << all_notes(info);
    // Its 552 triangles are read as the groups only: those of the model's surfaces
    // as 'ends' and 'jacket', the same triangles as unpartitioned (the partition
    // surfaces follow their parents), those between partitions in none (Gmsh gives
    // them their volume's physical tag; they were read as a group of it).
    EXPECT_EQ(info.surface_elements_not_kept, 552u);
    ASSERT_EQ(info.surface_groups.size(), order2_info.surface_groups.size());
    ASSERT_EQ(info.surface_groups.size(), 2u);
    for (size_t g = 0; g < 2; ++g) {
      const InputSurfaceGroup &a = info.surface_groups[g], &b = order2_info.surface_groups[g];
      EXPECT_EQ(a.name, g == 0 ? "ends" : "jacket");
      EXPECT_EQ(a.name, b.name);
      EXPECT_EQ(a.tag, b.tag);
      EXPECT_EQ(a.triangles.size(), b.triangles.size());
    }
  }
  EXPECT_TRUE(has_note(order2_info,
                       "1386 higher-order tetrahedra (10 nodes or more) were read as 4-node ones"))
      << all_notes(order2_info);
}

// The triangles of a surface group by their corners, each sorted, for comparisons.
std::vector<std::array<std::array<double, 3>, 3>> sorted_triangles(const InputSurfaceGroup& g) {
  std::vector<std::array<std::array<double, 3>, 3>> out;
  for (const auto& t : g.triangles) {
    std::array<std::array<double, 3>, 3> c;
    for (size_t k = 0; k < 3; ++k) c[k] = {t[k].x, t[k].y, t[k].z};
    std::sort(c.begin(), c.end());
    out.push_back(c);
  }
  std::sort(out.begin(), out.end());
  return out;
}

// Gmsh's own VTK export writes the physical surfaces' triangles with their group's
// number (CellEntityIds): they are read as those surface groups, unnamed, the same
// triangles as the .msh's 'ends' (20) and 'jacket' (21); triangles in no group (-1)
// and of tag 0 are in none.
TEST(IoGmshFiles, VtkExportKeepsThePhysicalSurfaces) {
  TetMesh msh, vtk;
  ReadInfo msh_info, vtk_info;
  ASSERT_TRUE(read_mesh(gmsh_file("coax_order2.msh"), &msh, &msh_info).ok());
  ASSERT_TRUE(read_mesh(gmsh_file("coax.vtk"), &vtk, &vtk_info).ok());
  EXPECT_EQ(tets_per_material(vtk), tets_per_material(msh));
  EXPECT_EQ(vtk_info.surface_elements_not_kept, 426u);
  ASSERT_EQ(vtk_info.surface_groups.size(), 2u);
  ASSERT_EQ(msh_info.surface_groups.size(), 2u);
  for (size_t g = 0; g < 2; ++g) {
    const InputSurfaceGroup &a = vtk_info.surface_groups[g], &b = msh_info.surface_groups[g];
    EXPECT_EQ(a.tag, g == 0 ? 20 : 21);
    EXPECT_EQ(a.tag, b.tag);
    EXPECT_EQ(a.name, "");
    EXPECT_EQ(a.triangles.size(), g == 0 ? 246u : 180u);
    EXPECT_EQ(sorted_triangles(a), sorted_triangles(b));
  }

  // The same by hand in a .vtu: a triangle of group 7, one in none (-1), one of tag
  // 0, and a quad; all four counted as surface cells.
  const std::string vtu =
      "<VTKFile type=\"UnstructuredGrid\" version=\"0.1\">\n<UnstructuredGrid>\n"
      "<Piece NumberOfPoints=\"5\" NumberOfCells=\"6\">\n<Points>\n"
      "<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n"
      "0 0 0 1 0 0 0 1 0 0 0 1 1 1 1\n</DataArray>\n</Points>\n<Cells>\n"
      "<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">"
      "0 1 2 3 1 2 3 4 0 1 2 0 2 3 0 1 3 0 1 4 2</DataArray>\n"
      "<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">4 8 11 14 17 21</DataArray>\n"
      "<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">10 10 5 5 5 9</DataArray>\n"
      "</Cells>\n<CellData>\n"
      "<DataArray type=\"Int32\" Name=\"CellEntityIds\" format=\"ascii\">1 2 7 -1 0 7"
      "</DataArray>\n</CellData>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n";
  TetMesh mesh;
  ReadInfo info;
  const Status s = read_mesh_from_memory(vtu, MeshFormat::kVtu, "m.vtu", &mesh, &info);
  ASSERT_TRUE(s.ok()) << s.message();
  EXPECT_EQ(mesh.tet_count(), 2u);
  EXPECT_EQ(info.surface_elements_not_kept, 4u);
  ASSERT_EQ(info.surface_groups.size(), 1u);
  EXPECT_EQ(info.surface_groups[0].tag, 7);
  ASSERT_EQ(info.surface_groups[0].triangles.size(), 1u);
  EXPECT_EQ(info.surface_groups[0].triangles[0][2], (Vec3{0, 1, 0}));
}

// Gmsh's Nastran export with physical tags (Mesh.SaveElementTagType 2) writes the
// physical surfaces' triangles as CTRIA3 with their group's number as PID: read as
// those surface groups, the same triangles as the .msh's (to the 8-character fields'
// precision); CQUAD4 are counted, and a blank PID is in no group.
TEST(IoGmshFiles, NastranExportKeepsThePhysicalSurfaces) {
  TetMesh msh, bdf;
  ReadInfo msh_info, bdf_info;
  ASSERT_TRUE(read_mesh(gmsh_file("coax_order2.msh"), &msh, &msh_info).ok());
  ASSERT_TRUE(read_mesh(gmsh_file("coax.bdf"), &bdf, &bdf_info).ok());
  EXPECT_EQ(tets_per_material(bdf), tets_per_material(msh));
  EXPECT_EQ(bdf_info.surface_elements_not_kept, 426u);
  ASSERT_EQ(bdf_info.surface_groups.size(), 2u);
  for (size_t g = 0; g < 2; ++g) {
    const InputSurfaceGroup &a = bdf_info.surface_groups[g], &b = msh_info.surface_groups[g];
    EXPECT_EQ(a.tag, b.tag);
    EXPECT_EQ(a.triangles.size(), b.triangles.size());
    // Each triangle is one of the .msh's group, its corners within the fields' rounding.
    for (const auto& t : a.triangles) {
      const Vec3 centroid = (t[0] + t[1] + t[2]) * (1.0 / 3);
      double nearest = 1e300;
      for (const auto& u : b.triangles)
        nearest = std::min(nearest, length((u[0] + u[1] + u[2]) * (1.0 / 3) - centroid));
      EXPECT_LT(nearest, 1e-4);
    }
  }
  TetMesh mesh;
  ReadInfo info;
  const std::string text =
      "GRID,1,,0.,0.,0.\nGRID,2,,1.,0.,0.\nGRID,3,,0.,1.,0.\nGRID,4,,0.,0.,1.\n"
      "CTETRA,1,3,1,2,3,4\nCTRIA3,2,5,1,2,3\nCTRIA3,3,,1,2,4\nCQUAD4,4,5,1,2,3,4\nENDDATA\n";
  const Status s = read_mesh_from_memory(text, MeshFormat::kNastran, "m.bdf", &mesh, &info);
  ASSERT_TRUE(s.ok()) << s.message();
  EXPECT_EQ(info.surface_elements_not_kept, 3u);
  ASSERT_EQ(info.surface_groups.size(), 1u);
  EXPECT_EQ(info.surface_groups[0].tag, 5);
  EXPECT_EQ(info.surface_groups[0].triangles.size(), 1u);
}

// Third-order (20-node) tets are read by their corners: the same mesh as Gmsh's
// first-order one (they were skipped, leaving no tets).
TEST(IoGmshFiles, HigherOrderTetsAreReadByTheirCorners) {
  TetMesh order3, order1;
  ReadInfo info;
  const Status s = read_mesh(gmsh_file("cube_order3.msh"), &order3, &info);
  ASSERT_TRUE(s.ok()) << s.message();
  ASSERT_TRUE(read_mesh(gmsh_file("cube_order1.msh"), &order1).ok());
  EXPECT_EQ(test::canonical_tets(order3), test::canonical_tets(order1));
  EXPECT_TRUE(has_note(info, std::to_string(order1.tet_count()) +
                                 " higher-order tetrahedra (10 nodes or more) were read as "
                                 "4-node ones"))
      << all_notes(info);
}

// An element in two physical groups is written twice by Gmsh 2.2: it is read once, in
// the first group, and the mesh is the same as the one without the second group
// (which used to fail as a non-manifold).
TEST(IoGmshFiles, ElementsInTwoGroupsAreReadOnce) {
  TetMesh twice, once;
  ReadInfo info;
  const Status s = read_mesh(gmsh_file("coax_two_groups22.msh"), &twice, &info);
  ASSERT_TRUE(s.ok()) << s.message();
  ASSERT_TRUE(read_mesh(gmsh_file("coax_order2.msh"), &once).ok());
  EXPECT_EQ(tets_per_material(twice), tets_per_material(once));
  EXPECT_TRUE(has_note(info, "620 tetrahedra are listed again in another physical group"))
      << all_notes(info);
  EXPECT_TRUE(has_note(info, "not in group(s) 100")) << all_notes(info);
  // The group of both conductors is not said to have no tets: they are in 1 and 4.
  EXPECT_TRUE(has_note(info,
                       "'conductors' = 100 (no tetrahedra of its own: they are read in "
                       "groups 1, 4, which hold the same volumes; a tet has one material, so this "
                       "group is not kept: name those)"))
      << all_notes(info);
  // Gmsh 4.1 writes a volume in two groups once, with both tags: its tets go to the
  // first, and the second is said to hold them too.
  const std::string two_tags =
      "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$PhysicalNames\n2\n3 1 \"iron\"\n"
      "3 2 \"all\"\n$EndPhysicalNames\n$Entities\n0 0 0 1\n1 0 0 0 1 1 1 2 1 2 0\n"
      "$EndEntities\n$Nodes\n1 4 1 4\n3 1 0 4\n1\n2\n3\n4\n0 0 0\n1 0 0\n0 1 0\n"
      "0 0 1\n$EndNodes\n$Elements\n1 1 1 1\n3 1 4 1\n1 1 2 3 4\n$EndElements\n";
  {
    TetMesh mesh;
    ReadInfo two;
    ASSERT_TRUE(read_mesh_from_memory(two_tags, MeshFormat::kGmsh41, "two.msh", &mesh, &two).ok());
    EXPECT_EQ(mesh.materials, std::vector<int32_t>{1});
    EXPECT_TRUE(
        has_note(two,
                 "'iron' = 1, 'all' = 2 (no tetrahedra of its own: they are read in "
                 "group 1, which holds the same volume; a tet has one material, so this group "
                 "is not kept: name that one)"))
        << all_notes(two);
    EXPECT_TRUE(has_note(two,
                         "1 tetrahedron is in a volume of more than one physical group: it is "
                         "read once, in the volume's first group, not in group(s) 2"))
        << all_notes(two);
  }
  // The same where the second group has a volume of its own: its tets are read in it,
  // those of the shared volume in the first group, and that is said (it was not).
  const std::string own =
      "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$PhysicalNames\n2\n3 1 \"iron\"\n"
      "3 2 \"all\"\n$EndPhysicalNames\n$Entities\n0 0 0 2\n1 0 0 0 1 1 1 2 1 2 0\n"
      "2 0 0 0 1 1 1 1 2 0\n$EndEntities\n$Nodes\n1 5 1 5\n3 1 0 5\n1\n2\n3\n4\n5\n"
      "0 0 0\n1 0 0\n0 1 0\n0 0 1\n1 1 1\n$EndNodes\n$Elements\n2 2 1 2\n3 1 4 1\n"
      "1 1 2 3 4\n3 2 4 1\n2 2 3 4 5\n$EndElements\n";
  {
    TetMesh mesh;
    ReadInfo notes;
    const Status read = read_mesh_from_memory(own, MeshFormat::kGmsh41, "own.msh", &mesh, &notes);
    ASSERT_TRUE(read.ok()) << read.message();
    EXPECT_EQ(mesh.materials, (std::vector<int32_t>{1, 2}));
    EXPECT_TRUE(has_note(notes, "1 tetrahedron is in a volume of more than one physical group"))
        << all_notes(notes);
    EXPECT_FALSE(has_note(notes, "no tetrahedra of its own")) << all_notes(notes);
  }
  // The same nodes in two elementary entities are not a repeat but a broken mesh.
  const std::string two_entities =
      "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n4\n1 0 0 0\n2 1 0 0\n3 0 1 0\n"
      "4 0 0 1\n$EndNodes\n$Elements\n3\n1 4 2 1 1 1 2 3 4\n2 4 2 2 1 1 2 3 4\n"
      "3 4 2 2 2 1 2 3 4\n$EndElements\n";
  TetMesh mesh;
  const Status broken =
      read_mesh_from_memory(two_entities, MeshFormat::kGmsh22, "m.msh", &mesh, &info);
  ASSERT_FALSE(broken.ok());
  EXPECT_NE(broken.message().find("m.msh:"), std::string::npos) << broken.message();
}

// Gmsh 2.2 with -setnumber Mesh.SaveParametric 1 writes $ParametricNodes: "tag x y z
// dimension entity" and a parameter per dimension for curves and surfaces. They read
// as the same nodes (they were refused as "$Elements before $Nodes"; found by a user
// test), in ASCII and in binary.
TEST(IoGmshFiles, ParametricNodesAreRead) {
  const std::string head = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n";
  const std::string elements = "$Elements\n1\n1 4 2 1 1 1 2 3 4\n$EndElements\n";
  const std::string plain =
      head + "$Nodes\n4\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n$EndNodes\n" + elements;
  const std::string parametric = head +
                                 "$ParametricNodes\n4\n1 0 0 0 0 1\n2 1 0 0 1 3 0.5\n"
                                 "3 0 1 0 2 7 0.25 0.75\n4 0 0 1 3 1\n$EndParametricNodes\n" +
                                 elements;
  TetMesh a, b;
  ASSERT_TRUE(read_mesh_from_memory(plain, MeshFormat::kGmsh22, "a.msh", &a).ok());
  const Status s = read_mesh_from_memory(parametric, MeshFormat::kGmsh22, "b.msh", &b);
  ASSERT_TRUE(s.ok()) << s.message();
  EXPECT_EQ(a.positions, b.positions);
  EXPECT_EQ(a.tets, b.tets);
  // A node of a curve without its parameter: the count is off, and the error says where.
  std::string short_node = parametric;
  short_node.replace(short_node.find("1 3 0.5"), 7, "1 3");
  const Status broken = read_mesh_from_memory(short_node, MeshFormat::kGmsh22, "c.msh", &b);
  EXPECT_NE(broken.message().find("c.msh:"), std::string::npos) << broken.message();
  // Binary, as Gmsh 4.8 writes it with -bin: int tag, three doubles, int dimension, int
  // entity, a double per dimension of a curve or surface.
  test::Bytes binary(false);
  binary.text("$MeshFormat\n2.2 1 8\n");
  binary.i32(1);
  binary.text("\n$EndMeshFormat\n$ParametricNodes\n4\n");
  const double xyz[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const int dims[4] = {0, 1, 2, 3};
  for (int n = 0; n < 4; ++n) {
    binary.i32(n + 1);
    for (double x : xyz[n]) binary.f64(x);
    binary.i32(dims[n]);
    binary.i32(7);
    for (int k = 0; k < (dims[n] == 1 || dims[n] == 2 ? dims[n] : 0); ++k) binary.f64(0.5);
  }
  binary.text("\n$EndParametricNodes\n$Elements\n1\n");
  // Type 4, one element, two tags; the element: its number, its tags, its nodes.
  for (int v : {4, 1, 2, 1, 1, 1, 1, 2, 3, 4}) binary.i32(v);
  binary.text("\n$EndElements\n");
  TetMesh c;
  const Status read_binary = read_mesh_from_memory(binary.data(), MeshFormat::kGmsh22, "d.msh", &c);
  ASSERT_TRUE(read_binary.ok()) << read_binary.message();
  EXPECT_EQ(c.positions, a.positions);
  EXPECT_EQ(c.tets, a.tets);
  const std::string cut = binary.data().substr(0, binary.data().find("$EndParametricNodes") - 9);
  EXPECT_NE(read_mesh_from_memory(cut, MeshFormat::kGmsh22, "e.msh", &c).message().find("e.msh"),
            std::string::npos);
}

// Prisms are not read: the note says so, and that the group they made has no tets.
TEST(IoGmshFiles, SkippedElementsAreNamed) {
  TetMesh mesh;
  ReadInfo info;
  ASSERT_TRUE(read_mesh(gmsh_file("mixed_prisms.msh"), &mesh, &info).ok());
  for (int32_t m : mesh.materials) EXPECT_EQ(m, 1);
  EXPECT_TRUE(has_note(info, "skipped 28 prisms: TetLOD reads tetrahedra only")) << all_notes(info);
  EXPECT_TRUE(has_note(info, "'layer' = 2 (no tetrahedra: not in the mesh)")) << all_notes(info);
  EXPECT_GT(info.validation.removed_unused_vertices, 0u);
}

// Tets without a physical group take their volume's tag, unless it is also a volume
// group's number (of tets read in a group, or one $PhysicalNames names): then they are
// a material of their own, numbered above the rest, and a note says so; before, the
// two bodies were read as one material (Gmsh 4.1), or a body was named after a group
// it is not in (2.2 with Mesh.SaveAll, which writes every element in no group).
TEST(IoGmshFiles, ElementaryTagsSharedWithAVolumeGroupGetANumberOfTheirOwn) {
  auto file = [](const std::string& names, const std::string& first_tags,
                 const std::string& second_tags) {
    return "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n" + names +
           "$Nodes\n5\n1 0 0 0\n2 1 0 0\n3 0 1 0\n"
           "4 0 0 1\n5 0 0 -1\n$EndNodes\n$Elements\n2\n1 4 2 " +
           first_tags + " 1 2 3 4\n2 4 2 " + second_tags + " 1 3 2 5\n$EndElements\n";
  };
  const std::string air = "$PhysicalNames\n1\n3 4 \"air\"\n$EndPhysicalNames\n";
  const struct {
    std::string names, first, second;  // physical and elementary tags of each tet
    std::vector<int32_t> materials;
    const char* note;
  } cases[] = {
      {"",
       "4 1",
       "0 4",
       {4, 5},
       "1 tetrahedra are in no physical group: their material is their volume's entity "
       "tag (4 as 5)\n"},
      {"",
       "4 1",
       "0 7",
       {4, 7},
       "1 tetrahedra are in no physical group: their material is their volume's entity "
       "tag (7)\n"},
      {"", "4 1", "2 7", {4, 2}, nullptr},
      // Mesh.SaveAll: no tet in a group, and the name of group 4 (entity 1's).
      {air, "0 4", "0 1", {5, 1}, "'air' = 4 (no tetrahedra: not in the mesh)"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.second);
    TetMesh mesh;
    ReadInfo info;
    const Status s = read_mesh_from_memory(file(c.names, c.first, c.second), MeshFormat::kGmsh22,
                                           "m.msh", &mesh, &info);
    ASSERT_TRUE(s.ok()) << s.message();
    EXPECT_EQ(mesh.materials, c.materials);
    const bool renumbered = c.materials[0] == 5 || c.materials[1] == 5;
    EXPECT_EQ(all_notes(info).find("are read as materials of their own: entity 4 as 5") !=
                  std::string::npos,
              renumbered)
        << all_notes(info);
    EXPECT_TRUE(info.material_names.empty() || info.material_names[0].material != 5);
    if (c.note) {
      EXPECT_NE(all_notes(info).find(c.note), std::string::npos) << all_notes(info);
    } else {
      EXPECT_TRUE(info.notes.empty()) << all_notes(info);
    }
  }
}

// Physical curves and points, and a $Periodic section, are not kept: notes say so
// (they were dropped silently).
TEST(IoGmshFiles, CurvesPointsAndPeriodicNodesAreNotedAsNotKept) {
  const std::string file =
      "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n4\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n"
      "$EndNodes\n$Elements\n4\n1 15 2 301 1 1\n2 1 2 201 1 1 2\n3 1 2 201 1 2 3\n"
      "4 4 2 1 1 1 2 3 4\n$EndElements\n$Periodic\n1\n2 1 2\n1\n1 2\n$EndPeriodic\n";
  TetMesh mesh;
  ReadInfo info;
  const Status s = read_mesh_from_memory(file, MeshFormat::kGmsh22, "p.msh", &mesh, &info);
  ASSERT_TRUE(s.ok()) << s.message();
  EXPECT_EQ(mesh.tet_count(), 1u);
  EXPECT_NE(all_notes(info).find("2 line and 1 point elements (Gmsh writes those of physical "
                                 "curves and points, or all with Mesh.SaveAll) are not kept"),
            std::string::npos)
      << all_notes(info);
  EXPECT_NE(all_notes(info).find("the $Periodic section is not kept"), std::string::npos)
      << all_notes(info);
}

}  // namespace
}  // namespace tetlod
