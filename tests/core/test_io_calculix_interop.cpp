// CalculiX (`ccx`, when it is on PATH) runs a frequency analysis on the .inp TetLOD
// writes: the solver reads every node, element and material set, and a free body
// has six rigid-body modes (eigenvalues near 0) below its first elastic one. A
// section on a set that does not exist is an error in CalculiX, so a set name it
// cannot read (as one with a hyphen could be) fails the test.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "core/io/mesh_io.h"
#include "core/test_io_helpers.h"

namespace tetlod {
namespace {

// Writes `mesh` as mesh.inp in `dir` (material 2 named `name_2`), runs a frequency
// analysis on it with ccx and checks its six rigid-body modes.
void expect_free_body_modes(const TetMesh& mesh, const std::string& dir,
                            const std::string& name_2) {
  const std::vector<MaterialName> names = {{2, name_2}};
  WriteOptions options;
  options.material_names = &names;
  ASSERT_TRUE(write_mesh(dir + "/mesh.inp", mesh, options).ok());
  // Steel in both materials' sets, which must exist for the sections to apply.
  test::write_text(dir + "/job.inp",
                   "*INCLUDE, INPUT=mesh.inp\n"
                   "*MATERIAL, NAME=STEEL\n*ELASTIC\n210000., 0.3\n*DENSITY\n"
                   "7.8e-9\n*SOLID SECTION, ELSET=MATERIAL_1, MATERIAL=STEEL\n"
                   "*SOLID SECTION, ELSET=" +
                       name_2 +
                       "_2, MATERIAL=STEEL\n"
                       "*STEP\n*FREQUENCY\n8\n*END STEP\n");
  const std::string log = dir + "/ccx.log";
  ASSERT_EQ(std::system(("cd '" + dir + "' && ccx job > ccx.log 2>&1").c_str()), 0)
      << test::read_text(log);
  const std::string dat = test::read_text(dir + "/job.dat");
  const size_t table = dat.find("E I G E N V A L U E   O U T P U T");
  ASSERT_NE(table, std::string::npos) << test::read_text(log);
  // Rows "mode eigenvalue ..." after the table's header.
  std::istringstream in(dat.substr(table));
  std::string line;
  std::vector<double> eigenvalues;
  while (std::getline(in, line) && eigenvalues.size() < 8) {
    int mode = 0;
    double value = 0;
    if (std::sscanf(line.c_str(), "%d %lf", &mode, &value) == 2 &&
        mode == int(eigenvalues.size()) + 1) {
      eigenvalues.push_back(value);
    }
  }
  ASSERT_EQ(eigenvalues.size(), 8u) << dat.substr(table, 800);
  for (int m = 0; m < 6; ++m) EXPECT_LT(std::abs(eigenvalues[m]), 1e-9 * eigenvalues[6]) << m;
  EXPECT_GT(eigenvalues[6], 0);
}

TEST(IoCalculixInterop, CcxRunsAFrequencyAnalysisOnOurMesh) {
  TETLOD_NEED_PROGRAM("ccx");
  TetMesh mesh;
  ASSERT_TRUE(read_mesh(std::string(TETLOD_SOURCE_DIR) + "/assets/box2.mesh", &mesh).ok());
  // Material 2 named as Abaqus/CAE names sets, with a hyphen.
  expect_free_body_modes(mesh, test::output_dir("calculix"), "Iron-Core");
}

// CalculiX reads each number of a *NODE line from its first 20 characters: the
// coordinates of a model in metres (box2 / 1e5, 17 digits and an exponent: 22
// characters; a node at -9.2e-15) are written within 20, to 5e-13, and ccx runs on
// them.
TEST(IoCalculixInterop, CoordinatesFitCalculixsTwentyCharacters) {
  TetMesh mesh;
  ASSERT_TRUE(read_mesh(std::string(TETLOD_SOURCE_DIR) + "/assets/box2.mesh", &mesh).ok());
  for (Vec3& p : mesh.positions) p = p * 1.2345678901234567e-5;
  mesh.positions[0].x = -9.184850993605149e-15;
  const std::string dir = test::output_dir("calculix_width");
  ASSERT_TRUE(write_mesh(dir + "/mesh.inp", mesh).ok());
  const std::string text = test::read_text(dir + "/mesh.inp");
  const size_t nodes = text.find("*NODE\n");
  ASSERT_NE(nodes, std::string::npos);
  std::istringstream in(text.substr(nodes + 6));
  std::string line;
  size_t lines = 0, shortened = 0;
  while (std::getline(in, line) && !line.empty() && line[0] != '*') {
    ++lines;
    std::istringstream fields(line);
    std::string field;
    std::getline(fields, field, ',');  // the node's number
    for (int k = 0; k < 3 && std::getline(fields, field, ','); ++k) {
      const std::string number = field.substr(field.find_first_not_of(' '));
      EXPECT_LE(number.size(), 20u) << line;
      const double read = std::strtod(number.c_str(), nullptr);
      const double written = mesh.positions[lines - 1][k];
      EXPECT_LE(std::abs(read - written), 5e-13 * std::abs(written)) << line;
      shortened += read != written;
    }
  }
  EXPECT_EQ(lines, mesh.vertex_count());
  EXPECT_GT(shortened, 0u);  // the test meets such numbers
  TETLOD_NEED_PROGRAM("ccx");
  expect_free_body_modes(mesh, dir, "Iron");
}

}  // namespace
}  // namespace tetlod
