#include "simplifiers/openmesh_appearance.h"

#include <OpenMesh/Tools/Decimater/BaseDecimaterT.hh>
#include <OpenMesh/Tools/Decimater/ModBaseT.hh>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <numeric>
#include <queue>

#include "metric/errors.h"
#include "simplifiers/openmesh_convert.h"
#include "simplifiers/openmesh_modules.h"

namespace meshdev {
namespace {

using Clock = std::chrono::steady_clock;
using Point = OmMesh::Point;
using VH = OmMesh::VertexHandle;
using CollapseInfo = OpenMesh::Decimater::CollapseInfoT<OmMesh>;
using ModBase = OpenMesh::Decimater::ModBaseT<OmMesh>;

constexpr double kPi = 3.14159265358979323846;

// ---------------------------------------------------------------------------------------------
// Generalized quadrics in R^n, packed as [A upper triangle (n(n+1)/2), b (n), c]:
// Q(x) = x^T A x + 2 b^T x + c.

std::size_t quadric_size(int n) {
  return std::size_t(n) * (n + 1) / 2 + n + 1;
}

// Packed index of A(i, j), i <= j.
inline std::size_t upper(int n, int i, int j) {
  return std::size_t(i) * n - std::size_t(i) * (i - 1) / 2 + (j - i);
}

double a_at(const double* q, int n, int i, int j) {
  return i <= j ? q[upper(n, i, j)] : q[upper(n, j, i)];
}

// Adds w x the GH98 quadric of the triangle (p, r, s) in R^n: squared distance to its plane.
// Returns false (nothing added) for a degenerate triangle.
bool add_triangle(double* q, int n, const double* p, const double* r, const double* s, double w) {
  std::vector<double> e1(n), e2(n);
  double l1 = 0;
  for (int i = 0; i < n; ++i) e1[i] = r[i] - p[i], l1 += e1[i] * e1[i];
  if (!(l1 > 0)) return false;
  l1 = std::sqrt(l1);
  double proj = 0;
  for (int i = 0; i < n; ++i) e1[i] /= l1, proj += e1[i] * (s[i] - p[i]);
  double l2 = 0;
  for (int i = 0; i < n; ++i) e2[i] = s[i] - p[i] - proj * e1[i], l2 += e2[i] * e2[i];
  if (!(l2 > 1e-30)) return false;
  l2 = std::sqrt(l2);
  double pe1 = 0, pe2 = 0, pp = 0;
  for (int i = 0; i < n; ++i) {
    e2[i] /= l2;
    pe1 += p[i] * e1[i], pe2 += p[i] * e2[i], pp += p[i] * p[i];
  }
  for (int i = 0; i < n; ++i)
    for (int j = i; j < n; ++j)
      q[upper(n, i, j)] += w * ((i == j ? 1.0 : 0.0) - e1[i] * e1[j] - e2[i] * e2[j]);
  double* b = q + std::size_t(n) * (n + 1) / 2;
  for (int i = 0; i < n; ++i) b[i] += w * (pe1 * e1[i] + pe2 * e2[i] - p[i]);
  b[n] += w * (pp - pe1 * pe1 - pe2 * pe2);
  return true;
}

// Adds w x (m . x_pos + d)^2: a plane acting on the three position coordinates only.
void add_position_plane(double* q, int n, const double m[3], double d, double w) {
  for (int i = 0; i < 3; ++i)
    for (int j = i; j < 3; ++j) q[upper(n, i, j)] += w * m[i] * m[j];
  double* b = q + std::size_t(n) * (n + 1) / 2;
  for (int i = 0; i < 3; ++i) b[i] += w * d * m[i];
  b[n] += w * d * d;
}

double evaluate(const double* q, int n, const double* x) {
  const double* b = q + std::size_t(n) * (n + 1) / 2;
  double v = b[n];
  for (int i = 0; i < n; ++i) {
    v += 2.0 * b[i] * x[i] + q[upper(n, i, i)] * x[i] * x[i];
    for (int j = i + 1; j < n; ++j) v += 2.0 * q[upper(n, i, j)] * x[i] * x[j];
  }
  return v;
}

// x = argmin Q by Cholesky of A; false when A is not safely positive definite (a pivot below
// 1e-9 of the largest diagonal entry): the minimum is then a valley, not a point.
bool minimize(const double* q, int n, double* x, std::vector<double>& L, std::vector<double>& y) {
  L.assign(std::size_t(n) * n, 0.0);
  y.assign(n, 0.0);
  double biggest = 0;
  for (int i = 0; i < n; ++i) biggest = std::max(biggest, q[upper(n, i, i)]);
  if (!(biggest > 0)) return false;
  for (int j = 0; j < n; ++j) {
    double d = a_at(q, n, j, j);
    for (int k = 0; k < j; ++k) d -= L[j * n + k] * L[j * n + k];
    if (!(d > 1e-9 * biggest)) return false;
    L[j * n + j] = std::sqrt(d);
    for (int i = j + 1; i < n; ++i) {
      double s = a_at(q, n, i, j);
      for (int k = 0; k < j; ++k) s -= L[i * n + k] * L[j * n + k];
      L[i * n + j] = s / L[j * n + j];
    }
  }
  const double* b = q + std::size_t(n) * (n + 1) / 2;
  for (int i = 0; i < n; ++i) {  // L y = -b
    double s = -b[i];
    for (int k = 0; k < i; ++k) s -= L[i * n + k] * y[k];
    y[i] = s / L[i * n + i];
  }
  for (int i = n - 1; i >= 0; --i) {  // L^T x = y
    double s = y[i];
    for (int k = i + 1; k < n; ++k) s -= L[k * n + i] * x[k];
    x[i] = s / L[i * n + i];
  }
  for (int i = 0; i < n; ++i)
    if (!std::isfinite(x[i])) return false;
  return true;
}

// ---------------------------------------------------------------------------------------------
// The setup shared by the module and the driver.

// One per-vertex channel inside the quadric: coordinate = weight * (value - offset) / scale.
struct QuadricChannel {
  const OmChannelSlot* slot = nullptr;
  int dim = 0;
  double weight = 0, offset = 0, scale = 1;
};

struct Setup {
  int n = 3;                                       // 3 + attribute coordinates
  Point origin;                                    // bbox min
  double diagonal = 1;                             // bbox diagonal
  std::vector<QuadricChannel> channels;            // in the quadric
  std::vector<const OmChannelSlot*> copied;        // per-vertex, not in the quadric
  std::vector<const OmChannelSlot*> corner_slots;  // per-corner (seams kept)
  double boundary_weight = 100;
  bool optimal = true;
  double cos_max_flip = 0.5;
};

// The values of a per-vertex slot at v, and writing them back.
std::vector<double> read_slot(const OmMesh& m, const OmChannelSlot& s, VH v) {
  switch (s.place) {
    case OmChannelSlot::Place::kVertexNormal: {
      auto x = m.normal(v);
      return {x[0], x[1], x[2]};
    }
    case OmChannelSlot::Place::kVertexColor: {
      auto x = m.color(v);
      return {x[0], x[1], x[2]};
    }
    case OmChannelSlot::Place::kVertexTexCoord: {
      auto x = m.texcoord2D(v);
      return {x[0], x[1]};
    }
    default:
      return m.property(s.vprop, v);
  }
}

void write_slot(OmMesh& m, const OmChannelSlot& s, VH v, const std::vector<double>& x) {
  switch (s.place) {
    case OmChannelSlot::Place::kVertexNormal:
      m.set_normal(v, OmMesh::Normal(x[0], x[1], x[2]));
      break;
    case OmChannelSlot::Place::kVertexColor:
      m.set_color(v, OmMesh::Color(x[0], x[1], x[2]));
      break;
    case OmChannelSlot::Place::kVertexTexCoord:
      m.set_texcoord2D(v, OmMesh::TexCoord2D(x[0], x[1]));
      break;
    default:
      m.property(s.vprop, v) = x;
  }
}

// s(v): the vertex as a point of R^n.
void vertex_point(const OmMesh& m, const Setup& setup, VH v, double* out) {
  Point p = (m.point(v) - setup.origin) / setup.diagonal;
  out[0] = p[0], out[1] = p[1], out[2] = p[2];
  int at = 3;
  for (const QuadricChannel& c : setup.channels) {
    std::vector<double> x = read_slot(m, *c.slot, v);
    for (int k = 0; k < c.dim; ++k) out[at++] = c.weight * (x[k] - c.offset) / c.scale;
  }
}

// Zero-area test of ModNoDegenerateT: |normal| = twice the area, below 1e-12 x the longest
// squared edge. `normal` = cross(p[1] - p[0], p[2] - p[0]).
bool degenerate(const Point& normal, const Point* p) {
  double longest =
      std::max({(p[1] - p[0]).sqrnorm(), (p[2] - p[1]).sqrnorm(), (p[0] - p[2]).sqrnorm()});
  return normal.norm() <= 1e-12 * longest;
}

// ---------------------------------------------------------------------------------------------
// The Decimater module: generalized quadric priority with placement.

class ModAppearanceQuadric : public ModBase {
 public:
  using Self = ModAppearanceQuadric;
  using Handle = OpenMesh::Decimater::ModHandleT<Self>;
  using Base = ModBase;
  DECIMATER_MODNAME(MeshdevAppearanceQuadric)

  explicit ModAppearanceQuadric(OmMesh& mesh) : Base(mesh, /*is_binary=*/false) {}

  // Builds every vertex's quadric from its faces (area-weighted) and border edges.
  void initialize() override {
    OmMesh& m = mesh();
    const int n = setup->n;
    const std::size_t qs = quadric_size(n);
    quadrics_.assign(m.n_vertices() * qs, 0.0);
    points_.assign(m.n_vertices() * std::size_t(n), 0.0);
    for (auto v : m.vertices()) vertex_point(m, *setup, v, &points_[v.idx() * std::size_t(n)]);
    q_.resize(qs);
    x_.resize(n);
    pending_x_.resize(n);
    last_x_.resize(n);
    for (auto f : m.faces()) {
      VH v[3];
      int i = 0;
      for (auto fv : m.fv_range(f)) v[i++] = fv;
      const double* pts[3];
      for (int k = 0; k < 3; ++k) pts[k] = &points_[v[k].idx() * std::size_t(n)];
      Point a = m.point(v[0]), b = m.point(v[1]), c = m.point(v[2]);
      Point normal = OpenMesh::cross(b - a, c - a);
      double area = 0.5 * normal.norm() / (setup->diagonal * setup->diagonal);
      std::vector<double> face_q(qs, 0.0);
      if (add_triangle(face_q.data(), n, pts[0], pts[1], pts[2], area))
        for (int k = 0; k < 3; ++k) accumulate(v[k], face_q.data());
      // Border planes: through the border edge, perpendicular to the face.
      if (!(normal.norm() > 0)) continue;
      normal.normalize();
      for (auto h : m.fh_range(f)) {
        if (!m.is_boundary(m.opposite_halfedge_handle(h))) continue;
        Point p0 = (m.point(m.from_vertex_handle(h)) - setup->origin) / setup->diagonal;
        Point p1 = (m.point(m.to_vertex_handle(h)) - setup->origin) / setup->diagonal;
        Point e = p1 - p0;
        Point mdir = OpenMesh::cross(e, normal);
        if (!(mdir.norm() > 0)) continue;
        mdir.normalize();
        const double md[3] = {mdir[0], mdir[1], mdir[2]};
        std::vector<double> edge_q(qs, 0.0);
        add_position_plane(edge_q.data(), n, md, -(mdir | p0),
                           setup->boundary_weight * e.sqrnorm());
        accumulate(m.from_vertex_handle(h), edge_q.data());
        accumulate(m.to_vertex_handle(h), edge_q.data());
      }
    }
  }

  float collapse_priority(const CollapseInfo& ci) override {
    last_ = place(ci);
    last_halfedge_ = ci.v0v1;
    if (last_.optimum) last_x_ = x_;
    return last_.valid ? float(std::max(0.0, last_.cost)) : float(Base::ILLEGAL_COLLAPSE);
  }

  // The driver evaluates the priority of the popped candidate right before collapsing it, so the
  // placement is usually at hand; otherwise it is computed again (same result: nothing changed).
  void preprocess_collapse(const CollapseInfo& ci) override {
    if (last_halfedge_ == ci.v0v1) {
      pending_ = last_;
      pending_x_ = last_x_;
    } else {
      pending_ = place(ci);
      if (pending_.optimum) pending_x_ = x_;
    }
    last_halfedge_ = OmMesh::HalfedgeHandle();
  }

  // v1 takes the summed quadric, the placed position and the placed attributes.
  void postprocess_collapse(const CollapseInfo& ci) override {
    OmMesh& m = mesh();
    const std::size_t qs = quadric_size(setup->n);
    accumulate(ci.v1, &quadrics_[ci.v0.idx() * qs]);
    if (!pending_.valid) return;  // cannot happen: the driver checks the priority first
    m.set_point(ci.v1, pending_.position);
    if (pending_.from_endpoint0) {  // v1 moves onto v0 with v0's values
      for (const QuadricChannel& c : setup->channels)
        write_slot(m, *c.slot, ci.v1, read_slot(m, *c.slot, ci.v0));
      for (const OmChannelSlot* s : setup->copied)
        write_slot(m, *s, ci.v1, read_slot(m, *s, ci.v0));
    } else if (pending_.optimum) {  // attributes from the quadric's optimum
      int at = 3;
      for (const QuadricChannel& c : setup->channels) {
        std::vector<double> x(c.dim);
        for (int k = 0; k < c.dim; ++k) x[k] = pending_x_[at++] / c.weight * c.scale + c.offset;
        if (c.slot->kind == AttributeKind::kColor)
          for (double& y : x) y = std::clamp(y, 0.0, 1.0);
        if (c.slot->kind == AttributeKind::kNormal && c.dim == 3) {
          double len = std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
          if (!(len > 1e-12)) continue;  // keep v1's normal
          for (double& y : x) y /= len;
        }
        write_slot(m, *c.slot, ci.v1, x);
      }
    }
    vertex_point(m, *setup, ci.v1, &points_[ci.v1.idx() * std::size_t(setup->n)]);
  }

  const Setup* setup = nullptr;

 private:
  struct Placement {
    bool valid = false;
    bool optimum = false;         // at argmin Q
    bool from_endpoint0 = false;  // at v0 (v1 moves there with v0's values)
    double cost = 0;
    Point position;
  };

  void accumulate(VH v, const double* q) {
    const std::size_t qs = quadric_size(setup->n);
    double* dst = &quadrics_[v.idx() * qs];
    for (std::size_t i = 0; i < qs; ++i) dst[i] += q[i];
  }

  // Candidates in order of cost: the optimum (if well-conditioned and near the edge), then the
  // endpoints (v0 only with optimal placement); the first that passes the flip and degeneracy
  // checks at its position wins.
  Placement place(const CollapseInfo& ci) {
    const int n = setup->n;
    const std::size_t qs = quadric_size(n);
    double* q = q_.data();
    const double* q0 = &quadrics_[ci.v0.idx() * qs];
    const double* q1 = &quadrics_[ci.v1.idx() * qs];
    for (std::size_t i = 0; i < qs; ++i) q[i] = q0[i] + q1[i];

    Placement candidates[3];
    int count = 0;
    Placement& end1 = candidates[count++];
    end1.valid = true, end1.position = ci.p1;
    end1.cost = evaluate(q, n, &points_[ci.v1.idx() * std::size_t(n)]);
    if (setup->optimal) {
      Placement& end0 = candidates[count++];
      end0.valid = true, end0.from_endpoint0 = true, end0.position = ci.p0;
      end0.cost = evaluate(q, n, &points_[ci.v0.idx() * std::size_t(n)]);
      if (minimize(q, n, x_.data(), L_, y_)) {
        Point pos(x_[0], x_[1], x_[2]);
        pos = pos * setup->diagonal + setup->origin;
        Point mid = 0.5 * (ci.p0 + ci.p1);
        if ((pos - mid).norm() <= (ci.p1 - ci.p0).norm()) {
          Placement& opt = candidates[count++];
          opt.valid = opt.optimum = true, opt.position = pos;
          opt.cost = evaluate(q, n, x_.data());
        }
      }
      std::stable_sort(candidates, candidates + count,
                       [](const Placement& a, const Placement& b) { return a.cost < b.cost; });
    }
    for (int i = 0; i < count; ++i)
      if (acceptable(ci, candidates[i].position)) return candidates[i];
    return {};
  }

  // No remaining face around v0 or v1 may become zero-area or turn its normal by more than the
  // flip limit when v0 and v1 sit at `position`.
  bool acceptable(const CollapseInfo& ci, const Point& position) {
    OmMesh& m = mesh();
    for (VH center : {ci.v0, ci.v1}) {
      for (auto f : m.vf_range(center)) {
        if (f == ci.fl || f == ci.fr) continue;
        Point before[3], after[3];
        int i = 0;
        bool moved = false;
        for (auto v : m.fv_range(f)) {
          before[i] = m.point(v);
          bool end = v == ci.v0 || v == ci.v1;
          after[i] = end ? position : before[i];
          moved |= end && after[i] != before[i];
          ++i;
        }
        if (!moved) continue;
        Point n0 = OpenMesh::cross(before[1] - before[0], before[2] - before[0]);
        if (degenerate(n0, before)) continue;  // not a new one
        Point n1 = OpenMesh::cross(after[1] - after[0], after[2] - after[0]);
        if (degenerate(n1, after)) return false;
        if ((n0 | n1) < setup->cos_max_flip * n0.norm() * n1.norm()) return false;
      }
    }
    return true;
  }

  std::vector<double> quadrics_;  // quadric_size(n) doubles per vertex, by vertex index
  std::vector<double> points_;    // s(v): n doubles per vertex, by vertex index
  std::vector<double> q_, x_, L_, y_, pending_x_;  // scratch
  Placement pending_, last_;
  std::vector<double> last_x_;
  OmMesh::HalfedgeHandle last_halfedge_;
};

// ---------------------------------------------------------------------------------------------
// The driver: DecimaterT's loop (best outgoing halfedge per vertex in a heap) with two changes:
// a popped candidate is re-evaluated against the current mesh and re-queued if its priority
// changed (a neighbour moved), and after a collapse the whole new one-ring of v1 is re-queued.
class AppearanceDecimater : public OpenMesh::Decimater::BaseDecimaterT<OmMesh> {
 public:
  explicit AppearanceDecimater(OmMesh& mesh) : BaseDecimaterT<OmMesh>(mesh), mesh_(mesh) {}

  // Collapses until `faces` <= target or no legal collapse is left; step(faces) runs after each
  // collapse and returns true to stop. Returns the final face count.
  std::size_t run(std::size_t faces, std::size_t target,
                  const std::function<bool(std::size_t)>& step) {
    target_.assign(mesh_.n_vertices(), OmMesh::HalfedgeHandle());
    version_.assign(mesh_.n_vertices(), 0);
    for (auto v : mesh_.vertices()) heap_vertex(v);
    while (faces > target && !heap_.empty()) {
      Entry e = heap_.top();
      heap_.pop();
      if (e.version != version_[e.vertex]) continue;  // superseded
      VH v(e.vertex);
      if (mesh_.status(v).deleted()) continue;
      CollapseInfo ci(mesh_, target_[e.vertex]);
      if (!is_collapse_legal(ci) || collapse_priority(ci) != e.priority) {
        heap_vertex(v);  // stale: re-evaluate against the current mesh
        continue;
      }
      preprocess_collapse(ci);
      mesh_.collapse(ci.v0v1);
      faces -= (ci.fl.is_valid() ? 1 : 0) + (ci.fr.is_valid() ? 1 : 0);
      postprocess_collapse(ci);
      ++version_[ci.v0.idx()];
      heap_vertex(ci.v1);
      for (auto w : mesh_.vv_range(ci.v1)) heap_vertex(w);
      if (step(faces)) break;
    }
    return faces;
  }

 private:
  struct Entry {
    float priority;
    int vertex;
    unsigned version;
    // std::priority_queue is a max-heap: the smallest priority (then index) on top.
    bool operator<(const Entry& o) const {
      return priority != o.priority ? priority > o.priority : vertex > o.vertex;
    }
  };

  void heap_vertex(VH v) {
    float best = 0;
    OmMesh::HalfedgeHandle best_h;
    for (auto h : mesh_.voh_range(v)) {
      CollapseInfo ci(mesh_, h);
      if (!is_collapse_legal(ci)) continue;
      float p = collapse_priority(ci);
      if (p >= 0.0f && (!best_h.is_valid() || p < best)) best = p, best_h = h;
    }
    unsigned version = ++version_[v.idx()];
    target_[v.idx()] = best_h;
    if (best_h.is_valid()) heap_.push({best, v.idx(), version});
  }

  OmMesh& mesh_;
  std::vector<OmMesh::HalfedgeHandle> target_;
  std::vector<unsigned> version_;
  std::priority_queue<Entry> heap_;
};

double parse_weight(const std::string& key, const std::string& value) {
  double w = detail::parse_double_option(key, value);
  if (!(w >= 0.0)) throw InvalidInput("option " + key + ": must be >= 0, got " + value);
  return w;
}

// The quadric channels: every per-vertex channel whose kind has a positive weight; scalars are
// divided by their range so one weight fits any unit.
Setup make_setup(const TriMesh& mesh, const OpenMeshConversion& conv,
                 const OpenMeshAppearanceOptions& o) {
  Setup setup;
  BoundingBox box = bounding_box(mesh);
  setup.origin = Point(box.min.x, box.min.y, box.min.z);
  setup.diagonal = box.diagonal() > 0 ? box.diagonal() : 1.0;
  setup.boundary_weight = o.boundary_weight;
  setup.optimal = o.optimal;
  setup.cos_max_flip = std::cos(o.max_flip_deg * kPi / 180.0);
  for (std::size_t i = 0; i < conv.slots.size(); ++i) {
    const OmChannelSlot& s = conv.slots[i];
    if (s.storage == Storage::kPerCorner) setup.corner_slots.push_back(&s);
    if (s.storage != Storage::kPerVertex) continue;
    double w = s.kind == AttributeKind::kColor      ? o.color_weight
               : s.kind == AttributeKind::kTexCoord ? o.texcoord_weight
               : s.kind == AttributeKind::kNormal   ? o.normal_weight
                                                    : o.scalar_weight;
    if (!(w > 0)) {
      setup.copied.push_back(&s);
      continue;
    }
    QuadricChannel c{&s, s.dim, w, 0.0, 1.0};
    if (s.kind == AttributeKind::kScalar) {
      const AttributeChannel& ch = mesh.channels[i];
      auto [lo, hi] = std::minmax_element(ch.values.begin(), ch.values.end());
      if (lo != ch.values.end() && *hi > *lo) c.offset = *lo, c.scale = *hi - *lo;
    }
    setup.channels.push_back(c);
    setup.n += s.dim;
  }
  return setup;
}

}  // namespace

OpenMeshAppearance::OpenMeshAppearance(OpenMeshAppearanceOptions options) : options_(options) {}

std::string OpenMeshAppearance::description() const {
  return "OpenMesh 9 halfedge collapses with our generalized quadric over position and "
         "per-vertex attributes (Garland-Heckbert 1998), emulated optimal placement, flips "
         "refused at the placed position";
}

std::string OpenMeshAppearance::role() const {
  return "appearance-preserving quadric (GH98)";
}

std::string OpenMeshAppearance::keeps() const {
  return "all channels: per-vertex colour/UV/normal/scalars in the quadric, written at the placed "
         "vertex (weight 0: copied from the surviving endpoint); per-corner with seams kept; "
         "per-face on surviving faces";
}

OutputGuarantees OpenMeshAppearance::guarantees() const {
  OutputGuarantees g;
  g.vertices_fixed = !options_.optimal;
  return g;
}

std::vector<OptionInfo> OpenMeshAppearance::options() const {
  return {{"color_weight", "0.1", "weight of per-vertex colour (sRGB in [0,1]) in the quadric"},
          {"texcoord_weight", "0.1", "weight of per-vertex UVs"},
          {"normal_weight", "0.05", "weight of per-vertex normals (0: recomputed instead)"},
          {"scalar_weight", "0.05", "weight of other per-vertex channels (divided by their range)"},
          {"boundary_weight", "100", "weight of the border planes (x edge length^2)"},
          {"optimal", "true", "place at the quadric's minimum (false: endpoint, vertices fixed)"},
          {"max_flip_deg", "60", "refuse a collapse turning a face normal by more (degrees)"}};
}

void OpenMeshAppearance::set_option(const std::string& key, const std::string& value) {
  if (key == "color_weight") {
    options_.color_weight = parse_weight(key, value);
  } else if (key == "texcoord_weight") {
    options_.texcoord_weight = parse_weight(key, value);
  } else if (key == "normal_weight") {
    options_.normal_weight = parse_weight(key, value);
  } else if (key == "scalar_weight") {
    options_.scalar_weight = parse_weight(key, value);
  } else if (key == "boundary_weight") {
    options_.boundary_weight = parse_weight(key, value);
  } else if (key == "optimal") {
    options_.optimal = detail::parse_bool_option(key, value);
  } else if (key == "max_flip_deg") {
    double deg = detail::parse_double_option(key, value);
    if (!(deg > 0.0 && deg <= 180.0))
      throw InvalidInput("option max_flip_deg: must be in (0, 180] degrees, got " + value);
    options_.max_flip_deg = deg;
  } else {
    detail::throw_unknown_option(name(), key, options());
  }
}

SimplifyResult OpenMeshAppearance::simplify(const TriMesh& mesh, const SimplifyRequest& request) {
  return simplify_sweep(mesh, {request}).front();
}

std::vector<SimplifyResult> OpenMeshAppearance::simplify_sweep(
    const TriMesh& mesh, const std::vector<SimplifyRequest>& requests) {
  detail::check_input(mesh, name());
  const std::size_t n = requests.size();
  std::vector<SimplifyResult> results = detail::results_for(mesh, requests);
  if (n == 0) return results;
  const auto start = Clock::now();
  auto seconds = [&] { return std::chrono::duration<double>(Clock::now() - start).count(); };
  OpenMeshQuiet quiet;

  // 1. Convert (a face OpenMesh refuses makes the run fail) and request the status flags.
  OpenMeshConversion conv;
  if (!convert_for_decimation(mesh, conv, results)) return results;
  OmMesh& om = conv.mesh;
  const Setup setup = make_setup(mesh, conv, options_);
  bool recompute_vertex_normals = false, face_normals = false;
  for (const OmChannelSlot* s : setup.copied)
    recompute_vertex_normals |= s->place == OmChannelSlot::Place::kVertexNormal;
  for (const OmChannelSlot& s : conv.slots)
    face_normals |= s.place == OmChannelSlot::Place::kFaceNormal;
  if (recompute_vertex_normals || face_normals) om.request_face_normals();

  // 2. The driver with our modules.
  AppearanceDecimater dec(om);
  ModAppearanceQuadric::Handle quadric;
  dec.add(quadric);
  dec.module(quadric).setup = &setup;
  if (!setup.corner_slots.empty()) {
    ModCornerSeamT<OmMesh>::Handle seam;
    dec.add(seam);
    dec.module(seam).slots = setup.corner_slots;
  }
  if (!dec.initialize()) {
    for (SimplifyResult& r : results) {
      r.status = SimplifyStatus::kFailed;
      r.message = "OpenMesh BaseDecimaterT::initialize() failed (module set rejected)";
      r.wall_seconds = seconds();
    }
    return results;
  }

  // 3. Targets from the largest down; a snapshot when the face count first reaches each.
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return results[a].target_faces > results[b].target_faces;
  });
  std::size_t next = 0;
  auto snapshot = [&](SimplifyResult& r) {
    if (recompute_vertex_normals || face_normals) om.update_face_normals();
    if (recompute_vertex_normals) om.update_vertex_normals();
    r.mesh = from_openmesh(om, conv.slots);
    r.wall_seconds = seconds();
  };
  auto step = [&](std::size_t faces) {
    while (next < n && faces <= results[order[next]].target_faces) snapshot(results[order[next++]]);
    return next == n;
  };
  if (!step(om.n_faces())) dec.run(om.n_faces(), results[order.back()].target_faces, step);
  while (next < n) snapshot(results[order[next++]]);

  for (SimplifyResult& r : results) {
    for (const AttributeChannel& c : mesh.channels) r.kept.push_back(c.name);
    detail::set_status_from_counts(r);
  }
  return results;
}

}  // namespace meshdev
