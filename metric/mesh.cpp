#include "metric/mesh.h"

#include <omp.h>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <memory>

#include "metric/errors.h"

namespace meshdev {
namespace {

// Below this many elements the parallel loops here run on one thread: a team's start costs more.
constexpr std::size_t kParallelFrom = 1u << 14;

}  // namespace

const AttributeChannel* TriMesh::channel(std::string_view name) const {
  for (const auto& c : channels)
    if (c.name == name) return &c;
  return nullptr;
}

AttributeChannel* TriMesh::channel(std::string_view name) {
  for (auto& c : channels)
    if (c.name == name) return &c;
  return nullptr;
}

AttributeChannel& TriMesh::add_channel(std::string name, AttributeKind kind, Storage storage,
                                       int dim) {
  std::size_t elements = storage == Storage::kPerVertex   ? positions.size()
                         : storage == Storage::kPerCorner ? 3 * faces.size()
                                                          : faces.size();
  AttributeChannel c{std::move(name), kind, storage, dim, std::vector<double>(elements * dim, 0.0)};
  if (AttributeChannel* existing = channel(c.name)) {
    *existing = std::move(c);
    return *existing;
  }
  channels.push_back(std::move(c));
  return channels.back();
}

double BoundingBox::diagonal() const {
  return empty() ? 0.0 : norm(max - min);
}

BoundingBox bounding_box(const TriMesh& mesh) {
  return bounding_box(mesh, referenced_vertices(mesh));
}

namespace {

// The box of what extend(box, i) adds for i in [0, count), each thread extending its own box over
// a static share, then merged: min and max per axis, the same whatever the split (extend ignores
// NaN).
template <class Extend>
BoundingBox box_on_team(std::int64_t count, int threads, Extend&& extend) {
  const int team = threads > 0 ? threads : omp_get_max_threads();
  std::vector<BoundingBox> part(static_cast<std::size_t>(team));
#pragma omp parallel num_threads(team)
  {
    BoundingBox box;
#pragma omp for schedule(static) nowait
    for (std::int64_t i = 0; i < count; ++i) extend(box, static_cast<std::size_t>(i));
    part[static_cast<std::size_t>(omp_get_thread_num())] = box;
  }
  BoundingBox box;
  for (const BoundingBox& b : part)
    for (int k = 0; k < 3; ++k) {
      box.min[k] = std::min(box.min[k], b.min[k]);
      box.max[k] = std::max(box.max[k], b.max[k]);
    }
  return box;
}

}  // namespace

BoundingBox corner_bounding_box(const TriMesh& mesh, int threads) {
  if (mesh.faces.empty()) return bounding_box(mesh);
  // The corners of the face 8 ahead are prefetched: where faces are stored in no spatial order,
  // their positions are cache misses, which this loop's dependent min/max chains keep from
  // overlapping on their own (torus1m with its faces shuffled: docs/performance-log.md §3).
  constexpr std::size_t kAhead = 8;
  const std::size_t n = mesh.faces.size();
  return box_on_team(static_cast<std::int64_t>(n), threads, [&](BoundingBox& box, std::size_t f) {
    if (f + kAhead < n)
      for (std::uint32_t v : mesh.faces[f + kAhead]) __builtin_prefetch(&mesh.positions[v]);
    for (std::uint32_t v : mesh.faces[f]) box.extend(mesh.positions[v]);
  });
}

BoundingBox position_bounding_box(const TriMesh& mesh, int threads) {
  return box_on_team(static_cast<std::int64_t>(mesh.positions.size()), threads,
                     [&](BoundingBox& box, std::size_t v) { box.extend(mesh.positions[v]); });
}

BoundingBox bounding_box(const TriMesh& mesh, const std::vector<bool>& used) {
  BoundingBox box;
  if (mesh.faces.empty()) {
    for (const Vec3& p : mesh.positions) box.extend(p);
    return box;
  }
  assert(used.size() == mesh.positions.size());
  for (std::size_t v = 0; v < mesh.positions.size(); ++v)
    if (used[v]) box.extend(mesh.positions[v]);
  return box;
}

double face_area(const TriMesh& mesh, std::size_t f) {
  const Triangle& t = mesh.faces[f];
  const Vec3& a = mesh.positions[t[0]];
  return 0.5 * norm(cross(mesh.positions[t[1]] - a, mesh.positions[t[2]] - a));
}

double surface_area(const TriMesh& mesh) {
  double area = 0.0;
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) area += face_area(mesh, f);
  return area;
}

double surface_area(const TriMesh& mesh, int threads) {
  const std::size_t n = mesh.faces.size();
  const int team = threads > 0 ? threads : omp_get_max_threads();
  if (team == 1 || n < kParallelFrom) return surface_area(mesh);
  // Uninitialised: each area is first written by the thread that computes it. The corners of the
  // face kAhead on are prefetched, as in corner_bounding_box, for faces stored in no spatial
  // order.
  constexpr std::size_t kAhead = 8;
  std::unique_ptr<double[]> areas(new double[n]);
#pragma omp parallel for num_threads(team) schedule(static)
  for (std::int64_t f = 0; f < static_cast<std::int64_t>(n); ++f) {
    const auto i = static_cast<std::size_t>(f);
    if (i + kAhead < n)
      for (std::uint32_t v : mesh.faces[i + kAhead]) __builtin_prefetch(&mesh.positions[v]);
    areas[i] = face_area(mesh, i);
  }
  double area = 0.0;
  for (std::size_t f = 0; f < n; ++f) area += areas[f];
  return area;
}

std::vector<bool> referenced_vertices(const TriMesh& mesh) {
  std::vector<bool> used(mesh.positions.size(), false);
  for (const Triangle& t : mesh.faces)
    for (std::uint32_t v : t)
      if (v < used.size()) used[v] = true;
  return used;
}

ReferencedVertices referenced_vertex_summary(const TriMesh& mesh, int threads) {
  ReferencedVertices r;
  if (mesh.faces.empty()) {
    r.box = position_bounding_box(mesh, threads);
    return r;
  }
  const std::size_t vertices = mesh.positions.size(), faces = mesh.faces.size();
  const int team = threads > 0 ? threads : omp_get_max_threads();
  // A byte per vertex, set by relaxed atomic stores (threads may mark the same vertex; every
  // store writes 1), read after the loop's barrier.
  std::unique_ptr<std::uint8_t[]> used(new std::uint8_t[vertices]);
  std::vector<ReferencedVertices> part(static_cast<std::size_t>(team));
#pragma omp parallel num_threads(team) if (faces >= kParallelFrom)
  {
#pragma omp for schedule(static)
    for (std::int64_t v = 0; v < static_cast<std::int64_t>(vertices); ++v) used[v] = 0;
#pragma omp for schedule(static)
    for (std::int64_t f = 0; f < static_cast<std::int64_t>(faces); ++f)
      for (std::uint32_t v : mesh.faces[static_cast<std::size_t>(f)])
        if (v < vertices) __atomic_store_n(&used[v], std::uint8_t{1}, __ATOMIC_RELAXED);
    ReferencedVertices mine;
#pragma omp for schedule(static) nowait
    for (std::int64_t v = 0; v < static_cast<std::int64_t>(vertices); ++v) {
      if (!used[v]) continue;
      ++mine.count;
      mine.box.extend(mesh.positions[static_cast<std::size_t>(v)]);
    }
    part[static_cast<std::size_t>(omp_get_thread_num())] = mine;
  }
  for (const ReferencedVertices& p : part) {
    r.count += p.count;
    for (int k = 0; k < 3; ++k) {
      r.box.min[k] = std::min(r.box.min[k], p.box.min[k]);
      r.box.max[k] = std::max(r.box.max[k], p.box.max[k]);
    }
  }
  return r;
}

namespace {

// The least i in [0, n) for which bad(i) holds, or n, on the team (a minimum: the same for any
// team).
template <class Bad>
std::size_t first_bad(std::size_t n, int team, Bad&& bad) {
  std::size_t first = n;
#pragma omp parallel for num_threads(team) schedule(static) \
    reduction(min                                           \
              : first) if (team > 1 && n >= kParallelFrom)
  for (std::int64_t i = 0; i < static_cast<std::int64_t>(n); ++i)
    if (bad(static_cast<std::size_t>(i))) first = std::min(first, static_cast<std::size_t>(i));
  return first;
}

}  // namespace

void validate(const TriMesh& mesh, const std::string& label, int threads) {
  const int team = threads > 0 ? threads : omp_get_max_threads();
  const std::size_t vertices = mesh.positions.size();
  const std::size_t v =
      first_bad(vertices, team, [&](std::size_t i) { return !is_finite(mesh.positions[i]); });
  if (v < vertices)
    throw InvalidInput(label + ": vertex " + std::to_string(v) + " has a non-finite coordinate");
  const std::size_t f = first_bad(mesh.faces.size(), team, [&](std::size_t i) {
    const Triangle& t = mesh.faces[i];
    return t[0] >= vertices || t[1] >= vertices || t[2] >= vertices;
  });
  if (f < mesh.faces.size())
    for (std::uint32_t corner : mesh.faces[f])
      if (corner >= vertices)
        throw InvalidInput(label + ": face " + std::to_string(f) + " uses vertex " +
                           std::to_string(corner) + " but the mesh has " +
                           std::to_string(vertices) + " vertices");
  for (const AttributeChannel& c : mesh.channels) {
    std::size_t elements = c.storage == Storage::kPerVertex   ? vertices
                           : c.storage == Storage::kPerCorner ? 3 * mesh.faces.size()
                                                              : mesh.faces.size();
    if (c.dim <= 0 || c.values.size() != elements * static_cast<std::size_t>(c.dim))
      throw InvalidInput(label + ": attribute '" + c.name + "' has " +
                         std::to_string(c.values.size()) + " values, expected " +
                         std::to_string(elements) + " x " + std::to_string(c.dim));
    const std::size_t i = first_bad(c.values.size(), team,
                                    [&](std::size_t k) { return !std::isfinite(c.values[k]); });
    if (i < c.values.size())
      throw InvalidInput(label + ": attribute '" + c.name + "' element " +
                         std::to_string(i / c.dim) + " is not finite");
  }
}

}  // namespace meshdev
