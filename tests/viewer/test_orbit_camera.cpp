// The viewer's orbit camera: framing agrees with render::frame_camera, and orbit,
// pan and zoom move it as a mouse would, reversibly.
#include <gtest/gtest.h>

#include <cmath>
#include <utility>

#include "app/orbit_camera.h"
#include "render/surface_builder.h"

namespace tetlod::app {
namespace {

const Vec3 kLo{-1, -2, -0.5}, kHi{3, 2, 1.5};

void expect_near(const Vec3& a, const Vec3& b, double tolerance) {
  EXPECT_NEAR(a.x, b.x, tolerance);
  EXPECT_NEAR(a.y, b.y, tolerance);
  EXPECT_NEAR(a.z, b.z, tolerance);
}

TEST(OrbitCamera, FitMatchesTheRenderersFraming) {
  for (const render::ViewDirection view :
       {render::ViewDirection::kIso, render::ViewDirection::kX, render::ViewDirection::kY}) {
    OrbitCamera camera;
    camera.fit(kLo, kHi, view);
    const render::Camera framed = render::frame_camera(kLo, kHi, view);
    const render::Camera c = camera.camera();
    expect_near(c.eye, framed.eye, 1e-9);
    expect_near(c.target, framed.target, 1e-12);
    EXPECT_EQ(c.fov_y_degrees, framed.fov_y_degrees);
    EXPECT_GT(c.near_distance, 0);
    EXPECT_GT(c.far_distance, c.near_distance);
  }
}

// The X, Y and Z views all look from the + side of their axis: the side a default
// (unflipped) cut at the centre removes (render::CutPlane keeps dot(n, c) <= offset),
// so each shows the cut face, not the uncut shell behind it. (Y looked from -y.)
TEST(OrbitCamera, AxisViewsLookAtTheFaceADefaultCutExposes) {
  const Vec3 center = 0.5 * (kLo + kHi);
  const std::pair<render::ViewDirection, Vec3> views[] = {{render::ViewDirection::kX, {1, 0, 0}},
                                                          {render::ViewDirection::kY, {0, 1, 0}},
                                                          {render::ViewDirection::kZ, {0, 0, 1}}};
  for (const auto& [view, axis] : views) {
    const render::CutPlane cut{axis, dot(axis, center)};  // as the viewer's default cut
    OrbitCamera camera;
    camera.fit(kLo, kHi, view);
    const render::Camera c = camera.camera();
    EXPECT_GT(dot(cut.normal, c.eye), cut.offset + 0.9 * length(c.eye - c.target))
        << "view along (" << axis.x << ", " << axis.y << ", " << axis.z << ")";
  }
}

TEST(OrbitCamera, TopViewIsWellDefined) {
  OrbitCamera camera;
  camera.fit(kLo, kHi, render::ViewDirection::kZ);
  const render::Camera c = camera.camera();
  const Vec3 d = c.eye - c.target;
  EXPECT_GT(d.z, 0.99 * length(d));  // looking down
  EXPECT_LT(d.y, 0);                 // from slightly -y, so +y is up on screen
  for (const float v : render::view_matrix(c)) EXPECT_TRUE(std::isfinite(v));
}

TEST(OrbitCamera, MovesAreReversible) {
  OrbitCamera camera;
  camera.fit(kLo, kHi, render::ViewDirection::kIso);
  const render::Camera start = camera.camera();

  camera.orbit(37, -12);
  const render::Camera orbited = camera.camera();
  EXPECT_GT(length(orbited.eye - start.eye), 0.1);
  expect_near(orbited.target, start.target, 1e-12);
  EXPECT_NEAR(length(orbited.eye - orbited.target), length(start.eye - start.target), 1e-9);
  camera.orbit(-37, 12);
  expect_near(camera.camera().eye, start.eye, 1e-9);

  camera.zoom(2);
  EXPECT_LT(length(camera.camera().eye - start.target), length(start.eye - start.target));
  camera.zoom(-2);
  expect_near(camera.camera().eye, start.eye, 1e-9);

  camera.pan(10, 0, 500);
  const render::Camera panned = camera.camera();
  EXPECT_GT(length(panned.target - start.target), 0);
  expect_near(panned.eye - panned.target, start.eye - start.target, 1e-9);  // same direction
  camera.pan(-10, 0, 500);
  expect_near(camera.camera().target, start.target, 1e-9);
}

// Fit (refit) frames the box again, centre and distance as fit() gives them, from the
// direction the user orbited to: it does not turn the view back to iso (the views
// 0-3 do that).
TEST(OrbitCamera, RefitKeepsTheDirection) {
  OrbitCamera camera;
  camera.fit(kLo, kHi, render::ViewDirection::kIso);
  camera.orbit(120, -40);
  const render::Camera orbited = camera.camera();
  camera.zoom(3);
  camera.pan(30, 20, 500);
  const Vec3 lo{0, 0, 0}, hi{1, 1, 1};  // another box: the materials shown changed
  camera.refit(lo, hi);
  const render::Camera c = camera.camera();
  const render::Camera framed = render::frame_camera(lo, hi, render::ViewDirection::kIso);
  expect_near(c.target, framed.target, 1e-12);
  EXPECT_NEAR(length(c.eye - c.target), length(framed.eye - framed.target), 1e-9);
  const Vec3 before = orbited.eye - orbited.target, after = c.eye - c.target;
  expect_near(after * (1 / length(after)), before * (1 / length(before)), 1e-9);
  EXPECT_GT(length(after * (1 / length(after)) -
                   (framed.eye - framed.target) * (1 / length(framed.eye - framed.target))),
            0.1);  // not the iso direction
}

// moved(): since the last framing, any orbit, pan or zoom that changes the view; a
// framing clears it.
TEST(OrbitCamera, MovedSinceTheLastFraming) {
  OrbitCamera camera;
  camera.fit(kLo, kHi, render::ViewDirection::kIso);
  camera.orbit(0, 0);
  camera.pan(0, 0, 500);
  camera.zoom(0);
  EXPECT_FALSE(camera.moved());
  camera.zoom(1);
  EXPECT_TRUE(camera.moved());
  camera.refit(kLo, kHi);
  EXPECT_FALSE(camera.moved());
  camera.pan(3, 0, 500);
  EXPECT_TRUE(camera.moved());
  camera.fit(kLo, kHi, render::ViewDirection::kX);
  camera.orbit(0, 2);
  EXPECT_TRUE(camera.moved());
}

// Framed on a small part (the other materials hidden), the near and far planes still
// hold the whole model once include_in_depth() is given it: showing the rest again
// draws it whole (an antenna's air sphere was drawn with a hole, its far side gone).
TEST(OrbitCamera, TheDepthRangeHoldsTheWholeModel) {
  OrbitCamera camera;
  const Vec3 lo{-1, -1, -1}, hi{1, 1, 1}, big_lo{-100, -100, -100}, big_hi{100, 100, 100};
  camera.fit(lo, hi, render::ViewDirection::kX);
  const render::Camera small = camera.camera();
  const double far_corner = length(small.eye - Vec3{-100, -100, -100});
  EXPECT_LT(small.far_distance, far_corner);
  camera.include_in_depth(big_lo, big_hi);
  const render::Camera whole = camera.camera();
  EXPECT_GE(whole.far_distance, far_corner);
  EXPECT_EQ(whole.eye, small.eye);  // the view itself is as it was
  EXPECT_FALSE(camera.moved());
}

TEST(OrbitCamera, PitchIsClampedBelowTheVertical) {
  OrbitCamera camera;
  camera.fit(kLo, kHi, render::ViewDirection::kIso);
  camera.orbit(0, 1e6);
  const render::Camera c = camera.camera();
  const Vec3 d = c.eye - c.target;
  EXPECT_LT(d.z, length(d));
  for (const float v : render::view_matrix(c)) EXPECT_TRUE(std::isfinite(v));
}

}  // namespace
}  // namespace tetlod::app
