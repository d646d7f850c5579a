#include "metric/mesh.h"

#include <omp.h>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdint>

#include "metric/errors.h"

namespace meshdev {

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
  // overlapping on their own (torus1m with its faces shuffled: docs/performance.md §3).
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

std::vector<bool> referenced_vertices(const TriMesh& mesh) {
  std::vector<bool> used(mesh.positions.size(), false);
  for (const Triangle& t : mesh.faces)
    for (std::uint32_t v : t)
      if (v < used.size()) used[v] = true;
  return used;
}

void validate(const TriMesh& mesh, const std::string& label) {
  for (std::size_t v = 0; v < mesh.positions.size(); ++v)
    if (!is_finite(mesh.positions[v]))
      throw InvalidInput(label + ": vertex " + std::to_string(v) + " has a non-finite coordinate");
  for (std::size_t f = 0; f < mesh.faces.size(); ++f)
    for (std::uint32_t v : mesh.faces[f])
      if (v >= mesh.positions.size())
        throw InvalidInput(label + ": face " + std::to_string(f) + " uses vertex " +
                           std::to_string(v) + " but the mesh has " +
                           std::to_string(mesh.positions.size()) + " vertices");
  for (const AttributeChannel& c : mesh.channels) {
    std::size_t elements = c.storage == Storage::kPerVertex   ? mesh.positions.size()
                           : c.storage == Storage::kPerCorner ? 3 * mesh.faces.size()
                                                              : mesh.faces.size();
    if (c.dim <= 0 || c.values.size() != elements * static_cast<std::size_t>(c.dim))
      throw InvalidInput(label + ": attribute '" + c.name + "' has " +
                         std::to_string(c.values.size()) + " values, expected " +
                         std::to_string(elements) + " x " + std::to_string(c.dim));
    for (std::size_t i = 0; i < c.values.size(); ++i)
      if (!std::isfinite(c.values[i]))
        throw InvalidInput(label + ": attribute '" + c.name + "' element " +
                           std::to_string(i / c.dim) + " is not finite");
  }
}

}  // namespace meshdev
