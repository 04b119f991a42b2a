// Surface groups (core/surface.h) and the writers that carry them (WriteOptions::
// surface_groups): the grouping and numbering, each format's text, and the tools
// that read them: Gmsh (physical surfaces) and CalculiX (node sets and element-face
// surfaces under a pressure load), when they are on PATH.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <map>
#include <set>
#include <sstream>

#include "core/adjacency.h"
#include "core/improve.h"
#include "core/io/mesh_io.h"
#include "core/lod.h"
#include "core/metrics.h"
#include "core/simplify.h"
#include "core/surface.h"
#include "core/test_io_helpers.h"
#include "core/test_meshes.h"

namespace tetlod {
namespace {

SurfaceGroups groups_of(const TetMesh& mesh) {
  SurfaceGroups groups;
  const Status s = group_surface(mesh, &groups);
  EXPECT_TRUE(s.ok()) << s.message();
  return groups;
}

TetMesh box2() {
  TetMesh mesh;
  const Status s = read_mesh(std::string(TETLOD_SOURCE_DIR) + "/assets/box2.mesh", &mesh);
  EXPECT_TRUE(s.ok()) << s.message();
  return mesh;
}

// Group g of `plain` (group_surface(mesh)) as an input file's group of that tag, its
// triangles facing the other way.
InputSurfaceGroup reversed_input_group(const TetMesh& mesh, const SurfaceGroups& plain,
                                       const SurfaceGroup& g, int32_t tag) {
  InputSurfaceGroup in;
  in.tag = tag;
  for (uint32_t i : g.triangles) {
    const auto& v = plain.surface[i].v;
    in.triangles.push_back({mesh.positions[v[2]], mesh.positions[v[1]], mesh.positions[v[0]]});
  }
  return in;
}

// A triangle by its corner positions, rotated to start at the smallest, so that it
// compares equal across renumberings but keeps its orientation.
using PositionTriangle = std::array<std::array<double, 3>, 3>;
PositionTriangle by_positions(const std::array<Vec3, 3>& corners) {
  PositionTriangle t;
  for (int k = 0; k < 3; ++k) t[k] = {corners[k].x, corners[k].y, corners[k].z};
  std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
  return t;
}
PositionTriangle by_positions(const std::vector<Vec3>& positions, std::array<uint32_t, 3> v) {
  return by_positions({positions[v[0]], positions[v[1]], positions[v[2]]});
}

// group tag -> its triangles by positions, sorted.
std::map<int32_t, std::vector<PositionTriangle>> triangles_by_tag(const TetMesh& mesh,
                                                                  const SurfaceGroups& groups) {
  std::map<int32_t, std::vector<PositionTriangle>> result;
  for (const SurfaceGroup& group : groups.groups) {
    auto& list = result[group.tag];
    for (uint32_t i : group.triangles)
      list.push_back(by_positions(mesh.positions, groups.surface[i].v));
    std::sort(list.begin(), list.end());
  }
  return result;
}

TEST(SurfaceGroups, Box2HasTwoBoundariesAndOneInterface) {
  const TetMesh mesh = box2();
  const SurfaceGroups groups = groups_of(mesh);
  ASSERT_EQ(groups.groups.size(), 3u);
  const char* names[] = {"boundary_1", "boundary_2", "interface_1_2"};
  size_t total = 0;
  for (size_t g = 0; g < 3; ++g) {
    const SurfaceGroup& group = groups.groups[g];
    EXPECT_EQ(group.name, names[g]);
    EXPECT_EQ(group.tag, int32_t(3 + g));  // above materials 1 and 2
    EXPECT_EQ(group.material, g == 1 ? 2 : 1);
    EXPECT_EQ(group.other, g == 2 ? 2 : kOutsideMaterial);
    EXPECT_TRUE(std::is_sorted(group.triangles.begin(), group.triangles.end()));
    for (uint32_t i : group.triangles) {
      EXPECT_EQ(groups.surface[i].inner, group.material);
      EXPECT_EQ(groups.surface[i].outer, group.other);
    }
    total += group.triangles.size();
  }
  EXPECT_EQ(total, groups.surface.size());
  // box2 is [0,2]x[0,1]x[0,1], split at x = 1: each boundary is five unit squares'
  // worth of area, the interface one, all of it facing +x from material 1.
  for (size_t g = 0; g < 3; ++g) {
    double area = 0;
    Vec3 vector_area{};
    for (uint32_t i : groups.groups[g].triangles) {
      const auto& v = groups.surface[i].v;
      const Vec3 n = cross(mesh.positions[v[1]] - mesh.positions[v[0]],
                           mesh.positions[v[2]] - mesh.positions[v[0]]) *
                     0.5;
      area += std::sqrt(dot(n, n));
      vector_area = vector_area + n;
    }
    EXPECT_NEAR(area, g == 2 ? 1.0 : 5.0, 1e-12) << g;
    // Normals point out of the group's material: the interface +x, and each
    // boundary closes its material with it.
    EXPECT_NEAR(vector_area.x, g == 0 ? -1.0 : 1.0, 1e-12) << g;
    EXPECT_NEAR(vector_area.y, 0.0, 1e-12) << g;
    EXPECT_NEAR(vector_area.z, 0.0, 1e-12) << g;
  }
}

TEST(SurfaceGroups, TagsStartAboveEveryMaterialTag) {
  auto first_tag = [](std::vector<int32_t> materials) {
    TetMesh mesh = test::make_grid_mesh(
        int(materials.size()), 1, 1, [&](int i, int, int) { return materials[size_t(i)]; }, 1.0);
    return first_surface_tag(mesh);
  };
  EXPECT_EQ(first_tag({5}), 6);
  EXPECT_EQ(first_tag({0}), 2);        // material 0 is Gmsh tag 1
  EXPECT_EQ(first_tag({0, 2}), 3);     // 0 is tag 1
  EXPECT_EQ(first_tag({0, 1, 2}), 4);  // 0 is tag 3
  EXPECT_EQ(first_tag({2, 7, 3}), 8);
  // Pairs in order: boundaries by material, then interfaces by pair.
  TetMesh mesh = test::make_grid_mesh(
      3, 1, 1, [](int i, int, int) { return i == 0   ? 7
                                            : i == 1 ? 0
                                                     : 3; }, 1.0);
  const SurfaceGroups groups = groups_of(mesh);
  std::vector<std::string> names;
  for (const SurfaceGroup& g : groups.groups) names.push_back(g.name + "=" + std::to_string(g.tag));
  EXPECT_EQ(names, (std::vector<std::string>{"boundary_0=8", "boundary_3=9", "boundary_7=10",
                                             "interface_0_3=11", "interface_0_7=12"}));
  // Tags end at 2^31 - 1: one group fits above 2^31 - 2, two groups do not.
  const int32_t top = std::numeric_limits<int32_t>::max();
  mesh = test::make_grid_mesh(
      2, 1, 1, [&](int, int, int) { return top - 1; }, 1.0);
  std::vector<std::string> one;
  for (const SurfaceGroup& g : groups_of(mesh).groups)
    one.push_back(g.name + "=" + std::to_string(g.tag));
  EXPECT_EQ(one, (std::vector<std::string>{"boundary_2147483646=2147483647"}));
  mesh.materials[0] = top;
  SurfaceGroups untouched;
  untouched.groups.resize(1);
  const Status s = group_surface(mesh, &untouched);
  EXPECT_NE(s.message().find("material ids up to 2147483647 leave no room"), std::string::npos)
      << s.message();
  EXPECT_EQ(untouched.groups.size(), 1u);
  WriteOptions options;
  options.surface_groups = true;
  const std::string path = test::output_dir("surface_groups_overflow") + "/x.msh";
  const Status w = write_mesh(path, mesh, options);
  EXPECT_NE(w.message().find(path + ": material ids up to"), std::string::npos) << w.message();
  EXPECT_FALSE(std::filesystem::exists(path));
}

// Reads a written file back: the same tets, and the groups' triangles read as the
// groups, not kept as elements (the CLI says so).
ReadInfo read_back(const std::string& path, const TetMesh& mesh, const SurfaceGroups& groups) {
  TetMesh back;
  ReadInfo info;
  EXPECT_TRUE(read_mesh(path, &back, &info).ok()) << path;
  test::expect_same_mesh(mesh, back);
  EXPECT_EQ(info.surface_elements_not_kept, groups.surface.size()) << path;
  return info;
}

TEST(SurfaceGroups, EachWriterCarriesThem) {
  const TetMesh mesh = box2();
  const SurfaceGroups groups = groups_of(mesh);
  const std::string dir = test::output_dir("surface_groups");
  WriteOptions options;
  options.surface_groups = true;

  // Medit: a Triangles section, reference = tag, and the tets read back unchanged.
  ASSERT_TRUE(write_mesh(dir + "/box2.mesh", mesh, options).ok());
  {
    const std::string text = test::read_text(dir + "/box2.mesh");
    std::istringstream in(text.substr(text.find("\nTriangles\n") + 11));
    size_t count = 0;
    in >> count;
    ASSERT_EQ(count, groups.surface.size());
    std::map<int32_t, std::vector<PositionTriangle>> read;
    for (size_t i = 0; i < count; ++i) {
      std::array<uint32_t, 3> v;
      int32_t ref;
      in >> v[0] >> v[1] >> v[2] >> ref;
      for (uint32_t& x : v) --x;
      read[ref].push_back(by_positions(mesh.positions, v));
    }
    for (auto& [tag, list] : read) std::sort(list.begin(), list.end());
    EXPECT_EQ(read, triangles_by_tag(mesh, groups));
    const ReadInfo info = read_back(dir + "/box2.mesh", mesh, groups);
    EXPECT_EQ(info.surface_groups.size(), 3u);
  }

  // TetGen: a .face file beside .node/.ele, boundary marker = tag.
  ASSERT_TRUE(write_mesh(dir + "/box2.node", mesh, options).ok());
  {
    std::istringstream in(test::read_text(dir + "/box2.face"));
    size_t count = 0, markers = 0;
    in >> count >> markers;
    ASSERT_EQ(count, groups.surface.size());
    EXPECT_EQ(markers, 1u);
    std::map<int32_t, std::vector<PositionTriangle>> read;
    for (size_t i = 0; i < count; ++i) {
      size_t index;
      std::array<uint32_t, 3> v;
      int32_t marker;
      in >> index >> v[0] >> v[1] >> v[2] >> marker;
      EXPECT_EQ(index, i + 1);
      for (uint32_t& x : v) --x;
      read[marker].push_back(by_positions(mesh.positions, v));
    }
    for (auto& [tag, list] : read) std::sort(list.begin(), list.end());
    EXPECT_EQ(read, triangles_by_tag(mesh, groups));
    const ReadInfo info = read_back(dir + "/box2.node", mesh, groups);
    EXPECT_EQ(info.surface_groups.size(), 3u);
  }

  // Gmsh, both versions: physical surfaces named after the groups; our reader keeps
  // the tets and says the surface groups were not kept.
  for (int version : {22, 41}) {
    SCOPED_TRACE(version);
    options.gmsh_version = version;
    const std::string path = dir + "/box2_" + std::to_string(version) + ".msh";
    ASSERT_TRUE(write_mesh(path, mesh, options).ok());
    const std::string text = test::read_text(path);
    EXPECT_NE(text.find("2 3 \"boundary_1\"\n2 4 \"boundary_2\"\n2 5 \"interface_1_2\"\n"),
              std::string::npos);
    const ReadInfo info = read_back(path, mesh, groups);
    ASSERT_EQ(info.surface_groups.size(), 3u);
    EXPECT_EQ(info.surface_groups[0].name, "boundary_1");
  }

  // VTK legacy and XML: triangle cells after the tets, the tag in the material array,
  // the stretch of the tet behind (so that ParaView colours the triangle as that tet's
  // face, and its range is the tets'); Nastran: a CTRIA3 per triangle after the
  // CTETRAs, the tag as its PID. Read back as the groups, by tag, named in .vtk and
  // .vtu (their field data), unnamed in Nastran (as .mesh).
  std::vector<double> stretch_expected;
  for (const Tet& tet : mesh.tets) stretch_expected.push_back(tet_shape(mesh, tet).stretch);
  for (const SurfaceGroup& group : groups.groups)
    for (uint32_t i : group.triangles)
      stretch_expected.push_back(stretch_expected[groups.surface[i].tet]);
  for (const char* name : {"/box2.vtk", "/box2.vtu", "/box2.bdf"}) {
    SCOPED_TRACE(name);
    const std::string path = dir + name;
    ASSERT_TRUE(write_mesh(path, mesh, options).ok());
    const std::string text = test::read_text(path);
    const std::string kind = std::string(name).substr(6);
    const size_t cells = mesh.tet_count() + groups.surface.size();
    if (kind == "vtu" || kind == "vtk") {
      const std::string cells_text = kind == "vtu"
                                         ? "NumberOfCells=\"" + std::to_string(cells) + "\""
                                         : "CELL_TYPES " + std::to_string(cells) + "\n";
      EXPECT_NE(text.find(cells_text), std::string::npos);
      const std::string header = kind == "vtu" ? "Name=\"stretch\" format=\"ascii\">"
                                               : "stretch 1 " + std::to_string(cells) + " double";
      const size_t at = text.find(header);
      ASSERT_NE(at, std::string::npos);
      std::istringstream in(text.substr(at + header.size()));
      for (size_t c = 0; c < cells; ++c) {
        double value = -2;
        in >> value;
        ASSERT_NEAR(value, stretch_expected[c], 1e-12) << "cell " << c;
      }
    } else {
      EXPECT_NE(text.find(std::to_string(groups.surface.size()) + " CTRIA3;"), std::string::npos);
      EXPECT_NE(text.find("\nCTRIA3  " + std::to_string(mesh.tet_count() + 1) + " "),
                std::string::npos);
    }
    const ReadInfo info = read_back(path, mesh, groups);
    ASSERT_EQ(info.surface_groups.size(), 3u);
    std::map<int32_t, std::vector<PositionTriangle>> read;
    for (const auto& group : info.surface_groups) {
      for (const auto& t : group.triangles) read[group.tag].push_back(by_positions(t));
      std::sort(read[group.tag].begin(), read[group.tag].end());
    }
    EXPECT_EQ(read, triangles_by_tag(mesh, groups));
    for (const auto& group : info.surface_groups) {
      // .vtk and .vtu name them in their field data, Nastran in comments.
      std::string written;
      for (const SurfaceGroup& g : groups.groups)
        if (g.tag == group.tag) written = g.name;
      EXPECT_EQ(group.name, written) << group.tag;
    }
  }
}

std::vector<std::string> names_and_tags(const SurfaceGroups& groups) {
  std::vector<std::string> written;
  for (const SurfaceGroup& g : groups.groups)
    written.push_back(g.name + "=" + std::to_string(g.tag) + ":" +
                      std::to_string(g.triangles.size()));
  return written;
}

// A Gmsh file's own physical surfaces (tests/data/gmsh/groups.geo, in each of the
// reader's paths) keep their names, tags and triangles: a whole boundary, an
// interface, and one face of a boundary, whose other faces stay in the pair's group,
// numbered around the tags taken.
// Every surface element of a Medit file is counted as not kept (the CLI's note):
// triangles with a reference (a group), without one (none), and quadrilaterals.
TEST(SurfaceGroups, MeditSurfaceElementsAreCounted) {
  const std::string text =
      "MeshVersionFormatted 2\nDimension 3\nVertices 5\n"
      "0 0 0 0\n1 0 0 0\n0 1 0 0\n0 0 1 0\n1 1 1 0\n"
      "Tetrahedra 2\n1 2 3 4 1\n2 3 4 5 2\n"
      "Triangles 2\n1 2 3 7\n1 2 4 0\nQuadrilaterals 1\n1 2 3 4 0\nEnd\n";
  TetMesh mesh;
  ReadInfo info;
  ASSERT_TRUE(read_mesh_from_memory(text, MeshFormat::kMedit, "m.mesh", &mesh, &info).ok());
  EXPECT_EQ(info.surface_elements_not_kept, 3u);
  ASSERT_EQ(info.surface_groups.size(), 1u);
  EXPECT_EQ(info.surface_groups[0].tag, 7);
}

TEST(SurfaceGroups, InputGroupsKeepTheirNamesTagsAndTriangles) {
  for (const char* file : {"groups41.msh", "groups41_bin.msh", "groups22.msh", "groups22_bin.msh",
                           "groups_order2.msh"}) {
    SCOPED_TRACE(file);
    TetMesh mesh;
    ReadInfo info;
    const Status s = read_mesh(test::data_path(std::string("gmsh/") + file), &mesh, &info);
    ASSERT_TRUE(s.ok()) << s.message();
    ASSERT_EQ(info.surface_groups.size(), 3u);
    EXPECT_EQ(info.surface_groups[0].tag, 100);
    EXPECT_EQ(info.surface_groups[0].name, "outer_left");
    EXPECT_EQ(info.surface_groups[1].name, "membrane");
    EXPECT_EQ(info.surface_groups[2].name, "right_end");
    const SurfacePatches patches(mesh, info.surface_groups);
    ASSERT_TRUE(patches.any());
    for (size_t g = 0; g < 3; ++g) {
      EXPECT_EQ(patches.groups()[g].missing, 0u);
      EXPECT_EQ(patches.groups()[g].triangles, info.surface_groups[g].triangles.size());
    }
    SurfaceGroups groups;
    ASSERT_TRUE(group_surface(mesh, &groups, patches).ok());
    const SurfaceGroups plain = groups_of(mesh);  // 3 boundary_1, 4 boundary_2, 5 interface
    const size_t right_end = info.surface_groups[2].triangles.size();
    EXPECT_EQ(names_and_tags(groups),
              (std::vector<std::string>{
                  "outer_left=100:" + std::to_string(plain.groups[0].triangles.size()),
                  "boundary_2=3:" + std::to_string(plain.groups[1].triangles.size() - right_end),
                  "right_end=300:" + std::to_string(right_end),
                  "membrane=200:" + std::to_string(plain.groups[2].triangles.size())}));
    // Each input triangle is in its group.
    for (size_t g : {0, 2}) {
      const std::string& name = info.surface_groups[g].name;
      const auto it = std::find_if(groups.groups.begin(), groups.groups.end(),
                                   [&](const SurfaceGroup& x) { return x.name == name; });
      ASSERT_NE(it, groups.groups.end());
      std::vector<std::array<double, 9>> want, got;
      auto key = [](const Vec3& a, const Vec3& b, const Vec3& c) {
        std::array<std::array<double, 3>, 3> k = {
            {{a.x, a.y, a.z}, {b.x, b.y, b.z}, {c.x, c.y, c.z}}};
        std::sort(k.begin(), k.end());
        return std::array<double, 9>{k[0][0], k[0][1], k[0][2], k[1][0], k[1][1],
                                     k[1][2], k[2][0], k[2][1], k[2][2]};
      };
      for (const auto& t : info.surface_groups[g].triangles) want.push_back(key(t[0], t[1], t[2]));
      for (uint32_t i : it->triangles) {
        const auto& v = groups.surface[i].v;
        got.push_back(key(mesh.positions[v[0]], mesh.positions[v[1]], mesh.positions[v[2]]));
      }
      std::sort(want.begin(), want.end());
      std::sort(got.begin(), got.end());
      EXPECT_EQ(got, want) << name;
    }
  }
  // Unnamed groups are surface_<tag>; a triangle in two groups is the smaller one's
  // (so that both are written); a triangle that is not on the surface is counted as
  // missing.
  TetMesh mesh = box2();
  const SurfaceGroups plain = groups_of(mesh);
  auto input_of = [&](const SurfaceGroup& g, int32_t tag) {
    return reversed_input_group(mesh, plain, g, tag);
  };
  std::vector<InputSurfaceGroup> input = {
      input_of(plain.groups[0], 4), input_of(plain.groups[1], 50), input_of(plain.groups[2], 60)};
  input[1].triangles.pop_back();
  input[2].triangles.push_back(input[0].triangles[0]);
  input[2].triangles.push_back({Vec3{0, 0, 0}, Vec3{9, 9, 9}, Vec3{1, 2, 3}});
  const SurfacePatches patches(mesh, input);
  EXPECT_EQ(patches.groups()[2].missing, 1u);
  EXPECT_EQ(patches.groups()[2].triangles, plain.groups[2].triangles.size() + 1);
  EXPECT_EQ(patches.groups()[0].shared, 1u);  // its triangle went to the smaller group 60
  SurfaceGroups groups;
  ASSERT_TRUE(group_surface(mesh, &groups, patches).ok());
  const size_t n2 = plain.groups[1].triangles.size();
  EXPECT_EQ(names_and_tags(groups),
            (std::vector<std::string>{
                "surface_4=4:" + std::to_string(plain.groups[0].triangles.size() - 1),
                "surface_60=60:" + std::to_string(plain.groups[2].triangles.size() + 1),
                "boundary_2=3:1", "surface_50=50:" + std::to_string(n2 - 1)}));
  // A user's name becomes a valid Abaqus label and stays inside Gmsh's quotes.
  std::vector<InputSurfaceGroup> odd = {input_of(plain.groups[0], 7)};
  odd[0].name = "1st \"outer\" wall";
  ASSERT_TRUE(group_surface(mesh, &groups, SurfacePatches(mesh, odd)).ok());
  WriteOptions options;
  options.surface_groups = true;
  options.groups = &groups;
  const std::string dir = test::output_dir("surface_groups_names");
  ASSERT_TRUE(write_mesh(dir + "/odd.inp", mesh, options).ok());
  EXPECT_NE(test::read_text(dir + "/odd.inp").find("*NSET, NSET=S_1st__outer__wall\n"),
            std::string::npos);
  ASSERT_TRUE(write_mesh(dir + "/odd.msh", mesh, options).ok());
  EXPECT_NE(test::read_text(dir + "/odd.msh").find("2 7 \"1st _outer_ wall\"\n"),
            std::string::npos);
  TetMesh back;
  ReadInfo info;
  ASSERT_TRUE(read_mesh(dir + "/odd.msh", &back, &info).ok());
  ASSERT_EQ(info.surface_groups.size(), 3u);  // by tag: 3, 5, 7
  EXPECT_EQ(info.surface_groups[2].tag, 7);
  EXPECT_EQ(info.surface_groups[2].name, "1st _outer_ wall");
}

// An input group's interface triangles face as the input's did (Gmsh's facing out of
// the larger material, here: a flux through it keeps its sign), in the input's mesh
// and in a simplified one, seen from the tet on their back (an Abaqus face is a tet's);
// a boundary group faces out of the mesh whatever its input's facing.
TEST(SurfaceGroups, InputGroupsKeepTheirFacingOnInterfaces) {
  const TetMesh mesh = box2();
  const SurfaceGroups plain = groups_of(mesh);  // boundary_1, boundary_2, interface_1_2
  ASSERT_EQ(plain.groups[2].name, "interface_1_2");
  const std::vector<InputSurfaceGroup> input = {
      reversed_input_group(mesh, plain, plain.groups[0], 40),
      reversed_input_group(mesh, plain, plain.groups[2], 60)};
  const SurfacePatches patches(mesh, input);
  // Each triangle of a group faces away from its tet's opposite corner, from `inner`.
  auto check = [](const TetMesh& m, const SurfaceGroups& groups, int32_t tag, int32_t back) {
    const auto it = std::find_if(groups.groups.begin(), groups.groups.end(),
                                 [&](const SurfaceGroup& g) { return g.tag == tag; });
    ASSERT_NE(it, groups.groups.end());
    EXPECT_EQ(it->material, 1);  // the pair, smaller first, whatever the facing
    ASSERT_FALSE(it->triangles.empty());
    for (uint32_t i : it->triangles) {
      const SurfaceTriangle& t = groups.surface[i];
      ASSERT_EQ(t.inner, back);
      ASSERT_EQ(m.materials[t.tet], back);
      const Tet& tet = m.tets[t.tet];
      for (uint32_t v : t.v) ASSERT_TRUE(tet_has(tet, v));
      ASSERT_FALSE(tet_has({t.v[0], t.v[1], t.v[2], t.v[0]}, tet[t.corner]));
      const Vec3& a = m.positions[t.v[0]];
      const Vec3 normal = cross(m.positions[t.v[1]] - a, m.positions[t.v[2]] - a);
      ASSERT_LT(dot(normal, m.positions[tet[t.corner]] - a), 0);
    }
  };
  SurfaceGroups groups;
  ASSERT_TRUE(group_surface(mesh, &groups, patches).ok());
  check(mesh, groups, 60, 2);  // as the input: out of material 2
  check(mesh, groups, 40, 1);  // a boundary: out of the mesh
  std::vector<PositionTriangle> want, got;
  for (const auto& t : input[1].triangles) want.push_back(by_positions(t));
  got = triangles_by_tag(mesh, groups).at(60);
  std::sort(want.begin(), want.end());
  EXPECT_EQ(got, want);
  // Simplified with the patches: the same facing.
  SimplifyParams params;
  params.sizing.uniform = 10;
  params.tolerance = 0.01;
  SimplifyResult r;
  ASSERT_TRUE(simplify(mesh, params, &r, {}, nullptr, &patches).ok());
  ASSERT_LT(r.output.tet_count(), mesh.tet_count());
  ASSERT_TRUE(group_surface(r.output, &groups, patches).ok());
  check(r.output, groups, 60, 2);
  check(r.output, groups, 40, 1);
}

// A surface group and a material of the same number (Gmsh numbers each dimension's
// physical groups apart) keep their own names through .vtk and .vtu (the field data's
// group_dim says which row is which); a file without group_dim, as TetLOD wrote
// before, still names the materials.
TEST(SurfaceGroups, AGroupAndAMaterialOfTheSameNumberKeepTheirNames) {
  const TetMesh mesh = box2();
  const SurfaceGroups plain = groups_of(mesh);
  std::vector<InputSurfaceGroup> input(2);
  for (size_t g = 0; g < 2; ++g) {
    input[g].tag = int32_t(g + 1);
    input[g].name = g == 0 ? "bottom" : "top";
    for (uint32_t i : plain.groups[g].triangles) {
      const auto& v = plain.surface[i].v;
      input[g].triangles.push_back(
          {mesh.positions[v[2]], mesh.positions[v[1]], mesh.positions[v[0]]});
    }
  }
  SurfaceGroups groups;
  ASSERT_TRUE(group_surface(mesh, &groups, SurfacePatches(mesh, input)).ok());
  const std::vector<MaterialName> names = {{1, "air"}, {2, "copper"}};
  WriteOptions options;
  options.surface_groups = true;
  options.groups = &groups;
  options.material_names = &names;
  const std::string dir = test::output_dir("surface_groups_same_number");
  for (const bool binary : {false, true})
    for (const char* extension : {".vtk", ".vtu"}) {
      SCOPED_TRACE(std::string(extension) + (binary ? " binary" : ""));
      options.vtk_binary = binary;
      const std::string path = dir + "/same" + extension;
      ASSERT_TRUE(write_mesh(path, mesh, options).ok());
      TetMesh back;
      ReadInfo info;
      ASSERT_TRUE(read_mesh(path, &back, &info).ok());
      ASSERT_EQ(info.material_names.size(), 2u);
      EXPECT_EQ(info.material_names[0].name, "air");
      EXPECT_EQ(info.material_names[1].name, "copper");
      std::map<int32_t, std::string> by_tag;
      for (const InputSurfaceGroup& g : info.surface_groups) by_tag[g.tag] = g.name;
      EXPECT_EQ(by_tag[1], "bottom");
      EXPECT_EQ(by_tag[2], "top");
    }
  // Without group_dim (the ASCII .vtk's lines taken out): the materials' names.
  options.vtk_binary = false;
  ASSERT_TRUE(write_mesh(dir + "/same.vtk", mesh, options).ok());
  std::string text = test::read_text(dir + "/same.vtk");
  const size_t at = text.find("group_dim");
  ASSERT_NE(at, std::string::npos);
  const size_t end = text.find("group_name", at);
  text.erase(at, end - at);
  const size_t field = text.find("FIELD FieldData 3");
  ASSERT_NE(field, std::string::npos);
  text.replace(field, 17, "FIELD FieldData 2");
  test::write_text(dir + "/old.vtk", text);
  TetMesh back;
  ReadInfo info;
  const Status s = read_mesh(dir + "/old.vtk", &back, &info);
  ASSERT_TRUE(s.ok()) << s.message();
  ASSERT_EQ(info.material_names.size(), 2u);
  EXPECT_EQ(info.material_names[0].name, "air");
}

// Face neighbours a caller already has (validation's, kept in ReadInfo) give the same
// patches and groups as those built anew.
TEST(SurfaceGroups, GivenFaceNeighboursGiveTheSameGroups) {
  TetMesh mesh;
  ReadInfo info;
  info.keep_face_neighbors = true;
  ASSERT_TRUE(read_mesh(test::data_path("gmsh/sheet.msh"), &mesh, &info).ok());
  ASSERT_EQ(info.face_neighbors.size(), 4 * mesh.tet_count());
  const SurfacePatches built(mesh, info.surface_groups);
  const SurfacePatches given(mesh, info.surface_groups, &info.face_neighbors);
  ASSERT_EQ(built.groups().size(), given.groups().size());
  for (size_t g = 0; g < built.groups().size(); ++g) {
    EXPECT_EQ(built.groups()[g].triangles, given.groups()[g].triangles);
    EXPECT_EQ(built.groups()[g].inside, given.groups()[g].inside);
  }
  EXPECT_EQ(built.inside_entries().size(), given.inside_entries().size());
  for (bool inside : {false, true}) {
    SurfaceGroups a, b;
    ASSERT_TRUE(group_surface(mesh, &a, built, inside).ok());
    ASSERT_TRUE(group_surface(mesh, &b, given, inside, &info.face_neighbors).ok());
    EXPECT_EQ(names_and_tags(a), names_and_tags(b));
    ASSERT_EQ(a.surface.size(), b.surface.size());
    for (size_t i = 0; i < a.surface.size(); ++i) {
      EXPECT_EQ(a.surface[i].v, b.surface[i].v);
      EXPECT_EQ(a.surface[i].tet, b.surface[i].tet);
    }
    ASSERT_EQ(a.groups.size(), b.groups.size());
    for (size_t g = 0; g < a.groups.size(); ++g)
      EXPECT_EQ(a.groups[g].triangles, b.groups[g].triangles);
  }
}

// Groups inside one material (Gmsh's embedded surfaces, tests/data/gmsh/sheet.msh:
// "sheet" wholly inside material 1, "top_and_sheet" a boundary face and another sheet):
// their triangles are faces between two tets of that material. SurfacePatches counts
// them; group_surface() with `inside` (convert) adds them to their groups, oriented as
// in the input and seen from the tet behind them, and every writer's file reads back
// with the same groups; without it (a simplified mesh's) they are left out. A triangle
// in two groups is the smaller one's; one that is no face is missing.
TEST(SurfaceGroups, GroupsInsideAMaterial) {
  TetMesh mesh;
  ReadInfo info;
  ASSERT_TRUE(read_mesh(test::data_path("gmsh/sheet.msh"), &mesh, &info).ok());
  ASSERT_EQ(info.surface_groups.size(), 3u);
  EXPECT_EQ(info.surface_groups[0].name, "sheet");
  EXPECT_EQ(info.surface_groups[2].name, "top_and_sheet");
  const SurfacePatches patches(mesh, info.surface_groups);
  const auto& counts = patches.groups();
  const size_t sheet = info.surface_groups[0].triangles.size();
  const size_t bottom = info.surface_groups[1].triangles.size();
  const size_t top = counts[2].triangles, top_inside = counts[2].inside;
  EXPECT_EQ(counts[0].triangles, 0u);
  EXPECT_EQ(counts[0].inside, sheet);
  EXPECT_EQ(counts[1].triangles, bottom);
  EXPECT_EQ(counts[1].inside, 0u);
  EXPECT_GT(top, 0u);
  EXPECT_GT(top_inside, 0u);
  EXPECT_EQ(top + top_inside, info.surface_groups[2].triangles.size());
  for (const auto& g : counts) EXPECT_EQ(g.missing + g.shared, 0u);
  EXPECT_EQ(patches.inside_entries().size(), sheet + top_inside);

  SurfaceGroups without, with;
  ASSERT_TRUE(group_surface(mesh, &without, patches).ok());
  ASSERT_TRUE(group_surface(mesh, &with, patches, true).ok());
  const size_t rest = groups_of(mesh).surface.size() - bottom - top;
  EXPECT_EQ(names_and_tags(without),
            (std::vector<std::string>{"boundary_1=2:" + std::to_string(rest),
                                      "bottom=200:" + std::to_string(bottom),
                                      "top_and_sheet=300:" + std::to_string(top)}));
  EXPECT_EQ(names_and_tags(with),
            (std::vector<std::string>{"boundary_1=2:" + std::to_string(rest),
                                      "bottom=200:" + std::to_string(bottom),
                                      "top_and_sheet=300:" + std::to_string(top + top_inside),
                                      "sheet=100:" + std::to_string(sheet)}));
  // Each inside triangle is the face of its tet opposite its corner, between two tets
  // of material 1, and its normal points away from that tet.
  const MeshAdjacency adjacency = build_adjacency(mesh);
  const auto& p = mesh.positions;
  size_t inside = 0;
  for (size_t i = without.surface.size(); i < with.surface.size(); ++i, ++inside) {
    const SurfaceTriangle& t = with.surface[i];
    EXPECT_EQ(t.inner, 1);
    EXPECT_EQ(t.outer, 1);
    const Tet& tet = mesh.tets[t.tet];
    std::array<uint32_t, 3> face = {tet[kTetFace[t.corner][0]], tet[kTetFace[t.corner][1]],
                                    tet[kTetFace[t.corner][2]]};
    std::array<uint32_t, 3> v = t.v;
    std::sort(face.begin(), face.end());
    std::sort(v.begin(), v.end());
    EXPECT_EQ(face, v);
    const uint32_t other = adjacency.tet_neighbors[4 * t.tet + t.corner];
    ASSERT_NE(other, kInvalidIndex);
    EXPECT_EQ(mesh.materials[other], 1);
    const Vec3 normal = cross(p[t.v[1]] - p[t.v[0]], p[t.v[2]] - p[t.v[0]]);
    EXPECT_LT(dot(normal, p[tet[t.corner]] - p[t.v[0]]), 0);
  }
  EXPECT_EQ(inside, sheet + top_inside);
  // The sheet's triangles, with their orientation, are the input's.
  std::vector<PositionTriangle> want;
  for (const auto& t : info.surface_groups[0].triangles) want.push_back(by_positions(t));
  std::sort(want.begin(), want.end());
  EXPECT_EQ(triangles_by_tag(mesh, with)[100], want);

  // Every writer of groups: read back, the same groups (by name where the format has
  // names, else by tag), those inside a material again inside.
  const std::string dir = test::output_dir("surface_groups_inside");
  WriteOptions options;
  options.surface_groups = true;
  options.groups = &with;
  for (const char* name : {"sheet.msh", "sheet.mesh", "sheet.inp", "sheet.node"}) {
    SCOPED_TRACE(name);
    const std::string ext = std::filesystem::path(name).extension().string();
    const bool named = ext == ".msh" || ext == ".inp";
    ASSERT_TRUE(write_mesh(dir + "/" + name, mesh, options).ok());
    TetMesh back;
    ReadInfo back_info;
    ASSERT_TRUE(read_mesh(dir + "/" + name, &back, &back_info).ok());
    const SurfacePatches again(back, back_info.surface_groups);
    std::vector<std::string> got, expected;
    for (const SurfacePatches::Group& g : again.groups())
      got.push_back((named ? g.name : std::to_string(g.tag)) + ":" + std::to_string(g.triangles) +
                    "+" + std::to_string(g.inside));
    for (const SurfaceGroup& g : with.groups) {
      size_t in = 0;
      for (uint32_t i : g.triangles) in += i >= without.surface.size();
      expected.push_back((named ? g.name : std::to_string(g.tag)) + ":" +
                         std::to_string(g.triangles.size() - in) + "+" + std::to_string(in));
    }
    std::sort(got.begin(), got.end());
    std::sort(expected.begin(), expected.end());
    EXPECT_EQ(got, expected);
  }

  // A triangle of the sheet in a smaller group too, and one that is not a face.
  std::vector<InputSurfaceGroup> input(2);
  input[0].tag = 7;
  input[0].triangles = {info.surface_groups[0].triangles[0]};
  input[1].tag = 8;
  input[1].triangles = info.surface_groups[0].triangles;
  const auto& first = info.surface_groups[0].triangles[0];
  input[1].triangles.push_back({first[0], first[1], info.surface_groups[1].triangles[0][0]});
  input[1].triangles.push_back({first[0], first[1], first[1]});  // not even a triangle
  const SurfacePatches overlapping(mesh, input);
  EXPECT_EQ(overlapping.groups()[0].inside, 1u);
  EXPECT_EQ(overlapping.groups()[1].inside, sheet - 1);
  EXPECT_EQ(overlapping.groups()[1].shared, 1u);
  EXPECT_EQ(overlapping.groups()[1].missing, 2u);
  ASSERT_TRUE(group_surface(mesh, &with, overlapping, true).ok());
  EXPECT_EQ(
      names_and_tags(with),
      (std::vector<std::string>{"boundary_1=2:" + std::to_string(without.surface.size()),
                                "surface_7=7:1", "surface_8=8:" + std::to_string(sheet - 1)}));
}

// simplify() with the patches keeps the groups' faces inside a material as they are:
// every level of the run has them all (so Save, lod and --surfaces write the groups
// whole), subdivision leaves their long edges unsplit and says so, improve_mesh()
// keeps them, and a history keeps them. Without the patches the same run coarsens them
// away, and improve_mesh() changes them.
TEST(SurfaceGroups, SimplificationKeepsGroupsInsideAMaterial) {
  TetMesh mesh;
  ReadInfo info;
  ASSERT_TRUE(read_mesh(test::data_path("gmsh/sheet.msh"), &mesh, &info).ok());
  const SurfacePatches patches(mesh, info.surface_groups);
  const size_t inside = patches.inside_entries().size();
  ASSERT_EQ(inside, 76u);  // 38 in 'sheet', 38 in 'top_and_sheet'
  ASSERT_EQ(inside_faces(mesh, patches).size(), inside);
  SimplifyParams params;
  params.sizing.uniform = 0.5;
  params.tolerance = 0.01;
  SimplifyResult result;
  ASSERT_TRUE(simplify(mesh, params, &result, {}, nullptr, &patches).ok());
  EXPECT_LT(result.output.tet_count(), mesh.tet_count() * 3 / 5);
  EXPECT_EQ(result.splits_skipped_inside, 0u);  // the sheets' edges are below 0.25
  SurfaceGroups input_groups;
  ASSERT_TRUE(group_surface(mesh, &input_groups, patches, true).ok());
  const auto sheet = triangles_by_tag(mesh, input_groups)[100];
  ASSERT_EQ(sheet.size(), 38u);
  Lod lod(result.base, &result.history);
  const size_t steps = lod.step_count();
  ASSERT_GT(steps, 100u);
  for (size_t step : {size_t(0), steps / 4, steps / 2, steps - 1, steps}) {
    SCOPED_TRACE(step);
    lod.seek(step);
    const TetMesh level = lod.extract();
    EXPECT_EQ(inside_faces(level, patches).size(), inside);
    SurfaceGroups groups;
    ASSERT_TRUE(group_surface(level, &groups, patches, true).ok());
    EXPECT_EQ(triangles_by_tag(level, groups)[100], sheet);
  }
  EXPECT_EQ(inside_faces(result.output, patches).size(), inside);

  // improve_mesh() with the patches keeps them too; without, it moves and flips them.
  TetMesh improved = result.output;
  const ImproveResult changes = improve_mesh(&improved, params, 4, nullptr, &patches);
  EXPECT_GT(changes.edge_removals + changes.flips_23 + changes.moves, 0u);
  EXPECT_EQ(inside_faces(improved, patches).size(), inside);
  improved = result.output;
  improve_mesh(&improved, params);
  EXPECT_LT(inside_faces(improved, patches).size(), inside);

  // Without the patches the run is free to coarsen the sheets.
  SimplifyResult free_run;
  ASSERT_TRUE(simplify(mesh, params, &free_run).ok());
  EXPECT_LT(inside_faces(free_run.output, patches).size(), inside / 2);

  // A size whose half is below the sheets' edges: those are left unsplit, and said.
  params.sizing.uniform = 0.3;
  ASSERT_TRUE(simplify(mesh, params, &result, {}, nullptr, &patches).ok());
  EXPECT_GT(result.splits_skipped_inside, 0u);
  EXPECT_GT(result.splits, 0u);
  EXPECT_EQ(inside_faces(result.output, patches).size(), inside);
  EXPECT_EQ(result.violations.created, 0u);

  // A history keeps them, with their groups.
  const std::string path = test::output_dir("surface_groups_inside_history") + "/sheet.tlh";
  ASSERT_TRUE(write_history(path, result.base, result.history, nullptr, nullptr, &patches).ok());
  TetMesh base;
  CollapseHistory history;
  SurfacePatches saved;
  ASSERT_TRUE(read_history(path, &base, &history, nullptr, nullptr, &saved).ok());
  ASSERT_EQ(saved.inside_entries().size(), inside);
  for (size_t g = 0; g < patches.groups().size(); ++g)
    EXPECT_EQ(saved.groups()[g].inside, patches.groups()[g].inside);
  for (size_t i = 0; i < inside; ++i) {
    EXPECT_EQ(saved.inside_entries()[i].p, patches.inside_entries()[i].p);
    EXPECT_EQ(saved.inside_entries()[i].group, patches.inside_entries()[i].group);
    EXPECT_EQ(saved.inside_entries()[i].inner, 1);
  }
  EXPECT_EQ(inside_faces(base, saved).size(), inside);
}

// Names that would clash in what is written: two that make one Abaqus label, one too
// long for Abaqus, and a user's group named as a generated one. Each .inp set and
// surface name is distinct and at most 80 characters; the generated group takes its
// tag after its name.
TEST(SurfaceGroups, ClashingNamesStayDistinct) {
  const TetMesh mesh = box2();
  const SurfaceGroups plain = groups_of(mesh);  // boundary_1 (3), boundary_2 (4), interface (5)
  auto part = [&](size_t g, size_t from, size_t to, int32_t tag, const std::string& name) {
    InputSurfaceGroup in;
    in.tag = tag;
    in.name = name;
    for (size_t k = from; k < to; ++k) {
      const auto& v = plain.surface[plain.groups[g].triangles[k]].v;
      in.triangles.push_back({mesh.positions[v[0]], mesh.positions[v[1]], mesh.positions[v[2]]});
    }
    return in;
  };
  const std::string long_name(85, 'x');
  const std::vector<InputSurfaceGroup> input = {
      part(0, 0, 4, 40, "port a"), part(0, 4, 8, 41, "port-a"), part(0, 8, 12, 42, long_name),
      part(1, 0, 4, 43, "boundary_2")};
  SurfaceGroups groups;
  ASSERT_TRUE(group_surface(mesh, &groups, SurfacePatches(mesh, input)).ok());
  std::set<std::string> names;
  for (const SurfaceGroup& g : groups.groups) EXPECT_TRUE(names.insert(g.name).second) << g.name;
  EXPECT_EQ(names.count("boundary_2_4"), 1u);  // the rest of boundary_2, tag 4
  WriteOptions options;
  options.surface_groups = true;
  options.groups = &groups;
  const std::string dir = test::output_dir("surface_groups_clash");
  ASSERT_TRUE(write_mesh(dir + "/clash.inp", mesh, options).ok());
  std::istringstream lines(test::read_text(dir + "/clash.inp"));
  std::set<std::string> sets;
  for (std::string line; std::getline(lines, line);) {
    for (const std::string key : {"NSET=", "NAME="}) {
      const size_t at = line.find(key);
      if (at == std::string::npos || line[0] != '*') continue;
      const std::string set = line.substr(at + key.size());
      EXPECT_LE(set.size(), 80u) << set;
      EXPECT_TRUE(sets.insert(key + set).second) << set;
    }
  }
  EXPECT_EQ(sets.size(), 2 * groups.groups.size());
}

// A Medit file's referenced triangles (as MMG and TetLOD write them) are read as
// groups by reference: written again, a whole pair's keeps its pair's name and every
// group its tag; a reference covering part of a pair is surface_<ref>.
TEST(SurfaceGroups, MeditTriangleReferencesAreGroups) {
  const TetMesh mesh = box2();
  WriteOptions options;
  options.surface_groups = true;
  const std::string dir = test::output_dir("surface_groups_medit");
  ASSERT_TRUE(write_mesh(dir + "/box2.mesh", mesh, options).ok());
  TetMesh back;
  ReadInfo info;
  ASSERT_TRUE(read_mesh(dir + "/box2.mesh", &back, &info).ok());
  ASSERT_EQ(info.surface_groups.size(), 3u);
  SurfaceGroups groups;
  ASSERT_TRUE(group_surface(back, &groups, SurfacePatches(back, info.surface_groups)).ok());
  const SurfaceGroups plain = groups_of(mesh);
  std::vector<std::string> expected;
  for (const SurfaceGroup& g : plain.groups)
    expected.push_back(g.name + "=" + std::to_string(g.tag) + ":" +
                       std::to_string(g.triangles.size()));
  EXPECT_EQ(names_and_tags(groups), expected);
  // Two of boundary_1's triangles under reference 9 instead.
  std::string text = test::read_text(dir + "/box2.mesh");
  for (int n = 0; n < 2; ++n) {
    const size_t at = text.find(" 3\n", text.find("\nTriangles\n"));
    ASSERT_NE(at, std::string::npos);
    text.replace(at, 3, " 9\n");
  }
  ASSERT_TRUE(read_mesh_from_memory(text, MeshFormat::kMedit, "r.mesh", &back, &info).ok());
  ASSERT_TRUE(group_surface(back, &groups, SurfacePatches(back, info.surface_groups)).ok());
  const size_t n1 = plain.groups[0].triangles.size();
  EXPECT_EQ(names_and_tags(groups),
            (std::vector<std::string>{"surface_3=3:" + std::to_string(n1 - 2), "surface_9=9:2",
                                      expected[1], expected[2]}));
  // The interface's triangles facing the other way (out of the other material): still
  // the whole pair's, under its name.
  std::istringstream in(test::read_text(dir + "/box2.mesh"));
  std::ostringstream flipped;
  const std::string interface_ref = " " + std::to_string(plain.groups[2].tag);
  bool triangles = false;
  size_t reversed = 0;
  for (std::string line; std::getline(in, line);) {
    if (line == "Triangles") triangles = true;
    if (line == "End") triangles = false;
    std::istringstream words(line);
    long a = 0, b = 0, c = 0, ref = 0;
    if (triangles && (words >> a >> b >> c >> ref) && " " + std::to_string(ref) == interface_ref) {
      line = std::to_string(a) + " " + std::to_string(c) + " " + std::to_string(b) + interface_ref;
      ++reversed;
    }
    flipped << line << "\n";
  }
  EXPECT_EQ(reversed, plain.groups[2].triangles.size());
  ASSERT_TRUE(
      read_mesh_from_memory(flipped.str(), MeshFormat::kMedit, "f.mesh", &back, &info).ok());
  ASSERT_TRUE(group_surface(back, &groups, SurfacePatches(back, info.surface_groups)).ok());
  EXPECT_EQ(names_and_tags(groups), expected);
}

// Overlapping groups (tests/data/gmsh/overlap.geo: "all outer" and one face of it,
// "x0", each of whose surfaces is in both): the reader gives both groups the face's
// triangles (text and binary 4.1: an entity's every physical tag), and both are
// written, the face in the smaller group.
TEST(SurfaceGroups, OverlappingGroupsAreBothWritten) {
  for (const char* file : {"overlap41.msh", "overlap41_bin.msh"}) {
    SCOPED_TRACE(file);
    TetMesh mesh;
    ReadInfo info;
    ASSERT_TRUE(read_mesh(test::data_path(std::string("gmsh/") + file), &mesh, &info).ok());
    ASSERT_EQ(info.surface_groups.size(), 2u);
    const size_t face = info.surface_groups[1].triangles.size();
    ASSERT_GT(face, 0u);
    const SurfacePatches patches(mesh, info.surface_groups);
    EXPECT_EQ(patches.groups()[0].shared, face);
    EXPECT_EQ(patches.groups()[1].triangles, face);
    SurfaceGroups groups;
    ASSERT_TRUE(group_surface(mesh, &groups, patches).ok());
    const SurfaceGroups plain = groups_of(mesh);  // boundary_1, boundary_2, interface_1_2
    const size_t outer = plain.groups[0].triangles.size() + plain.groups[1].triangles.size();
    EXPECT_EQ(names_and_tags(groups),
              (std::vector<std::string>{
                  "all outer=30:" + std::to_string(outer - face), "x0=31:" + std::to_string(face),
                  "interface_1_2=3:" + std::to_string(plain.groups[2].triangles.size())}));
  }
}

// A round port on a flat face (tests/data/gmsh/port.geo): simplified with the
// file's groups, the port's border stays within the tolerance of where it was, the
// group is found again on the simplified surface with its area, and every triangle
// of it lies inside the circle. Without the groups the simplifier moves the border
// vertices far off it.
TEST(SurfaceGroups, SimplificationKeepsAGroupsBorder) {
  TetMesh mesh;
  ReadInfo info;
  ASSERT_TRUE(read_mesh(test::data_path("gmsh/port.msh"), &mesh, &info).ok());
  ASSERT_EQ(info.surface_groups.size(), 1u);
  const SurfacePatches patches(mesh, info.surface_groups);
  SimplifyParams params;
  params.sizing.uniform = 0.5;
  params.tolerance = 0.01;
  const Vec3 center{1, 0.5, 1};
  const double radius = 0.3;
  // The input's border vertices: on the circle (Gmsh puts them there).
  auto border_of = [&](const TetMesh& m, const SurfaceGroup& g, const SurfaceGroups& all) {
    std::map<std::pair<uint32_t, uint32_t>, int> uses;
    for (uint32_t i : g.triangles) {
      const auto& v = all.surface[i].v;
      for (int e = 0; e < 3; ++e)
        ++uses[{std::min(v[e], v[(e + 1) % 3]), std::max(v[e], v[(e + 1) % 3])}];
    }
    std::vector<Vec3> border;
    for (const auto& [edge, n] : uses)
      if (n == 1)
        border.push_back(m.positions[edge.first]), border.push_back(m.positions[edge.second]);
    return border;
  };
  for (const bool with_patches : {true, false}) {
    SCOPED_TRACE(with_patches);
    SimplifyResult result;
    ASSERT_TRUE(
        simplify(mesh, params, &result, {}, nullptr, with_patches ? &patches : nullptr).ok());
    EXPECT_LT(result.output.tet_count(), mesh.tet_count() / 3);
    SurfaceGroups groups;
    ASSERT_TRUE(group_surface(result.output, &groups, patches).ok());
    const auto port = std::find_if(groups.groups.begin(), groups.groups.end(),
                                   [](const SurfaceGroup& g) { return g.name == "port"; });
    ASSERT_NE(port, groups.groups.end());
    EXPECT_EQ(port->tag, 20);
    double area = 0, off_circle = 0;
    for (uint32_t i : port->triangles) {
      const auto& v = groups.surface[i].v;
      const Vec3 &a = result.output.positions[v[0]], &b = result.output.positions[v[1]],
                 &c = result.output.positions[v[2]];
      area += 0.5 * length(cross(b - a, c - a));
      for (const Vec3* q : {&a, &b, &c}) {
        EXPECT_NEAR(q->z, 1.0, 1e-9);
        if (with_patches) {
          EXPECT_LE(length(*q - center), radius + 1e-9);
        }
      }
    }
    for (const Vec3& q : border_of(result.output, *port, groups))
      off_circle = std::max(off_circle, std::abs(length(q - center) - radius));
    // The input's border is a polygon of ~19 vertices on the circle (its edges' midpoints
    // 0.004 inside); the simplified one stays within the tolerance of it.
    if (with_patches) {
      EXPECT_LT(off_circle, params.tolerance + 0.005);
      EXPECT_NEAR(area, M_PI * radius * radius, 0.05 * M_PI * radius * radius);
    } else {
      EXPECT_GT(off_circle, 0.05);  // the border was collapsed across
    }
  }
}

// Gmsh reads the physical surfaces: it saves them again (as 2.2 text) with the same
// triangles, oriented the same way, under the same tags.
TEST(SurfaceGroups, GmshKeepsOurPhysicalSurfaces) {
  TETLOD_NEED_PROGRAM("gmsh");
  const TetMesh mesh = test::make_grid_mesh(
      3, 2, 2, [](int i, int j, int) { return i == 2 && j == 1 ? 1000000 : (i + j) % 4; }, 0.25);
  const SurfaceGroups groups = groups_of(mesh);
  const std::string dir = test::output_dir("surface_groups_gmsh");
  for (int version : {22, 41}) {
    SCOPED_TRACE(version);
    WriteOptions options;
    options.surface_groups = true;
    options.gmsh_version = version;
    const std::string ours = dir + "/ours" + std::to_string(version) + ".msh";
    const std::string theirs = dir + "/gmsh" + std::to_string(version) + ".msh";
    ASSERT_TRUE(write_mesh(ours, mesh, options).ok());
    const std::string log = theirs + ".log";
    ASSERT_EQ(std::system(
                  ("gmsh '" + ours + "' -0 -format msh22 -o '" + theirs + "' > '" + log + "' 2>&1")
                      .c_str()),
              0)
        << test::read_text(log);
    // Gmsh's 2.2 text: nodes "tag x y z", elements "tag type ntags physical ...".
    std::istringstream in(test::read_text(theirs));
    std::string line;
    std::map<long, std::array<double, 3>> nodes;
    std::map<int32_t, std::vector<PositionTriangle>> read;
    std::map<int32_t, std::string> names;
    enum { kNone, kNames, kNodes, kElements } section = kNone;
    bool counted = false;
    while (std::getline(in, line)) {
      if (line.rfind("$End", 0) == 0) {
        section = kNone;
      } else if (line[0] == '$') {
        section = line == "$PhysicalNames" ? kNames
                  : line == "$Nodes"       ? kNodes
                  : line == "$Elements"    ? kElements
                                           : kNone;
        counted = false;
      } else if (section != kNone && !counted) {
        counted = true;  // the count line
      } else if (section == kNames) {
        std::istringstream f(line);
        int dimension, tag;
        std::string name;
        f >> dimension >> tag >> name;
        if (dimension == 2) names[tag] = name.substr(1, name.size() - 2);
      } else if (section == kNodes) {
        std::istringstream f(line);
        long tag;
        std::array<double, 3> p;
        f >> tag >> p[0] >> p[1] >> p[2];
        nodes[tag] = p;
      } else if (section == kElements) {
        std::istringstream f(line);
        long tag, type, tag_count;
        f >> tag >> type >> tag_count;
        if (type != 2) continue;
        std::vector<long> tags(static_cast<size_t>(tag_count));
        for (long& t : tags) f >> t;
        PositionTriangle t;
        for (auto& corner : t) {
          long node;
          f >> node;
          corner = nodes.at(node);
        }
        std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
        read[int32_t(tags[0])].push_back(t);
      }
    }
    for (auto& [tag, list] : read) std::sort(list.begin(), list.end());
    EXPECT_EQ(read, triangles_by_tag(mesh, groups));
    std::map<int32_t, std::string> expected_names;
    for (const SurfaceGroup& g : groups.groups) expected_names[g.tag] = g.name;
    EXPECT_EQ(names, expected_names);
  }
}

// CalculiX applies a unit pressure on the surface boundary_2_FACES and holds the
// node set BOUNDARY_1: the reaction at BOUNDARY_1 balances the pressure's resultant,
// (1, 0, 0) on box2 (the interface at x = 1 closes material 2's boundary). Wrong
// face labels would load other faces, wrong node sets hold other nodes.
TEST(SurfaceGroups, CalculixLoadsOurSurfacesAndHoldsOurNodeSets) {
  TETLOD_NEED_PROGRAM("ccx");
  const std::string dir = test::output_dir("surface_groups_calculix");
  WriteOptions options;
  options.surface_groups = true;
  ASSERT_TRUE(write_mesh(dir + "/mesh.inp", box2(), options).ok());
  test::write_text(dir + "/job.inp",
                   "*INCLUDE, INPUT=mesh.inp\n"
                   "*MATERIAL, NAME=STEEL\n*ELASTIC\n210000., 0.3\n"
                   "*SOLID SECTION, ELSET=MATERIAL_1, MATERIAL=STEEL\n"
                   "*SOLID SECTION, ELSET=MATERIAL_2, MATERIAL=STEEL\n"
                   "*STEP\n*STATIC\n*BOUNDARY\nBOUNDARY_1, 1, 3\n"
                   "*DLOAD\nBOUNDARY_2_FACES, P, 1.0\n"
                   "*NODE PRINT, NSET=BOUNDARY_1, TOTALS=ONLY\nRF\n*END STEP\n");
  ASSERT_EQ(std::system(("cd '" + dir + "' && ccx job > ccx.log 2>&1").c_str()), 0)
      << test::read_text(dir + "/ccx.log");
  const std::string dat = test::read_text(dir + "/job.dat");
  const size_t at = dat.find("total force (fx,fy,fz) for set BOUNDARY_1");
  ASSERT_NE(at, std::string::npos) << dat << test::read_text(dir + "/ccx.log");
  std::istringstream in(dat.substr(dat.find('\n', at)));
  double f[3] = {0, 0, 0};
  in >> f[0] >> f[1] >> f[2];
  EXPECT_NEAR(f[0], 1.0, 1e-9);
  EXPECT_NEAR(f[1], 0.0, 1e-9);
  EXPECT_NEAR(f[2], 0.0, 1e-9);
}

}  // namespace
}  // namespace tetlod
