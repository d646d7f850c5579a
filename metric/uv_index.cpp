#include "metric/uv_index.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "metric/errors.h"

namespace meshdev {
namespace {

constexpr double kInsideSlack = 1e-9;

// Barycentrics of (u, v) in the UV triangle t, or false if its UV area is (numerically) zero.
template <class T>
bool barycentric(const T& t, double u, double v, std::array<double, 3>& b) {
  const double e1u = t.u[1] - t.u[0], e1v = t.v[1] - t.v[0];
  const double e2u = t.u[2] - t.u[0], e2v = t.v[2] - t.v[0];
  const double det = e1u * e2v - e2u * e1v;
  const double scale = std::max({std::fabs(e1u), std::fabs(e1v), std::fabs(e2u), std::fabs(e2v)});
  if (!(std::fabs(det) > 1e-14 * scale * scale)) return false;
  const double pu = u - t.u[0], pv = v - t.v[0];
  const double s = (pu * e2v - e2u * pv) / det;
  const double r = (e1u * pv - pu * e1v) / det;
  b = {1.0 - s - r, s, r};
  return true;
}

// Closest point of segment (a, b) to q in 2D: parameter in [0, 1] and squared distance.
double segment_closest(double au, double av, double bu, double bv, double qu, double qv,
                       double& t) {
  const double du = bu - au, dv = bv - av;
  const double len2 = du * du + dv * dv;
  t = len2 > 0.0 ? std::clamp(((qu - au) * du + (qv - av) * dv) / len2, 0.0, 1.0) : 0.0;
  const double eu = au + t * du - qu, ev = av + t * dv - qv;
  return eu * eu + ev * ev;
}

}  // namespace

UvIndex::UvIndex(const TriMesh& mesh, const AttributeChannel& tc) {
  if (tc.dim != 2 || tc.storage == Storage::kPerFace)
    throw InvalidInput("the UV index needs 2-D texture coordinates per vertex or per corner");
  if (mesh.faces.empty()) throw InvalidInput("the UV index needs a mesh with faces");
  const std::size_t nf = mesh.faces.size();
  uv_.resize(nf);
  double umin = 1e300, vmin = 1e300, umax = -1e300, vmax = -1e300;
  for (std::size_t f = 0; f < nf; ++f)
    for (int c = 0; c < 3; ++c) {
      const double* x =
          tc.storage == Storage::kPerVertex ? tc.element(mesh.faces[f][c]) : tc.element(3 * f + c);
      uv_[f].u[c] = x[0];
      uv_[f].v[c] = x[1];
      umin = std::min(umin, x[0]);
      umax = std::max(umax, x[0]);
      vmin = std::min(vmin, x[1]);
      vmax = std::max(vmax, x[1]);
    }
  // About one cell per face, square-ish cells.
  const double wu = std::max(umax - umin, 1e-12), wv = std::max(vmax - vmin, 1e-12);
  const double cells = std::max<double>(1.0, static_cast<double>(nf));
  const double side = std::sqrt(wu * wv / cells);
  nu_ = std::clamp(static_cast<int>(std::ceil(wu / side)), 1, 4096);
  nv_ = std::clamp(static_cast<int>(std::ceil(wv / side)), 1, 4096);
  u0_ = umin;
  v0_ = vmin;
  cell_u_ = wu / nu_;
  cell_v_ = wv / nv_;

  // Two passes (count, fill) into a CSR layout.
  const std::size_t ncell = static_cast<std::size_t>(nu_) * static_cast<std::size_t>(nv_);
  start_.assign(ncell + 1, 0);
  auto for_cells = [&](std::size_t f, auto&& fn) {
    const Uv3& t = uv_[f];
    const int i0 = cell_u(std::min({t.u[0], t.u[1], t.u[2]}));
    const int i1 = cell_u(std::max({t.u[0], t.u[1], t.u[2]}));
    const int j0 = cell_v(std::min({t.v[0], t.v[1], t.v[2]}));
    const int j1 = cell_v(std::max({t.v[0], t.v[1], t.v[2]}));
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) fn(static_cast<std::size_t>(j) * nu_ + i);
  };
  for (std::size_t f = 0; f < nf; ++f) for_cells(f, [&](std::size_t c) { ++start_[c + 1]; });
  for (std::size_t c = 0; c < ncell; ++c) start_[c + 1] += start_[c];
  items_.resize(start_[ncell]);
  std::vector<std::uint32_t> fill(start_.begin(), start_.end() - 1);
  for (std::size_t f = 0; f < nf; ++f)
    for_cells(f, [&](std::size_t c) { items_[fill[c]++] = static_cast<std::uint32_t>(f); });
}

int UvIndex::cell_u(double u) const {
  return std::clamp(static_cast<int>(std::floor((u - u0_) / cell_u_)), 0, nu_ - 1);
}
int UvIndex::cell_v(double v) const {
  return std::clamp(static_cast<int>(std::floor((v - v0_) / cell_v_)), 0, nv_ - 1);
}

void UvIndex::containing(double u, double v, std::vector<UvHit>& out) const {
  out.clear();
  const std::size_t c = static_cast<std::size_t>(cell_v(v)) * nu_ + cell_u(u);
  for (std::uint32_t k = start_[c]; k < start_[c + 1]; ++k) {
    const std::uint32_t f = items_[k];
    std::array<double, 3> b;
    if (!barycentric(uv_[f], u, v, b)) continue;
    if (b[0] >= -kInsideSlack && b[1] >= -kInsideSlack && b[2] >= -kInsideSlack)
      out.push_back({f, b, 0.0});
  }
  std::sort(out.begin(), out.end(), [](const UvHit& x, const UvHit& y) { return x.face < y.face; });
}

UvHit UvIndex::nearest(double u, double v) const {
  UvHit best;
  double best_d2 = std::numeric_limits<double>::infinity();
  auto consider = [&](std::uint32_t f) {
    const Uv3& t = uv_[f];
    std::array<double, 3> b;
    if (barycentric(t, u, v, b) && b[0] >= 0 && b[1] >= 0 && b[2] >= 0) {
      if (0.0 < best_d2 || (best_d2 == 0.0 && f < best.face)) best = {f, b, 0.0};
      best_d2 = 0.0;
      return;
    }
    for (int e = 0; e < 3; ++e) {
      const int a = e, c = (e + 1) % 3;
      double s = 0;
      const double d2 = segment_closest(t.u[a], t.v[a], t.u[c], t.v[c], u, v, s);
      if (d2 < best_d2 || (d2 == best_d2 && f < best.face)) {
        best_d2 = d2;
        best.face = f;
        best.bary = {0, 0, 0};
        best.bary[a] = 1.0 - s;
        best.bary[c] += s;
      }
    }
  };
  const int ci = cell_u(u), cj = cell_v(v);
  const double ring_step = std::min(cell_u_, cell_v_);
  for (int r = 0; r <= std::max(nu_, nv_); ++r) {
    // Cells at Chebyshev distance r from (ci, cj). Every unvisited cell is at least r·step away
    // from the query projected onto the grid box, hence from the query (projection shrinks).
    for (int j = cj - r; j <= cj + r; ++j) {
      if (j < 0 || j >= nv_) continue;
      const bool edge_row = j == cj - r || j == cj + r;
      for (int i = ci - r; i <= ci + r; i += edge_row ? 1 : 2 * r) {
        if (i >= 0 && i < nu_) {
          const std::size_t c = static_cast<std::size_t>(j) * nu_ + i;
          for (std::uint32_t k = start_[c]; k < start_[c + 1]; ++k) consider(items_[k]);
        }
        if (r == 0) break;
      }
    }
    const double bound = static_cast<double>(r) * ring_step;
    if (best_d2 < std::numeric_limits<double>::infinity() && bound * bound >= best_d2) break;
  }
  best.uv_distance = std::sqrt(best_d2);
  return best;
}

}  // namespace meshdev
