#pragma once
// A colour bar with its numbers (PNG via an Image, and SVG), so a picture of a coloured mesh can be
// read without the tool: the scale of metric/colormap.h over [lo, hi], ticks and a title.
#include <string>

#include "metric/colormap.h"
#include "metric/texture_image.h"

namespace meshdev {

struct ColorBarOptions {
  ColorScale scale = ColorScale::kPaper;
  double lo = 0, hi = 1;  // the range the mesh was coloured with (values outside were clamped)
  std::string title;      // e.g. "geometry (mesh units), A -> B"
  int width = 640;        // pixels (PNG) or user units (SVG)
  int ticks = 5;          // labelled values, evenly spaced from lo to hi (at least 2)
};

// The bar as an RGB image (white background, title above, ticks and numbers below; numbers with 4
// significant digits). O(width x height).
Image colorbar_image(const ColorBarOptions& options);

// The same bar as a standalone SVG document (a linear gradient with 33 stops). O(ticks).
std::string colorbar_svg(const ColorBarOptions& options);

// A tick label: 4 significant digits, like "0.0123", "1.5e-05". O(1).
std::string format_tick(double value);

}  // namespace meshdev
