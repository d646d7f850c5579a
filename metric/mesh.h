#pragma once
// The compact indexed triangle mesh the metric works on: double positions, triangles, and named
// attribute channels of any dimension stored per vertex, per face corner (wedge) or per face.
// Readers (metric/io) produce it; simplifiers convert to and from their own types at their
// boundary. Units are those of the file (absolute).
#include <array>
#include <cstdint>
#include <deque>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "metric/vec3.h"

namespace meshdev {

using Triangle = std::array<std::uint32_t, 3>;

// Where an attribute channel stores its values.
enum class Storage : std::uint8_t {
  kPerVertex,  // values[v * dim + k]
  kPerCorner,  // values[(3 * f + c) * dim + k], c = corner 0..2 of triangle f (UV seams, hard
               // normals)
  kPerFace,    // values[f * dim + k] (flat over the triangle)
};

// What a channel means; decides how its deviation is measured (docs/metric.md).
enum class AttributeKind : std::uint8_t {
  kNormal,    // dim 3, need not be unit length in the file; normalised when evaluated
  kColor,     // dim 3, sRGB in [0, 1] (uchar colours are divided by 255)
  kTexCoord,  // dim 2, (u, v)
  kScalar,    // any other named property of any dim (quality, confidence, temperature, ...)
};

// "No face" (a point-cloud vertex, an empty slot, no answer yet).
inline constexpr std::uint32_t kNoFace = std::numeric_limits<std::uint32_t>::max();

struct AttributeChannel {
  std::string name;  // "normal", "color", "texcoord", or the file's own property name
  AttributeKind kind = AttributeKind::kScalar;
  Storage storage = Storage::kPerVertex;
  int dim = 1;
  std::vector<double> values;

  std::size_t element_count() const { return dim > 0 ? values.size() / dim : 0; }
  const double* element(std::size_t i) const { return values.data() + i * dim; }
  double* element(std::size_t i) { return values.data() + i * dim; }
};

struct TriMesh {
  std::vector<Vec3> positions;
  std::vector<Triangle> faces;
  // A deque, not a vector: the reference add_channel() returns stays valid when more channels
  // are added (a vector's reallocation made `auto& c = add_channel(..); add_channel(..); c...`
  // a use-after-free, found by the ASan test run).
  std::deque<AttributeChannel> channels;

  // Provenance, filled by the readers.
  std::string source_file;          // the path it was read from ("" if built in code)
  std::size_t source_polygons = 0;  // polygons in the file before triangulation
  std::string texture_file;  // map_Kd / "comment TextureFile", resolved against the file's folder

  std::size_t num_vertices() const { return positions.size(); }
  std::size_t num_faces() const { return faces.size(); }

  // The channel with this name, or nullptr.
  const AttributeChannel* channel(std::string_view name) const;
  AttributeChannel* channel(std::string_view name);
  // Adds (or replaces) a zero-filled channel sized for the current vertex/face counts.
  AttributeChannel& add_channel(std::string name, AttributeKind kind, Storage storage, int dim);
};

struct BoundingBox {
  Vec3 min{+1e300, +1e300, +1e300};
  Vec3 max{-1e300, -1e300, -1e300};

  bool empty() const { return min.x > max.x; }
  void extend(const Vec3& p) {  // NaN coordinates are ignored
    for (int k = 0; k < 3; ++k) {
      if (p[k] < min[k]) min[k] = p[k];
      if (p[k] > max[k]) max[k] = p[k];
    }
  }
  double diagonal() const;  // 0 for an empty box
};

// Box of the vertices used by a face (of all vertices if the mesh has no faces). O(V + F).
BoundingBox bounding_box(const TriMesh& mesh);
// The same box from `used` = referenced_vertices(mesh), for a caller that has it already (unread
// for a mesh without faces). O(V).
BoundingBox bounding_box(const TriMesh& mesh, const std::vector<bool>& used);
// The same box as bounding_box(mesh), from the faces' corners on `threads` OpenMP threads (0: the
// default), for large meshes in a parallel phase. O(F / threads).
BoundingBox corner_bounding_box(const TriMesh& mesh, int threads);
// Box of all vertices, referenced by a face or not (NaN ignored), on `threads` OpenMP threads (0:
// the default): it holds every face, reading the positions in order (corner_bounding_box reads
// them through the faces, three times as many reads out of order). O(V / threads).
BoundingBox position_bounding_box(const TriMesh& mesh, int threads);

// Area of triangle f (0 for a degenerate one). O(1).
double face_area(const TriMesh& mesh, std::size_t f);

// Sum of the triangle areas in face order, in file units squared. O(F).
double surface_area(const TriMesh& mesh);
// The same sum, bit for bit, with the areas computed on `threads` OpenMP threads (0: the
// default) and then added in face order on one thread. Precondition: face indices in range.
// O(F / threads + F) time, 8 F bytes of scratch.
double surface_area(const TriMesh& mesh, int threads);

// referenced[v] is true if some face uses vertex v. O(V + F).
std::vector<bool> referenced_vertices(const TriMesh& mesh);

// How many vertices some face uses, and their box: the count of true in referenced_vertices(mesh)
// and bounding_box(mesh) (so 0 and the box of all vertices for a mesh without faces), on
// `threads` OpenMP threads (0: the default), the same for any team. O((V + F) / threads).
struct ReferencedVertices {
  std::size_t count = 0;
  BoundingBox box;
};
ReferencedVertices referenced_vertex_summary(const TriMesh& mesh, int threads);

// Checks the invariants every algorithm relies on: finite positions, face indices in range,
// channel sizes consistent with their storage, finite channel values. Throws InvalidInput naming
// `label`, the first offending element (lowest index, whatever the team) and what is wrong.
// `threads`: OpenMP threads for the checks (0: the default). O((V + F + channel sizes) /
// threads).
void validate(const TriMesh& mesh, const std::string& label, int threads = 1);

}  // namespace meshdev
