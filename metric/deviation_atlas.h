#pragma once
// The deviation texture atlas (paper §4): every face of the sampled mesh gets a small deviation
// image whose pixels are its scan-conversion samples, and the face images are packed into one
// square texture. The mesh gets per-corner texture coordinates into the atlas, so any viewer shows
// the deviation inside faces, not only at vertices.
//
//   for each face f = (A, B, C), step Δ:
//     sample (i, j) (s = iΔ/|AB|, t = jΔ/|AC|)  ->  texel (x_f + i, y_f + j)
//     texels of f's rectangle that hold no sample (beyond edge BC, one gutter row/column) copy the
//     nearest sample of f (clamp i, then j), so bilinear filtering never mixes faces
//     UV of the point with barycentrics (1-s-t, s, t): ((x_f + 0.5 + s|AB|/Δ) / S,
//                                                       1 - (y_f + 0.5 + t|AC|/Δ) / S)
//   rectangles ((n_u + 2) x (n_v + 2) texels) are shelf-packed, tallest first, into the smallest
//   square S x S found by growing S from sqrt(total rectangle area) in 2 % steps.
// The map from a sample to its texel is exact: the texel centre is the sample's UV.
#include <cstdint>
#include <string>
#include <vector>

#include "metric/colormap.h"
#include "metric/compare.h"
#include "metric/texture_image.h"

namespace meshdev {

struct AtlasOptions {
  std::size_t measure = 0;  // index into the comparison's measures (0 = geometry)
  ColorScale scale = ColorScale::kPaper;
  bool fixed_range = false;  // use [lo, hi] instead of the direction's [min, max]
  double lo = 0, hi = 0;
  int max_size = 16384;               // largest atlas side accepted (texels); larger: InvalidInput
  Vec3 background{0.25, 0.25, 0.25};  // texels no face uses
};

struct DeviationAtlas {
  int size = 0;  // S: the atlas is S x S texels
  Image image;   // the deviations coloured on the scale
  // Per texel (row-major, top row first): the face it belongs to (-1 = unused), whether it holds
  // one of that face's samples (else a copy for filtering), and the deviation value (NaN unused).
  std::vector<std::int32_t> texel_face;
  std::vector<std::uint8_t> texel_is_sample;
  std::vector<float> texel_value;
  TriMesh mesh;  // the sampled mesh: positions, faces, per-corner "texcoord" into the atlas
  double lo = 0, hi = 0;            // the colour range used
  std::size_t sample_texels = 0;    // texels holding a face sample (= face samples)
  std::size_t face_texels = 0;      // texels inside the faces' rectangles (samples + copies)
  double sample_efficiency = 0;     // sample_texels / S^2: the texture area that carries data
  double rectangle_efficiency = 0;  // face_texels / S^2: how well the rectangles are packed
  double seconds = 0;
};

// Builds the atlas of `direction` (computed with keep_samples and scan-conversion face samples)
// on `sampled`, the mesh that was sampled. Throws InvalidInput if the samples were not kept, there
// are no face samples, they are not on the scan-conversion grid (Monte Carlo), or S > max_size.
// O(F log F + S^2) time, O(S^2) memory.
DeviationAtlas build_deviation_atlas(const TriMesh& sampled, const DirectionResult& direction,
                                     const AtlasOptions& options);

}  // namespace meshdev
