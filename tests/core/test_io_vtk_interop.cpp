// VTK 9 itself (Debian's python3-vtk9, the library ParaView is built on) reads the
// .vtk and .vtu files TetLOD writes, in text and in binary (WriteOptions::vtk_binary),
// without a warning: the same points, cells, materials, surface-group triangles,
// arrays and names from all four (tests/core/vtk_read.py prints what VTK read and a
// digest of it), and the solver's fields in both forms of .vtu. And what VTK writes
// of them again, in each of its encodings, reads as what TetLOD wrote.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <numeric>
#include <sstream>

#include "core/io/mesh_io.h"
#include "core/test_io_helpers.h"

namespace tetlod {
namespace {

// Debian's Python, which has the vtk module once python3-vtk9 is installed (a
// python3 earlier on PATH, from pyenv say, may not).
std::string vtk_python() {
  for (const char* python : {"/usr/bin/python3", "python3"}) {
    if (std::system((std::string(python) + " -c 'import vtk' > /dev/null 2>&1").c_str()) == 0)
      return python;
  }
  return "";
}

#define TETLOD_NEED_VTK_PYTHON(python)                                          \
  const std::string python = vtk_python();                                      \
  if (python.empty()) {                                                         \
    const char* ci = std::getenv("CI");                                         \
    if (ci && std::string(ci) == "true") FAIL() << "no python3 with vtk in CI"; \
    GTEST_SKIP() << "no python3 with the vtk module (Debian: python3-vtk9)";    \
  }

// What vtk_read.py printed of each file: its "key=value" words by key.
using Report = std::map<std::string, std::string>;

// Runs vtk_read.py with `args`; its output, and a failure if it failed.
std::string run_vtk_read(const std::string& python, const std::vector<std::string>& args) {
  std::string command = python + " '" + TETLOD_SOURCE_DIR + "/tests/core/vtk_read.py'";
  for (const std::string& a : args) command += " '" + a + "'";
  std::string output;
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  if (!pipe) {
    ADD_FAILURE() << "cannot run " << command;
    return output;
  }
  char buffer[4096];
  for (size_t n; (n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0;) output.append(buffer, n);
  EXPECT_EQ(pclose(pipe), 0) << command << "\n" << output;
  return output;
}

std::map<std::string, Report> read_with_vtk(const std::string& python,
                                            const std::vector<std::string>& paths) {
  const std::string output = run_vtk_read(python, paths);
  std::map<std::string, Report> reports;
  std::istringstream lines(output);
  for (std::string line; std::getline(lines, line);) {
    const size_t first = line.find(" points=");
    if (first == std::string::npos) continue;
    Report& r = reports[line.substr(0, first)];
    std::istringstream words(line.substr(first + 1));
    for (std::string word; words >> word;) {
      const size_t eq = word.find('=');
      if (eq != std::string::npos) r[word.substr(0, eq)] = word.substr(eq + 1);
    }
  }
  EXPECT_EQ(reports.size(), paths.size()) << output;
  return reports;
}

// Names with a space, a comma, UTF-8 letters (written by vtk_read.py with %XX for
// space, comma and '%').
const std::vector<MaterialName> kNames = {{1, "Rotor, laminated"}, {2, "air gap \u00e4"}};

// The four files of `mesh`: .vtk and .vtu, text and binary.
std::vector<std::string> write_four(const std::string& dir, const std::string& name,
                                    const TetMesh& mesh, bool groups) {
  std::vector<std::string> paths;
  for (const char* extension : {".vtk", ".vtu"}) {
    for (bool binary : {false, true}) {
      WriteOptions options;
      options.vtk_binary = binary;
      options.surface_groups = groups;
      options.material_names = &kNames;
      paths.push_back(dir + "/" + name + (binary ? "_binary" : "_text") + extension);
      EXPECT_TRUE(write_mesh(paths.back(), mesh, options).ok()) << paths.back();
    }
  }
  return paths;
}

TEST(IoVtkInterop, VtkReadsOurFilesInTextAndBinary) {
  TETLOD_NEED_VTK_PYTHON(python);
  const std::string dir = test::output_dir("vtk_interop_meshes");
  TetMesh box2;
  ASSERT_TRUE(read_mesh(std::string(TETLOD_SOURCE_DIR) + "/assets/box2.mesh", &box2).ok());
  SurfaceGroups groups;
  ASSERT_TRUE(group_surface(box2, &groups).ok());
  struct Case {
    std::string name;
    TetMesh mesh;
    bool groups;
  };
  for (const Case& c : {Case{"box2", box2, true}, Case{"io", test::make_io_mesh(), false}}) {
    SCOPED_TRACE(c.name);
    const std::vector<std::string> paths = write_four(dir, c.name, c.mesh, c.groups);
    const std::map<std::string, Report> reports = read_with_vtk(python, paths);
    int64_t material_sum =
        std::accumulate(c.mesh.materials.begin(), c.mesh.materials.end(), int64_t{0});
    size_t triangles = 0;
    if (c.groups) {
      for (const SurfaceGroup& g : groups.groups) {
        triangles += g.triangles.size();
        material_sum += int64_t(g.tag) * int64_t(g.triangles.size());
      }
    }
    const Vec3& p = c.mesh.positions[0];
    // The names: box2's two materials, then its groups; none for the other mesh.
    std::string names;
    if (c.groups) {
      names = "1:Rotor%2C%20laminated,2:air%20gap%20\u00e4";
      for (const SurfaceGroup& g : groups.groups)
        names += "," + std::to_string(g.tag) + ":" + g.name;
    }
    for (const std::string& path : paths) {
      SCOPED_TRACE(path);
      ASSERT_EQ(reports.count(path), 1u);
      const Report& r = reports.at(path);
      EXPECT_EQ(r.at("points"), std::to_string(c.mesh.vertex_count()));
      EXPECT_EQ(r.at("tets"), std::to_string(c.mesh.tet_count()));
      EXPECT_EQ(r.at("triangles"), std::to_string(triangles));
      EXPECT_EQ(r.at("other"), "0");
      EXPECT_EQ(r.at("material_sum"), std::to_string(material_sum));
      EXPECT_EQ(r.at("arrays"), "material,stretch");
      EXPECT_EQ(r.at("names"), names);
      // The first point exactly: Python prints the shortest text of the double.
      std::istringstream xyz(r.at("first_point"));
      std::string x, y, z;
      std::getline(xyz, x, ',');
      std::getline(xyz, y, ',');
      std::getline(xyz, z, ',');
      EXPECT_EQ(std::strtod(x.c_str(), nullptr), p.x);
      EXPECT_EQ(std::strtod(y.c_str(), nullptr), p.y);
      EXPECT_EQ(std::strtod(z.c_str(), nullptr), p.z);
      // Everything VTK holds, the same from each of the four files.
      EXPECT_EQ(r.at("digest"), reports.at(paths[0]).at("digest"));
    }
  }
}

TEST(IoVtkInterop, VtkReadsOurFieldsInTextAndBinary) {
  TETLOD_NEED_VTK_PYTHON(python);
  const std::string dir = test::output_dir("vtk_interop_fields");
  TetMesh mesh;
  ASSERT_TRUE(read_mesh(std::string(TETLOD_SOURCE_DIR) + "/assets/box2.mesh", &mesh).ok());
  std::vector<double> potential, field;
  for (const Vec3& p : mesh.positions) potential.push_back(p.x / 3);
  for (size_t t = 0; t < mesh.tet_count(); ++t) field.push_back(1.0 / double(t + 1));
  MeshFields fields;
  fields.point_data = {{"potential", &potential}};
  fields.cell_data = {{"field magnitude", &field}};
  const std::string text = dir + "/fields_text.vtu", binary = dir + "/fields_binary.vtu";
  ASSERT_TRUE(write_vtu_with_fields(text, mesh, fields).ok());
  ASSERT_TRUE(write_vtu_with_fields(binary, mesh, fields, true).ok());
  const std::map<std::string, Report> reports = read_with_vtk(python, {text, binary});
  ASSERT_EQ(reports.size(), 2u);
  // vtk_read.py names the point arrays first, then the cell arrays.
  EXPECT_EQ(reports.at(text).at("arrays"), "potential,material,stretch,field%20magnitude");
  EXPECT_EQ(reports.at(binary).at("arrays"), "potential,material,stretch,field%20magnitude");
  EXPECT_EQ(reports.at(text).at("digest"), reports.at(binary).at("digest"));
}

// VTK writes our files again in each of its encodings (inline and appended base64,
// zlib-compressed, and text; legacy binary and text): TetLOD reads each as the mesh,
// names and surface groups it wrote.
TEST(IoVtkInterop, WeReadWhatVtkWritesOfOurFiles) {
  TETLOD_NEED_VTK_PYTHON(python);
  const std::string dir = test::output_dir("vtk_interop_resaved");
  TetMesh box2;
  ASSERT_TRUE(read_mesh(std::string(TETLOD_SOURCE_DIR) + "/assets/box2.mesh", &box2).ok());
  for (const std::string& path : write_four(dir, "box2", box2, true)) {
    TetMesh ours;
    ReadInfo our_info;
    ASSERT_TRUE(read_mesh(path, &ours, &our_info).ok()) << path;
    ASSERT_EQ(our_info.material_names.size(), 2u);
    ASSERT_FALSE(our_info.surface_groups.empty());
    const bool xml = path.substr(path.size() - 4) == ".vtu";
    // (VTK encodes an uncompressed array's header with its values, a compressed one's
    // apart.)
    for (const std::string& mode :
         xml ? std::vector<std::string>{"ascii", "binary", "appended", "binary+uncompressed",
                                        "appended+uncompressed", "appended+uncompressed+uint64"}
             : std::vector<std::string>{"ascii", "binary"}) {
      std::string tag = mode;
      std::replace(tag.begin(), tag.end(), '+', '_');
      const std::string again =
          path.substr(0, path.size() - 4) + "_vtk_" + tag + path.substr(path.size() - 4);
      SCOPED_TRACE(again);
      run_vtk_read(python, {"--resave", path, again, mode});
      TetMesh theirs;
      ReadInfo their_info;
      const Status s = read_mesh(again, &theirs, &their_info);
      ASSERT_TRUE(s.ok()) << s.message();
      test::expect_same_mesh(ours, theirs);
      ASSERT_EQ(their_info.material_names.size(), our_info.material_names.size());
      for (size_t i = 0; i < our_info.material_names.size(); ++i) {
        EXPECT_EQ(their_info.material_names[i].material, our_info.material_names[i].material);
        EXPECT_EQ(their_info.material_names[i].name, our_info.material_names[i].name);
      }
      test::expect_same_groups(our_info.surface_groups, their_info.surface_groups);
    }
  }
}

}  // namespace
}  // namespace tetlod
