// GetDP (`getdp`, when it is on PATH), the finite-element solver of the Gmsh family
// that electromagnetics analysts use, solves the spheres' capacitor on a mesh TetLOD
// writes with its surface groups (WriteOptions::surface_groups): the Dirichlet
// conditions sit on the physical surfaces interface_1_2 (the inner electrode, at 1)
// and interface_3_4 (the outer one, at 0), eps on the two dielectric volumes. Its
// energy must be TetLOD's own (solve_electrostatics(), the same P1 elements on the
// same mesh), which holds only if every group carries exactly its triangles.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <utility>
#include <vector>

#include "core/electrostatics.h"
#include "core/io/mesh_io.h"
#include "core/simplify.h"
#include "core/surface.h"
#include "core/test_io_helpers.h"

namespace tetlod {
namespace {

// The formulation, after GetDP's electrostatics tutorials, with the physical tags of
// the two electrodes' surfaces and the permittivity of each dielectric volume
// (Debian's GetDP reads Gmsh 2.2 files itself).
std::string electrostatics_pro(int32_t inner, int32_t outer,
                               const std::vector<std::pair<int, double>>& eps) {
  const std::string in = std::to_string(inner), out = std::to_string(outer);
  std::string volumes, functions;
  for (const auto& [region, value] : eps) {
    volumes += (volumes.empty() ? "" : ", ") + std::to_string(region);
    std::ostringstream f;
    f << "epsr[Region[" << region << "]] = " << value << "; ";
    functions += f.str();
  }
  return "Group {\n"
         "  Inner = Region[" +
         in + "]; Outer = Region[" + out + "]; Vol = Region[{" + volumes +
         "}];\n"
         "  Dir = Region[{" +
         in + ", " + out +
         "}];\n"
         "}\n"
         "Function { " +
         functions +
         "}\n"
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
  TETLOD_NEED_PROGRAM("getdp");
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
  test::write_text(dir + "/spheres.pro", electrostatics_pro(inner, outer, {{2, 2.0}, {3, 5.0}}));
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

// Runs GetDP on `msh` (Gmsh 2.2) with `pro`; the energy it prints, or -1.
double getdp_energy(const std::string& dir, const std::string& msh, const std::string& pro) {
  test::write_text(dir + "/problem.pro", pro);
  std::remove((dir + "/W.txt").c_str());
  if (std::system(("cd '" + dir + "' && getdp problem.pro -msh '" + msh +
                   "' -solve EleSta -pos Energy > getdp.log 2>&1")
                      .c_str()) != 0)
    return -1;
  std::istringstream table(test::read_text(dir + "/W.txt"));
  double zero = -1, energy = -1;
  table >> zero >> energy;
  return energy;
}

// A Gmsh coax (tests/data/gmsh/coax.geo) whose outer electrode is its own physical
// surface "jacket", part of the shield's boundary: simplified by TetLOD, which keeps
// the group, GetDP solves with V = 1 on the inner conductor's interface and V = 0 on
// the jacket, and finds the energy it finds on the input mesh, and the exact one of
// the three cylindrical layers (the ends are insulating, so the field is radial).
TEST(IoGetdpInterop, GetdpSolvesOnAnInputGroupThroughSimplification) {
  TETLOD_NEED_PROGRAM("getdp");
  TETLOD_NEED_PROGRAM("gmsh");
  const std::string dir = test::output_dir("getdp_coax");
  ASSERT_EQ(std::system(("gmsh '" + std::string(TETLOD_SOURCE_DIR) +
                         "/tests/data/gmsh/coax.geo' -3 -clmax 0.4 -v 0 -format msh41 -o '" + dir +
                         "/coax.msh' > '" + dir + "/gmsh.log' 2>&1")
                            .c_str()),
            0)
      << test::read_text(dir + "/gmsh.log");
  TetMesh input;
  ReadInfo info;
  ASSERT_TRUE(read_mesh(dir + "/coax.msh", &input, &info).ok());
  const SurfacePatches patches(input, info.surface_groups);
  ASSERT_TRUE(patches.any());
  SimplifyParams params;
  params.sizing.uniform = 1.2;
  params.tolerance = 0.02;
  SimplifyResult result;
  ASSERT_TRUE(simplify(input, params, &result, {}, nullptr, &patches).ok());
  ASSERT_LT(result.output.tet_count(), input.tet_count() / 2);

  const std::vector<std::pair<int, double>> eps = {{2, 2.0}, {3, 4.0}, {4, 1.0}};
  const double exact =
      0.5 * 2 * M_PI * 4.0 / (std::log(2.0) / 2 + std::log(3.5 / 2) / 4 + std::log(4 / 3.5) / 1);
  double energies[2] = {0, 0};
  for (int k = 0; k < 2; ++k) {
    SCOPED_TRACE(k == 0 ? "input" : "simplified");
    const TetMesh& mesh = k == 0 ? input : result.output;
    SurfaceGroups groups;
    ASSERT_TRUE(group_surface(mesh, &groups, patches).ok());
    int32_t inner = 0, jacket = 0;
    for (const SurfaceGroup& g : groups.groups) {
      if (g.name == "interface_1_2") inner = g.tag;
      if (g.name == "jacket") jacket = g.tag;
    }
    ASSERT_GT(inner, 0);
    ASSERT_EQ(jacket, 21);
    WriteOptions options;
    options.gmsh_version = 22;
    options.surface_groups = true;
    options.groups = &groups;
    const std::string msh = k == 0 ? "input22.msh" : "simplified22.msh";
    ASSERT_TRUE(write_mesh(dir + "/" + msh, mesh, options).ok());
    energies[k] = getdp_energy(dir, msh, electrostatics_pro(inner, jacket, eps));
    ASSERT_GT(energies[k], 0) << test::read_text(dir + "/getdp.log");
    // P1 energies lie above the exact one; the polygonal cylinders add a little.
    EXPECT_GT(energies[k], 0.97 * exact);
    EXPECT_LT(energies[k], 1.06 * exact);
  }
  EXPECT_NEAR(energies[1], energies[0], 0.03 * energies[0]);
  // The figures of docs/RESULTS.md.
  std::printf("coax jacket: input %zu tets W %.4f, simplified %zu tets W %.4f, exact %.4f\n",
              input.tet_count(), energies[0], result.output.tet_count(), energies[1], exact);
}

}  // namespace
}  // namespace tetlod
