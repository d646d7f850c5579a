#include "metric/colorbar.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "metric/draw_text.h"

namespace meshdev {
namespace {

constexpr int kMargin = 24, kBarHeight = 36, kTextScale = 2;

std::string svg_escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '<')
      out += "&lt;";
    else if (c == '>')
      out += "&gt;";
    else if (c == '&')
      out += "&amp;";
    else
      out += c;
  }
  return out;
}

std::string hex(const Vec3& c) {
  char buf[8];
  auto b = [](double x) { return static_cast<int>(std::lround(std::clamp(x, 0.0, 1.0) * 255)); };
  std::snprintf(buf, sizeof buf, "#%02x%02x%02x", b(c.x), b(c.y), b(c.z));
  return buf;
}

double tick_value(const ColorBarOptions& o, int k, int ticks) {
  return o.lo + (o.hi - o.lo) * static_cast<double>(k) / static_cast<double>(ticks - 1);
}

}  // namespace

std::string format_tick(double value) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", value);
  return buf;
}

Image colorbar_image(const ColorBarOptions& o) {
  const int ticks = std::max(o.ticks, 2);
  const int line = text_height("0", kTextScale) + 6;
  const int width = std::max(o.width, 4 * kMargin);
  const int bar_top = kMargin + (o.title.empty() ? 0 : line + 4);
  const int height = bar_top + kBarHeight + 8 + line + kMargin / 2;
  Image image(width, height, {1, 1, 1});
  const Vec3 black{0, 0, 0};
  if (!o.title.empty()) draw_text(image, kMargin, kMargin - 6, o.title, black, kTextScale);
  const int x0 = kMargin, x1 = width - kMargin;
  for (int x = x0; x < x1; ++x) {
    const double t = (x - x0 + 0.5) / static_cast<double>(x1 - x0);
    const Vec3 c = map_color(o.lo + t * (o.hi - o.lo), o.lo, o.hi, o.scale);
    for (int y = bar_top; y < bar_top + kBarHeight; ++y) image.set(x, y, c);
  }
  for (int x = x0 - 1; x <= x1; ++x) {  // frame
    image.set(x, bar_top - 1, black);
    image.set(x, bar_top + kBarHeight, black);
  }
  for (int y = bar_top - 1; y <= bar_top + kBarHeight; ++y) {
    image.set(x0 - 1, y, black);
    image.set(x1, y, black);
  }
  for (int k = 0; k < ticks; ++k) {
    const int x = x0 + static_cast<int>(std::lround((x1 - x0 - 1) * k / double(ticks - 1)));
    for (int y = bar_top + kBarHeight; y < bar_top + kBarHeight + 6; ++y) image.set(x, y, black);
    const std::string label = format_tick(tick_value(o, k, ticks));
    const int w = text_width(label, kTextScale);
    const int lx = std::clamp(x - w / 2, 2, width - w - 2);
    draw_text(image, lx, bar_top + kBarHeight + 9, label, black, kTextScale);
  }
  return image;
}

std::string colorbar_svg(const ColorBarOptions& o) {
  const int ticks = std::max(o.ticks, 2);
  const int width = std::max(o.width, 4 * kMargin);
  const int bar_top = o.title.empty() ? 12 : 36;
  const int height = bar_top + kBarHeight + 34;
  const int x0 = kMargin, x1 = width - kMargin;
  std::ostringstream s;
  s << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
    << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width << "\" height=\"" << height
    << "\" viewBox=\"0 0 " << width << ' ' << height << "\" font-family=\"sans-serif\">\n"
    << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
    << "<defs><linearGradient id=\"scale\" x1=\"0\" x2=\"1\" y1=\"0\" y2=\"0\">\n";
  for (int k = 0; k <= 32; ++k) {
    const double t = k / 32.0;
    s << "<stop offset=\"" << t << "\" stop-color=\""
      << hex(map_color(o.lo + t * (o.hi - o.lo), o.lo, o.hi, o.scale)) << "\"/>\n";
  }
  s << "</linearGradient></defs>\n";
  if (!o.title.empty())
    s << "<text x=\"" << x0 << "\" y=\"24\" font-size=\"16\">" << svg_escape(o.title)
      << "</text>\n";
  s << "<rect x=\"" << x0 << "\" y=\"" << bar_top << "\" width=\"" << x1 - x0 << "\" height=\""
    << kBarHeight << "\" fill=\"url(#scale)\" stroke=\"black\"/>\n";
  for (int k = 0; k < ticks; ++k) {
    const double x = x0 + (x1 - x0) * k / double(ticks - 1);
    s << "<line x1=\"" << x << "\" x2=\"" << x << "\" y1=\"" << bar_top + kBarHeight << "\" y2=\""
      << bar_top + kBarHeight + 6 << "\" stroke=\"black\"/>\n"
      << "<text x=\"" << x << "\" y=\"" << bar_top + kBarHeight + 22
      << "\" font-size=\"14\" text-anchor=\""
      << (k == 0           ? "start"
          : k == ticks - 1 ? "end"
                           : "middle")
      << "\">" << format_tick(tick_value(o, k, ticks)) << "</text>\n";
  }
  s << "</svg>\n";
  return s.str();
}

}  // namespace meshdev
