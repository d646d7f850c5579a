#include "metric/triangle_grid.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace meshdev {
namespace {

constexpr int kAxisBits = 21;
// Cell size = kCellFactor x sqrt(area / F), about one triangle width (coarsened while the
// reference count exceeds 16 F).
constexpr double kCellFactor = 1.0;
constexpr std::int64_t kMaxDim = (std::int64_t{1} << kAxisBits) - 1;

std::uint64_t pack(std::int64_t i, std::int64_t j, std::int64_t k) {
  return static_cast<std::uint64_t>(i) | static_cast<std::uint64_t>(j) << kAxisBits |
         static_cast<std::uint64_t>(k) << (2 * kAxisBits);
}

std::size_t hash(std::uint64_t key, std::size_t mask) {
  return static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ull) >> 20) & mask;
}

}  // namespace

TriangleGrid::TriangleGrid(const TriMesh& target, const TieOptions& ties, int threads)
    : eval_(target, ties, /*with_spheres=*/true, threads), bvh_(target, ties, threads) {
  const std::size_t faces = target.faces.size();
  const BoundingBox& box = eval_.box;
  const Vec3 extent = box.max - box.min;
  const double diag = box.diagonal();
  origin_ = box.min;
  const double area = surface_area(target);
  h_ = area > 0.0 ? kCellFactor * std::sqrt(area / static_cast<double>(faces)) : diag;
  if (!(h_ > 1e-9 * diag) || !std::isfinite(h_)) h_ = diag > 0.0 ? diag : 1.0;

  // Cell ranges of every triangle's box; coarsen until the reference count stays linear.
  std::vector<std::pair<std::uint64_t, std::uint32_t>> pairs;
  for (int attempt = 0;; ++attempt) {
    for (int k = 0; k < 3; ++k) {
      while (extent[k] / h_ >= static_cast<double>(kMaxDim)) h_ *= 2.0;
      dims_[k] = static_cast<std::int64_t>(std::floor(extent[k] / h_)) + 1;
    }
    inv_h_ = 1.0 / h_;
    pairs.clear();
    const std::size_t budget = 16 * faces + 1024;
    bool over = false;
    for (std::uint32_t f = 0; f < faces && !over; ++f) {
      std::int64_t lo[3], hi[3];
      for (int k = 0; k < 3; ++k) {
        double mn = +std::numeric_limits<double>::infinity(), mx = -mn;
        for (std::uint32_t v : target.faces[f]) {
          mn = std::min(mn, target.positions[v][k]);
          mx = std::max(mx, target.positions[v][k]);
        }
        lo[k] = std::clamp<std::int64_t>(
            static_cast<std::int64_t>(std::floor((mn - origin_[k]) * inv_h_)), 0, dims_[k] - 1);
        hi[k] = std::clamp<std::int64_t>(
            static_cast<std::int64_t>(std::floor((mx - origin_[k]) * inv_h_)), 0, dims_[k] - 1);
      }
      for (std::int64_t i = lo[0]; i <= hi[0] && !over; ++i)
        for (std::int64_t j = lo[1]; j <= hi[1] && !over; ++j)
          for (std::int64_t k = lo[2]; k <= hi[2]; ++k) {
            pairs.emplace_back(pack(i, j, k), f);
            if (pairs.size() > budget) {
              over = true;
              break;
            }
          }
    }
    if (!over || attempt > 40) break;
    h_ *= 2.0;
  }
  std::sort(pairs.begin(), pairs.end());

  // Compact reference lists and the hash table of occupied cells.
  refs_.resize(pairs.size());
  for (std::size_t i = 0; i < pairs.size(); ++i) refs_[i] = pairs[i].second;
  cell_count_ = 0;
  for (std::size_t i = 0; i < pairs.size(); ++i)
    cell_count_ += (i == 0 || pairs[i].first != pairs[i - 1].first);
  std::size_t capacity = 16;
  while (capacity < 2 * cell_count_) capacity *= 2;
  table_.assign(capacity, Slot{});
  const std::size_t mask = capacity - 1;
  for (std::size_t begin = 0; begin < pairs.size();) {
    std::size_t end = begin;
    while (end < pairs.size() && pairs[end].first == pairs[begin].first) ++end;
    std::size_t s = hash(pairs[begin].first, mask);
    while (table_[s].key != kEmpty) s = (s + 1) & mask;
    table_[s] = {pairs[begin].first, static_cast<std::uint32_t>(begin),
                 static_cast<std::uint32_t>(end)};
    begin = end;
  }
  double magnitude = 0.0;
  for (int k = 0; k < 3; ++k)
    magnitude = std::max(magnitude, std::fabs(origin_[k]) + extent[k] + h_);
  slack_ = 1e-9 * h_ + 1e-12 * magnitude;
}

std::size_t TriangleGrid::memory_bytes() const {
  return table_.size() * sizeof(Slot) + refs_.size() * sizeof(std::uint32_t) + bvh_.memory_bytes();
}

const TriangleGrid::Slot* TriangleGrid::lookup(std::uint64_t key) const {
  const std::size_t mask = table_.size() - 1;
  for (std::size_t s = hash(key, mask);; s = (s + 1) & mask) {
    if (table_[s].key == key) return &table_[s];
    if (table_[s].key == kEmpty) return nullptr;
  }
}

double TriangleGrid::find(const Vec3& p, const QueryHint& hint,
                          std::vector<SurfaceHit>& ties) const {
  std::int64_t cell[3];
  for (int k = 0; k < 3; ++k) {
    const double q = (p[k] - origin_[k]) * inv_h_;
    if (!(q >= 0.0 && q < static_cast<double>(dims_[k]))) return bvh_.find(p, hint, ties);
    cell[k] = static_cast<std::int64_t>(q);
  }
  const Slot* slot = lookup(pack(cell[0], cell[1], cell[2]));
  if (slot == nullptr) return bvh_.find(p, hint, ties);

  ties.clear();
  double best_sq = std::numeric_limits<double>::infinity();
  double limit = best_sq, limit_dist = best_sq;
  std::uint32_t best_face = kNoFace;
  // Faces identical to the query's source triangle are kept within the exact check's reach (see
  // TriangleBvh::find), so the search radius never falls below it.
  const double floor_dist = hint.has_source() ? std::sqrt(eval_.exact_check_sq) : 0.0;
  auto consider = [&](std::uint32_t f) {
    if (eval_.rejects(p, f, std::max(limit_dist, floor_dist))) return;
    const SurfaceHit h = eval_.evaluate(p, f, hint);
    if (h.sq_distance > limit) return;
    if (h.sq_distance < best_sq) {
      best_sq = h.sq_distance;
      best_face = h.face;
      limit = eval_.limit_sq(best_sq);
      limit_dist = std::sqrt(limit);
    }
    ties.push_back(h);
  };
  // The caller's start face (usually the previous sample's nearest) first: a tight bound early
  // lets the sphere test skip most of the cell's faces.
  const bool has_start = hint.start_face != kNoFace && hint.start_face < eval_.mesh->faces.size();
  if (has_start) consider(hint.start_face);
  for (std::uint32_t r = slot->begin; r < slot->end; ++r)
    if (refs_[r] != hint.start_face) consider(refs_[r]);
  // Exact only if the ball of the tie limit lies inside the cell: then every possible tie
  // overlaps the cell and is listed in it.
  double margin = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k) {
    const double lo = origin_[k] + static_cast<double>(cell[k]) * h_;
    margin = std::min({margin, p[k] - lo, lo + h_ - p[k]});
  }
  if (!(std::max(std::sqrt(limit), floor_dist) + slack_ < margin)) {
    QueryHint seeded = hint;
    seeded.start_face = best_face;
    return bvh_.find(p, seeded, ties);
  }
  detail::keep_ties(ties, limit);
  return std::sqrt(best_sq);
}

}  // namespace meshdev
