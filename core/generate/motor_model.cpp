// motor: an interior permanent-magnet motor after the cross-section of Date et al.
// (IEEE Trans. Magn., Fig. 4), as a planar straight-line graph in the xy plane that is
// extruded over |z| <= kMotorHalfLength inside an air box.
//
// Cross-section, from the axis outwards:
//   shaft disk (kMotorShaftSegments-gon) | rotor iron with kMotorPoleCount rectangular
//   magnets on the pole axes | rotor circle (kMotorGapSegments-gon) | air gap | stator
//   bore: per tooth a tip arc at r = 26.5, two radial shoe sides up to r = 28.5 and, across
//   each slot opening, the straight coil bottom | coils | parallel-sided teeth and the
//   yoke | stator outer circle (kMotorOuterSegments-gon) | air.
// Each coil touches iron on the shoe undersides, tooth sides and slot bottom, and air
// through the slot opening, which belongs to the air gap.
#include <array>
#include <cassert>
#include <cmath>
#include <vector>

#include "core/generate/model_generator.h"

namespace tetlod {
namespace {

constexpr double kPi = 3.14159265358979323846;

constexpr int32_t kBoxMarker = 1;
constexpr int32_t kCapMarker = 2;
constexpr int32_t kSideMarker = 3;

struct Point2 {
  double x = 0, y = 0;
};

Point2 polar(double radius, double angle) {
  return {radius * std::cos(angle), radius * std::sin(angle)};
}

// A point given in a frame rotated by `angle`: u along the rotated x axis, v along y.
Point2 rotated(double u, double v, double angle) {
  const double c = std::cos(angle);
  const double s = std::sin(angle);
  return {u * c - v * s, u * s + v * c};
}

// The number of segments for an arc of `angle` radians, about as fine as a circle of
// `circle_segments`.
int arc_segments(double angle, int circle_segments) {
  const double step = 2.0 * kPi / circle_segments;
  return std::max(1, static_cast<int>(std::ceil(angle / step - 1e-9)));
}

// A planar straight-line graph: every segment separates two materials.
struct CrossSection {
  std::vector<Point2> points;
  std::vector<std::array<uint32_t, 2>> segments;
  std::vector<uint32_t> outer_loop;  // the boundary of the extruded motor
  std::vector<Point2> seeds;
  std::vector<int32_t> seed_materials;

  uint32_t add_point(const Point2& p) {
    points.push_back(p);
    return static_cast<uint32_t>(points.size() - 1);
  }
  void add_chain(const std::vector<uint32_t>& ids, bool closed) {
    for (size_t i = 0; i + 1 < ids.size(); ++i) segments.push_back({ids[i], ids[i + 1]});
    if (closed) segments.push_back({ids.back(), ids.front()});
  }
  std::vector<uint32_t> add_circle(double radius, int segment_count) {
    std::vector<uint32_t> ids;
    for (int i = 0; i < segment_count; ++i) {
      ids.push_back(add_point(polar(radius, 2.0 * kPi * i / segment_count)));
    }
    add_chain(ids, true);
    return ids;
  }
  void add_seed(const Point2& p, int32_t material) {
    seeds.push_back(p);
    seed_materials.push_back(material);
  }
};

void add_rotor(CrossSection* section) {
  section->add_circle(kMotorShaftRadius, kMotorShaftSegments);
  section->add_seed({0, 0}, kMotorShaft);
  section->add_circle(kMotorRotorRadius, kMotorGapSegments);
  // Between the shaft and the magnets on the pole axis at angle 0.
  const double magnet_inner = kMotorMagnetCenterRadius - 0.5 * kMotorMagnetThickness;
  section->add_seed({0.5 * (kMotorShaftRadius + magnet_inner), 0}, kMotorRotorIron);

  const double u0 = kMotorMagnetCenterRadius - 0.5 * kMotorMagnetThickness;
  const double u1 = kMotorMagnetCenterRadius + 0.5 * kMotorMagnetThickness;
  const double v = 0.5 * kMotorMagnetWidth;
  for (int pole = 0; pole < kMotorPoleCount; ++pole) {
    const double angle = 2.0 * kPi * pole / kMotorPoleCount;
    std::vector<uint32_t> ids = {
        section->add_point(rotated(u0, -v, angle)), section->add_point(rotated(u1, -v, angle)),
        section->add_point(rotated(u1, v, angle)), section->add_point(rotated(u0, v, angle))};
    section->add_chain(ids, true);
    section->add_seed(polar(kMotorMagnetCenterRadius, angle), kMotorMagnet);
  }
}

void add_stator(CrossSection* section) {
  const double pitch = 2.0 * kPi / kMotorSlotCount;
  const double opening = 2.0 * std::asin(0.5 * kMotorSlotOpening / kMotorStatorInnerRadius);
  const double tip = 0.5 * (pitch - opening);  // half-angle of a tooth tip
  const double half_width = 0.5 * kMotorToothWidth;
  const double yoke_u =
      std::sqrt(kMotorYokeInnerRadius * kMotorYokeInnerRadius - half_width * half_width);
  const double yoke_half_angle = std::asin(half_width / kMotorYokeInnerRadius);
  const double body_u = kMotorShoeRadius * std::cos(tip) + kMotorShoeTaper;
  assert(kMotorShoeRadius * std::sin(tip) > half_width);
  const int tip_segments = arc_segments(2.0 * tip, kMotorGapSegments);
  const int yoke_segments = arc_segments(pitch - 2.0 * yoke_half_angle, kMotorOuterSegments);

  // Per tooth: shoe corners, tip arc, body corners and yoke corners (- before +).
  struct Tooth {
    uint32_t shoe_minus, shoe_plus, body_minus, body_plus, yoke_minus, yoke_plus;
  };
  std::vector<Tooth> teeth(kMotorSlotCount);
  std::vector<uint32_t> bore;  // the closed stator bore, counter-clockwise
  for (int k = 0; k < kMotorSlotCount; ++k) {
    const double angle = pitch * k;
    Tooth& tooth = teeth[k];
    tooth.shoe_minus = section->add_point(polar(kMotorShoeRadius, angle - tip));
    bore.push_back(tooth.shoe_minus);
    for (int i = 0; i <= tip_segments; ++i) {
      const double a = angle - tip + 2.0 * tip * i / tip_segments;
      bore.push_back(section->add_point(polar(kMotorStatorInnerRadius, a)));
    }
    tooth.shoe_plus = section->add_point(polar(kMotorShoeRadius, angle + tip));
    bore.push_back(tooth.shoe_plus);
    tooth.body_minus = section->add_point(rotated(body_u, -half_width, angle));
    tooth.body_plus = section->add_point(rotated(body_u, half_width, angle));
    tooth.yoke_minus = section->add_point(rotated(yoke_u, -half_width, angle));
    tooth.yoke_plus = section->add_point(rotated(yoke_u, half_width, angle));
  }
  section->add_chain(bore, true);  // includes each coil bottom, shoe_plus -> next shoe_minus
  section->add_seed({0.5 * (kMotorRotorRadius + kMotorStatorInnerRadius), 0}, kMotorAirGap);

  // Slot k lies between tooth k and tooth k + 1.
  for (int k = 0; k < kMotorSlotCount; ++k) {
    const Tooth& left = teeth[k];
    const Tooth& right = teeth[(k + 1) % kMotorSlotCount];
    std::vector<uint32_t> coil = {left.shoe_plus, left.body_plus, left.yoke_plus};
    const double a0 = pitch * k + yoke_half_angle;
    const double a1 = pitch * (k + 1) - yoke_half_angle;
    for (int i = 1; i < yoke_segments; ++i) {
      coil.push_back(
          section->add_point(polar(kMotorYokeInnerRadius, a0 + (a1 - a0) * i / yoke_segments)));
    }
    coil.insert(coil.end(), {right.yoke_minus, right.body_minus, right.shoe_minus});
    section->add_chain(coil, false);  // the coil bottom is part of the bore
    section->add_seed(polar(0.5 * (body_u + kMotorYokeInnerRadius), pitch * (k + 0.5)), kMotorCoil);
  }
  section->add_seed({0.5 * (kMotorYokeInnerRadius + kMotorStatorOuterRadius), 0}, kMotorStatorIron);
}

CrossSection make_cross_section() {
  CrossSection section;
  section.outer_loop = section.add_circle(kMotorStatorOuterRadius, kMotorOuterSegments);
  add_rotor(&section);
  add_stator(&section);
  return section;
}

}  // namespace

Plc build_motor_plc() {
  const CrossSection section = make_cross_section();
  const uint32_t n = static_cast<uint32_t>(section.points.size());
  const double z0 = -kMotorHalfLength;
  const double z1 = kMotorHalfLength;

  Plc plc;
  // Point i of the section at z0 is i, at z1 is n + i; then the box corners.
  for (const Point2& p : section.points) plc.add_point({p.x, p.y, z0});
  for (const Point2& p : section.points) plc.add_point({p.x, p.y, z1});

  // The two caps: the outer loop, then every other segment as a two-point polygon.
  const size_t outer_segments = section.outer_loop.size();
  for (uint32_t offset : {0u, n}) {
    std::vector<uint32_t> loop = section.outer_loop;
    for (uint32_t& v : loop) v += offset;
    plc.add_polygon(loop);
    for (size_t s = outer_segments; s < section.segments.size(); ++s) {
      plc.add_polygon({section.segments[s][0] + offset, section.segments[s][1] + offset});
    }
    plc.close_facet(kCapMarker);
  }
  // One vertical quad per segment.
  for (const auto& s : section.segments) {
    plc.add_facet({s[0], s[1], s[1] + n, s[0] + n}, kSideMarker);
  }

  const double w = kMotorBoxHalfWidth;
  const double h = kMotorBoxHalfHeight;
  const uint32_t first = static_cast<uint32_t>(plc.points.size());
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i) plc.add_point({i ? w : -w, j ? w : -w, k ? h : -h});
  auto corner = [first](uint32_t i, uint32_t j, uint32_t k) { return first + i + 2 * j + 4 * k; };
  for (uint32_t s = 0; s < 2; ++s) {
    plc.add_facet({corner(s, 0, 0), corner(s, 1, 0), corner(s, 1, 1), corner(s, 0, 1)}, kBoxMarker);
    plc.add_facet({corner(0, s, 0), corner(1, s, 0), corner(1, s, 1), corner(0, s, 1)}, kBoxMarker);
    plc.add_facet({corner(0, 0, s), corner(1, 0, s), corner(1, 1, s), corner(0, 1, s)}, kBoxMarker);
  }

  for (size_t i = 0; i < section.seeds.size(); ++i) {
    plc.add_region({section.seeds[i].x, section.seeds[i].y, 0.0}, section.seed_materials[i]);
  }
  // Air: a box corner region, outside the motor in xy.
  plc.add_region({0.5 * (kMotorStatorOuterRadius + w), 0.5 * (kMotorStatorOuterRadius + w), 0.0},
                 kMotorAir);
  return plc;
}

}  // namespace tetlod
