#include "metric/color_space.h"

#include <algorithm>
#include <cmath>

namespace meshdev {
namespace {

constexpr double kPi = 3.14159265358979323846;

double srgb_to_linear(double c) {
  c = std::clamp(c, 0.0, 1.0);
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

double lab_f(double t) {
  constexpr double d = 6.0 / 29.0;
  return t > d * d * d ? std::cbrt(t) : t / (3 * d * d) + 4.0 / 29.0;
}

double deg(double rad) {
  return rad * 180.0 / kPi;
}
double rad(double deg) {
  return deg * kPi / 180.0;
}

}  // namespace

Vec3 srgb_to_lab(const Vec3& rgb) {
  const double r = srgb_to_linear(rgb.x), g = srgb_to_linear(rgb.y), b = srgb_to_linear(rgb.z);
  const double x = 0.4124564 * r + 0.3575761 * g + 0.1804375 * b;
  const double y = 0.2126729 * r + 0.7151522 * g + 0.0721750 * b;
  const double z = 0.0193339 * r + 0.1191920 * g + 0.9503041 * b;
  // D65 reference white.
  const double fx = lab_f(x / 0.95047), fy = lab_f(y / 1.0), fz = lab_f(z / 1.08883);
  return {116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz)};
}

double delta_e76(const Vec3& lab1, const Vec3& lab2) {
  return norm(lab1 - lab2);
}

double delta_e2000(const Vec3& lab1, const Vec3& lab2) {
  const double L1 = lab1.x, a1 = lab1.y, b1 = lab1.z;
  const double L2 = lab2.x, a2 = lab2.y, b2 = lab2.z;
  const double C1 = std::hypot(a1, b1), C2 = std::hypot(a2, b2);
  const double Cbar = 0.5 * (C1 + C2);
  const double Cbar7 = std::pow(Cbar, 7.0);
  const double G = 0.5 * (1.0 - std::sqrt(Cbar7 / (Cbar7 + std::pow(25.0, 7.0))));
  const double a1p = (1.0 + G) * a1, a2p = (1.0 + G) * a2;
  const double C1p = std::hypot(a1p, b1), C2p = std::hypot(a2p, b2);
  auto hue = [](double b, double ap) {
    if (b == 0.0 && ap == 0.0) return 0.0;
    double h = deg(std::atan2(b, ap));
    return h < 0.0 ? h + 360.0 : h;
  };
  const double h1p = hue(b1, a1p), h2p = hue(b2, a2p);
  const double dLp = L2 - L1;
  const double dCp = C2p - C1p;
  double dhp = 0.0;
  if (C1p * C2p != 0.0) {
    dhp = h2p - h1p;
    if (dhp > 180.0)
      dhp -= 360.0;
    else if (dhp < -180.0)
      dhp += 360.0;
  }
  const double dHp = 2.0 * std::sqrt(C1p * C2p) * std::sin(rad(dhp / 2.0));
  const double Lbarp = 0.5 * (L1 + L2);
  const double Cbarp = 0.5 * (C1p + C2p);
  double hbarp = h1p + h2p;
  if (C1p * C2p != 0.0) {
    if (std::fabs(h1p - h2p) <= 180.0)
      hbarp = 0.5 * (h1p + h2p);
    else
      hbarp = (h1p + h2p < 360.0) ? 0.5 * (h1p + h2p + 360.0) : 0.5 * (h1p + h2p - 360.0);
  }
  const double T = 1.0 - 0.17 * std::cos(rad(hbarp - 30.0)) + 0.24 * std::cos(rad(2.0 * hbarp)) +
                   0.32 * std::cos(rad(3.0 * hbarp + 6.0)) -
                   0.20 * std::cos(rad(4.0 * hbarp - 63.0));
  const double dTheta = 30.0 * std::exp(-((hbarp - 275.0) / 25.0) * ((hbarp - 275.0) / 25.0));
  const double Cbarp7 = std::pow(Cbarp, 7.0);
  const double Rc = 2.0 * std::sqrt(Cbarp7 / (Cbarp7 + std::pow(25.0, 7.0)));
  const double Lm50 = (Lbarp - 50.0) * (Lbarp - 50.0);
  const double Sl = 1.0 + 0.015 * Lm50 / std::sqrt(20.0 + Lm50);
  const double Sc = 1.0 + 0.045 * Cbarp;
  const double Sh = 1.0 + 0.015 * Cbarp * T;
  const double Rt = -std::sin(rad(2.0 * dTheta)) * Rc;
  const double l = dLp / Sl, c = dCp / Sc, h = dHp / Sh;
  return std::sqrt(l * l + c * c + h * h + Rt * c * h);
}

}  // namespace meshdev
