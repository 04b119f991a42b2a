// Tests of the procedural TetGen models: validity, material sets, exact volumes,
// connected material regions, sphere interfaces, determinism, density control and
// option checks. Densities are coarse so the whole file runs in a few seconds.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <numeric>
#include <set>
#include <vector>

#include "core/adjacency.h"
#include "core/generate/model_generator.h"
#include "core/io/mesh_io.h"
#include "core/validate.h"

namespace tetlod {
namespace {

constexpr double kPi = 3.14159265358979323846;

TetMesh generate(Model model, GenerateOptions options = {}, GenerateInfo* info = nullptr) {
  TetMesh mesh;
  const Status status = generate_model(model, options, &mesh, info);
  EXPECT_TRUE(status.ok()) << status.message();
  return mesh;
}

std::map<int32_t, double> volume_per_material(const TetMesh& mesh) {
  std::map<int32_t, double> volume;
  for (size_t t = 0; t < mesh.tet_count(); ++t) {
    volume[mesh.materials[t]] += signed_volume6(mesh, mesh.tets[t]) / 6.0;
  }
  return volume;
}

std::set<int32_t> material_set(const TetMesh& mesh) {
  return std::set<int32_t>(mesh.materials.begin(), mesh.materials.end());
}

// Connected components of each material through shared faces.
std::map<int32_t, int> components_per_material(const TetMesh& mesh) {
  std::vector<uint32_t> neighbors;
  EXPECT_EQ(build_face_neighbors(mesh, &neighbors).kind, FaceProblem::Kind::kNone);
  std::vector<uint32_t> parent(mesh.tet_count());
  std::iota(parent.begin(), parent.end(), 0u);
  auto find = [&](uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  for (uint32_t t = 0; t < mesh.tet_count(); ++t) {
    for (int f = 0; f < 4; ++f) {
      const uint32_t u = neighbors[4 * t + f];
      if (u != kInvalidIndex && mesh.materials[u] == mesh.materials[t]) parent[find(t)] = find(u);
    }
  }
  std::map<int32_t, int> count;
  for (uint32_t t = 0; t < mesh.tet_count(); ++t) {
    if (find(t) == t) ++count[mesh.materials[t]];
  }
  return count;
}

// Vertices on faces between material a and material b.
std::set<uint32_t> interface_vertices(const TetMesh& mesh, int32_t a, int32_t b) {
  std::vector<uint32_t> neighbors;
  EXPECT_EQ(build_face_neighbors(mesh, &neighbors).kind, FaceProblem::Kind::kNone);
  std::set<uint32_t> vertices;
  for (uint32_t t = 0; t < mesh.tet_count(); ++t) {
    if (mesh.materials[t] != a) continue;
    for (int f = 0; f < 4; ++f) {
      const uint32_t u = neighbors[4 * t + f];
      if (u == kInvalidIndex || mesh.materials[u] != b) continue;
      for (int k : kTetFace[f]) vertices.insert(mesh.tets[t][k]);
    }
  }
  return vertices;
}

// The generator's contract: valid as is (no repairs), PLC points first and unchanged.
void expect_valid_and_keeps_plc_points(Model model, const GenerateOptions& options,
                                       const TetMesh& mesh) {
  TetMesh copy = mesh;
  ValidationReport report;
  const Status status = validate_mesh(&copy, "generated", {}, &report);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_EQ(report.reoriented_tets, 0u);
  EXPECT_EQ(report.removed_unused_vertices, 0u);
  const Plc plc = build_model_plc(model, options);
  ASSERT_GE(mesh.vertex_count(), plc.points.size());
  for (size_t i = 0; i < plc.points.size(); ++i) ASSERT_EQ(mesh.positions[i], plc.points[i]) << i;
}

double polygon_area(int sides, double radius) {  // regular polygon, circumradius `radius`
  return 0.5 * sides * radius * radius * std::sin(2.0 * kPi / sides);
}

double icosphere_volume(const Icosphere& sphere) {
  double volume6 = 0;
  for (const auto& t : sphere.triangles) {
    volume6 += dot(sphere.vertices[t[0]], cross(sphere.vertices[t[1]], sphere.vertices[t[2]]));
  }
  return volume6 / 6.0;
}

// ---- box2 ----------------------------------------------------------------------

TEST(Box2, ExactVolumesMaterialsAndConnectivity) {
  const TetMesh mesh = generate(Model::kBox2);
  expect_valid_and_keeps_plc_points(Model::kBox2, {}, mesh);
  EXPECT_GE(mesh.tet_count(), 24u);
  EXPECT_LE(mesh.tet_count(), 1000u);
  EXPECT_EQ(material_set(mesh), (std::set<int32_t>{kBox2Left, kBox2Right}));
  const auto volume = volume_per_material(mesh);
  EXPECT_NEAR(volume.at(kBox2Left), 1.0, 1e-13);
  EXPECT_NEAR(volume.at(kBox2Right), 1.0, 1e-13);
  EXPECT_EQ(components_per_material(mesh), (std::map<int32_t, int>{{1, 1}, {2, 1}}));
  for (size_t t = 0; t < mesh.tet_count(); ++t) {
    for (uint32_t v : mesh.tets[t]) {
      const double x = mesh.positions[v].x;
      EXPECT_TRUE(mesh.materials[t] == kBox2Left ? x <= 1.0 : x >= 1.0);
    }
  }
  for (uint32_t v : interface_vertices(mesh, kBox2Left, kBox2Right)) {
    EXPECT_EQ(mesh.positions[v].x, 1.0);
  }
}

// ---- spheres -------------------------------------------------------------------

TEST(Icosphere, CountsRadiiAndOutwardTriangles) {
  for (int level = 0; level <= 3; ++level) {
    const Icosphere sphere = make_icosphere(level, 2.0);
    EXPECT_EQ(sphere.triangles.size(), 20u << (2 * level));
    EXPECT_EQ(sphere.vertices.size(), (10u << (2 * level)) + 2);
    for (const Vec3& v : sphere.vertices) EXPECT_NEAR(length(v), 2.0, 2.0 * 1e-15);
    for (const auto& t : sphere.triangles) {
      const Vec3& a = sphere.vertices[t[0]];
      const Vec3 normal = cross(sphere.vertices[t[1]] - a, sphere.vertices[t[2]] - a);
      EXPECT_GT(dot(normal, a), 0.0);
    }
  }
  // Faceting: the polyhedron of level 3 holds 99.1 % of the ball's volume.
  EXPECT_NEAR(icosphere_volume(make_icosphere(3, 1.0)) / (4.0 / 3.0 * kPi), 0.99139, 1e-5);
}

TEST(Spheres, ExactVolumesMaterialsAndConnectivity) {
  GenerateOptions options;
  options.sphere_level = 2;
  options.max_volume = 1.0;
  const TetMesh mesh = generate(Model::kSpheres, options);
  expect_valid_and_keeps_plc_points(Model::kSpheres, options, mesh);
  EXPECT_EQ(material_set(mesh), (std::set<int32_t>{1, 2, 3, 4}));
  EXPECT_EQ(components_per_material(mesh),
            (std::map<int32_t, int>{{1, 1}, {2, 1}, {3, 1}, {4, 1}}));

  // Cumulative volumes inside each sphere are those of the icosphere polyhedra.
  const auto volume = volume_per_material(mesh);
  const double radii[3] = {kSpheresRadius1, kSpheresRadius2, kSpheresRadius3};
  double inside = 0;
  for (int s = 0; s < 3; ++s) {
    inside += volume.at(s + 1);
    const double polyhedron = icosphere_volume(make_icosphere(options.sphere_level, radii[s]));
    const double ball = 4.0 / 3.0 * kPi * std::pow(radii[s], 3);
    EXPECT_NEAR(inside, polyhedron, 1e-12 * polyhedron) << "sphere " << s;
    EXPECT_NEAR(inside / ball, 1.0, 0.04) << "sphere " << s;  // level 2: 96.6 %
  }
  const double box = std::pow(2 * kSpheresBoxHalfWidth, 3);
  EXPECT_NEAR(inside + volume.at(kSpheresBox), box, 1e-12 * box);
}

// Every interface vertex lies on its icosphere: the icosphere's own vertices on the
// sphere, any Steiner point TetGen added in the plane of an icosphere triangle.
TEST(Spheres, InterfaceVerticesLieOnTheirSpheres) {
  GenerateOptions options;  // the asset's density and level
  const TetMesh mesh = generate(Model::kSpheres, options);
  const double radii[3] = {kSpheresRadius1, kSpheresRadius2, kSpheresRadius3};
  for (int s = 0; s < 3; ++s) {
    const Icosphere sphere = make_icosphere(options.sphere_level, radii[s]);
    const std::set<uint32_t> vertices = interface_vertices(mesh, s + 1, s + 2);
    size_t on_sphere = 0;
    for (uint32_t v : vertices) {
      const Vec3& p = mesh.positions[v];
      if (std::abs(length(p) / radii[s] - 1.0) <= 1e-9) {
        ++on_sphere;
        continue;
      }
      // A Steiner point: in the plane of the triangle its ray from the centre crosses.
      bool on_polyhedron = false;
      for (const auto& t : sphere.triangles) {
        const Vec3& a = sphere.vertices[t[0]];
        const Vec3& b = sphere.vertices[t[1]];
        const Vec3& c = sphere.vertices[t[2]];
        if (dot(p, cross(a, b)) < 0 || dot(p, cross(b, c)) < 0 || dot(p, cross(c, a)) < 0) {
          continue;
        }
        const Vec3 normal = cross(b - a, c - a);
        on_polyhedron = std::abs(dot(normal, p - a)) <= 1e-9 * radii[s] * length(normal);
        break;
      }
      EXPECT_TRUE(on_polyhedron) << "sphere " << s << " vertex " << v;
    }
    // Every icosphere vertex is an interface vertex.
    EXPECT_GE(on_sphere, sphere.vertices.size()) << "sphere " << s;
    EXPECT_EQ(on_sphere, sphere.vertices.size()) << "sphere " << s;
  }
}

// ---- motor ---------------------------------------------------------------------

TEST(Motor, ExactVolumesMaterialsAndConnectivity) {
  const TetMesh mesh = generate(Model::kMotor);
  expect_valid_and_keeps_plc_points(Model::kMotor, {}, mesh);
  EXPECT_EQ(material_set(mesh),
            (std::set<int32_t>{kMotorAir, kMotorAirGap, kMotorShaft, kMotorRotorIron, kMotorMagnet,
                               kMotorStatorIron, kMotorCoil}));
  EXPECT_EQ(components_per_material(mesh), (std::map<int32_t, int>{{kMotorAir, 1},
                                                                   {kMotorAirGap, 1},
                                                                   {kMotorShaft, 1},
                                                                   {kMotorRotorIron, 1},
                                                                   {kMotorMagnet, kMotorPoleCount},
                                                                   {kMotorStatorIron, 1},
                                                                   {kMotorCoil, kMotorSlotCount}}));

  const auto volume = volume_per_material(mesh);
  double total = 0;
  for (const auto& [material, v] : volume) total += v;
  const double length = 2 * kMotorHalfLength;
  const double box = 4 * kMotorBoxHalfWidth * kMotorBoxHalfWidth * 2 * kMotorBoxHalfHeight;
  const double magnets = kMotorPoleCount * kMotorMagnetWidth * kMotorMagnetThickness * length;
  const double shaft = polygon_area(kMotorShaftSegments, kMotorShaftRadius) * length;
  const double rotor = polygon_area(kMotorGapSegments, kMotorRotorRadius) * length;
  const double motor = polygon_area(kMotorOuterSegments, kMotorStatorOuterRadius) * length;
  const double tolerance = 1e-12 * box;
  EXPECT_NEAR(total, box, tolerance);
  EXPECT_NEAR(volume.at(kMotorMagnet), magnets, tolerance);
  EXPECT_NEAR(volume.at(kMotorShaft), shaft, tolerance);
  EXPECT_NEAR(volume.at(kMotorRotorIron), rotor - shaft - magnets, tolerance);
  EXPECT_NEAR(volume.at(kMotorAir), box - motor, tolerance);
  EXPECT_NEAR(volume.at(kMotorAirGap) + volume.at(kMotorStatorIron) + volume.at(kMotorCoil),
              motor - rotor, tolerance);
  // The air gap: at least the annulus between the rotor and the tooth tips.
  EXPECT_GT(volume.at(kMotorAirGap), kPi *
                                         (kMotorStatorInnerRadius * kMotorStatorInnerRadius -
                                          kMotorRotorRadius * kMotorRotorRadius) *
                                         length * 0.98);

  // Everything but air lies in the motor's cylinder.
  for (size_t t = 0; t < mesh.tet_count(); ++t) {
    if (mesh.materials[t] == kMotorAir) continue;
    for (uint32_t v : mesh.tets[t]) {
      const Vec3& p = mesh.positions[v];
      ASSERT_LE(std::abs(p.z), kMotorHalfLength);
      ASSERT_LE(std::hypot(p.x, p.y), kMotorStatorOuterRadius * (1 + 1e-12));
    }
  }
}

// ---- determinism and density ---------------------------------------------------

void expect_identical(const TetMesh& a, const TetMesh& b) {
  ASSERT_EQ(a.positions.size(), b.positions.size());
  ASSERT_EQ(a.tets.size(), b.tets.size());
  for (size_t i = 0; i < a.positions.size(); ++i) ASSERT_EQ(a.positions[i], b.positions[i]);
  EXPECT_EQ(a.tets, b.tets);
  EXPECT_EQ(a.materials, b.materials);
}

TEST(Generate, SameOptionsGiveTheSameMesh) {
  expect_identical(generate(Model::kMotor), generate(Model::kMotor));
  GenerateOptions options;
  options.target_tets = 30000;
  expect_identical(generate(Model::kSpheres, options), generate(Model::kSpheres, options));
}

std::string read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

TEST(Generate, SameOptionsGiveTheSameFileByteForByte) {
  const std::string dir = std::string(TETLOD_TEST_OUTPUT_DIR) + "/generate";
  std::filesystem::create_directories(dir);
  GenerateOptions options;
  options.max_volume = 2000;
  for (int i = 0; i < 2; ++i) {
    const Status status =
        write_mesh(dir + "/motor_" + std::to_string(i) + ".mesh", generate(Model::kMotor, options));
    ASSERT_TRUE(status.ok()) << status.message();
  }
  const std::string first = read_bytes(dir + "/motor_0.mesh");
  EXPECT_GT(first.size(), 100000u);
  EXPECT_TRUE(first == read_bytes(dir + "/motor_1.mesh"));
}

// The committed assets are what `tetlod generate MODEL -o assets/MODEL.mesh` makes
// (assets/README.md); regenerate them when a model or its default density changes.
TEST(Generate, CommittedAssetsMatchTheDefaultModels) {
  for (Model model : {Model::kMotor, Model::kSpheres, Model::kBox2}) {
    const std::string path =
        std::string(TETLOD_SOURCE_DIR) + "/assets/" + model_name(model) + ".mesh";
    TetMesh asset;
    const Status status = read_mesh(path, &asset);
    ASSERT_TRUE(status.ok()) << status.message();
    SCOPED_TRACE(path);
    expect_identical(asset, generate(model));
  }
}

TEST(Generate, TargetTetCountIsMet) {
  struct Case {
    Model model;
    size_t target;
  };
  for (const Case& c :
       {Case{Model::kMotor, 60000}, Case{Model::kSpheres, 40000}, Case{Model::kBox2, 2000}}) {
    GenerateOptions options;
    options.target_tets = c.target;
    GenerateInfo info;
    const TetMesh mesh = generate(c.model, options, &info);
    EXPECT_NEAR(static_cast<double>(mesh.tet_count()) / c.target, 1.0, 0.25)
        << model_name(c.model) << ": " << mesh.tet_count() << " tets";
    EXPECT_GE(info.meshing_runs, 1);
    EXPECT_LE(info.meshing_runs, 4);
    EXPECT_GT(info.max_volume, 0.0);
  }
}

TEST(Generate, SmallerVolumeBoundGivesMoreTets) {
  GenerateOptions coarse;
  coarse.max_volume = 0.1;
  GenerateOptions fine;
  fine.max_volume = 0.01;
  EXPECT_GT(generate(Model::kBox2, fine).tet_count(),
            2 * generate(Model::kBox2, coarse).tet_count());
}

// ---- options and failures --------------------------------------------------------

TEST(Generate, ModelNames) {
  Model model;
  for (Model m : {Model::kMotor, Model::kSpheres, Model::kBox2}) {
    ASSERT_TRUE(parse_model_name(model_name(m), &model));
    EXPECT_EQ(model, m);
  }
  EXPECT_FALSE(parse_model_name("torus", &model));
  EXPECT_FALSE(parse_model_name("", &model));
}

TEST(Generate, BadOptionsAreErrorsNamingTheValue) {
  struct Case {
    GenerateOptions options;
    const char* needle;
  };
  auto with = [](auto edit) {
    GenerateOptions options;
    edit(options);
    return options;
  };
  const Case cases[] = {
      {with([](GenerateOptions& o) { o.max_volume = -1; }), "-1"},
      {with([](GenerateOptions& o) { o.max_volume = std::nan(""); }), "nan"},
      {with([](GenerateOptions& o) { o.max_volume = HUGE_VAL; }), "inf"},
      {with([](GenerateOptions& o) { o.max_volume = 1e-9; }), "1e-09"},
      {with([](GenerateOptions& o) { o.target_tets = 1'000'000'000'000; }), "1000000000000"},
      {with([](GenerateOptions& o) {
         o.target_tets = 100;
         o.max_volume = 1;
       }),
       "not both"},
      {with([](GenerateOptions& o) { o.quality = 1.0; }), "not 1"},
      {with([](GenerateOptions& o) { o.quality = std::nan(""); }), "nan"},
      {with([](GenerateOptions& o) { o.sphere_level = 9; }), "9"},
      {with([](GenerateOptions& o) { o.sphere_level = -1; }), "-1"},
  };
  for (const Case& c : cases) {
    TetMesh mesh;
    const Status status = generate_model(Model::kMotor, c.options, &mesh);
    ASSERT_FALSE(status.ok()) << c.needle;
    EXPECT_NE(status.message().find(c.needle), std::string::npos) << status.message();
  }
}

TEST(Tetrahedralize, UnseededRegionIsAnError) {
  Plc plc = build_box2_plc();
  plc.regions.pop_back();
  TetMesh mesh;
  const Status status = tetrahedralize_plc(plc, {0.1, 2.0}, &mesh);
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.message().find("no seed"), std::string::npos) << status.message();
}

TEST(Tetrahedralize, BadParametersAreErrors) {
  const Plc plc = build_box2_plc();
  TetMesh mesh;
  EXPECT_FALSE(tetrahedralize_plc(plc, {0.0, 2.0}, &mesh).ok());
  EXPECT_FALSE(tetrahedralize_plc(plc, {0.1, 1.0}, &mesh).ok());
  EXPECT_FALSE(tetrahedralize_plc(Plc(), {0.1, 2.0}, &mesh).ok());
  Plc broken = plc;
  broken.polygon_vertices[0] = 1000;
  EXPECT_FALSE(tetrahedralize_plc(broken, {0.1, 2.0}, &mesh).ok());
}

// A facet that pierces another one: TetGen throws, the caller gets a Status.
TEST(Tetrahedralize, IntersectingFacetsAreAnError) {
  Plc plc = build_box2_plc();
  const uint32_t a = plc.add_point({0.5, 0.5, -0.5});
  const uint32_t b = plc.add_point({0.5, 0.5, 1.5});
  const uint32_t c = plc.add_point({0.5, 1.5, 0.5});
  plc.add_facet({a, b, c}, 9);
  TetMesh mesh;
  const Status status = tetrahedralize_plc(plc, {0.1, 2.0}, &mesh);
  EXPECT_FALSE(status.ok());
  EXPECT_NE(status.message().find("TetGen"), std::string::npos) << status.message();
}

}  // namespace
}  // namespace tetlod
