#include "metric/draw_text.h"

#include <cmath>
#include <vector>

#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#endif
#include <stb/stb_easy_font.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

namespace meshdev {

void draw_text(Image& image, int x, int y, const std::string& text, const Vec3& color, int scale) {
  std::vector<char> buffer(text.begin(), text.end());
  buffer.push_back('\0');
  std::vector<float> quads(text.size() * 4 * 70 * 4 + 64);  // ~70 quads per character at most
  unsigned char rgba[4] = {255, 255, 255, 255};
  const int n = stb_easy_font_print(0, 0, buffer.data(), rgba, quads.data(),
                                    static_cast<int>(quads.size() * sizeof(float)));
  // Each vertex is 16 bytes: x, y, z floats and 4 colour bytes; 4 vertices per quad.
  for (int q = 0; q < n; ++q) {
    const float* v0 = &quads[static_cast<std::size_t>(q) * 16];
    const float* v2 = v0 + 8;
    const int x0 = x + static_cast<int>(std::lround(static_cast<double>(v0[0]) * scale));
    const int y0 = y + static_cast<int>(std::lround(static_cast<double>(v0[1]) * scale));
    const int x1 = x + static_cast<int>(std::lround(static_cast<double>(v2[0]) * scale));
    const int y1 = y + static_cast<int>(std::lround(static_cast<double>(v2[1]) * scale));
    for (int py = y0; py < y1; ++py)
      for (int px = x0; px < x1; ++px) image.set(px, py, color);
  }
}

int text_width(const std::string& text, int scale) {
  std::vector<char> buffer(text.begin(), text.end());
  buffer.push_back('\0');
  return stb_easy_font_width(buffer.data()) * scale;
}

int text_height(const std::string& text, int scale) {
  std::vector<char> buffer(text.begin(), text.end());
  buffer.push_back('\0');
  return stb_easy_font_height(buffer.data()) * scale;
}

}  // namespace meshdev
