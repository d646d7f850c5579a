#pragma once
// An 8-bit RGB image: textures read from PNG/JPEG (stb_image, Debian's libstb-dev), and the
// pictures meshdev makes (deviation atlas, colour bar, renderings), written by metric/io/write_png.
#include <cstdint>
#include <string>
#include <vector>

#include "metric/vec3.h"

namespace meshdev {

struct Image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;  // row-major, top row first, 3 bytes per pixel

  Image() = default;
  Image(int w, int h, const Vec3& fill = {1, 1, 1});
  bool empty() const { return width <= 0 || height <= 0; }
  // Pixel (x, y) as sRGB in [0,1]; (0, 0) is the top-left pixel. Precondition: inside.
  Vec3 pixel(int x, int y) const;
  // Sets pixel (x, y) from sRGB in [0,1] (clamped, rounded; NaN as 0); ignores pixels outside.
  void set(int x, int y, const Vec3& c);
};

// Reads a PNG, JPEG, BMP or TGA file (anything stb_image reads) as RGB (alpha dropped, grey
// expanded). Throws IoError naming the file and stb's reason. O(pixels).
Image load_image(const std::string& path);

// Colour of `image` at texture coordinates (u, v), bilinear between texel centres, as sRGB in
// [0,1]. OpenGL/OBJ convention: v = 0 is the bottom row, texel (x, y) has its centre at
// ((x + 0.5)/W, 1 - (y + 0.5)/H). Coordinates outside [0,1] wrap (GL_REPEAT, OBJ's default).
// Interpolates the stored sRGB values (as viewers without sRGB decoding do). O(1).
Vec3 sample_bilinear(const Image& image, double u, double v);

}  // namespace meshdev
