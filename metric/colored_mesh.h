#pragma once
// The reference mesh coloured by a deviation (paper §5, Fig. 4-7): per-vertex colour on a scale
// and the value itself as the vertex "quality" channel (MeshLab shows both).
#include "metric/colormap.h"
#include "metric/compare.h"

namespace meshdev {

struct ColoringOptions {
  std::size_t measure = 0;  // index into ComparisonResult::measures (0 = geometry)
  ColorScale scale = ColorScale::kPaper;
  bool fixed_range = false;  // use [lo, hi] below instead of the data's [min, max]
  double lo = 0, hi = 0;
};

// Per-vertex deviation values of the sampled mesh of `direction` (which must have been computed
// with keep_samples): a vertex's own sample where vertices were sampled, else the area-weighted
// mean of the face samples of its incident faces (0 for a vertex with none). O(V + samples).
std::vector<double> vertex_deviation(const TriMesh& sampled, const DirectionResult& direction,
                                     std::size_t measure);

// A copy of `sampled` with "color" (per vertex, replacing any) and "quality" channels set from
// the direction's deviations. Throws InvalidInput if the samples were not kept. O(V + samples).
TriMesh color_by_deviation(const TriMesh& sampled, const DirectionResult& direction,
                           const ColoringOptions& options);

}  // namespace meshdev
