// Procedurally built multi-material test models, meshed with TetGen (see plc.h).
//
//   motor    a permanent-magnet motor after Date et al. (IEEE Trans. Magn., Fig. 4,
//            cross-section of a PM motor): shaft, rotor iron with interior rectangular
//            magnets, air gap, stator iron with teeth and slots, coils filling the slots;
//            the 2D cross-section is extruded over the motor length and sits inside an
//            air box that extends beyond it in x, y and z, so every material interface is
//            a closed surface. Millimetres.
//   spheres  concentric spheres in a box, for the two-layer spherical capacitor
//              1/C = (1/(4 pi eps2)) (1/r1 - 1/r2) + (1/(4 pi eps3)) (1/r2 - 1/r3)
//            with material 4 (outside r3) grounded. Sphere surfaces are icospheres whose
//            vertices lie on the sphere; TetGen may add Steiner points inside their flat
//            triangles, so interfaces are exactly the icosphere polyhedra.
//   box2     [0,2]x[0,1]x[0,1] split at x = 1 into materials 1 and 2, for exact tests.
//
// Same model and options give the same mesh, bit for bit.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/generate/plc.h"
#include "core/status.h"
#include "core/tet_mesh.h"

namespace tetlod {

enum class Model { kMotor, kSpheres, kBox2 };

// ---- motor: material ids -------------------------------------------------------
inline constexpr int32_t kMotorAir = 1;         // surrounding air box
inline constexpr int32_t kMotorAirGap = 2;      // gap between rotor and stator, with slot openings
inline constexpr int32_t kMotorShaft = 3;       // non-magnetic shaft
inline constexpr int32_t kMotorRotorIron = 4;   // rotor lamination
inline constexpr int32_t kMotorMagnet = 5;      // the kMotorPoleCount magnets (one component each)
inline constexpr int32_t kMotorStatorIron = 6;  // stator yoke and teeth
inline constexpr int32_t kMotorCoil = 7;        // one coil per slot (one component each)

// ---- motor: geometry (mm); the motor axis is z, the cross-section is centred on it --
inline constexpr int kMotorPoleCount = 8;   // magnets
inline constexpr int kMotorSlotCount = 12;  // stator slots = teeth = coils
inline constexpr double kMotorShaftRadius = 6.0;
inline constexpr double kMotorRotorRadius = 25.0;
inline constexpr double kMotorStatorInnerRadius = 26.5;  // tooth tips; air gap 1.5 mm
inline constexpr double kMotorShoeRadius = 28.5;         // tooth shoe depth / coil bottom
inline constexpr double kMotorYokeInnerRadius = 41.0;    // slot bottom
inline constexpr double kMotorStatorOuterRadius = 50.0;
inline constexpr double kMotorToothWidth = 6.0;           // parallel-sided tooth body
inline constexpr double kMotorShoeTaper = 1.5;            // radial rise of the shoe underside
inline constexpr double kMotorSlotOpening = 3.0;          // chord between tooth tips
inline constexpr double kMotorMagnetWidth = 12.0;         // tangential
inline constexpr double kMotorMagnetThickness = 3.0;      // radial
inline constexpr double kMotorMagnetCenterRadius = 20.0;  // magnet centre, on the pole axis
inline constexpr double kMotorHalfLength = 20.0;          // motor occupies |z| <= 20
inline constexpr double kMotorBoxHalfWidth = 60.0;        // air box |x|, |y| <= 60
inline constexpr double kMotorBoxHalfHeight = 30.0;       // air box |z| <= 30
// Circles are regular polygons with a vertex at angle 0; arcs are split as finely.
inline constexpr int kMotorGapSegments = 72;    // rotor circle and tooth tip arcs
inline constexpr int kMotorOuterSegments = 48;  // stator outer circle and slot bottoms
inline constexpr int kMotorShaftSegments = 16;

// ---- spheres: material ids and geometry (no units) -----------------------------
inline constexpr int32_t kSpheresCore = 1;   // r < r1
inline constexpr int32_t kSpheresInner = 2;  // r1 < r < r2 (permittivity eps2)
inline constexpr int32_t kSpheresOuter = 3;  // r2 < r < r3 (permittivity eps3)
inline constexpr int32_t kSpheresBox = 4;    // outside r3, inside the box (ground)
inline constexpr double kSpheresRadius1 = 1.0;
inline constexpr double kSpheresRadius2 = 2.0;
inline constexpr double kSpheresRadius3 = 3.0;
inline constexpr double kSpheresBoxHalfWidth = 4.0;  // box [-4, 4]^3
inline constexpr int kDefaultSphereLevel = 3;        // 20 * 4^3 = 1280 triangles per sphere
inline constexpr int kMaxSphereLevel = 5;

// ---- box2: material ids and geometry -------------------------------------------
inline constexpr int32_t kBox2Left = 1;   // [0,1]x[0,1]x[0,1]
inline constexpr int32_t kBox2Right = 2;  // [1,2]x[0,1]x[0,1]

// ---- density limits -------------------------------------------------------------
inline constexpr double kMinQuality = 1.2;  // smaller radius-edge bounds may not terminate
inline constexpr double kMaxQuality = 100.0;
inline constexpr double kDefaultQuality = 2.0;  // TetGen's default for `q`
inline constexpr size_t kMaxTets = 10'000'000;  // refuse requests estimated above this

struct GenerateOptions {
  // At most one of these is set (> 0); with neither, the model's default density
  // (the one of the committed asset) is used.
  double max_volume = 0;                   // TetGen `a`, in the model's units cubed
  size_t target_tets = 0;                  // aim for this many tets, see generate_model
  double quality = kDefaultQuality;        // radius-edge ratio bound, TetGen `q`
  int sphere_level = kDefaultSphereLevel;  // icosphere subdivisions, spheres only
};

struct GenerateInfo {
  double max_volume = 0;  // the volume bound of the returned mesh
  int meshing_runs = 0;   // TetGen runs (up to 4 when aiming at target_tets)
};

// "motor", "spheres", "box2".
const char* model_name(Model model);
// False if `name` is not a model name.
bool parse_model_name(const std::string& name, Model* model);

// Checks the options for `model`: finite positive values, quality in
// [kMinQuality, kMaxQuality], sphere level in [0, kMaxSphereLevel], not both densities,
// no request estimated above kMaxTets. Messages name the offending value.
Status check_generate_options(Model model, const GenerateOptions& options);

// Builds the model's PLC (sphere_level is used by spheres only).
Plc build_model_plc(Model model, const GenerateOptions& options);
Plc build_motor_plc();
Plc build_spheres_plc(int sphere_level);
Plc build_box2_plc();

// The exact volume of the model's domain (the bounding box for every model).
double model_domain_volume(Model model);

// Meshes the model. On success `mesh` passed validate_mesh() without repairs and its
// first points are the PLC's points, unchanged. With options.target_tets, TetGen runs
// up to 4 times with volume bounds fitted to the counts it returned, stopping within
// 15 % of the target, and the closest mesh is kept; a target below what the model's
// features need (motor about 23k, spheres about 15k at level 3) gives that minimum.
Status generate_model(Model model, const GenerateOptions& options, TetMesh* mesh,
                      GenerateInfo* info = nullptr);

// An icosphere: the icosahedron subdivided `level` times (each triangle into four),
// every vertex normalized and scaled to `radius`, so all vertices lie on the sphere up
// to rounding. Triangles are oriented outwards. 20 * 4^level triangles,
// 10 * 4^level + 2 vertices.
struct Icosphere {
  std::vector<Vec3> vertices;
  std::vector<std::array<uint32_t, 3>> triangles;
};
Icosphere make_icosphere(int level, double radius);

}  // namespace tetlod
