// The viewer's camera: orbits a target point (z up), pans in the view plane, zooms
// by distance. Framing and axis views come from render::frame_camera, so the window
// and `tetlod render --view` agree.
#pragma once

#include "core/vec3.h"
#include "render/camera.h"

namespace tetlod::app {

class OrbitCamera {
 public:
  // Frames the box [lo, hi] from `view` (and remembers the box for near/far), in a
  // view `aspect` = width / height wide, clear of its `legend` (render::frame_camera()).
  void fit(const Vec3& lo, const Vec3& hi, render::ViewDirection view, double aspect = 1,
           const render::LegendSpace& legend = {});
  // Frames the box [lo, hi] as fit() does (target at its centre, at the distance that
  // shows it whole, clear of the legend), looking from the current direction (the Fit
  // button: only the views set a direction).
  void refit(const Vec3& lo, const Vec3& hi, double aspect = 1,
             const render::LegendSpace& legend = {});
  // Widens the box that sets the near and far planes (fit() and refit() set it to the
  // box framed) to hold [lo, hi] too: the whole model, when only some materials are
  // framed and the others may be shown again without a new framing.
  void include_in_depth(const Vec3& lo, const Vec3& hi);
  // Mouse drags in pixels; `viewport_height` in pixels scales the pan.
  void orbit(double dx, double dy);
  void pan(double dx, double dy, int viewport_height);
  // Wheel clicks: positive zooms in.
  void zoom(double clicks);

  render::Camera camera() const;
  // Whether the camera was orbited, panned or zoomed since it was last framed.
  bool moved() const { return moved_; }

 private:
  void take_framing(const Vec3& lo, const Vec3& hi, const render::Camera& framed);

  Vec3 lo_{-1, -1, -1}, hi_{1, 1, 1};
  Vec3 target_{0, 0, 0};
  double distance_ = 5;
  double yaw_ = 0, pitch_ = 0;  // radians; eye direction from the target
  double fov_y_degrees_ = 30;
  bool moved_ = false;
};

}  // namespace tetlod::app
