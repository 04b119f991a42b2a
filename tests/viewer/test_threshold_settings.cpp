// The threshold panel's settings and core parameters: from_simplify_params() (a
// history's saved thresholds shown in the panel) gives back, through
// to_simplify_params(), the parameters it was given, in every sizing mode the panel
// has (region rules and per-material sizes together too); and it declines what the
// panel cannot hold.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <string>

#include "core/simplify.h"
#include "core/size_map.h"
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

  // Region rules with per-material sizes (--size-field with --material-size), with
  // and without a cap, and region rules without a cap: "region and per material".
  ui::ThresholdSettings settings;
  SimplifyParams both = region;
  both.sizing.material_sizes = {{1, 4}};
  expect_same(both, round_trip(both));
  ASSERT_TRUE(ui::from_simplify_params(both, &settings));
  EXPECT_EQ(settings.sizing_mode, ui::SizingMode::kRegionAndMaterial);
  EXPECT_TRUE(settings.material_cap);
  both.sizing.uniform = std::numeric_limits<double>::infinity();
  expect_same(both, round_trip(both));
  SimplifyParams uncapped = region;
  uncapped.sizing.uniform = std::numeric_limits<double>::infinity();
  expect_same(uncapped, round_trip(uncapped));
  ASSERT_TRUE(ui::from_simplify_params(uncapped, &settings));
  EXPECT_EQ(settings.sizing_mode, ui::SizingMode::kRegionAndMaterial);
  EXPECT_FALSE(settings.material_cap);
  ASSERT_TRUE(ui::from_simplify_params(region, &settings));
  EXPECT_EQ(settings.sizing_mode, ui::SizingMode::kRegion);
  // Shown as typed, each number in its shortest text (it showed 0.20000000000000001).
  SimplifyParams tenths = uniform;
  ASSERT_TRUE(parse_size_field("box:0,0,0,0.1,0.2,0.3,0.2", &tenths.sizing).ok());
  ASSERT_TRUE(ui::from_simplify_params(tenths, &settings));
  EXPECT_EQ(settings.region_spec, "box:0,0,0,0.1,0.2,0.3,0.2");
  expect_same(tenths, round_trip(tenths));

  // What the panel cannot hold: left to the caller (the panel keeps its defaults).
  settings = ui::ThresholdSettings();
  settings.size = 99;
  SimplifyParams map_and_region = region;
  map_and_region.sizing.map = std::make_shared<SizeMap>();
  EXPECT_FALSE(ui::from_simplify_params(map_and_region, &settings));
  EXPECT_EQ(settings.size, 99);

  // A crease angle other than the default (it was declined, leaving the panel at its
  // defaults for a history made with --crease-angle).
  SimplifyParams crease = uniform;
  crease.crease_angle_degrees = 30;
  EXPECT_EQ(round_trip(crease).crease_angle_degrees, 30);
  ASSERT_TRUE(ui::from_simplify_params(crease, &settings));
  EXPECT_EQ(settings.crease_angle, 30);
  EXPECT_TRUE(ui::same_thresholds(settings, crease));
  settings.crease_angle = 40;
  EXPECT_FALSE(ui::same_thresholds(settings, crease));
}

// Several bad thresholds (as typed before the sliders clamped typed values, or given
// by a script) are all named at once, in check_params()'s words; a good set passes.
TEST(ThresholdSettings, EveryBadThresholdIsNamedAtOnce) {
  ui::ThresholdSettings settings;
  settings.stretch = 5.0;
  settings.valence = 1;
  settings.tolerance = -1;
  settings.size = 0;
  settings.crease_angle = 180;
  SimplifyParams params;
  std::string error;
  EXPECT_FALSE(ui::to_simplify_params(settings, &params, &error));
  for (const char* part : {"tolerance -1 must be", "stretch 5 must lie strictly between 0 and 1",
                           "valence 1 must be at least 4", "size must be > 0",
                           "crease angle must lie between 0 and 180 degrees"})
    EXPECT_NE(error.find(part), std::string::npos) << part << " in: " << error;
  settings.sizing_mode = ui::SizingMode::kPerMaterial;
  settings.material_sizes = {{1, 2}, {2, -3}};
  EXPECT_FALSE(ui::to_simplify_params(settings, &params, &error));
  EXPECT_NE(error.find("size of material 2 must be > 0"), std::string::npos) << error;
  EXPECT_EQ(error.find("size must be > 0"), std::string::npos) << error;  // no cap: unused
  EXPECT_NE(error.find("valence 1"), std::string::npos) << error;
  // Per material with nothing ticked: what to tick, not the size this mode does not show.
  settings = {};
  settings.sizing_mode = ui::SizingMode::kPerMaterial;
  EXPECT_FALSE(ui::to_simplify_params(settings, &params, &error));
  EXPECT_EQ(error, "no size limit given: tick a material to give it a size, or \"all\"");
  settings = {};
  EXPECT_TRUE(ui::to_simplify_params(settings, &params, &error)) << error;
  EXPECT_EQ(params.min_stretch, settings.stretch);
  EXPECT_EQ(params.sizing.uniform, settings.size);
}

// The size and tolerance sliders follow the model's extent: a model in metres (the
// user's: diagonal 0.18, defaults size 0.023 and tolerance 0.00018) and one 10^6 times
// larger get the same ranges relative to the model, with the defaults well inside. (The
// fixed ranges, size 0.1 to 100 and tolerance 0 to 5, held neither model's defaults.)
TEST(ThresholdSettings, SliderRangesFollowTheModel) {
  for (const double scale : {1.0, 1e6}) {
    const double diagonal = 0.18 * scale;
    const double size = 0.023 * scale, tolerance = 0.00018 * scale;
    const ui::SliderRange s = ui::size_slider_range(diagonal, size);
    EXPECT_DOUBLE_EQ(s.min, diagonal / 1e4);
    EXPECT_DOUBLE_EQ(s.max, diagonal);
    EXPECT_LT(s.min, size / 100);  // room on both sides, on a log scale
    EXPECT_GT(s.max, size * 5);
    const ui::SliderRange t = ui::tolerance_slider_range(diagonal, tolerance);
    EXPECT_DOUBLE_EQ(t.min, diagonal * 1e-7);
    EXPECT_DOUBLE_EQ(t.max, diagonal / 10);
    EXPECT_LT(t.min, tolerance / 100);
    EXPECT_GT(t.max, tolerance * 10);
  }
}

// A value outside the model's range (a history's, a script's) widens the range rather
// than being moved by showing it; a tolerance of 0 puts the range's start at 0.
TEST(ThresholdSettings, SliderRangesHoldTheCurrentValue) {
  EXPECT_EQ(ui::size_slider_range(10, 25).max, 25);
  EXPECT_EQ(ui::size_slider_range(10, 1e-5).min, 1e-5);
  EXPECT_EQ(ui::tolerance_slider_range(10, 3).max, 3);
  EXPECT_EQ(ui::tolerance_slider_range(10, 0).min, 0);
  // Not a length: left out (Simplify says what is wrong with it).
  EXPECT_EQ(ui::size_slider_range(10, -1).min, 1e-3);
  EXPECT_EQ(ui::size_slider_range(10, 0).min, 1e-3);
  // No mesh, or a flat one: a diagonal of 1.
  EXPECT_EQ(ui::size_slider_range(0, 0.5).max, 1);
}

// ImGui's logarithmic slider takes values below 10^-(the format's digits) as 0: the
// format has enough digits for the range's start.
TEST(ThresholdSettings, LogSliderFormatReachesTheRangesStart) {
  EXPECT_EQ(ui::log_slider_format({0.01, 100}), "%.4g");
  EXPECT_EQ(ui::log_slider_format({0.01, 100}, "cap "), "cap %.4g");
  for (const ui::SliderRange r : {ui::SliderRange{1.8e-8, 0.018}, ui::SliderRange{0, 0.018},
                                  ui::SliderRange{2.3e-13, 1e-5}}) {
    const std::string format = ui::log_slider_format(r);
    ASSERT_EQ(format.substr(0, 2), "%.");
    const int digits = std::stoi(format.substr(2));
    const double low = r.min > 0 ? r.min : r.max * 1e-7;
    EXPECT_LE(std::pow(10.0, -digits), low / 5) << format;
  }
}

}  // namespace
}  // namespace tetlod
