// The P1 electrostatic solver: an exact answer on a layered plate capacitor (P1 holds
// the exact solution, so the energy must match to rounding), clear errors for every
// bad set-up, nested refinement lowering the energy, agreement of the direct and
// iterative solvers, cancellation, and the .vtu field output.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>

#include "core/electrostatics.h"
#include "core/io/mesh_io.h"
#include "core/lod.h"
#include "core/refine.h"
#include "core/simplify.h"
#include "core/test_meshes.h"
#include "core/validate.h"

namespace tetlod {
namespace {

constexpr double kPi = 3.14159265358979323846;

// [0,3] x [0,1] x [0,1] in slabs of 0.5 along x: conductor (1) | eps2 (2) x2 |
// eps3 (3) x2 | ground (4). The field is one-dimensional and piecewise linear.
TetMesh layered_plates() {
  return test::make_grid_mesh(
      6, 2, 2, [](int i, int, int) { return i == 0   ? 1
                                            : i <= 2 ? 2
                                            : i <= 4 ? 3
                                                     : 4; }, 0.5);
}

ElectrostaticsProblem plates_problem() {
  ElectrostaticsProblem p;
  p.conductors = {{1, 2.0}};
  p.ground_materials = {4};
  p.permittivities = {{2, 3.0}, {3, 0.5}};
  return p;
}

// A 6^3 grid of unit cubes, the 2^3 cubes in the middle a conductor (1), the rest a
// dielectric (2), the outer boundary grounded.
TetMesh cube_in_box() {
  return test::make_grid_mesh(6, 6, 6, [](int i, int j, int k) {
    auto mid = [](int c) { return c == 2 || c == 3; };
    return mid(i) && mid(j) && mid(k) ? 1 : 2;
  });
}

ElectrostaticsProblem cube_problem() {
  ElectrostaticsProblem p;
  p.conductors = {{1, 1.0}};
  p.ground_boundary = true;
  p.permittivities = {{2, 1.5}};
  return p;
}

std::string solve_error(const TetMesh& mesh, const ElectrostaticsProblem& problem,
                        const SolveOptions& options = {}) {
  ElectrostaticsSolution solution;
  const Status s = solve_electrostatics(mesh, problem, options, &solution);
  EXPECT_FALSE(s.ok()) << "solved, C = " << solution.capacitance;
  return s.message();
}

TEST(Electrostatics, LayeredPlatesAreExact) {
  const TetMesh mesh = layered_plates();
  // Series capacitor, plate area 1, gaps 1 and 1: C = 1 / (1/3 + 1/0.5) = 3/7.
  const double exact_c = 3.0 / 7.0;
  for (const SolverMethod method : {SolverMethod::kDirect, SolverMethod::kIterative}) {
    for (const Preconditioner pre :
         {Preconditioner::kJacobi, Preconditioner::kIncompleteCholesky}) {
      SolveOptions options;
      options.method = method;
      options.preconditioner = pre;
      options.tolerance = 1e-13;
      ElectrostaticsSolution s;
      ASSERT_TRUE(solve_electrostatics(mesh, plates_problem(), options, &s).ok());
      EXPECT_EQ(s.method, method);
      EXPECT_NEAR(s.capacitance, exact_c, 1e-12);
      EXPECT_NEAR(s.energy, 0.5 * exact_c * 4.0, 1e-12);
      EXPECT_DOUBLE_EQ(s.voltage, 2.0);
      EXPECT_LT(s.relative_residual, 1e-12);
      // u(x): 2 on the conductor (x <= 0.5), slope -2/7 in eps2, -12/7 in eps3.
      for (size_t v = 0; v < mesh.vertex_count(); ++v) {
        const double x = mesh.positions[v].x;
        const double exact = x <= 0.5   ? 2.0
                             : x <= 1.5 ? 2.0 - 2.0 / 7.0 * (x - 0.5)
                             : x <= 2.5 ? 12.0 / 7.0 - 12.0 / 7.0 * (x - 1.5)
                                        : 0.0;
        EXPECT_NEAR(s.potential[v], exact, 1e-11) << "vertex " << v;
      }
      for (size_t t = 0; t < mesh.tet_count(); ++t) {
        const int32_t m = mesh.materials[t];
        const double exact = m == 2 ? 2.0 / 7.0 : m == 3 ? 12.0 / 7.0 : 0.0;
        EXPECT_NEAR(s.field_magnitude[t], exact, 1e-11) << "tet " << t;
      }
      if (method == SolverMethod::kDirect) break;  // the preconditioner is not used
    }
  }
}

TEST(Electrostatics, ConcentricSpheresFormula) {
  // One shell: C = 4 pi eps r1 r2 / (r2 - r1).
  EXPECT_NEAR(concentric_spheres_capacitance({1, 3}, {2}), 4 * kPi * 2 * 3 / 2, 1e-12);
  // Two shells in series: 1/C adds.
  const double c = concentric_spheres_capacitance({1, 2, 3}, {2, 5});
  const double c1 = concentric_spheres_capacitance({1, 2}, {2});
  const double c2 = concentric_spheres_capacitance({2, 3}, {5});
  EXPECT_NEAR(1 / c, 1 / c1 + 1 / c2, 1e-15);
}

TEST(Electrostatics, BadSetUpsNameTheOffendingValue) {
  const TetMesh mesh = layered_plates();
  auto with = [](auto edit) {
    ElectrostaticsProblem p = plates_problem();
    edit(&p);
    return p;
  };
  using P = ElectrostaticsProblem;
  auto has = [](const std::string& message, const std::string& part) {
    return message.find(part) != std::string::npos;
  };
  std::string m = solve_error(mesh, with([](P* p) { p->conductors.clear(); }));
  EXPECT_TRUE(has(m, "no conductor")) << m;
  m = solve_error(mesh, with([](P* p) { p->conductors = {{9, 1.0}}; }));
  EXPECT_TRUE(has(m, "conductor material 9 does not exist")) << m;
  m = solve_error(mesh, with([](P* p) { p->ground_materials = {7}; }));
  EXPECT_TRUE(has(m, "ground material 7 does not exist")) << m;
  m = solve_error(mesh, with([](P* p) { p->permittivities.push_back({12, 1.0}); }));
  EXPECT_TRUE(has(m, "material 12")) << m;
  for (const double bad : {0.0, -1.0, std::nan(""), std::numeric_limits<double>::infinity()}) {
    m = solve_error(mesh, with([&](P* p) { p->permittivities = {{2, bad}}; }));
    EXPECT_TRUE(has(m, "permittivity of material 2")) << m;
  }
  m = solve_error(mesh, with([](P* p) { p->permittivities.push_back({2, 4.0}); }));
  EXPECT_TRUE(has(m, "more than once")) << m;
  m = solve_error(mesh, with([](P* p) { p->default_permittivity = -2; }));
  EXPECT_TRUE(has(m, "default permittivity -2")) << m;
  m = solve_error(mesh, with([](P* p) { p->conductors = {{1, std::nan("")}}; }));
  EXPECT_TRUE(has(m, "potential nan")) << m;
  m = solve_error(mesh, with([](P* p) { p->ground_materials = {1}; }));
  EXPECT_TRUE(has(m, "material 1 is given more than once")) << m;
  m = solve_error(mesh, with([](P* p) { p->conductors = {{1, 0.0}}; }));
  EXPECT_TRUE(has(m, "no potential difference")) << m;
  // A conductor next to a grounded material, or on the grounded boundary.
  m = solve_error(mesh, with([](P* p) { p->ground_materials = {2}; }));
  EXPECT_TRUE(has(m, "conductor material 1 (held at 2) touches material 2")) << m;
  m = solve_error(mesh, with([](P* p) {
                    p->ground_materials.clear();
                    p->ground_boundary = true;
                  }));
  EXPECT_TRUE(has(m, "touches the grounded outer boundary")) << m;
  // Two conductors at different potentials touching.
  m = solve_error(mesh, with([](P* p) { p->conductors = {{1, 2.0}, {2, 1.0}}; }));
  EXPECT_TRUE(has(m, "touches material 1")) << m;
  // Held surfaces: a ground surface alone is no conductor; a vertex out of range, an
  // empty surface, a potential out of range and one given twice are named.
  m = solve_error(mesh, with([](P* p) {
                    p->conductors.clear();
                    p->surfaces = {{"g", {0}, 0.0, true}};
                  }));
  EXPECT_TRUE(has(m, "no conductor: at least one material or surface")) << m;
  m = solve_error(mesh, with([&](P* p) { p->surfaces = {{"far", {99999}, 1.0, false}}; }));
  EXPECT_TRUE(has(m, "surface 'far': vertex 99999 is not in the mesh")) << m;
  m = solve_error(mesh, with([](P* p) { p->surfaces = {{"none", {}, 1.0, false}}; }));
  EXPECT_TRUE(has(m, "conductor surface 'none' has no vertices")) << m;
  m = solve_error(mesh, with([](P* p) { p->surfaces = {{"big", {0}, 1e31, false}}; }));
  EXPECT_TRUE(has(m, "conductor surface 'big': potential 9.99")) << m;
  m = solve_error(mesh, with([](P* p) {
                    p->surfaces = {{"s", {0}, 1.0, false}, {"s", {1}, 0.0, true}};
                  }));
  EXPECT_TRUE(has(m, "surface 's' is given more than once")) << m;
}

// A surface held at a potential is a Dirichlet condition like a material's: the plates'
// conductor (material 1, x <= 0.5) given instead by its face x = 0.5 gives the same
// capacitance (the conductor's inside is then free, at the same potential).
TEST(Electrostatics, AHeldSurfaceIsAConductor) {
  const TetMesh mesh = layered_plates();
  ElectrostaticsProblem by_surface = plates_problem();
  ElectrostaticsProblem::HeldSurface face{"x = 0.5", {}, by_surface.conductors[0].second, false};
  for (uint32_t v = 0; v < mesh.vertex_count(); ++v)
    if (mesh.positions[v].x == 0.5) face.vertices.push_back(v);
  ASSERT_FALSE(face.vertices.empty());
  by_surface.conductors.clear();
  by_surface.surfaces = {face};
  SolveOptions options;
  options.method = SolverMethod::kDirect;
  ElectrostaticsSolution a, b;
  ASSERT_TRUE(solve_electrostatics(mesh, plates_problem(), options, &a).ok());
  const Status s = solve_electrostatics(mesh, by_surface, options, &b);
  ASSERT_TRUE(s.ok()) << s.message();
  EXPECT_NEAR(b.capacitance, a.capacitance, 1e-12);
  EXPECT_GT(b.free_count, a.free_count);
}

TEST(Electrostatics, FloatingRegionIsAnError) {
  // The plates plus a separate tet far away that touches no electrode.
  TetMesh mesh = layered_plates();
  const uint32_t base = static_cast<uint32_t>(mesh.vertex_count());
  for (const Vec3& p : test::make_single_tet().positions)
    mesh.positions.push_back(p + Vec3{10, 0, 0});
  mesh.tets.push_back({base, base + 1, base + 2, base + 3});
  mesh.materials.push_back(3);
  ElectrostaticsSolution solution;
  const Status s = solve_electrostatics(mesh, plates_problem(), {}, &solution);
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.message().find("floating region of 4 nodes (material 3, node " +
                             std::to_string(base) + " at (10, 0, 0))"),
            std::string::npos)
      << s.message();
}

// A conductor and a ground in separate bodies (the conductor in its dielectric, the
// ground apart): no region lies between two potentials, so there is no field. That is
// an error, not a capacitance of rounding noise (8.96e-30 was printed).
TEST(Electrostatics, SeparateBodiesHaveNoCapacitance) {
  TetMesh mesh = test::make_grid_mesh(2, 1, 1, [](int i, int, int) { return i == 0 ? 1 : 2; });
  const uint32_t base = static_cast<uint32_t>(mesh.vertex_count());
  for (const Vec3& p : test::make_single_tet().positions)
    mesh.positions.push_back(p + Vec3{10, 0, 0});
  mesh.tets.push_back({base, base + 1, base + 2, base + 3});
  mesh.materials.push_back(3);
  ElectrostaticsProblem problem;
  problem.conductors = {{1, 1.0}};
  problem.ground_materials = {3};
  ElectrostaticsSolution solution;
  const Status s = solve_electrostatics(mesh, problem, {}, &solution);
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.message().find("no dielectric lies between two potentials"), std::string::npos)
      << s.message();
  // Joined (the ground beside the dielectric), there is.
  TetMesh joined = test::make_grid_mesh(3, 1, 1, [](int i, int, int) {
    return i == 0 ? 1 : i == 1 ? 2 : 3;
  });
  EXPECT_TRUE(solve_electrostatics(joined, problem, {}, &solution).ok());
  EXPECT_GT(solution.capacitance, 0);
}

TEST(Electrostatics, BrokenMeshesAreErrors) {
  TetMesh inverted = layered_plates();
  std::swap(inverted.tets[5][2], inverted.tets[5][3]);
  std::string m = solve_error(inverted, plates_problem());
  EXPECT_NE(m.find("tet 5 (material 1) is inverted"), std::string::npos) << m;
  TetMesh flat = test::make_single_tet();
  flat.positions[3] = {0.5, 0.5, 0};
  m = solve_error(flat, plates_problem());
  EXPECT_NE(m.find("tet 0 (material 1) is degenerate"), std::string::npos) << m;
  TetMesh out_of_range = layered_plates();
  out_of_range.tets[3][1] = 100000;
  m = solve_error(out_of_range, plates_problem());
  EXPECT_NE(m.find("tet 3 uses vertex 100000"), std::string::npos) << m;
  TetMesh short_materials = layered_plates();
  short_materials.materials.pop_back();
  m = solve_error(short_materials, plates_problem());
  EXPECT_NE(m.find("materials for"), std::string::npos) << m;
  TetMesh nan_position = layered_plates();
  nan_position.positions[7].y = std::nan("");
  m = solve_error(nan_position, plates_problem());
  EXPECT_NE(m.find("vertex 7 has a non-finite coordinate"), std::string::npos) << m;
  SolveOptions bad_options;
  bad_options.tolerance = 0;
  m = solve_error(layered_plates(), plates_problem(), bad_options);
  EXPECT_NE(m.find("tolerance 0"), std::string::npos) << m;
}

TEST(Electrostatics, NotConvergingIsAnErrorNotANumber) {
  SolveOptions options;
  options.method = SolverMethod::kIterative;
  options.max_iterations = 2;
  const std::string m = solve_error(cube_in_box(), cube_problem(), options);
  EXPECT_NE(m.find("did not converge in 2 iterations"), std::string::npos) << m;
}

TEST(Electrostatics, NestedRefinementLowersTheEnergy) {
  // P1 on a refined mesh contains P1 on the coarse one with the same Dirichlet data,
  // so the minimum energy can only go down; with a 1:8 refinement the error of a
  // smooth problem falls about 4x, of this one (re-entrant cube edges) less.
  TetMesh mesh = cube_in_box();
  double previous = 0;
  for (int level = 0; level < 3; ++level) {
    if (level > 0) {
      const TetMesh refined = refine_uniform(mesh);
      ASSERT_EQ(refined.tet_count(), 8 * mesh.tet_count());
      TetMesh check = refined;
      ValidationReport report;
      ASSERT_TRUE(validate_mesh(&check, "refined", {}, &report).ok());
      EXPECT_EQ(report.reoriented_tets, 0u);
      EXPECT_EQ(report.removed_unused_vertices, 0u);
      mesh = refined;
    }
    ElectrostaticsSolution s;
    ASSERT_TRUE(solve_electrostatics(mesh, cube_problem(), {}, &s).ok());
    EXPECT_LT(s.relative_residual, 1e-9);
    if (level > 0) {
      EXPECT_LT(s.capacitance, previous) << "level " << level;
    }
    // A cube of side 2 holds less than the sphere around it (radius sqrt 3) against the
    // box's inscribed sphere (radius 3), and more than the inscribed ball (radius 1)
    // against the circumscribed sphere (radius 3 sqrt 3).
    EXPECT_GT(s.capacitance, concentric_spheres_capacitance({1, 3 * std::sqrt(3.0)}, {1.5}));
    previous = s.capacitance;
  }
}

TEST(Electrostatics, DirectAndIterativeAgree) {
  const TetMesh mesh = refine_uniform(cube_in_box());
  SolveOptions direct;
  direct.method = SolverMethod::kDirect;
  ElectrostaticsSolution a, b, c;
  ASSERT_TRUE(solve_electrostatics(mesh, cube_problem(), direct, &a).ok());
  SolveOptions iterative;
  iterative.method = SolverMethod::kIterative;
  iterative.preconditioner = Preconditioner::kJacobi;
  ASSERT_TRUE(solve_electrostatics(mesh, cube_problem(), iterative, &b).ok());
  iterative.preconditioner = Preconditioner::kIncompleteCholesky;
  ASSERT_TRUE(solve_electrostatics(mesh, cube_problem(), iterative, &c).ok());
  EXPECT_EQ(a.iterations, 0);
  EXPECT_GT(b.iterations, c.iterations);  // IC is the stronger preconditioner
  EXPECT_NEAR(b.capacitance, a.capacitance, 1e-9 * a.capacitance);
  EXPECT_NEAR(c.capacitance, a.capacitance, 1e-9 * a.capacitance);
  double largest = 0;
  for (size_t v = 0; v < mesh.vertex_count(); ++v) {
    largest = std::max(largest, std::abs(a.potential[v] - b.potential[v]));
  }
  EXPECT_LT(largest, 1e-7);
  // Every boundary node is at 0, every conductor node at 1, the rest in between
  // (maximum principle of the P1 solution on this acute-enough Kuhn mesh).
  for (size_t v = 0; v < mesh.vertex_count(); ++v) {
    EXPECT_GE(a.potential[v], -1e-12);
    EXPECT_LE(a.potential[v], 1 + 1e-12);
  }
}

TEST(Electrostatics, CancelAndProgress) {
  const TetMesh mesh = refine_uniform(cube_in_box());
  SolveOptions options;
  options.method = SolverMethod::kIterative;
  std::atomic<bool> cancel{false};
  std::vector<std::string> phases;
  int solve_reports = 0;
  ElectrostaticsSolution s;
  ASSERT_TRUE(solve_electrostatics(
                  mesh, cube_problem(), options, &s,
                  [&](const SolveProgress& p) {
                    if (phases.empty() || phases.back() != p.phase) phases.push_back(p.phase);
                    if (std::string(p.phase) == "solve") {
                      ++solve_reports;
                      EXPECT_GE(p.fraction, 0.0);
                      EXPECT_LE(p.fraction, 1.0);
                      cancel = true;  // stop at the next iteration
                    }
                  },
                  &cancel)
                  .ok());
  EXPECT_TRUE(s.cancelled);
  EXPECT_EQ(solve_reports, 1);
  EXPECT_EQ(phases, (std::vector<std::string>{"setup", "assemble", "factor", "solve"}));
  // Cancelled before it starts.
  ElectrostaticsSolution t;
  ASSERT_TRUE(solve_electrostatics(mesh, cube_problem(), options, &t, {}, &cancel).ok());
  EXPECT_TRUE(t.cancelled);
}

TEST(Electrostatics, SphereAssetApproachesTheExactCapacitance) {
  // The bundled spheres mesh (level-3 icospheres) as the two-layer capacitor. The
  // polyhedral conductor is a little smaller than the ball, so the converged value
  // lies a little below the exact one; the FE value of each mesh lies above the
  // converged one and falls under refinement.
  TetMesh mesh;
  ASSERT_TRUE(read_mesh(std::string(TETLOD_SOURCE_DIR) + "/assets/spheres.mesh", &mesh).ok());
  ElectrostaticsProblem problem;
  problem.conductors = {{1, 1.0}};
  problem.ground_materials = {4};
  problem.permittivities = {{2, 2.0}, {3, 5.0}};
  const double exact = concentric_spheres_capacitance({1, 2, 3}, {2, 5});
  ElectrostaticsSolution coarse, fine;
  ASSERT_TRUE(solve_electrostatics(mesh, problem, {}, &coarse).ok());
  ASSERT_TRUE(solve_electrostatics(refine_uniform(mesh), problem, {}, &fine).ok());
  EXPECT_LT(fine.capacitance, coarse.capacitance);
  EXPECT_GT(coarse.capacitance, exact);
  EXPECT_LT(coarse.capacitance / exact - 1, 0.08);
  EXPECT_LT(fine.capacitance / exact - 1, 0.02);
}

TEST(Electrostatics, VtuCarriesPotentialAndField) {
  const TetMesh mesh = layered_plates();
  ElectrostaticsSolution s;
  ASSERT_TRUE(solve_electrostatics(mesh, plates_problem(), {}, &s).ok());
  const std::string dir = std::string(TETLOD_TEST_OUTPUT_DIR) + "/electrostatics";
  std::filesystem::create_directories(dir);
  const std::string path = dir + "/plates.vtu";
  MeshFields fields;
  fields.point_data = {{"potential", &s.potential}};
  fields.cell_data = {{"field magnitude", &s.field_magnitude}};
  ASSERT_TRUE(write_vtu_with_fields(path, mesh, fields).ok());
  std::stringstream text;
  text << std::ifstream(path).rdbuf();
  EXPECT_NE(text.str().find("<PointData Scalars=\"potential\">"), std::string::npos);
  EXPECT_NE(text.str().find("Name=\"field magnitude\""), std::string::npos);
  TetMesh back;
  ASSERT_TRUE(read_mesh(path, &back).ok());
  EXPECT_EQ(back.tets, mesh.tets);
  EXPECT_EQ(back.materials, mesh.materials);
  // Wrong sizes and names are errors that leave no file.
  const std::string bad_path = dir + "/bad.vtu";
  std::vector<double> short_values(3, 0.0);
  fields.point_data = {{"potential", &short_values}};
  Status bad = write_vtu_with_fields(bad_path, mesh, fields);
  EXPECT_NE(bad.message().find("\"potential\" has 3 values"), std::string::npos) << bad.message();
  fields.point_data = {{"a<b", &s.potential}};
  bad = write_vtu_with_fields(bad_path, mesh, fields);
  EXPECT_NE(bad.message().find("a<b"), std::string::npos) << bad.message();
  EXPECT_FALSE(std::filesystem::exists(bad_path));
}

// The values of the array `name` in a .vtu with raw appended data and UInt64 headers
// (as write_vtu_with_fields() writes it in binary), read by hand from the offset
// the array's element gives; empty if not found.
std::vector<double> appended_doubles(const std::string& file, const std::string& name) {
  const std::string element = "Name=\"" + name + "\" format=\"appended\" offset=\"";
  const size_t at = file.find(element);
  const size_t data = file.find("<AppendedData encoding=\"raw\">\n   _");
  if (at == std::string::npos || data == std::string::npos) return {};
  const size_t base = data + 34 + std::stoull(file.substr(at + element.size()));
  if (base + 8 > file.size()) return {};
  uint64_t bytes = 0;
  std::memcpy(&bytes, file.data() + base, 8);  // little-endian host
  if (bytes > file.size() - base - 8) return {};
  std::vector<double> values(bytes / 8);
  std::memcpy(values.data(), file.data() + base + 8, bytes);
  return values;
}

TEST(Electrostatics, BinaryVtuCarriesTheSameFields) {
  const TetMesh mesh = layered_plates();
  ElectrostaticsSolution s;
  ASSERT_TRUE(solve_electrostatics(mesh, plates_problem(), {}, &s).ok());
  const std::string dir = std::string(TETLOD_TEST_OUTPUT_DIR) + "/electrostatics";
  std::filesystem::create_directories(dir);
  const std::string path = dir + "/plates_binary.vtu";
  MeshFields fields;
  fields.point_data = {{"potential", &s.potential}};
  fields.cell_data = {{"field magnitude", &s.field_magnitude}};
  ASSERT_TRUE(write_vtu_with_fields(path, mesh, fields, true).ok());
  std::stringstream file;
  file << std::ifstream(path, std::ios::binary).rdbuf();
  EXPECT_NE(file.str().find("<PointData Scalars=\"potential\">"), std::string::npos);
  EXPECT_EQ(appended_doubles(file.str(), "potential"), s.potential);
  EXPECT_EQ(appended_doubles(file.str(), "field magnitude"), s.field_magnitude);
  TetMesh back;
  ASSERT_TRUE(read_mesh(path, &back).ok());
  EXPECT_EQ(back.positions, mesh.positions);
  EXPECT_EQ(back.tets, mesh.tets);
  EXPECT_EQ(back.materials, mesh.materials);
}

TEST(Electrostatics, EveryLodLevelOfThePlatesIsExact) {
  // The layered plates at 4x the resolution, simplified with a tolerance that keeps the
  // planar interfaces and boundary exactly: every level still conforms to the layers,
  // so P1 holds the exact piecewise-linear potential and C = 3/7 on every level — the
  // path the viewer takes (simplify, seek a level, extract, solve).
  const TetMesh mesh = test::make_grid_mesh(
      12, 4, 4, [](int i, int, int) { return i < 2    ? 1
                                             : i < 6  ? 2
                                             : i < 10 ? 3
                                                      : 4; }, 0.25);
  SimplifyParams params;
  params.tolerance = 1e-9;
  params.min_stretch = 0.05;
  params.max_valence = 40;
  params.sizing.uniform = 2;
  params.subdivide = false;
  SimplifyResult result;
  ASSERT_TRUE(simplify(mesh, params, &result).ok());
  const size_t steps = result.history.step_count();
  ASSERT_GT(steps, 100u);
  Lod lod(result.base, &result.history);
  for (const size_t step : {size_t{0}, steps / 3, 2 * steps / 3, steps}) {
    lod.seek(step);
    const TetMesh level = lod.extract();
    ElectrostaticsSolution s;
    ASSERT_TRUE(solve_electrostatics(level, plates_problem(), {}, &s).ok()) << "step " << step;
    EXPECT_NEAR(s.capacitance, 3.0 / 7.0, 1e-9)
        << "step " << step << ", " << level.tet_count() << " tets";
  }
}

TEST(Electrostatics, RefinementKeepsEveryMaterialVolume) {
  const TetMesh mesh = layered_plates();
  const TetMesh refined = refine_uniform(mesh);
  std::vector<double> before(5, 0.0), after(5, 0.0);
  for (size_t t = 0; t < mesh.tet_count(); ++t) {
    before[mesh.materials[t]] += signed_volume6(mesh, mesh.tets[t]) / 6;
  }
  for (size_t t = 0; t < refined.tet_count(); ++t) {
    const double v = signed_volume6(refined, refined.tets[t]) / 6;
    EXPECT_GT(v, 0);
    after[refined.materials[t]] += v;
  }
  for (int m = 1; m <= 4; ++m) EXPECT_NEAR(after[m], before[m], 1e-14) << "material " << m;
  // Every input vertex keeps its id and position; 8x the tets.
  EXPECT_EQ(refined.tet_count(), 8 * mesh.tet_count());
  for (size_t v = 0; v < mesh.vertex_count(); ++v)
    EXPECT_EQ(refined.positions[v], mesh.positions[v]);
}

}  // namespace
}  // namespace tetlod
