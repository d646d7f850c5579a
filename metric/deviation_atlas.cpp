#include "metric/deviation_atlas.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numeric>

#include "metric/errors.h"

namespace meshdev {
namespace {

constexpr double kGridSlack = 1e-9;  // as in sampling.cpp: points within 1e-9 steps count as on
constexpr double kOnGrid = 1e-6;     // |i - round(i)| accepted as a scan-conversion sample

struct FaceRect {
  int nu = 0, nv = 0;  // last sample column / row index (Eq. 6, floored)
  int w = 0, h = 0;    // rectangle: (nu + 2) x (nv + 2) texels
  int x = 0, y = 0;    // its top-left texel in the atlas
  double lab = 0, lac = 0;
};

// Shelf packing, tallest first, into side s; false if it does not fit.
bool shelf_pack(std::vector<FaceRect>& rects, const std::vector<std::uint32_t>& order, int s) {
  int x = 0, y = 0, shelf = 0;
  for (std::uint32_t f : order) {
    FaceRect& r = rects[f];
    if (r.w > s) return false;
    if (x + r.w > s) {
      y += shelf;
      x = 0;
      shelf = 0;
    }
    if (y + r.h > s) return false;
    r.x = x;
    r.y = y;
    x += r.w;
    shelf = std::max(shelf, r.h);
  }
  return true;
}

}  // namespace

DeviationAtlas build_deviation_atlas(const TriMesh& m, const DirectionResult& d,
                                     const AtlasOptions& o) {
  const auto start = std::chrono::steady_clock::now();
  if (d.deviations.values.size() <= o.measure || d.sample_set.samples.empty())
    throw InvalidInput("per-sample deviations were not kept: cannot build the deviation atlas");
  if (d.sample_set.face_count == 0 || !(d.sample_set.step > 0.0))
    throw InvalidInput(
        "the deviation atlas needs scan-conversion face samples (--sampling with 'faces')");
  const double step = d.sample_set.step;
  const SampleVector& samples = d.sample_set.samples;
  const DeviationArray& values = d.deviations.values[o.measure];

  // 1. Each face's sample grid: (n_u, n_v) and its rectangle.
  const std::size_t nf = m.num_faces();
  std::vector<FaceRect> rects(nf);
  double rect_area = 0;
  for (std::size_t f = 0; f < nf; ++f) {
    const Triangle& t = m.faces[f];
    FaceRect& r = rects[f];
    r.lab = norm(m.positions[t[1]] - m.positions[t[0]]);
    r.lac = norm(m.positions[t[2]] - m.positions[t[0]]);
    r.nu = r.lab > 0.0 ? static_cast<int>(std::floor(r.lab / step + kGridSlack)) : 0;
    r.nv = r.lac > 0.0 ? static_cast<int>(std::floor(r.lac / step + kGridSlack)) : 0;
    r.w = r.nu + 2;
    r.h = r.nv + 2;
    rect_area += static_cast<double>(r.w) * r.h;
  }

  // 2. Pack: tallest first, smallest square side found by growing from sqrt(area).
  std::vector<std::uint32_t> order(nf);
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    return rects[a].h != rects[b].h ? rects[a].h > rects[b].h : rects[a].w > rects[b].w;
  });
  int side = std::max(1, static_cast<int>(std::ceil(std::sqrt(rect_area))));
  for (std::size_t f = 0; f < nf; ++f) side = std::max(side, rects[f].w);
  while (!shelf_pack(rects, order, side)) {
    side = std::max(side + 1, static_cast<int>(std::ceil(side * 1.02)));
    if (side > o.max_size)
      throw InvalidInput("the deviation atlas would need more than " + std::to_string(o.max_size) +
                         " x " + std::to_string(o.max_size) +
                         " texels; use a larger sampling step");
  }

  DeviationAtlas a;
  a.size = side;
  const std::size_t texels = static_cast<std::size_t>(side) * side;
  a.texel_face.assign(texels, -1);
  a.texel_is_sample.assign(texels, 0);
  a.texel_value.assign(texels, std::numeric_limits<float>::quiet_NaN());
  auto texel = [&](const FaceRect& r, int i, int j) {
    return static_cast<std::size_t>(r.y + j) * side + (r.x + i);
  };

  // 3. Samples to their texels, checking they are on the scan-conversion grid.
  for (std::size_t k = 0; k < samples.size(); ++k) {
    const Sample& s = samples[k];
    if (s.kind != SampleKind::kFace) continue;
    const FaceRect& r = rects[s.face];
    const double fi = r.lab > 0.0 ? s.bary[1] * r.lab / step : 0.0;
    const double fj = r.lac > 0.0 ? s.bary[2] * r.lac / step : 0.0;
    const long i = std::lround(fi), j = std::lround(fj);
    if (std::fabs(fi - static_cast<double>(i)) > kOnGrid ||
        std::fabs(fj - static_cast<double>(j)) > kOnGrid || i < 0 || j < 0 || i > r.nu || j > r.nv)
      throw InvalidInput(
          "the deviation atlas needs scan-conversion face samples; these are not on the grid "
          "(Monte Carlo sampling?)");
    const std::size_t t = texel(r, static_cast<int>(i), static_cast<int>(j));
    a.texel_face[t] = static_cast<std::int32_t>(s.face);
    a.texel_is_sample[t] = 1;
    a.texel_value[t] = static_cast<float>(values[k]);
    ++a.sample_texels;
  }

  // 4. Fill each rectangle's other texels with the nearest sample of the same face (clamp i to
  //    the last column, then j to that column's last sample), so filtering stays inside the face.
  for (std::size_t f = 0; f < nf; ++f) {
    const FaceRect& r = rects[f];
    for (int i = 0; i < r.w; ++i) {
      const int ci = std::min(i, r.nu);
      int last = -1;
      for (int j = 0; j <= r.nv; ++j)
        if (a.texel_is_sample[texel(r, ci, j)]) last = j;
      for (int j = 0; j < r.h; ++j) {
        const std::size_t t = texel(r, i, j);
        a.texel_face[t] = static_cast<std::int32_t>(f);
        ++a.face_texels;
        if (a.texel_is_sample[t]) continue;
        if (last >= 0) a.texel_value[t] = a.texel_value[texel(r, ci, std::min(j, last))];
      }
    }
  }

  // 5. Colours, and the mesh with atlas texture coordinates (exact: texel centre = sample UV).
  if (o.fixed_range) check_color_range(o.lo, o.hi);
  a.lo = o.fixed_range ? o.lo : d.stats[o.measure].min;
  a.hi = o.fixed_range ? o.hi : d.stats[o.measure].max;
  a.image = Image(side, side, o.background);
  for (int y = 0; y < side; ++y)
    for (int x = 0; x < side; ++x) {
      const std::size_t t = static_cast<std::size_t>(y) * side + x;
      if (a.texel_face[t] >= 0 && !std::isnan(a.texel_value[t]))
        a.image.set(x, y, map_color(a.texel_value[t], a.lo, a.hi, o.scale));
    }
  a.mesh.positions = m.positions;
  a.mesh.faces = m.faces;
  AttributeChannel& uv =
      a.mesh.add_channel("texcoord", AttributeKind::kTexCoord, Storage::kPerCorner, 2);
  const double inv = 1.0 / side;
  for (std::size_t f = 0; f < nf; ++f) {
    const FaceRect& r = rects[f];
    const double x0 = r.x + 0.5, y0 = r.y + 0.5;
    const double corner[3][2] = {{x0, y0}, {x0 + r.lab / step, y0}, {x0, y0 + r.lac / step}};
    for (int c = 0; c < 3; ++c) {
      uv.values[(3 * f + c) * 2] = corner[c][0] * inv;
      uv.values[(3 * f + c) * 2 + 1] = 1.0 - corner[c][1] * inv;
    }
  }
  a.sample_efficiency = static_cast<double>(a.sample_texels) / static_cast<double>(texels);
  a.rectangle_efficiency = static_cast<double>(a.face_texels) / static_cast<double>(texels);
  a.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return a;
}

}  // namespace meshdev
