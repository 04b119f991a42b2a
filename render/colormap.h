// Colour maps for per-tet scalars (perceptual, monotone in lightness where the map
// allows) and the categorical material palette. Values are linear 0..1 RGB.
#pragma once

#include <array>
#include <cstdint>

namespace tetlod::render {

enum class ColorMap { kViridis, kTurbo };

using Rgb = std::array<float, 3>;

// The map at t in [0, 1] (clamped). Viridis and Turbo from their published
// polynomial fits (M. Zucker's viridis fit; A. Mikhailov, Google, 2019, for Turbo).
Rgb colormap_rgb(ColorMap map, double t);

// Colour of a material id (ids >= 0): a 20-colour qualitative palette for ids 0-19,
// then generated_rgb(id - 20) up to kColorCycle - 1, cycled after that: two materials
// share a colour only kColorCycle ids apart (ids 1 and 21 of a 24-material motor were
// one orange).
inline constexpr int kPaletteSize = 20;
inline constexpr int kColorCycle = 256;  // the shader's palette (surface.frag)
Rgb material_rgb(int32_t material);
// The k-th of a sequence of colours spread over hue, saturation and value, none near
// another in the first few hundred (material and surface group colours past their
// palettes).
Rgb generated_rgb(uint32_t k);

// The colour of highlighted (low-stretch) tets; in neither colour map.
inline constexpr Rgb kHighlightRgb = {1.0f, 0.1f, 0.75f};

}  // namespace tetlod::render
