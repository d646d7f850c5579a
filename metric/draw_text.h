#pragma once
// Labels on meshdev's pictures (colour bars, renderings): ASCII text drawn with stb_easy_font
// (Debian's libstb-dev), a public-domain bitmap font made of axis-aligned quads.
#include <string>

#include "metric/texture_image.h"

namespace meshdev {

// Draws `text` with its top-left corner at pixel (x, y), each font unit `scale` pixels (the font
// is about 7 units tall). Pixels outside the image are skipped. O(characters x scale^2).
void draw_text(Image& image, int x, int y, const std::string& text, const Vec3& color,
               int scale = 2);

// Width and height in pixels that draw_text would cover. O(characters).
int text_width(const std::string& text, int scale = 2);
int text_height(const std::string& text, int scale = 2);

}  // namespace meshdev
