// Gmsh itself reads what we write: run the `gmsh` binary (when it is on PATH) on
// our 2.2 and 4.1 files, text and binary, have it save the mesh again, as text and as
// binary, and read its output back.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <map>

#include "core/io/mesh_io.h"
#include "core/surface.h"
#include "core/test_io_helpers.h"
#include "core/test_meshes.h"

namespace tetlod {
namespace {

// Runs gmsh with `arguments`, its output going to `log`; true on exit status 0.
bool run_gmsh(const std::string& arguments, const std::string& log) {
  return std::system(("gmsh " + arguments + " > '" + log + "' 2>&1").c_str()) == 0;
}

TEST(IoGmshInterop, GmshReadsOurFilesWithTheirPhysicalGroups) {
  TETLOD_NEED_PROGRAM("gmsh");
  const std::string dir = test::output_dir("gmsh_interop");
  // Materials 0 (named "material_0"), 1..3 and a large id.
  TetMesh mesh = test::make_grid_mesh(
      3, 2, 2, [](int i, int j, int) { return i == 2 && j == 1 ? 1000000 : (i + j) % 4; }, 0.25);
  // Ours in text and in binary (--msh-binary), with the surface groups.
  for (int ours_version : {22, 41, -22, -41}) {
    const int version = std::abs(ours_version);
    SCOPED_TRACE(ours_version < 0 ? "ours binary" : "ours text");
    SCOPED_TRACE(version);
    const std::string ours = dir + "/ours" + std::to_string(ours_version) + ".msh";
    WriteOptions options;
    options.gmsh_version = version;
    options.gmsh_binary = ours_version < 0;
    options.surface_groups = true;
    ASSERT_TRUE(write_mesh(ours, mesh, options).ok());
    // The header: file type 1 and the binary 1 (this machine's byte order), or type 0.
    const std::string type = ours_version < 0 ? std::string(" 1 8\n\1\0\0\0\n", 10) : " 0 8\n";
    EXPECT_EQ(test::read_text(ours).find(type), std::string("$MeshFormat\n2.2").size());
    TetMesh ours_back;
    ReadInfo ours_info;
    ASSERT_TRUE(read_mesh(ours, &ours_back, &ours_info).ok());
    size_t triangles = 0;
    for (const auto& group : ours_info.surface_groups) triangles += group.triangles.size();
    // Gmsh's own files, text and binary.
    for (const char* out_format : {"msh22", "msh41", "msh22 -bin", "msh41 -bin"}) {
      SCOPED_TRACE(out_format);
      std::string suffix = out_format;
      std::replace(suffix.begin(), suffix.end(), ' ', '_');
      const std::string theirs =
          dir + "/gmsh_" + std::to_string(ours_version) + "_" + suffix + ".msh";
      const std::string log = theirs + ".log";
      ASSERT_TRUE(run_gmsh("'" + ours + "' -0 -format " + out_format + " -o '" + theirs + "'", log))
          << test::read_text(log);
      if (suffix.find("bin") != std::string::npos) {
        ASSERT_NE(test::read_text(theirs).find(" 1 8\n"), std::string::npos) << "not binary";
      }
      const std::string output = test::read_text(log);
      EXPECT_NE(output.find(std::to_string(mesh.tet_count() + triangles) + " elements"),
                std::string::npos)
          << output;
      EXPECT_EQ(output.find("Error"), std::string::npos) << output;
      // Gmsh renumbers nodes: compare tets by their corner positions and materials.
      TetMesh back;
      ReadInfo info;
      const Status status = read_mesh(theirs, &back, &info);
      ASSERT_TRUE(status.ok()) << status.message();
      EXPECT_EQ(info.validation.reoriented_tets, 0u);
      EXPECT_EQ(test::canonical_tets(back), test::canonical_tets(mesh));
      // The surface groups too, by tag, name and triangles.
      ASSERT_EQ(info.surface_groups.size(), ours_info.surface_groups.size());
      for (size_t g = 0; g < info.surface_groups.size(); ++g) {
        EXPECT_EQ(info.surface_groups[g].tag, ours_info.surface_groups[g].tag);
        EXPECT_EQ(info.surface_groups[g].name, ours_info.surface_groups[g].name);
        EXPECT_EQ(info.surface_groups[g].triangles.size(),
                  ours_info.surface_groups[g].triangles.size());
      }
    }
  }
}

// Gmsh reads our legacy .vtk, text and binary, with the surface groups and the names
// in the dataset's field data (Gmsh 4.8 refused the file when those came before POINTS).
TEST(IoGmshInterop, GmshReadsOurVtkWithNames) {
  TETLOD_NEED_PROGRAM("gmsh");
  const std::string dir = test::output_dir("gmsh_vtk");
  TetMesh mesh = test::make_grid_mesh(3, 2, 2, [](int i, int j, int) { return (i + j) % 3; });
  for (bool binary : {false, true}) {
    SCOPED_TRACE(binary ? "binary" : "text");
    const std::string ours = dir + (binary ? "/ours_binary.vtk" : "/ours.vtk");
    WriteOptions options;
    options.vtk_binary = binary;
    options.surface_groups = true;
    ASSERT_TRUE(write_mesh(ours, mesh, options).ok());
    TetMesh back;
    ReadInfo info;
    ASSERT_TRUE(read_mesh(ours, &back, &info).ok());
    ASSERT_FALSE(info.surface_groups.empty());
    size_t triangles = 0;
    for (const auto& group : info.surface_groups) triangles += group.triangles.size();
    const std::string log = ours + ".log";
    ASSERT_TRUE(run_gmsh("'" + ours + "' -0 -format msh41 -o '" + ours + ".msh'", log))
        << test::read_text(log);
    const std::string output = test::read_text(log);
    EXPECT_EQ(output.find("Error"), std::string::npos) << output;
    EXPECT_NE(output.find("Reading " + std::to_string(mesh.tet_count() + triangles) + " cells"),
              std::string::npos)
        << output;
    // What Gmsh wrote holds our tets (Gmsh keeps no material from a .vtk).
    TetMesh theirs;
    ReadInfo theirs_info;
    const Status status = read_mesh(ours + ".msh", &theirs, &theirs_info);
    ASSERT_TRUE(status.ok()) << status.message();
    EXPECT_EQ(theirs.tet_count(), mesh.tet_count());
  }
}

// Nastran bulk data both ways: Gmsh reads what we write (PID = material), and we
// read what Gmsh writes in each of its three field formats.
TEST(IoGmshInterop, NastranBothWays) {
  TETLOD_NEED_PROGRAM("gmsh");
  const std::string dir = test::output_dir("gmsh_nastran");
  const TetMesh mesh = test::make_grid_mesh(
      3, 2, 2, [](int i, int j, int) { return 1 + (i + j) % 4; }, 0.25);
  const std::string ours = dir + "/ours.bdf";
  ASSERT_TRUE(write_mesh(ours, mesh).ok());
  const std::string read_by_gmsh = dir + "/gmsh_read.msh";
  std::string log = dir + "/read.log";
  ASSERT_TRUE(run_gmsh("'" + ours + "' -0 -format msh41 -o '" + read_by_gmsh + "'", log))
      << test::read_text(log);
  TetMesh back;
  Status status = read_mesh(read_by_gmsh, &back);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_EQ(test::canonical_tets(back), test::canonical_tets(mesh));

  // With surface groups: Gmsh reads each group's CTRIA3s as a surface entity tagged with
  // the group's tag (a block "2 tag 2 count" of its elements).
  SurfaceGroups groups;
  ASSERT_TRUE(group_surface(mesh, &groups).ok());
  WriteOptions with_groups;
  with_groups.surface_groups = true;
  ASSERT_TRUE(write_mesh(dir + "/ours_groups.bdf", mesh, with_groups).ok());
  log = dir + "/groups.log";
  ASSERT_TRUE(run_gmsh(
      "'" + dir + "/ours_groups.bdf' -0 -format msh41 -o '" + dir + "/gmsh_groups.msh'", log))
      << test::read_text(log);
  const std::string gmsh_groups = test::read_text(dir + "/gmsh_groups.msh");
  for (const SurfaceGroup& g : groups.groups) {
    EXPECT_NE(gmsh_groups.find("\n2 " + std::to_string(g.tag) + " 2 " +
                               std::to_string(g.triangles.size()) + "\n"),
              std::string::npos)
        << g.name;
  }
  status = read_mesh(dir + "/gmsh_groups.msh", &back);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_EQ(test::canonical_tets(back), test::canonical_tets(mesh));

  ASSERT_TRUE(write_mesh(dir + "/ours.msh", mesh).ok());
  for (int field_format : {0, 1, 2}) {  // free, small, large
    SCOPED_TRACE(field_format);
    const std::string theirs = dir + "/gmsh_" + std::to_string(field_format) + ".bdf";
    log = theirs + ".log";
    ASSERT_TRUE(run_gmsh("'" + dir + "/ours.msh' -0 -format bdf -setnumber Mesh.BdfFieldFormat " +
                             std::to_string(field_format) + " -o '" + theirs + "'",
                         log))
        << test::read_text(log);
    status = read_mesh(theirs, &back);
    ASSERT_TRUE(status.ok()) << status.message();
    EXPECT_EQ(test::canonical_tets(back), test::canonical_tets(mesh));
  }
}

// Gmsh's binary legacy VTK: points, cells and, as cell data CellEntityIds, each
// element's physical group, read as the materials; -1 (in no group) is material 0.
TEST(IoGmshInterop, WeReadGmshBinaryVtk) {
  TETLOD_NEED_PROGRAM("gmsh");
  const std::string dir = test::output_dir("gmsh_vtk");
  const TetMesh mesh = test::make_grid_mesh(
      3, 2, 2, [](int i, int, int) { return i == 0 ? 4 : 1; }, 0.25);
  ASSERT_TRUE(write_mesh(dir + "/ours.msh", mesh).ok());
  const std::string theirs = dir + "/gmsh.vtk";
  const std::string log = dir + "/vtk.log";
  ASSERT_TRUE(run_gmsh("'" + dir + "/ours.msh' -0 -format vtk -bin -o '" + theirs + "'", log))
      << test::read_text(log);
  ASSERT_NE(test::read_text(theirs).find("\nBINARY\n"), std::string::npos);
  TetMesh back;
  ReadInfo info;
  const Status status = read_mesh(theirs, &back, &info);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_EQ(test::canonical_tets(back), test::canonical_tets(mesh));
  ASSERT_EQ(info.notes.size(), 1u);
  EXPECT_EQ(info.notes[0],
            "the materials are Gmsh's physical groups (cell array CellEntityIds of its VTK "
            "export)");

  // Two volumes, one in a physical group (7): saved with -save_all, the other's tets
  // are -1.
  test::write_text(dir + "/two.geo",
                   "SetFactory(\"OpenCASCADE\");\nBox(1) = {0, 0, 0, 1, 1, 1};\n"
                   "Box(2) = {1, 0, 0, 1, 1, 1};\nCoherence;\nPhysical Volume(7) = {1};\n"
                   "Mesh.MeshSizeMax = 0.5;\n");
  ASSERT_TRUE(
      run_gmsh("'" + dir + "/two.geo' -3 -save_all -format vtk -o '" + dir + "/two.vtk'", log))
      << test::read_text(log);
  ASSERT_TRUE(read_mesh(dir + "/two.vtk", &back, &info).ok());
  std::map<int32_t, size_t> counts;
  for (const int32_t m : back.materials) ++counts[m];
  ASSERT_EQ(counts.size(), 2u);
  EXPECT_GT(counts[0], 0u);
  EXPECT_GT(counts[7], 0u);
  const std::string materials_note =
      "the materials are Gmsh's physical groups (cell array CellEntityIds of its VTK export); " +
      std::to_string(counts[0]) + " tetrahedra in none (-1) are material 0";
  EXPECT_NE(std::find(info.notes.begin(), info.notes.end(), materials_note), info.notes.end())
      << ::testing::PrintToString(info.notes);
  // -save_all writes the curves' and points' elements too: said not kept (they were
  // dropped without a word).
  EXPECT_TRUE(std::any_of(info.notes.begin(), info.notes.end(), [](const std::string& n) {
    return n.find(" vertex and line cells are not kept") != std::string::npos;
  })) << ::testing::PrintToString(info.notes);
}

// Gmsh's Abaqus input: its physical groups (our materials) as *ELSET material_<n>.
TEST(IoGmshInterop, WeReadGmshAbaqusInput) {
  TETLOD_NEED_PROGRAM("gmsh");
  const std::string dir = test::output_dir("gmsh_inp");
  const TetMesh mesh = test::make_grid_mesh(
      3, 2, 2, [](int i, int j, int k) { return 1 + (i + 2 * j + k) % 3; }, 0.25);
  ASSERT_TRUE(write_mesh(dir + "/ours.msh", mesh).ok());
  const std::string theirs = dir + "/gmsh.inp";
  const std::string log = dir + "/inp.log";
  ASSERT_TRUE(run_gmsh("'" + dir + "/ours.msh' -0 -format inp -o '" + theirs + "'", log))
      << test::read_text(log);
  TetMesh back;
  const Status status = read_mesh(theirs, &back);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_EQ(test::canonical_tets(back), test::canonical_tets(mesh));
}

// Gmsh's .inp export writes a physical surface as CPS3 elements in an *ELSET named
// after it: read, it is the same group, of the same triangles, as in the .msh.
TEST(IoGmshInterop, GmshAbaqusPhysicalSurfacesAreGroups) {
  TETLOD_NEED_PROGRAM("gmsh");
  const std::string dir = test::output_dir("gmsh_inp_groups");
  const std::string theirs = dir + "/port.inp";
  const std::string log = dir + "/inp.log";
  ASSERT_TRUE(run_gmsh(
      "'" + test::data_path("gmsh/port.msh") + "' -0 -format inp -o '" + theirs + "'", log))
      << test::read_text(log);
  TetMesh from_msh, from_inp;
  ReadInfo msh_info, inp_info;
  ASSERT_TRUE(read_mesh(test::data_path("gmsh/port.msh"), &from_msh, &msh_info).ok());
  const Status status = read_mesh(theirs, &from_inp, &inp_info);
  ASSERT_TRUE(status.ok()) << status.message();
  ASSERT_EQ(msh_info.surface_groups.size(), 1u);
  ASSERT_EQ(inp_info.surface_groups.size(), 1u);
  EXPECT_EQ(inp_info.surface_groups[0].name, msh_info.surface_groups[0].name);
  EXPECT_EQ(inp_info.surface_groups[0].triangles.size(), 79u);
  // Its triangle elements are counted as kept only in the group, as in the .msh.
  EXPECT_EQ(inp_info.surface_elements_not_kept, 79u);
  EXPECT_EQ(msh_info.surface_elements_not_kept, 79u);
  auto sorted = [](std::vector<std::array<Vec3, 3>> triangles) {
    std::vector<std::array<double, 9>> out;
    for (const auto& t : triangles) {
      std::array<std::array<double, 3>, 3> c;
      // Gmsh's .inp has coordinates to about 9 digits: rounded to 1e-6.
      auto round = [](double v) { return std::round(v * 1e6) / 1e6; };
      for (size_t k = 0; k < 3; ++k) c[k] = {round(t[k].x), round(t[k].y), round(t[k].z)};
      std::sort(c.begin(), c.end());
      out.push_back(
          {c[0][0], c[0][1], c[0][2], c[1][0], c[1][1], c[1][2], c[2][0], c[2][1], c[2][2]});
    }
    std::sort(out.begin(), out.end());
    return out;
  };
  EXPECT_EQ(sorted(inp_info.surface_groups[0].triangles),
            sorted(msh_info.surface_groups[0].triangles));
}

// Gmsh's second-order exports (10-node tets, 6-node triangles) read as the same mesh,
// with the same surface groups, as its first-order exports of the same geometry: the
// corners are the same, the mid-edge nodes (on the sphere: moved onto it) are dropped,
// and a note says so. In every format Gmsh writes that TetLOD reads.
TEST(IoGmshInterop, WeReadGmshSecondOrderExports) {
  TETLOD_NEED_PROGRAM("gmsh");
  const std::string dir = test::output_dir("gmsh_p2");
  test::write_text(dir + "/ball.geo",
                   "SetFactory(\"OpenCASCADE\");\nBox(1) = {0, 0, 0, 1, 1, 1};\n"
                   "Sphere(2) = {0.5, 0.5, 0.5, 0.3};\n"
                   "BooleanFragments{ Volume{1}; Delete; }{ Volume{2}; Delete; }\n"
                   "Physical Volume(1) = {2};\nPhysical Volume(2) = {3};\n"
                   "Physical Surface(5) = Boundary{ Volume{2}; };\nMesh.MeshSizeMax = 0.3;\n");
  const std::string log = dir + "/gmsh.log";
  const struct {
    const char* format;  // Gmsh's -format
    const char* extension;
    const char* note;  // TetLOD's note on the second-order file (and not on the other)
  } exports[] = {
      {"mesh", "mesh", " TetrahedraP2 (10-node) were read as 4-node tetrahedra"},
      {"msh41", "msh", " higher-order tetrahedra (10 nodes or more) were read"},
      {"vtk", "vtk", " quadratic (10-node) tetrahedra were read as 4-node ones"},
      {"bdf", "bdf", " 10-node CTETRAs were read as 4-node ones"},
      {"inp", "inp", " 10-node tetrahedra (C3D10 and variants) were read"},
  };
  for (const auto& e : exports) {
    SCOPED_TRACE(e.format);
    TetMesh mesh[2];
    ReadInfo info[2];
    for (int order : {1, 2}) {
      const std::string out =
          dir + "/ball" + std::to_string(order) + "." + e.format + "." + e.extension;
      ASSERT_TRUE(run_gmsh("'" + dir + "/ball.geo' -3 -order " + std::to_string(order) +
                               " -format " + e.format + " -o '" + out + "'",
                           log))
          << test::read_text(log);
      const Status status = read_mesh(out, &mesh[order - 1], &info[order - 1]);
      ASSERT_TRUE(status.ok()) << status.message();
    }
    const TetMesh &linear = mesh[0], &quadratic = mesh[1];
    EXPECT_EQ(test::canonical_tets(quadratic), test::canonical_tets(linear));
    EXPECT_EQ(quadratic.vertex_count(), linear.vertex_count());
    EXPECT_EQ(info[0].validation.removed_unused_vertices, 0u);
    EXPECT_GT(info[1].validation.removed_unused_vertices, linear.vertex_count());
    const std::string note = std::to_string(quadratic.tet_count()) + e.note;
    auto has_note = [&](const ReadInfo& i) {
      return std::any_of(i.notes.begin(), i.notes.end(),
                         [&](const std::string& n) { return n.rfind(note, 0) == 0; });
    };
    EXPECT_TRUE(has_note(info[1])) << "no note starting '" << note << "'";
    EXPECT_FALSE(has_note(info[0]));
    ASSERT_FALSE(info[0].surface_groups.empty());
    test::expect_same_groups(info[0].surface_groups, info[1].surface_groups);
  }
}

// Tets of every order Gmsh makes, complete or not (16-node incomplete third order,
// type 137; 22-node incomplete fourth order, type 32; 84-node sixth order, type 71),
// are read by their corners: the first-order mesh. They were skipped, and the file
// said to have no tets. Quadrangles of a surface group are said to be lost, by group
// (they were counted as "in no group").
TEST(IoGmshInterop, WeReadGmshTetsOfEveryOrder) {
  TETLOD_NEED_PROGRAM("gmsh");
  const std::string dir = test::output_dir("gmsh_orders");
  test::write_text(dir + "/box.geo",
                   "SetFactory(\"OpenCASCADE\");\nBox(1) = {0, 0, 0, 1, 1, 1};\n"
                   "Physical Volume(\"solid\", 1) = {1};\n"
                   "Physical Surface(\"top quads\", 20) = {6};\nRecombine Surface{6};\n"
                   "Mesh.MeshSizeMax = 0.4;\n");
  const std::string log = dir + "/gmsh.log";
  auto mesh_of = [&](const std::string& options, const std::string& name, TetMesh* mesh,
                     ReadInfo* info) {
    const std::string out = dir + "/" + name + ".msh";
    ASSERT_TRUE(
        run_gmsh("'" + dir + "/box.geo' -3 " + options + " -format msh41 -o '" + out + "'", log))
        << test::read_text(log);
    const Status status = read_mesh(out, mesh, info);
    ASSERT_TRUE(status.ok()) << name << ": " << status.message();
  };
  TetMesh linear;
  ReadInfo linear_info;
  mesh_of("-order 1", "order1", &linear, &linear_info);
  if (HasFatalFailure()) return;
  ASSERT_GT(linear.tet_count(), 0u);
  bool quads_noted = false;
  for (const std::string& note : linear_info.notes)
    quads_noted = quads_noted || note.find(
                                     "quadrangles of the surface group 'top quads' are "
                                     "not kept") != std::string::npos;
  EXPECT_TRUE(quads_noted) << ::testing::PrintToString(linear_info.notes);
  const struct {
    const char* options;
    const char* name;
  } orders[] = {{"-order 3 -setnumber Mesh.SecondOrderIncomplete 1", "tet16"},
                {"-order 4 -setnumber Mesh.SecondOrderIncomplete 1", "tet22"},
                {"-order 6", "tet84"},
                // Binary: its third-order pyramids (type 118) need their node count, or
                // the file cannot be read (it was refused whole). (Its positions are the
                // exact doubles, the text files' their printed digits: the same tets by
                // count.)
                {"-order 3 -bin", "binary3"}};
  for (const auto& o : orders) {
    SCOPED_TRACE(o.name);
    TetMesh mesh;
    ReadInfo info;
    mesh_of(o.options, o.name, &mesh, &info);
    if (HasFatalFailure()) return;
    if (std::string(o.name) == "binary3")
      EXPECT_EQ(mesh.tet_count(), linear.tet_count());
    else
      EXPECT_EQ(test::canonical_tets(mesh), test::canonical_tets(linear));
    const std::string note = std::to_string(linear.tet_count()) + " higher-order tetrahedra";
    EXPECT_TRUE(std::any_of(info.notes.begin(), info.notes.end(), [&](const std::string& n) {
      return n.rfind(note, 0) == 0;
    })) << ::testing::PrintToString(info.notes);
    // The pyramids under the recombined face are named as such, at every order.
    EXPECT_TRUE(std::any_of(info.notes.begin(), info.notes.end(), [](const std::string& n) {
      return n.rfind("skipped ", 0) == 0 && n.find(" pyramids: ") != std::string::npos;
    })) << ::testing::PrintToString(info.notes);
  }
}

TEST(IoGmshInterop, GmshFindsNoInvertedTets) {
  TETLOD_NEED_PROGRAM("gmsh");
  const std::string dir = test::output_dir("gmsh_orientation");
  const TetMesh mesh = test::make_io_mesh();
  ASSERT_TRUE(write_mesh(dir + "/m.msh", mesh).ok());
  // Gmsh's mesh quality plugin warns about every inverted element.
  test::write_text(dir + "/check.geo", "Merge \"" + dir +
                                           "/m.msh\";\n"
                                           "Plugin(AnalyseMeshQuality).JacobianDeterminant = 1;\n"
                                           "Plugin(AnalyseMeshQuality).CreateView = 0;\n"
                                           "Plugin(AnalyseMeshQuality).Run;\n");
  const std::string log = dir + "/check.log";
  ASSERT_TRUE(run_gmsh("'" + dir + "/check.geo' -0 -o '" + dir + "/unused.msh'", log))
      << test::read_text(log);
  const std::string output = test::read_text(log);
  EXPECT_NE(output.find("Jacobian"), std::string::npos) << output;
  EXPECT_EQ(output.find("inverted"), std::string::npos) << output;
}

}  // namespace
}  // namespace tetlod
