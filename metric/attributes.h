#pragma once
// Which attributes a comparison measures, how they are evaluated at a point of a mesh, and how
// two values are compared (the f_i and ||.|| of the paper's Eq. 3).
#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "metric/mesh.h"
#include "metric/texture_image.h"
#include "metric/vertex_normals.h"

namespace meshdev {

enum class MeasureKind : std::uint8_t {
  kGeometry,         // |p - p'|, mesh units
  kNormalEuclidean,  // |n(p) - n(p')| of unit normals (the paper's measure), in [0, 2]
  kNormalAngle,      // angle between n(p) and n(p'), degrees in [0, 180]
  kColorRgb,         // Euclidean sRGB distance, components in [0, 1], so in [0, sqrt(3)]
  kColorDeltaE76,    // CIE76 ΔE*ab in CIELAB
  kColorDeltaE2000,  // CIEDE2000 ΔE00
  kTexCoord,         // Euclidean distance in (u, v)
  kScalar,           // Euclidean distance of any other channel (absolute value for 1-D)
  // Not nearest-point measures of a channel value (metric/texture_deviation.h):
  kCohenTexture,  // Cohen's texture deviation (paper Eq. 2): |p - p''|, p'' = the point of the
                  // target with the same (u, v) as p; mesh units
  // The colour of each mesh's texture image at the (u, v) of p and of the nearest point p':
  kTextureColorRgb,         // Euclidean sRGB distance, components in [0, 1]
  kTextureColorDeltaE76,    // CIE76 ΔE*ab
  kTextureColorDeltaE2000,  // CIEDE2000 ΔE00
};

// True for the measures that compare texture images (need PreparedMesh::texture on both sides).
bool is_texture_color(MeasureKind kind);

struct Measure {
  std::string name;  // column/key name: geometry, normal, normal_angle, color, color_de76, ...
  MeasureKind kind = MeasureKind::kGeometry;
  std::string channel;  // channel compared ("" for geometry)
  std::string unit;     // human-readable unit
};

// Where normals come from.
enum class NormalSource : std::uint8_t {
  kAuto,     // the file's normals if both meshes have them, else computed kUniform on both
  kFile,     // the files' normals (error if a mesh has none)
  kUniform,  // computed: plain average of face normals (the paper)
  kArea,     // computed: area-weighted
  kAngle,    // computed: angle-weighted
};

struct AttributeOptions {
  // Attributes to measure: "geometry", "normal", "color", "texcoord" or a channel name present on
  // both meshes (e.g. "quality", "temperature"); "cohen" adds Cohen's texture deviation
  // ("texcoord_cohen", with "texcoord" beside it); "texture" compares the texture images at the
  // texture coordinates (texture_color, texture_color_de76, texture_color_de2000; both meshes
  // need "texcoord" and a texture_file, which is read here: IoError if unreadable). Neither is
  // part of the automatic set. Empty = automatic: geometry, normal, and every
  // channel present on both meshes with the same dimension. An explicitly requested attribute
  // missing on either mesh is an InvalidInput error.
  std::vector<std::string> attributes;
  NormalSource normals = NormalSource::kAuto;
  int threads = 0;  // OpenMP threads for computed normals (0 = OpenMP's default); same result
};

// A mesh with the channels a comparison needs: its own plus any computed ones (normals).
struct PreparedMesh {
  const TriMesh* mesh = nullptr;
  std::vector<AttributeChannel> computed;  // looked up before the mesh's own channels
  std::shared_ptr<const Image> texture;    // the mesh's texture_file, when "texture" is measured

  const AttributeChannel* channel(std::string_view name) const;
};

// The resolved plan: what is measured and the two prepared meshes.
struct AttributePlan {
  std::vector<Measure> measures;  // geometry first
  PreparedMesh a, b;
  std::string normal_source;  // what was used: "file", "computed (uniform average)", ...
};

// What plan_attributes derives from mesh A alone, kept for the next plan with the same A
// (ComparisonReference, metric/compare.h: a sweep compares one A with many simplifications): A's
// computed normals, per weighting, and A's texture image. Empty until a plan fills it.
struct ReferenceAttributes {
  std::vector<std::pair<NormalWeighting, AttributeChannel>> normals;
  std::shared_ptr<const Image> texture;
};

// Resolves `options` against both meshes (labels name them in errors). Throws InvalidInput for
// an unknown or one-sided attribute, or dimension mismatch. With `a_cache` (made for this A and
// no other), A's computed normals and texture image are taken from it where it has them and put
// into it where it has not: the same plan either way. O(V + F) for computed normals.
AttributePlan plan_attributes(const TriMesh& a, const TriMesh& b, const AttributeOptions& options,
                              const std::string& label_a, const std::string& label_b,
                              ReferenceAttributes* a_cache = nullptr);

// Component k of the value at barycentrics `bary` between the corner values a, b and c: the one
// barycentric mix of the metric (interpolate, and the deviation loop's inline path), so both
// give the same bits. O(1).
inline double barycentric_mix(const std::array<double, 3>& bary, const double* a, const double* b,
                              const double* c, int k) {
  return bary[0] * a[k] + bary[1] * b[k] + bary[2] * c[k];
}

// Value of `channel` at barycentrics `bary` of `face` (kNoFace: at vertex `vertex`, for point
// clouds), written to out[0..dim). Barycentric interpolation in corner order 0, 1, 2; per-corner
// channels use the corners of that face, per-face channels are constant on it. O(dim).
// Inline: it runs once per sample and tie in the metric's inner loop.
inline void interpolate(const AttributeChannel& channel, const TriMesh& mesh, std::uint32_t face,
                        const std::array<double, 3>& bary, std::uint32_t vertex, double* out) {
  const int dim = channel.dim;
  if (face == kNoFace) {  // a point-cloud vertex: only per-vertex channels exist
    const double* v = channel.element(vertex);
    for (int k = 0; k < dim; ++k) out[k] = v[k];
    return;
  }
  if (channel.storage == Storage::kPerFace) {
    const double* v = channel.element(face);
    for (int k = 0; k < dim; ++k) out[k] = v[k];
    return;
  }
  const double* v[3];
  for (int i = 0; i < 3; ++i)
    v[i] = channel.storage == Storage::kPerVertex ? channel.element(mesh.faces[face][i])
                                                  : channel.element(3 * face + i);
  auto mix = [&](int k) { return barycentric_mix(bary, v[0], v[1], v[2], k); };
  // Normals and colours: all three read before any is written (out may alias the channel, so
  // otherwise each store must land before the next read), which lets GCC store 16 + 8 bytes, the
  // widths that to_form and form_distance load them with. Three 8-byte stores cannot forward to a
  // 16-byte load, and that version was 7-10 % slower (torus100k -> 10k, 1 thread: 3.93 vs 4.19 M/s;
  // the stall is inferred, this VM has no hardware counters).
  if (dim == 3) {
    const double x = mix(0), y = mix(1), z = mix(2);  // all read before `out` is written
    out[0] = x;
    out[1] = y;
    out[2] = z;
    return;
  }
  for (int k = 0; k < dim; ++k) out[k] = mix(k);
}

// Deviation between two channel values under `kind` (not kGeometry). O(dim).
// Equal, bit for bit, to form_distance(kind, to_form(x), to_form(y), dim) with the form of kind.
double attribute_distance(MeasureKind kind, const double* x, const double* y, int dim);

// What a measure compares of a channel value: the value itself, its unit vector (normals) or its
// CIELAB colour (ΔE measures). Measures of one channel with one form share the transform, so it
// is computed once per point (metric/attribute_deviation.cpp).
enum class ValueForm : std::uint8_t { kRaw, kUnit, kLab };
ValueForm value_form(MeasureKind kind);
// Writes `x` (dim components) in `form` to `out`: a copy (dim values), the unit vector (0 for a
// zero normal) or sRGB -> CIELAB (3 values; x has 3 components). O(dim).
void to_form(ValueForm form, const double* x, int dim, double* out);
// attribute_distance of two values already in value_form(kind) (from to_form). O(dim).
double form_distance(MeasureKind kind, const double* x, const double* y, int dim);

// to_form's kUnit, inline for the deviation loop: n / |n|, or 0 for a zero vector. O(1).
inline Vec3 unit_normal(const Vec3& n) {
  const double len = norm(n);
  return len > 0.0 ? (1.0 / len) * n : Vec3{};
}
// True for the measures of unit normals (form kUnit): kNormalEuclidean, kNormalAngle.
inline bool is_unit_normal_measure(MeasureKind kind) {
  return kind == MeasureKind::kNormalEuclidean || kind == MeasureKind::kNormalAngle;
}
// The angle in degrees between unit normals n and m (from unit_normal) from their chords
// `chord` = |n - m| and `across` = |n + m|; 90 if either normal is 0 (`either_zero`: undefined,
// no information). 2 asin(|n - m| / 2) up to 90 degrees, pi - 2 asin(|n + m| / 2) beyond, each
// well conditioned where it is used (Kahan, "How futile are mindless assessments of roundoff",
// 2006, sec. 12); as accurate as atan2(|n x m|, n.m) and cheaper in glibc (torus100k -> 10k,
// 1 thread: 3.74 -> 4.16 M samples/s, docs/performance-log.md §3). Taking the chords lets a caller
// that also reports |n - m| compute it once, and one that computes them two samples at a time
// (the deviation loop) share this. O(1).
inline double unit_normal_angle(double chord, double across, bool either_zero) {
  constexpr double kPi = 3.14159265358979323846;
  if (either_zero) return 90.0;
  const double radians =
      chord <= across ? 2.0 * std::asin(0.5 * chord) : kPi - 2.0 * std::asin(0.5 * across);
  return radians * (180.0 / kPi);
}
// The same given the normals themselves and their chord |n - m|. O(1).
inline double unit_normal_angle(double chord, const Vec3& n, const Vec3& m) {
  if (n == Vec3{} || m == Vec3{}) return unit_normal_angle(chord, 0.0, true);
  return unit_normal_angle(chord, norm(n + m), false);
}
// form_distance of two unit normals (from unit_normal) under a kind with is_unit_normal_measure,
// given their chord |n - m| (so a caller with both normal measures computes it once), inline for
// the deviation loop. kNormalEuclidean: the chord; kNormalAngle: unit_normal_angle. O(1).
inline double unit_normal_distance(MeasureKind kind, double chord, const Vec3& n, const Vec3& m) {
  return kind == MeasureKind::kNormalEuclidean ? chord : unit_normal_angle(chord, n, m);
}
// The same from both chords |n - m| and |n + m| and whether either normal is 0 (the deviation
// loop's two-sample path, which computes them for two samples at once). O(1).
inline double unit_normal_distance(MeasureKind kind, double chord, double across,
                                   bool either_zero) {
  return kind == MeasureKind::kNormalEuclidean ? chord
                                               : unit_normal_angle(chord, across, either_zero);
}
// The same with the chord computed here (form_distance calls it). O(1).
inline double unit_normal_distance(MeasureKind kind, const Vec3& n, const Vec3& m) {
  return unit_normal_distance(kind, norm(n - m), n, m);
}

// Parses a --normals value: auto, file, uniform (= average), area, angle.
NormalSource parse_normal_source(const std::string& text);

}  // namespace meshdev
