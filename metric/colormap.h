#pragma once
// Colour scales for deviation values.
#include <string>

#include "metric/vec3.h"

namespace meshdev {

enum class ColorScale {
  kPaper,    // Fig. 4 of the paper: blue (minimum) -> green (middle) -> red (maximum), through
             // cyan and yellow as MeshDev 0.5 did (5 stops)
  kViridis,  // perceptually uniform (matplotlib's viridis), dark purple -> yellow
  kTurbo,    // Google's turbo rainbow, blue -> red
};

// sRGB colour in [0,1]^3 of `value` on `scale` over [lo, hi] (values outside are clamped; a
// NaN or an empty range gives the middle colour). O(1).
Vec3 map_color(double value, double lo, double hi, ColorScale scale = ColorScale::kPaper);

// A colour range given by a user (--range LO HI, a fixed range of ColoringOptions or
// AtlasOptions): throws InvalidInput unless both ends are finite and lo < hi. (map_color takes
// any range: NaN or reversed ends gave a mesh of one colour without a word.) O(1).
void check_color_range(double lo, double hi);

// Parses "paper", "viridis", "turbo"; throws InvalidInput otherwise.
ColorScale parse_color_scale(const std::string& name);

}  // namespace meshdev
