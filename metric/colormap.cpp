#include "metric/colormap.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <sstream>

#include "metric/errors.h"

namespace meshdev {
namespace {

struct Stop {
  double t;
  Vec3 c;
};

const Stop kPaperStops[] = {
    {0.00, {0, 0, 1}}, {0.25, {0, 1, 1}}, {0.50, {0, 1, 0}}, {0.75, {1, 1, 0}}, {1.00, {1, 0, 0}}};
// Samples of matplotlib's viridis and of turbo at t = 0, 1/8, ..., 1.
const Stop kViridisStops[] = {
    {0.000, {0.267, 0.005, 0.329}}, {0.125, {0.283, 0.141, 0.458}}, {0.250, {0.254, 0.265, 0.530}},
    {0.375, {0.207, 0.372, 0.553}}, {0.500, {0.164, 0.471, 0.558}}, {0.625, {0.128, 0.567, 0.551}},
    {0.750, {0.135, 0.659, 0.518}}, {0.875, {0.478, 0.821, 0.318}}, {1.000, {0.993, 0.906, 0.144}}};
const Stop kTurboStops[] = {
    {0.000, {0.190, 0.072, 0.232}}, {0.125, {0.275, 0.404, 0.867}}, {0.250, {0.158, 0.683, 0.975}},
    {0.375, {0.102, 0.895, 0.714}}, {0.500, {0.643, 0.989, 0.235}}, {0.625, {0.937, 0.835, 0.212}},
    {0.750, {0.984, 0.508, 0.125}}, {0.875, {0.832, 0.200, 0.029}}, {1.000, {0.480, 0.016, 0.011}}};

template <std::size_t N>
Vec3 lerp_stops(const Stop (&stops)[N], double t) {
  for (std::size_t i = 1; i < N; ++i)
    if (t <= stops[i].t) {
      const double u = (t - stops[i - 1].t) / (stops[i].t - stops[i - 1].t);
      return (1.0 - u) * stops[i - 1].c + u * stops[i].c;
    }
  return stops[N - 1].c;
}

}  // namespace

Vec3 map_color(double value, double lo, double hi, ColorScale scale) {
  double t = 0.5;
  if (hi > lo && std::isfinite(value)) t = std::clamp((value - lo) / (hi - lo), 0.0, 1.0);
  switch (scale) {
    case ColorScale::kViridis:
      return lerp_stops(kViridisStops, t);
    case ColorScale::kTurbo:
      return lerp_stops(kTurboStops, t);
    case ColorScale::kPaper:
      break;
  }
  return lerp_stops(kPaperStops, t);
}

void check_color_range(double lo, double hi) {
  if (std::isfinite(lo) && std::isfinite(hi) && lo < hi) return;
  std::ostringstream m;
  m << "colour range [" << lo << ", " << hi << "]: both ends must be finite, the first below the "
    << "second";
  throw InvalidInput(m.str());
}

ColorScale parse_color_scale(const std::string& name) {
  if (name == "paper") return ColorScale::kPaper;
  if (name == "viridis") return ColorScale::kViridis;
  if (name == "turbo") return ColorScale::kTurbo;
  throw InvalidInput("unknown colour scale '" + name + "' (use paper, viridis or turbo)");
}

}  // namespace meshdev
