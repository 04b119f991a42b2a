// CalculiX (`ccx`, when it is on PATH) runs a frequency analysis on the .inp TetLOD
// writes: the solver reads every node, element and material set, and a free body
// has six rigid-body modes (eigenvalues near 0) below its first elastic one. A
// section on a set that does not exist is an error in CalculiX, so a set name it
// cannot read (as one with a hyphen could be) fails the test.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <sstream>

#include "core/io/mesh_io.h"
#include "core/test_io_helpers.h"

namespace tetlod {
namespace {

TEST(IoCalculixInterop, CcxRunsAFrequencyAnalysisOnOurMesh) {
  TETLOD_NEED_PROGRAM("ccx");
  const std::string dir = test::output_dir("calculix");
  TetMesh mesh;
  ASSERT_TRUE(read_mesh(std::string(TETLOD_SOURCE_DIR) + "/assets/box2.mesh", &mesh).ok());
  // Material 2 named as Abaqus/CAE names sets, with a hyphen.
  const std::vector<MaterialName> names = {{2, "Iron-Core"}};
  WriteOptions options;
  options.material_names = &names;
  ASSERT_TRUE(write_mesh(dir + "/mesh.inp", mesh, options).ok());
  // Steel in both materials' sets, which must exist for the sections to apply.
  test::write_text(dir + "/job.inp",
                   "*INCLUDE, INPUT=mesh.inp\n"
                   "*MATERIAL, NAME=STEEL\n*ELASTIC\n210000., 0.3\n*DENSITY\n7.8e-9\n"
                   "*SOLID SECTION, ELSET=MATERIAL_1, MATERIAL=STEEL\n"
                   "*SOLID SECTION, ELSET=Iron-Core_2, MATERIAL=STEEL\n"
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
  EXPECT_GT(eigenvalues[6], 1e6);
}

}  // namespace
}  // namespace tetlod
