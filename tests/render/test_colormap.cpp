// Colour maps against published reference values, and the embedded shaders.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

#include "render/colormap.h"
#include "render/embedded_shaders.h"

namespace tetlod::render {
namespace {

// matplotlib's viridis at 0, 0.25, 0.5, 0.75, 1.
TEST(Colormap, ViridisMatchesReferenceValues) {
  const double t[5] = {0, 0.25, 0.5, 0.75, 1};
  const Rgb reference[5] = {{0.267f, 0.005f, 0.329f},
                            {0.229f, 0.322f, 0.546f},
                            {0.128f, 0.567f, 0.551f},
                            {0.369f, 0.789f, 0.383f},
                            {0.993f, 0.906f, 0.144f}};
  for (int i = 0; i < 5; ++i) {
    const Rgb c = colormap_rgb(ColorMap::kViridis, t[i]);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(c[k], reference[i][k], 0.02) << "t " << t[i];
  }
}

double luminance(const Rgb& c) {
  return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
}

TEST(Colormap, ViridisGetsLighterAndTurboPeaksInTheMiddle) {
  double previous = -1;
  for (int i = 0; i <= 100; ++i) {
    const double l = luminance(colormap_rgb(ColorMap::kViridis, i / 100.0));
    EXPECT_GT(l, previous) << i;
    previous = l;
  }
  const double ends = std::max(luminance(colormap_rgb(ColorMap::kTurbo, 0)),
                               luminance(colormap_rgb(ColorMap::kTurbo, 1)));
  EXPECT_GT(luminance(colormap_rgb(ColorMap::kTurbo, 0.5)), ends + 0.4);
  // Clamped outside [0, 1].
  EXPECT_EQ(colormap_rgb(ColorMap::kTurbo, -3), colormap_rgb(ColorMap::kTurbo, 0));
  EXPECT_EQ(colormap_rgb(ColorMap::kViridis, 7), colormap_rgb(ColorMap::kViridis, 1));
}

TEST(Colormap, MaterialsGetDistinctColoursAndHighlightStandsOut) {
  for (int a = 0; a < kPaletteSize; ++a)
    for (int b = a + 1; b < kPaletteSize; ++b) EXPECT_NE(material_rgb(a), material_rgb(b));
  // Past the palette, other colours, none of them twice before the cycle: ids 1 and 21
  // are not one orange, nor 4 and 24 one green.
  for (int a = 0; a < kColorCycle; ++a) {
    for (int b = a + 1; b < kColorCycle; ++b)
      EXPECT_NE(material_rgb(a), material_rgb(b)) << a << " " << b;
    for (const float c : material_rgb(a)) EXPECT_TRUE(c >= 0 && c <= 1) << a;
  }
  const auto apart = [](const Rgb& x, const Rgb& y) {
    return std::abs(x[0] - y[0]) + std::abs(x[1] - y[1]) + std::abs(x[2] - y[2]);
  };
  EXPECT_GT(apart(material_rgb(1), material_rgb(21)), 0.3);
  EXPECT_GT(apart(material_rgb(4), material_rgb(24)), 0.3);
  // Past the palette none is near another (golden-angle hues alone came back near every
  // 144th: ids 28 and 172 differed by under 10 of 255 in each channel).
  double nearest = 3;
  for (int a = kPaletteSize; a < kColorCycle; ++a)
    for (int b = a + 1; b < kColorCycle; ++b)
      nearest = std::min(nearest, double(apart(material_rgb(a), material_rgb(b))));
  EXPECT_GT(nearest, 20 / 255.0);
  EXPECT_EQ(material_rgb(3), material_rgb(3 + kColorCycle));
  for (int i = 0; i <= 20; ++i)
    for (const ColorMap map : {ColorMap::kViridis, ColorMap::kTurbo}) {
      const Rgb c = colormap_rgb(map, i / 20.0);
      const double distance = std::abs(c[0] - kHighlightRgb[0]) +
                              std::abs(c[1] - kHighlightRgb[1]) + std::abs(c[2] - kHighlightRgb[2]);
      EXPECT_GT(distance, 0.5) << i;
    }
}

TEST(EmbeddedShaders, AllFourAreInTheBinary) {
  for (const char* name : {"surface.vert", "surface.frag", "overlay.vert", "overlay.frag"}) {
    const char* source = embedded_shader(name);
    ASSERT_NE(source, nullptr) << name;
    EXPECT_EQ(std::strncmp(source, "#version 330 core", 17), 0) << name;
    EXPECT_NE(std::string(source).find("void main()"), std::string::npos) << name;
  }
  EXPECT_EQ(embedded_shader("missing.frag"), nullptr);
}

}  // namespace
}  // namespace tetlod::render
