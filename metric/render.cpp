#include "metric/render.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "metric/attributes.h"
#include "metric/draw_text.h"
#include "metric/errors.h"
#include "metric/nearest_point.h"
#include "metric/vertex_normals.h"

namespace meshdev {
namespace {

struct Camera {
  Vec3 right, up, back;  // back points from the mesh towards the viewer
};

Vec3 unit(const Vec3& v) {
  const double n = norm(v);
  return n > 0.0 ? (1.0 / n) * v : v;
}

Camera camera_for(View v) {
  switch (v) {
    case View::kFront:
      return {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    case View::kBack:
      return {{-1, 0, 0}, {0, 1, 0}, {0, 0, -1}};
    case View::kLeft:
      return {{0, 0, 1}, {0, 1, 0}, {-1, 0, 0}};
    case View::kRight:
      return {{0, 0, -1}, {0, 1, 0}, {1, 0, 0}};
    case View::kTop:
      return {{1, 0, 0}, {0, 0, -1}, {0, 1, 0}};
    case View::kBottom:
      return {{1, 0, 0}, {0, 0, 1}, {0, -1, 0}};
    case View::kIso:
      break;
  }
  const Vec3 back = unit({1, 0.8, 1});
  const Vec3 right = unit(cross({0, 1, 0}, back));
  return {right, cross(back, right), back};
}

// One view at n x n pixels.
Image render_view(const TriMesh& m, const std::vector<Vec3>& pos, const std::vector<Vec3>& vn,
                  const Image* texture, const RenderOptions& o, View view, int n) {
  const Camera cam = camera_for(view);
  BoundingBox box;
  for (const Triangle& t : m.faces)
    for (std::uint32_t v : t) box.extend(pos[v]);
  const Vec3 centre = 0.5 * (box.min + box.max);
  const double radius = std::max(0.5 * box.diagonal(), 1e-300);
  const double scale = 0.46 * n / radius;  // the bounding sphere fills 92 % of the tile

  const AttributeChannel* uv = m.channel("texcoord");
  const bool textured =
      o.use_texture && texture != nullptr && !texture->empty() && uv != nullptr && uv->dim == 2;
  const AttributeChannel* color = m.channel("color");
  if (color != nullptr && color->dim != 3) color = nullptr;
  const Vec3 light = unit(cam.back + 0.45 * cam.up - 0.3 * cam.right);

  Image image(n, n, o.background);
  std::vector<double> depth(static_cast<std::size_t>(n) * n,
                            -std::numeric_limits<double>::infinity());
  std::vector<Vec3> screen(pos.size());
  for (std::size_t v = 0; v < pos.size(); ++v) {
    const Vec3 d = pos[v] - centre;
    screen[v] = {0.5 * n + scale * dot(d, cam.right), 0.5 * n - scale * dot(d, cam.up),
                 dot(d, cam.back)};
  }
  double value[3];
  for (std::uint32_t f = 0; f < m.faces.size(); ++f) {
    const Triangle& t = m.faces[f];
    const Vec3 &a = screen[t[0]], &b = screen[t[1]], &c = screen[t[2]];
    const double area = (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
    if (std::fabs(area) < 1e-12) continue;
    const int x0 = std::max(0, static_cast<int>(std::floor(std::min({a.x, b.x, c.x}))));
    const int x1 = std::min(n - 1, static_cast<int>(std::ceil(std::max({a.x, b.x, c.x}))));
    const int y0 = std::max(0, static_cast<int>(std::floor(std::min({a.y, b.y, c.y}))));
    const int y1 = std::min(n - 1, static_cast<int>(std::ceil(std::max({a.y, b.y, c.y}))));
    const Vec3 fn = face_normal(m, f);
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        const double px = x + 0.5, py = y + 0.5;
        // Edge functions: barycentrics in screen space (affine = exact for orthographic views).
        const double w0 = ((b.x - px) * (c.y - py) - (c.x - px) * (b.y - py)) / area;
        const double w1 = ((c.x - px) * (a.y - py) - (a.x - px) * (c.y - py)) / area;
        const double w2 = 1.0 - w0 - w1;
        if (w0 < 0 || w1 < 0 || w2 < 0) continue;
        const double z = w0 * a.z + w1 * b.z + w2 * c.z;
        double& zb = depth[static_cast<std::size_t>(y) * n + x];
        if (z <= zb) continue;
        zb = z;
        const std::array<double, 3> bary{w0, w1, w2};
        Vec3 base = o.plain;
        if (textured) {
          interpolate(*uv, m, f, bary, kNoFace, value);
          base = sample_bilinear(*texture, value[0], value[1]);
        } else if (color != nullptr) {
          interpolate(*color, m, f, bary, kNoFace, value);
          base = {value[0], value[1], value[2]};
        }
        Vec3 normal = o.flat ? fn : unit(w0 * vn[t[0]] + w1 * vn[t[1]] + w2 * vn[t[2]]);
        if (normal == Vec3{}) normal = fn;
        const double light_amount = o.ambient + (1.0 - o.ambient) * std::fabs(dot(normal, light));
        image.set(x, y, light_amount * base);
      }
  }
  return image;
}

Image downsample(const Image& big, int factor) {
  if (factor <= 1) return big;
  Image out(big.width / factor, big.height / factor);
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x) {
      Vec3 sum{};
      for (int j = 0; j < factor; ++j)
        for (int i = 0; i < factor; ++i) sum = sum + big.pixel(x * factor + i, y * factor + j);
      out.set(x, y, (1.0 / (factor * factor)) * sum);
    }
  return out;
}

}  // namespace

const char* view_name(View v) {
  switch (v) {
    case View::kFront:
      return "front";
    case View::kBack:
      return "back";
    case View::kLeft:
      return "left";
    case View::kRight:
      return "right";
    case View::kTop:
      return "top";
    case View::kBottom:
      return "bottom";
    case View::kIso:
      return "iso";
  }
  return "?";
}

std::vector<View> parse_views(const std::string& text) {
  std::vector<View> out;
  std::stringstream in(text);
  std::string item;
  const View all[] = {View::kFront, View::kBack,   View::kLeft, View::kRight,
                      View::kTop,   View::kBottom, View::kIso};
  while (std::getline(in, item, ',')) {
    if (item.empty()) continue;
    if (item == "all") {
      out.insert(out.end(), std::begin(all), std::end(all));
      continue;
    }
    bool found = false;
    for (View v : all)
      if (item == view_name(v)) {
        out.push_back(v);
        found = true;
      }
    if (!found)
      throw InvalidInput("unknown view '" + item +
                         "' (use front, back, left, right, top, bottom, iso, all)");
  }
  if (out.empty()) throw InvalidInput("no view given");
  return out;
}

Image render_mesh(const TriMesh& mesh, const Image* texture, const RenderOptions& o) {
  if (mesh.faces.empty()) throw InvalidInput("cannot render a mesh without faces");
  if (o.size < 16 || o.size > 8192 || o.supersample < 1 || o.supersample > 4)
    throw InvalidInput("render size must be in [16, 8192] and supersampling in [1, 4]");
  if (o.views.empty()) throw InvalidInput("no view given");
  if (!(o.ambient >= 0.0 && o.ambient <= 1.0))  // (NaN passed the command line's range check)
    throw InvalidInput("ambient light must be in [0, 1]");
  // Positions in a y-up frame; normals from the geometry (area-weighted).
  std::vector<Vec3> pos = mesh.positions;
  if (o.up == 'z')
    for (Vec3& p : pos) p = {p.x, p.z, -p.y};
  TriMesh view_mesh = mesh;  // y-up positions (face_normal reads them), the original channels
  view_mesh.positions = pos;
  const std::vector<Vec3> vn = compute_vertex_normals(view_mesh, NormalWeighting::kArea);

  const int n = static_cast<int>(o.views.size());
  const int columns = n <= 3 ? n : (n + 1) / 2;
  const int rows = (n + columns - 1) / columns;
  Image out(columns * o.size, rows * o.size, o.background);
  for (int k = 0; k < n; ++k) {
    Image tile =
        downsample(render_view(view_mesh, pos, vn, texture, o, o.views[k], o.size * o.supersample),
                   o.supersample);
    if (o.labels) draw_text(tile, 8, 8, view_name(o.views[k]), {0.2, 0.2, 0.2}, 2);
    const int ox = (k % columns) * o.size, oy = (k / columns) * o.size;
    for (int y = 0; y < tile.height; ++y)
      for (int x = 0; x < tile.width; ++x) out.set(ox + x, oy + y, tile.pixel(x, y));
  }
  return out;
}

}  // namespace meshdev
