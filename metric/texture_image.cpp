#include "metric/texture_image.h"

#include <algorithm>
#include <cmath>

#include "metric/errors.h"

#define STB_IMAGE_IMPLEMENTATION
#define STBI_NO_HDR
#define STBI_NO_LINEAR
#include <stb/stb_image.h>

namespace meshdev {

Image::Image(int w, int h, const Vec3& fill) : width(w), height(h) {
  rgb.resize(static_cast<std::size_t>(std::max(w, 0)) * static_cast<std::size_t>(std::max(h, 0)) *
             3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) set(x, y, fill);
}

Vec3 Image::pixel(int x, int y) const {
  const std::uint8_t* p = &rgb[(static_cast<std::size_t>(y) * width + x) * 3];
  return {p[0] / 255.0, p[1] / 255.0, p[2] / 255.0};
}

void Image::set(int x, int y, const Vec3& c) {
  if (x < 0 || y < 0 || x >= width || y >= height) return;
  std::uint8_t* p = &rgb[(static_cast<std::size_t>(y) * width + x) * 3];
  for (int k = 0; k < 3; ++k)  // NaN as 0 (std::clamp passes it through, lround's is unspecified)
    p[k] = c[k] == c[k] ? static_cast<std::uint8_t>(std::lround(std::clamp(c[k], 0.0, 1.0) * 255.0))
                        : std::uint8_t{0};
}

Image load_image(const std::string& path) {
  int w = 0, h = 0, channels = 0;
  stbi_uc* data = stbi_load(path.c_str(), &w, &h, &channels, 3);
  if (data == nullptr)
    throw IoError(path + ": cannot read the image (" + std::string(stbi_failure_reason()) + ")");
  Image image;
  image.width = w;
  image.height = h;
  image.rgb.assign(data, data + static_cast<std::size_t>(w) * h * 3);
  stbi_image_free(data);
  return image;
}

Vec3 sample_bilinear(const Image& image, double u, double v) {
  if (image.empty()) return {0.5, 0.5, 0.5};
  u -= std::floor(u);  // repeat
  v -= std::floor(v);
  const double x = u * image.width - 0.5;
  const double y = (1.0 - v) * image.height - 0.5;
  const double fx = std::floor(x), fy = std::floor(y);
  const double ax = x - fx, ay = y - fy;
  auto wrap = [](long i, int n) { return static_cast<int>(((i % n) + n) % n); };
  const int x0 = wrap(static_cast<long>(fx), image.width);
  const int x1 = wrap(static_cast<long>(fx) + 1, image.width);
  const int y0 = wrap(static_cast<long>(fy), image.height);
  const int y1 = wrap(static_cast<long>(fy) + 1, image.height);
  return (1 - ay) * ((1 - ax) * image.pixel(x0, y0) + ax * image.pixel(x1, y0)) +
         ay * ((1 - ax) * image.pixel(x0, y1) + ax * image.pixel(x1, y1));
}

}  // namespace meshdev
