#pragma once
// TriMesh <-> OpenMesh triangle mesh with double positions, carrying the attribute channels:
//   per-vertex  normal (kNormal, dim 3) -> vertex_normals, colour (kColor, dim 3) -> vertex_colors,
//               texcoord (kTexCoord, dim 2) -> vertex_texcoords2D, any other -> a vertex property
//               std::vector<double> named after the channel;
//   per-corner  texcoord -> halfedge_texcoords2D, normal -> halfedge_normals, other -> halfedge
//               property (the halfedge of a face pointing to the corner's vertex holds it);
//   per-face    normal (kNormal, dim 3) -> face_normals, other -> face property.
// Only the first channel of each standard kind goes to the standard property; the rest become
// named properties. Internal to meshdev::simplifiers (it includes OpenMesh).
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <cstddef>
#include <string>
#include <vector>

#include "metric/mesh.h"
#include "simplifiers/simplifier.h"

namespace meshdev {

struct OpenMeshTraits : public OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;
  using Normal = OpenMesh::Vec3d;
  using Color = OpenMesh::Vec3d;  // sRGB in [0,1], as in TriMesh
  using TexCoord2D = OpenMesh::Vec2d;
};
using OmMesh = OpenMesh::TriMesh_ArrayKernelT<OpenMeshTraits>;

// Where one TriMesh channel lives in the OpenMesh mesh.
struct OmChannelSlot {
  enum class Place {
    kVertexNormal,
    kVertexColor,
    kVertexTexCoord,
    kVertexProperty,
    kHalfedgeNormal,
    kHalfedgeTexCoord,
    kHalfedgeProperty,
    kFaceNormal,
    kFaceProperty,
  };
  std::string name;
  AttributeKind kind = AttributeKind::kScalar;
  Storage storage = Storage::kPerVertex;
  int dim = 1;
  Place place = Place::kVertexProperty;
  OpenMesh::VPropHandleT<std::vector<double>> vprop;  // valid for kVertexProperty
  OpenMesh::HPropHandleT<std::vector<double>> hprop;  // valid for kHalfedgeProperty
  OpenMesh::FPropHandleT<std::vector<double>> fprop;  // valid for kFaceProperty
};

struct OpenMeshConversion {
  OmMesh mesh;
  std::vector<OmChannelSlot> slots;  // one per input channel, in the input's order
  std::size_t refused_faces = 0;     // faces add_face rejected (non-manifold edge or vertex,
                                     // repeated vertex index); they are missing from `mesh`
};

// Builds the OpenMesh mesh: one vertex per TriMesh vertex (same index), faces in order (a face
// OpenMesh refuses is counted in refused_faces and skipped, so face indices shift after it).
// OpenMesh's own error output is silenced during the call. O(V + F + channel sizes).
OpenMeshConversion to_openmesh(const TriMesh& mesh);

// The common start of the OpenMesh-based backends: converts `mesh` into `conv` and requests the
// vertex/halfedge/edge/face status flags (reference counted, so they outlive the decimater; see
// docs/simplifiers.md). If OpenMesh refused faces (non-manifold input), every result becomes
// kFailed with the reason and the conversion time, and false is returned. O(V + F).
bool convert_for_decimation(const TriMesh& mesh, OpenMeshConversion& conv,
                            std::vector<SimplifyResult>& results);

// Converts back, skipping deleted elements (no garbage_collection needed) and vertices no face
// uses; survivors keep their relative order. Fills the channels listed in `slots`.
// O(V + F + channel sizes).
TriMesh from_openmesh(const OmMesh& mesh, const std::vector<OmChannelSlot>& slots);

// Silences OpenMesh's omerr/omlog/omout streams while alive (they are global).
class OpenMeshQuiet {
 public:
  OpenMeshQuiet();
  ~OpenMeshQuiet();
  OpenMeshQuiet(const OpenMeshQuiet&) = delete;
  OpenMeshQuiet& operator=(const OpenMeshQuiet&) = delete;

 private:
  bool err_, log_, out_;
};

}  // namespace meshdev
