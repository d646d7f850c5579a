#include "simplifiers/openmesh_convert.h"

#include <chrono>

#include <OpenMesh/Core/System/omstream.hh>

namespace meshdev {

OpenMeshQuiet::OpenMeshQuiet()
    : err_(omerr().is_enabled()), log_(omlog().is_enabled()), out_(omout().is_enabled()) {
  omerr().disable();
  omlog().disable();
  omout().disable();
}

OpenMeshQuiet::~OpenMeshQuiet() {
  if (err_) omerr().enable();
  if (log_) omlog().enable();
  if (out_) omout().enable();
}

namespace {

using Place = OmChannelSlot::Place;
const OmMesh::VertexHandle kNoV;
const OmMesh::HalfedgeHandle kNoH;
const OmMesh::FaceHandle kNoF;

// Chooses the OpenMesh home of each channel: the first channel of a standard kind and dimension
// takes the standard property, every other one a named property.
std::vector<OmChannelSlot> plan_slots(const TriMesh& mesh, OmMesh& om) {
  std::vector<OmChannelSlot> slots;
  bool used[9] = {};
  auto take = [&](Place p) {
    if (used[static_cast<int>(p)]) return false;
    used[static_cast<int>(p)] = true;
    return true;
  };
  for (const AttributeChannel& c : mesh.channels) {
    OmChannelSlot s;
    s.name = c.name;
    s.kind = c.kind;
    s.storage = c.storage;
    s.dim = c.dim;
    bool normal = c.kind == AttributeKind::kNormal && c.dim == 3;
    bool color = c.kind == AttributeKind::kColor && c.dim == 3;
    bool uv = c.kind == AttributeKind::kTexCoord && c.dim == 2;
    switch (c.storage) {
      case Storage::kPerVertex:
        if (normal && take(Place::kVertexNormal)) {
          s.place = Place::kVertexNormal;
        } else if (color && take(Place::kVertexColor)) {
          s.place = Place::kVertexColor;
        } else if (uv && take(Place::kVertexTexCoord)) {
          s.place = Place::kVertexTexCoord;
        } else {
          s.place = Place::kVertexProperty;
          om.add_property(s.vprop, "meshdev:" + c.name);
        }
        break;
      case Storage::kPerCorner:
        if (normal && take(Place::kHalfedgeNormal)) {
          s.place = Place::kHalfedgeNormal;
        } else if (uv && take(Place::kHalfedgeTexCoord)) {
          s.place = Place::kHalfedgeTexCoord;
        } else {
          s.place = Place::kHalfedgeProperty;
          om.add_property(s.hprop, "meshdev:" + c.name);
        }
        break;
      case Storage::kPerFace:
        if (normal && take(Place::kFaceNormal)) {
          s.place = Place::kFaceNormal;
        } else {
          s.place = Place::kFaceProperty;
          om.add_property(s.fprop, "meshdev:" + c.name);
        }
        break;
    }
    slots.push_back(s);
  }
  if (used[static_cast<int>(Place::kVertexNormal)]) om.request_vertex_normals();
  if (used[static_cast<int>(Place::kVertexColor)]) om.request_vertex_colors();
  if (used[static_cast<int>(Place::kVertexTexCoord)]) om.request_vertex_texcoords2D();
  if (used[static_cast<int>(Place::kHalfedgeNormal)]) om.request_halfedge_normals();
  if (used[static_cast<int>(Place::kHalfedgeTexCoord)]) om.request_halfedge_texcoords2D();
  if (used[static_cast<int>(Place::kFaceNormal)]) om.request_face_normals();
  return slots;
}

std::vector<double> values_of(const AttributeChannel& c, std::size_t element) {
  const double* p = c.element(element);
  return std::vector<double>(p, p + c.dim);
}

// Stores element `element` of channel `c` into the vertex / halfedge / face handle `h`.
void store(OmMesh& om, const OmChannelSlot& s, const AttributeChannel& c, std::size_t element,
           OmMesh::VertexHandle v, OmMesh::HalfedgeHandle h, OmMesh::FaceHandle f) {
  const double* p = c.element(element);
  switch (s.place) {
    case Place::kVertexNormal:
      om.set_normal(v, OmMesh::Normal(p[0], p[1], p[2]));
      break;
    case Place::kVertexColor:
      om.set_color(v, OmMesh::Color(p[0], p[1], p[2]));
      break;
    case Place::kVertexTexCoord:
      om.set_texcoord2D(v, OmMesh::TexCoord2D(p[0], p[1]));
      break;
    case Place::kVertexProperty:
      om.property(s.vprop, v) = values_of(c, element);
      break;
    case Place::kHalfedgeNormal:
      om.set_normal(h, OmMesh::Normal(p[0], p[1], p[2]));
      break;
    case Place::kHalfedgeTexCoord:
      om.set_texcoord2D(h, OmMesh::TexCoord2D(p[0], p[1]));
      break;
    case Place::kHalfedgeProperty:
      om.property(s.hprop, h) = values_of(c, element);
      break;
    case Place::kFaceNormal:
      om.set_normal(f, OmMesh::Normal(p[0], p[1], p[2]));
      break;
    case Place::kFaceProperty:
      om.property(s.fprop, f) = values_of(c, element);
      break;
  }
}

// Appends the value held at v / h / f for slot s to `out`.
void load(const OmMesh& om, const OmChannelSlot& s, OmMesh::VertexHandle v,
          OmMesh::HalfedgeHandle h, OmMesh::FaceHandle f, std::vector<double>& out) {
  auto push3 = [&](const OpenMesh::Vec3d& x) { out.insert(out.end(), {x[0], x[1], x[2]}); };
  switch (s.place) {
    case Place::kVertexNormal:
      push3(om.normal(v));
      break;
    case Place::kVertexColor:
      push3(om.color(v));
      break;
    case Place::kVertexTexCoord: {
      const auto& t = om.texcoord2D(v);
      out.insert(out.end(), {t[0], t[1]});
      break;
    }
    case Place::kVertexProperty: {
      const auto& x = om.property(s.vprop, v);
      out.insert(out.end(), x.begin(), x.end());
      break;
    }
    case Place::kHalfedgeNormal:
      push3(om.normal(h));
      break;
    case Place::kHalfedgeTexCoord: {
      const auto& t = om.texcoord2D(h);
      out.insert(out.end(), {t[0], t[1]});
      break;
    }
    case Place::kHalfedgeProperty: {
      const auto& x = om.property(s.hprop, h);
      out.insert(out.end(), x.begin(), x.end());
      break;
    }
    case Place::kFaceNormal:
      push3(om.normal(f));
      break;
    case Place::kFaceProperty: {
      const auto& x = om.property(s.fprop, f);
      out.insert(out.end(), x.begin(), x.end());
      break;
    }
  }
}

// The halfedge of face f that points to vertex v.
OmMesh::HalfedgeHandle corner_halfedge(const OmMesh& om, OmMesh::FaceHandle f,
                                       OmMesh::VertexHandle v) {
  for (OmMesh::HalfedgeHandle h : om.fh_range(f))
    if (om.to_vertex_handle(h) == v) return h;
  return OmMesh::HalfedgeHandle();
}

}  // namespace

OpenMeshConversion to_openmesh(const TriMesh& mesh) {
  OpenMeshQuiet quiet;
  OpenMeshConversion out;
  OmMesh& om = out.mesh;
  out.slots = plan_slots(mesh, om);

  // Vertices, then faces (add_face refuses complex edges/vertices: count them).
  std::vector<OmMesh::VertexHandle> vh(mesh.num_vertices());
  for (std::size_t v = 0; v < mesh.num_vertices(); ++v) {
    const Vec3& p = mesh.positions[v];
    vh[v] = om.add_vertex(OmMesh::Point(p.x, p.y, p.z));
  }
  std::vector<OmMesh::FaceHandle> fh(mesh.num_faces());
  for (std::size_t f = 0; f < mesh.num_faces(); ++f) {
    const Triangle& t = mesh.faces[f];
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) {
      ++out.refused_faces;
      continue;
    }
    fh[f] = om.add_face(vh[t[0]], vh[t[1]], vh[t[2]]);
    if (!fh[f].is_valid()) ++out.refused_faces;
  }

  // Attribute values.
  for (std::size_t i = 0; i < mesh.channels.size(); ++i) {
    const AttributeChannel& c = mesh.channels[i];
    const OmChannelSlot& s = out.slots[i];
    if (c.storage == Storage::kPerVertex) {
      for (std::size_t v = 0; v < mesh.num_vertices(); ++v) store(om, s, c, v, vh[v], kNoH, kNoF);
    } else {
      for (std::size_t f = 0; f < mesh.num_faces(); ++f) {
        if (!fh[f].is_valid()) continue;
        if (c.storage == Storage::kPerFace) {
          store(om, s, c, f, kNoV, kNoH, fh[f]);
          continue;
        }
        for (int k = 0; k < 3; ++k) {
          OmMesh::HalfedgeHandle h = corner_halfedge(om, fh[f], vh[mesh.faces[f][k]]);
          store(om, s, c, 3 * f + k, kNoV, h, kNoF);
        }
      }
    }
  }
  return out;
}

TriMesh from_openmesh(const OmMesh& om, const std::vector<OmChannelSlot>& slots) {
  TriMesh out;
  const bool has_status = om.has_vertex_status() && om.has_face_status();
  auto vertex_gone = [&](OmMesh::VertexHandle v) {
    return (has_status && om.status(v).deleted()) || om.is_isolated(v);
  };
  auto face_gone = [&](OmMesh::FaceHandle f) { return has_status && om.status(f).deleted(); };

  // Surviving vertices and faces, in index order.
  std::vector<std::uint32_t> index(om.n_vertices(), UINT32_MAX);
  std::vector<OmMesh::VertexHandle> kept_v;
  for (std::size_t i = 0; i < om.n_vertices(); ++i) {
    OmMesh::VertexHandle v(static_cast<int>(i));
    if (vertex_gone(v)) continue;
    index[i] = static_cast<std::uint32_t>(kept_v.size());
    kept_v.push_back(v);
    const auto& p = om.point(v);
    out.positions.push_back({p[0], p[1], p[2]});
  }
  std::vector<OmMesh::FaceHandle> kept_f;
  std::vector<std::array<OmMesh::HalfedgeHandle, 3>> corners;
  for (std::size_t i = 0; i < om.n_faces(); ++i) {
    OmMesh::FaceHandle f(static_cast<int>(i));
    if (face_gone(f)) continue;
    OmMesh::HalfedgeHandle h0 = om.halfedge_handle(f);
    OmMesh::HalfedgeHandle h1 = om.next_halfedge_handle(h0);
    OmMesh::HalfedgeHandle h2 = om.next_halfedge_handle(h1);
    out.faces.push_back({index[om.to_vertex_handle(h0).idx()], index[om.to_vertex_handle(h1).idx()],
                         index[om.to_vertex_handle(h2).idx()]});
    kept_f.push_back(f);
    corners.push_back({h0, h1, h2});
  }

  // Channels.
  for (const OmChannelSlot& s : slots) {
    AttributeChannel c;
    c.name = s.name;
    c.kind = s.kind;
    c.storage = s.storage;
    c.dim = s.dim;
    if (s.storage == Storage::kPerVertex) {
      c.values.reserve(kept_v.size() * s.dim);
      for (OmMesh::VertexHandle v : kept_v) load(om, s, v, kNoH, kNoF, c.values);
    } else if (s.storage == Storage::kPerFace) {
      c.values.reserve(kept_f.size() * s.dim);
      for (OmMesh::FaceHandle f : kept_f) load(om, s, kNoV, kNoH, f, c.values);
    } else {
      c.values.reserve(3 * kept_f.size() * s.dim);
      for (const auto& hs : corners)
        for (OmMesh::HalfedgeHandle h : hs) load(om, s, kNoV, h, kNoF, c.values);
    }
    out.channels.push_back(std::move(c));
  }
  return out;
}

bool convert_for_decimation(const TriMesh& mesh, OpenMeshConversion& conv,
                            std::vector<SimplifyResult>& results) {
  const auto start = std::chrono::steady_clock::now();
  conv = to_openmesh(mesh);
  if (conv.refused_faces > 0) {
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    for (SimplifyResult& r : results) {
      r.status = SimplifyStatus::kFailed;
      r.message = "OpenMesh refused " + std::to_string(conv.refused_faces) + " of " +
                  std::to_string(mesh.num_faces()) +
                  " faces (non-manifold edge or vertex, or a repeated vertex index)";
      r.wall_seconds = seconds;
    }
    return false;
  }
  conv.mesh.request_vertex_status();
  conv.mesh.request_halfedge_status();
  conv.mesh.request_edge_status();
  conv.mesh.request_face_status();
  return true;
}

}  // namespace meshdev
