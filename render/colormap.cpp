#include "render/colormap.h"

#include <algorithm>
#include <cmath>

namespace tetlod::render {

Rgb colormap_rgb(ColorMap map, double t) {
  t = std::clamp(t, 0.0, 1.0);
  if (map == ColorMap::kTurbo) {
    const double t2 = t * t, t3 = t2 * t, t4 = t2 * t2, t5 = t4 * t;
    auto poly = [&](double c0, double c1, double c2, double c3, double c4, double c5) {
      return static_cast<float>(
          std::clamp(c0 + c1 * t + c2 * t2 + c3 * t3 + c4 * t4 + c5 * t5, 0.0, 1.0));
    };
    return {poly(0.13572138, 4.61539260, -42.66032258, 132.13108234, -152.94239396, 59.28637943),
            poly(0.09140261, 2.19418839, 4.84296658, -14.18503333, 4.27729857, 2.82956604),
            poly(0.10667330, 12.64194608, -60.58204836, 110.36276771, -89.90310912, 27.34824973)};
  }
  static constexpr double kViridis[7][3] = {
      {0.2777273272234177, 0.005407344544966578, 0.3340998053353061},
      {0.1050930431085774, 1.404613529898575, 1.384590162594685},
      {-0.3308618287255563, 0.214847559468213, 0.09509516302823659},
      {-4.634230498983486, -5.799100973351585, -19.33244095627987},
      {6.228269936347081, 14.17993336680509, 56.69055260068105},
      {4.776384997670288, -13.74514537774601, -65.35303263337234},
      {-5.435455855934631, 4.645852612178535, 26.3124352495832}};
  Rgb rgb;
  for (int c = 0; c < 3; ++c) {
    double v = kViridis[6][c];
    for (int k = 5; k >= 0; --k) v = kViridis[k][c] + t * v;
    rgb[c] = static_cast<float>(std::clamp(v, 0.0, 1.0));
  }
  return rgb;
}

Rgb generated_rgb(uint32_t k) {
  // Hue, saturation and value from the R3 low-discrepancy sequence (the plastic number's
  // powers): any two of the first few hundred differ in at least one by a good step (a
  // golden angle of hue alone came back near every 144th).
  constexpr double g = 1.22074408460575947536;
  const double h = 6 * std::fmod(0.13 + k / g, 1.0);
  const double sat = 0.45 + 0.45 * std::fmod(0.5 + k / (g * g), 1.0);
  const double val = 0.55 + 0.4 * std::fmod(0.5 + k / (g * g * g), 1.0);
  const int sector = static_cast<int>(h) % 6;
  const double f = h - std::floor(h);
  const double p = val * (1 - sat), q = val * (1 - sat * f), t = val * (1 - sat * (1 - f));
  const double rgb[6][3] = {{val, t, p}, {q, val, p}, {p, val, t},
                            {p, q, val}, {t, p, val}, {val, p, q}};
  return {static_cast<float>(rgb[sector][0]), static_cast<float>(rgb[sector][1]),
          static_cast<float>(rgb[sector][2])};
}

Rgb material_rgb(int32_t material) {
  static constexpr Rgb kPalette[kPaletteSize] = {
      {0.306f, 0.475f, 0.655f},
      {0.949f, 0.557f, 0.169f},
      {0.882f, 0.341f, 0.349f},
      {0.463f, 0.718f, 0.698f},
      {0.349f, 0.631f, 0.310f},
      {0.929f, 0.788f, 0.282f},
      {0.690f, 0.478f, 0.631f},
      {1.000f, 0.616f, 0.655f},
      {0.612f, 0.459f, 0.373f},
      {0.729f, 0.690f, 0.675f},
      // Ten more, apart from the first ten and from the highlight's magenta (a PCB has
      // fourteen materials: with ten, its 11th and 1st were one orange).
      {0.102f, 0.396f, 0.439f},
      {0.553f, 0.553f, 0.141f},
      {0.192f, 0.212f, 0.525f},
      {0.647f, 0.110f, 0.247f},
      {0.659f, 0.871f, 0.365f},
      {0.447f, 0.247f, 0.651f},
      {0.553f, 0.808f, 0.961f},
      {0.749f, 0.396f, 0.133f},
      {0.392f, 0.392f, 0.416f},
      {0.741f, 0.918f, 0.780f}};
  const int32_t index = material < 0 ? 0 : material % kColorCycle;
  if (index < kPaletteSize) return kPalette[index];
  return generated_rgb(uint32_t(index - kPaletteSize));
}

}  // namespace tetlod::render
