#include "metric/colored_mesh.h"

#include "metric/errors.h"

namespace meshdev {

std::vector<double> vertex_deviation(const TriMesh& sampled, const DirectionResult& d,
                                     std::size_t measure) {
  if (d.deviations.values.size() <= measure || d.sample_set.samples.empty())
    throw InvalidInput("per-sample deviations were not kept: cannot colour the mesh");
  const SampleVector& samples = d.sample_set.samples;
  const DeviationArray& values = d.deviations.values[measure];
  std::vector<double> out(sampled.num_vertices(), 0.0);
  std::vector<bool> have(sampled.num_vertices(), false);
  for (std::size_t i = 0; i < samples.size(); ++i)
    if (samples[i].kind == SampleKind::kVertex) {
      out[samples[i].vertex] = values[i];
      have[samples[i].vertex] = true;
    }
  // Vertices without their own sample: area-weighted mean over the incident faces' samples.
  std::vector<double> face_sum(sampled.num_faces(), 0.0), face_weight(sampled.num_faces(), 0.0);
  for (std::size_t i = 0; i < samples.size(); ++i)
    if (samples[i].kind == SampleKind::kFace) {
      face_sum[samples[i].face] += samples[i].weight * values[i];
      face_weight[samples[i].face] += samples[i].weight;
    }
  std::vector<double> sum(sampled.num_vertices(), 0.0), weight(sampled.num_vertices(), 0.0);
  for (std::size_t f = 0; f < sampled.num_faces(); ++f)
    for (std::uint32_t v : sampled.faces[f]) {
      sum[v] += face_sum[f];
      weight[v] += face_weight[f];
    }
  for (std::size_t v = 0; v < out.size(); ++v)
    if (!have[v] && weight[v] > 0.0) out[v] = sum[v] / weight[v];
  return out;
}

TriMesh color_by_deviation(const TriMesh& sampled, const DirectionResult& d,
                           const ColoringOptions& o) {
  const std::vector<double> values = vertex_deviation(sampled, d, o.measure);
  double lo = o.lo, hi = o.hi;
  if (o.fixed_range) {
    check_color_range(lo, hi);
  } else {
    lo = d.stats[o.measure].min;
    hi = d.stats[o.measure].max;
  }
  TriMesh out = sampled;
  out.add_channel("color", AttributeKind::kColor, Storage::kPerVertex, 3);
  out.add_channel("quality", AttributeKind::kScalar, Storage::kPerVertex, 1);
  AttributeChannel& color = *out.channel("color");  // fetched after both adds: no reallocation
  AttributeChannel& quality = *out.channel("quality");
  for (std::size_t v = 0; v < values.size(); ++v) {
    const Vec3 c = map_color(values[v], lo, hi, o.scale);
    color.values[3 * v] = c.x;
    color.values[3 * v + 1] = c.y;
    color.values[3 * v + 2] = c.z;
    quality.values[v] = values[v];
  }
  return out;
}

}  // namespace meshdev
