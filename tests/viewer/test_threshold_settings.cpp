// The threshold panel's settings and core parameters: from_simplify_params() (a
// history's saved thresholds shown in the panel) gives back, through
// to_simplify_params(), the parameters it was given, in every sizing mode the panel
// has; and it declines what the panel cannot hold.
#include <gtest/gtest.h>

#include <cstring>
#include <limits>

#include "core/simplify.h"
#include "ui/viewer_ui.h"

namespace tetlod {
namespace {

// Through the panel and back (doubles: any value comes back).
SimplifyParams round_trip(const SimplifyParams& p) {
  ui::ThresholdSettings settings;
  EXPECT_TRUE(ui::from_simplify_params(p, &settings));
  SimplifyParams back;
  std::string error;
  EXPECT_TRUE(ui::to_simplify_params(settings, &back, &error)) << error;
  return back;
}

void expect_same(const SimplifyParams& a, const SimplifyParams& b) {
  EXPECT_EQ(a.tolerance, b.tolerance);
  EXPECT_EQ(a.min_stretch, b.min_stretch);
  EXPECT_EQ(a.max_valence, b.max_valence);
  EXPECT_EQ(a.subdivide, b.subdivide);
  EXPECT_EQ(a.sizing.uniform, b.sizing.uniform);
  EXPECT_EQ(a.sizing.material_sizes, b.sizing.material_sizes);
  ASSERT_EQ(a.sizing.radial.size(), b.sizing.radial.size());
  for (size_t i = 0; i < a.sizing.radial.size(); ++i)
    EXPECT_EQ(std::memcmp(&a.sizing.radial[i], &b.sizing.radial[i], sizeof a.sizing.radial[i]), 0);
  ASSERT_EQ(a.sizing.boxes.size(), b.sizing.boxes.size());
  for (size_t i = 0; i < a.sizing.boxes.size(); ++i)
    EXPECT_EQ(std::memcmp(&a.sizing.boxes[i], &b.sizing.boxes[i], sizeof a.sizing.boxes[i]), 0);
}

TEST(ThresholdSettings, HistoryThresholdsRoundTripThroughThePanel) {
  SimplifyParams uniform;
  uniform.tolerance = 0.0625;
  uniform.min_stretch = 0.25;
  uniform.max_valence = 30;
  uniform.subdivide = false;
  uniform.sizing.uniform = 12;
  expect_same(uniform, round_trip(uniform));

  SimplifyParams materials = uniform;
  materials.sizing.uniform = std::numeric_limits<double>::infinity();
  materials.sizing.material_sizes = {{1, 4}, {3, 0.5}};
  expect_same(materials, round_trip(materials));
  materials.sizing.uniform = 8;  // the "all" cap
  expect_same(materials, round_trip(materials));

  SimplifyParams region = uniform;
  SimplifyParams parsed;
  ASSERT_TRUE(parse_size_field("radial:1,2,3,0.5,0.25;axis:0,0,0,0,0,1,0.75,0.125;"
                               "box:0,0,0,1,2,3,0.375",
                               &parsed.sizing)
                  .ok());
  region.sizing.radial = parsed.sizing.radial;
  region.sizing.boxes = parsed.sizing.boxes;
  expect_same(region, round_trip(region));

  // What the panel cannot hold: left to the caller (the panel keeps its defaults).
  ui::ThresholdSettings settings;
  settings.size = 99;
  SimplifyParams both = region;
  both.sizing.material_sizes = {{1, 4}};
  EXPECT_FALSE(ui::from_simplify_params(both, &settings));
  SimplifyParams uncapped = region;
  uncapped.sizing.uniform = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(ui::from_simplify_params(uncapped, &settings));
  SimplifyParams crease = uniform;
  crease.crease_angle_degrees = 30;
  EXPECT_FALSE(ui::from_simplify_params(crease, &settings));
  EXPECT_EQ(settings.size, 99);
}

}  // namespace
}  // namespace tetlod
