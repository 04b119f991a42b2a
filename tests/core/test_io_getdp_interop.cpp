// GetDP (`getdp`, when it is on PATH), the finite-element solver of the Gmsh family
// that electromagnetics analysts use, solves the spheres' capacitor on a mesh TetLOD
// writes with its surface groups (WriteOptions::surface_groups): the Dirichlet
// conditions sit on the physical surfaces interface_1_2 (the inner electrode, at 1)
// and interface_3_4 (the outer one, at 0), eps on the two dielectric volumes. Its
// energy must be TetLOD's own (solve_electrostatics(), the same P1 elements on the
// same mesh), which holds only if every group carries exactly its triangles.
#include <gtest/gtest.h>

#include <cstdlib>
#include <sstream>

#include "core/electrostatics.h"
#include "core/io/mesh_io.h"
#include "core/surface.h"
#include "core/test_io_helpers.h"

namespace tetlod {
namespace {

// The formulation, after GetDP's electrostatics tutorials, with the physical tags of
// the two electrodes' surfaces (Debian's GetDP reads Gmsh 2.2 files itself).
std::string electrostatics_pro(int32_t inner, int32_t outer) {
  const std::string in = std::to_string(inner), out = std::to_string(outer);
  return "Group {\n"
         "  Inner = Region[" +
         in + "]; Outer = Region[" + out +
         "];\n"
         "  Shell2 = Region[2]; Shell3 = Region[3]; Vol = Region[{2, 3}];\n"
         "  Dir = Region[{" +
         in + ", " + out +
         "}];\n"
         "}\n"
         "Function { epsr[Shell2] = 2; epsr[Shell3] = 5; }\n"
         "Constraint { { Name V; Case { { Region Inner; Value 1; }\n"
         "                              { Region Outer; Value 0; } } } }\n"
         "Jacobian { { Name Vol; Case { { Region All; Jacobian Vol; } } } }\n"
         "Integration { { Name Int; Case { { Type Gauss; Case {\n"
         "  { GeoElement Tetrahedron; NumberOfPoints 4; }\n"
         "  { GeoElement Triangle; NumberOfPoints 3; } } } } } }\n"
         "FunctionSpace { { Name Hgrad_v; Type Form0;\n"
         "  BasisFunction { { Name sn; NameOfCoef vn; Function BF_Node;\n"
         "    Support Region[{Vol, Dir}]; Entity NodesOf[All]; } }\n"
         "  Constraint { { NameOfCoef vn; EntityType NodesOf; NameOfConstraint V; } } } }\n"
         "Formulation { { Name Electrostatics; Type FemEquation;\n"
         "  Quantity { { Name v; Type Local; NameOfSpace Hgrad_v; } }\n"
         "  Equation { Galerkin { [ epsr[] * Dof{d v}, {d v} ];\n"
         "    In Vol; Jacobian Vol; Integration Int; } } } }\n"
         "Resolution { { Name EleSta; System { { Name Sys; NameOfFormulation Electrostatics; } }\n"
         "  Operation { Generate[Sys]; Solve[Sys]; SaveSolution[Sys]; } } }\n"
         "PostProcessing { { Name EleSta; NameOfFormulation Electrostatics;\n"
         "  Quantity { { Name W; Value { Integral { [ 0.5 * epsr[] * SquNorm[{d v}] ];\n"
         "    In Vol; Jacobian Vol; Integration Int; } } } } } }\n"
         "PostOperation { { Name Energy; NameOfPostProcessing EleSta;\n"
         "  Operation { Print[ W[Vol], OnGlobal, Format Table, File \"W.txt\" ]; } } }\n";
}

TEST(IoGetdpInterop, GetdpSolvesOnOurSurfaceGroups) {
  if (std::system("command -v getdp > /dev/null 2>&1") != 0) GTEST_SKIP() << "no getdp on PATH";
  const std::string dir = test::output_dir("getdp");
  TetMesh mesh;
  ASSERT_TRUE(read_mesh(std::string(TETLOD_SOURCE_DIR) + "/assets/spheres.mesh", &mesh).ok());
  WriteOptions options;
  options.gmsh_version = 22;
  options.surface_groups = true;
  ASSERT_TRUE(write_mesh(dir + "/spheres.msh", mesh, options).ok());
  int32_t inner = 0, outer = 0;
  SurfaceGroups groups;
  ASSERT_TRUE(group_surface(mesh, &groups).ok());
  for (const SurfaceGroup& g : groups.groups) {
    if (g.name == "interface_1_2") inner = g.tag;
    if (g.name == "interface_3_4") outer = g.tag;
  }
  ASSERT_GT(inner, 0);
  ASSERT_GT(outer, 0);
  test::write_text(dir + "/spheres.pro", electrostatics_pro(inner, outer));
  std::remove((dir + "/W.txt").c_str());
  ASSERT_EQ(std::system(("cd '" + dir +
                         "' && getdp spheres.pro -msh spheres.msh -solve EleSta -pos Energy "
                         "> getdp.log 2>&1")
                            .c_str()),
            0)
      << test::read_text(dir + "/getdp.log");
  // "0  <W>": the region number of the global print, then the value.
  std::istringstream table(test::read_text(dir + "/W.txt"));
  double zero = -1, getdp_energy = 0;
  table >> zero >> getdp_energy;
  ASSERT_GT(getdp_energy, 0) << test::read_text(dir + "/getdp.log");

  ElectrostaticsProblem problem;
  problem.conductors = {{1, 1.0}};
  problem.ground_materials = {4};
  problem.permittivities = {{2, 2.0}, {3, 5.0}};
  ElectrostaticsSolution ours;
  SolveOptions solve;
  solve.method = SolverMethod::kDirect;
  ASSERT_TRUE(solve_electrostatics(mesh, problem, solve, &ours).ok());
  EXPECT_NEAR(getdp_energy, ours.energy, 1e-8 * ours.energy);
  // And both near the exact energy of the smooth spheres (C / 2, 44.352 / 2; docs/
  // RESULTS.md), above it as P1 energies are, by the bundled mesh's few per cent.
  EXPECT_GT(getdp_energy, 44.352 / 2);
  EXPECT_LT(getdp_energy, 1.1 * 44.352 / 2);
}

}  // namespace
}  // namespace tetlod
