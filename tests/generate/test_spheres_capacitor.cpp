// Validation of the electrostatic solver against the exact two-layer spherical
// capacitor (issue 6): the spheres model, conductor r < r1 at u = 1, material 4
// grounded (so exactly the sphere r3 is the ground), eps2 = 2 and eps3 = 5:
//   1/C = (1/(4 pi eps2)) (1/r1 - 1/r2) + (1/(4 pi eps3)) (1/r2 - 1/r3).
// The icosphere facets make a geometric error of the same order as the discretisation
// error, so the two are checked apart:
//  - discretisation: uniform 1:8 refinement keeps every facet, so on one geometry C_h
//    falls monotonically (nested P1 spaces) to the polyhedral value C_poly at the
//    energy rate, about h^2: successive differences shrink 3.5-4x (see below);
//  - geometry: C_poly (Richardson-extrapolated) approaches C_exact as the icosphere
//    level rises, the gap shrinking about 4x per level (facet distance ~ level^-2).
#include <gtest/gtest.h>

#include <cmath>

#include "core/electrostatics.h"
#include "core/generate/model_generator.h"
#include "core/generate/plc.h"
#include "core/refine.h"

namespace tetlod {
namespace {

ElectrostaticsProblem capacitor() {
  ElectrostaticsProblem p;
  p.conductors = {{kSpheresCore, 1.0}};
  p.ground_materials = {kSpheresBox};
  p.permittivities = {{kSpheresInner, 2.0}, {kSpheresOuter, 5.0}};
  return p;
}

double exact() {
  return concentric_spheres_capacitance({kSpheresRadius1, kSpheresRadius2, kSpheresRadius3},
                                        {2.0, 5.0});
}

// C on `mesh` and on its `refinements` successive 1:8 refinements.
std::vector<double> refinement_sequence(TetMesh mesh, int refinements) {
  std::vector<double> c;
  for (int level = 0; level <= refinements; ++level) {
    if (level > 0) mesh = refine_uniform(mesh);
    ElectrostaticsSolution s;
    const Status status = solve_electrostatics(mesh, capacitor(), {}, &s);
    EXPECT_TRUE(status.ok()) << status.message();
    EXPECT_LT(s.relative_residual, 1e-9);
    c.push_back(s.capacitance);
  }
  return c;
}

TetMesh spheres(int sphere_level, double max_volume) {
  GenerateOptions options;
  options.sphere_level = sphere_level;
  options.max_volume = max_volume;
  TetMesh mesh;
  const Status s = generate_model(Model::kSpheres, options, &mesh);
  EXPECT_TRUE(s.ok()) << s.message();
  return mesh;
}

TEST(SpheresCapacitor, ConvergesAtTheEnergyRateAndToTheExactValue) {
  // Level 2 icospheres: three meshes, 1:8 apart.
  const TetMesh coarse = spheres(2, 0.3);
  ASSERT_GT(coarse.tet_count(), 1000u);
  ASSERT_LT(coarse.tet_count(), 40000u) << coarse.tet_count();
  const std::vector<double> c2 = refinement_sequence(coarse, 2);
  // Level 3 icospheres (the bundled density), likewise.
  const std::vector<double> c3 = refinement_sequence(spheres(3, 1.0), 2);
  double poly[2];
  for (int i = 0; i < 2; ++i) {
    const std::vector<double>& c = i == 0 ? c2 : c3;
    // Monotone from above: nested spaces, same Dirichlet data.
    EXPECT_GT(c[0], c[1]);
    EXPECT_GT(c[1], c[2]);
    // Energy error ~ h^(2s): each 1:8 refinement divides it by 2^(2s), 4 for a smooth
    // solution. The conductor's facet edges are re-entrant for the field (exterior angle
    // a = 2 pi - dihedral, a bit above pi), where u ~ r^(pi/a): s = pi/a is about 0.9 at
    // level 2 and 0.95 at level 3, so the factor tends to about 3.5 and 3.7.
    const double rate = (c[0] - c[1]) / (c[1] - c[2]);
    EXPECT_GT(rate, 3.0) << "level " << i + 2 << ": " << c[0] << " " << c[1] << " " << c[2];
    EXPECT_LT(rate, 4.5) << "level " << i + 2 << ": " << c[0] << " " << c[1] << " " << c[2];
    // Richardson extrapolation at the observed rate: the polyhedral geometry's C.
    poly[i] = c[2] - (c[1] - c[2]) / (rate - 1);
    EXPECT_LT(poly[i], c[2]);
  }
  const double poly2 = poly[0], poly3 = poly[1];

  // The geometric error: the inscribed polyhedral conductor is smaller than the ball,
  // so C_poly < C_exact; one icosphere level more cuts the gap about 4x.
  const double geometric2 = poly2 / exact() - 1;
  const double geometric3 = poly3 / exact() - 1;
  EXPECT_LT(geometric2, 0);
  EXPECT_LT(geometric3, 0);
  EXPECT_GT(geometric2, -0.02);
  EXPECT_GT(std::abs(geometric2) / std::abs(geometric3), 2.5) << geometric2 << " " << geometric3;
  EXPECT_LT(std::abs(geometric2) / std::abs(geometric3), 6.0) << geometric2 << " " << geometric3;
  // Total error on the finest meshes of each sequence.
  EXPECT_LT(std::abs(c2[2] / exact() - 1), 0.02) << c2[2];
  EXPECT_LT(std::abs(c3[1] / exact() - 1), 0.015) << c3[1];
  EXPECT_LT(std::abs(c3[2] / exact() - 1), 0.003) << c3[2];
  std::printf(
      "C_exact %.6f; level 2: %.6f %.6f %.6f (C_poly %.6f, %+.3f%%); "
      "level 3: %.6f %.6f %.6f (C_poly %.6f, %+.3f%%)\n",
      exact(), c2[0], c2[1], c2[2], poly2, 100 * geometric2, c3[0], c3[1], c3[2], poly3,
      100 * geometric3);
}

TEST(SpheresCapacitor, RegionVolumeBoundsAreHonoured) {
  // The graded meshes of the convergence study: a volume bound per PLC region.
  Plc plc = build_spheres_plc(2);
  for (PlcRegion& region : plc.regions) {
    if (region.material == kSpheresInner) region.max_volume = 0.02;
  }
  TetMesh graded, plain;
  ASSERT_TRUE(tetrahedralize_plc(plc, {1.0, kDefaultQuality}, &graded).ok());
  ASSERT_TRUE(tetrahedralize_plc(build_spheres_plc(2), {1.0, kDefaultQuality}, &plain).ok());
  size_t inner_graded = 0, inner_plain = 0;
  for (size_t t = 0; t < graded.tet_count(); ++t) {
    if (graded.materials[t] != kSpheresInner) continue;
    ++inner_graded;
    EXPECT_LE(signed_volume6(graded, graded.tets[t]) / 6, 0.02 * (1 + 1e-9)) << "tet " << t;
  }
  for (const int32_t m : plain.materials) inner_plain += m == kSpheresInner;
  EXPECT_GT(inner_graded, inner_plain);
  // A non-finite bound is an error, not a TetGen crash.
  plc.regions[0].max_volume = std::nan("");
  EXPECT_FALSE(tetrahedralize_plc(plc, {1.0, kDefaultQuality}, &graded).ok());
}

}  // namespace
}  // namespace tetlod
