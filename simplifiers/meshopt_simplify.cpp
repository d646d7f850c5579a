#include "simplifiers/meshopt_simplify.h"

#include <meshoptimizer.h>

#include <chrono>
#include <cstdint>

#include "metric/errors.h"

namespace meshdev {
namespace {

// The meshopt vertex buffer: one entry per distinct (vertex, per-corner values) pair.
struct Wedges {
  std::vector<float> positions;           // 3 per wedge
  std::vector<std::uint32_t> vertex;      // wedge -> our vertex
  std::vector<std::size_t> first_corner;  // wedge -> a corner (3 f + c) it stands for, or SIZE_MAX
  std::vector<unsigned> indices;          // 3 per input face, wedge ids
};

Wedges build_wedges(const TriMesh& mesh) {
  Wedges w;
  std::vector<const AttributeChannel*> corner_channels;
  for (const AttributeChannel& c : mesh.channels)
    if (c.storage == Storage::kPerCorner) corner_channels.push_back(&c);
  auto add = [&](std::uint32_t v, std::size_t corner) {
    const Vec3& p = mesh.positions[v];
    w.positions.insert(w.positions.end(),
                       {static_cast<float>(p.x), static_cast<float>(p.y), static_cast<float>(p.z)});
    w.vertex.push_back(v);
    w.first_corner.push_back(corner);
    return static_cast<unsigned>(w.vertex.size() - 1);
  };
  w.indices.resize(3 * mesh.num_faces());
  if (corner_channels.empty()) {
    for (std::uint32_t v = 0; v < mesh.num_vertices(); ++v) add(v, SIZE_MAX);
    for (std::size_t f = 0; f < mesh.num_faces(); ++f)
      for (int k = 0; k < 3; ++k) w.indices[3 * f + k] = mesh.faces[f][k];
    return w;
  }
  // Corners of the same vertex with equal values in every per-corner channel share a wedge.
  auto same = [&](std::size_t a, std::size_t b) {
    for (const AttributeChannel* c : corner_channels)
      for (int k = 0; k < c->dim; ++k)
        if (c->element(a)[k] != c->element(b)[k]) return false;
    return true;
  };
  std::vector<std::vector<unsigned>> wedges_of(mesh.num_vertices());
  for (std::size_t f = 0; f < mesh.num_faces(); ++f) {
    for (int k = 0; k < 3; ++k) {
      std::size_t corner = 3 * f + k;
      std::uint32_t v = mesh.faces[f][k];
      unsigned id = UINT32_MAX;
      for (unsigned candidate : wedges_of[v])
        if (same(w.first_corner[candidate], corner)) id = candidate;
      if (id == UINT32_MAX) {
        id = add(v, corner);
        wedges_of[v].push_back(id);
      }
      w.indices[corner] = id;
    }
  }
  return w;
}

}  // namespace

MeshoptSimplifier::MeshoptSimplifier(MeshoptVariant variant, MeshoptOptions options)
    : variant_(variant), options_(options) {}

std::string MeshoptSimplifier::name() const {
  return variant_ == MeshoptVariant::kSimplify ? "meshopt" : "meshopt-sloppy";
}

std::string MeshoptSimplifier::description() const {
  return variant_ == MeshoptVariant::kSimplify
             ? "meshoptimizer 0.18 meshopt_simplify: edge collapse onto input vertices, quadric "
               "error, keeps topology and UV seams"
             : "meshoptimizer 0.18 meshopt_simplifySloppy: vertex clustering, ignores topology, "
               "may undershoot the target";
}

std::string MeshoptSimplifier::role() const {
  return variant_ == MeshoptVariant::kSimplify ? "fast vertex-subset quadric (game-engine LOD)"
                                               : "fast clustering baseline";
}

std::string MeshoptSimplifier::keeps() const {
  return "per-vertex channels (exact, vertices never move), per-corner channels (unwelded "
         "wedges); per-face channels dropped";
}

OutputGuarantees MeshoptSimplifier::guarantees() const {
  OutputGuarantees g;
  g.manifold = variant_ == MeshoptVariant::kSimplify;
  g.no_new_degenerate = false;
  return g;
}

std::vector<OptionInfo> MeshoptSimplifier::options() const {
  std::vector<OptionInfo> o{
      {"target_error", "1.0", "max error relative to the mesh extent (1 = stop at the count)"}};
  if (variant_ == MeshoptVariant::kSimplify)
    o.push_back({"lock_border", "false", "meshopt_SimplifyLockBorder: keep border vertices"});
  return o;
}

void MeshoptSimplifier::set_option(const std::string& key, const std::string& value) {
  if (key == "target_error") {
    double v = detail::parse_double_option(key, value);
    if (!(v >= 0.0)) throw InvalidInput("option target_error: must be >= 0, got " + value);
    options_.target_error = v;
  } else if (key == "lock_border" && variant_ == MeshoptVariant::kSimplify) {
    options_.lock_border = detail::parse_bool_option(key, value);
  } else {
    detail::throw_unknown_option(name(), key, options());
  }
}

SimplifyResult MeshoptSimplifier::simplify(const TriMesh& mesh, const SimplifyRequest& request) {
  detail::check_input(mesh, name());
  SimplifyResult result;
  result.input_faces = mesh.num_faces();
  result.target_faces = resolve_target_faces(request, mesh.num_faces());
  const auto start = std::chrono::steady_clock::now();

  // 1. Float wedge buffer, then one meshopt call (dst must hold index_count entries).
  Wedges w = build_wedges(mesh);
  const std::size_t wedge_count = w.vertex.size();
  std::vector<unsigned> dst(w.indices.size());
  float error = 0.0f;
  std::size_t out_indices = 0;
  const std::size_t target_indices = 3 * result.target_faces;
  const float target_error = static_cast<float>(options_.target_error);
  if (result.target_faces >= mesh.num_faces()) {
    dst = w.indices;
    out_indices = dst.size();
  } else if (variant_ == MeshoptVariant::kSimplify) {
    out_indices =
        meshopt_simplify(dst.data(), w.indices.data(), w.indices.size(), w.positions.data(),
                         wedge_count, 3 * sizeof(float), target_indices, target_error,
                         options_.lock_border ? unsigned{meshopt_SimplifyLockBorder} : 0u, &error);
  } else {
    out_indices = meshopt_simplifySloppy(dst.data(), w.indices.data(), w.indices.size(),
                                         w.positions.data(), wedge_count, 3 * sizeof(float),
                                         target_indices, target_error, &error);
  }
  result.backend_error = error;

  // 2. Weld back: wedges -> our vertices (compacted, in input order); drop triangles that land
  //    on a repeated vertex.
  TriMesh& out = result.mesh;
  std::vector<std::uint32_t> new_index(mesh.num_vertices(), UINT32_MAX);
  std::vector<unsigned> kept_tris;
  std::size_t collapsed = 0;
  for (std::size_t t = 0; t + 2 < out_indices; t += 3) {
    std::uint32_t a = w.vertex[dst[t]], b = w.vertex[dst[t + 1]], c = w.vertex[dst[t + 2]];
    if (a == b || b == c || a == c) {
      ++collapsed;
      continue;
    }
    kept_tris.insert(kept_tris.end(), {dst[t], dst[t + 1], dst[t + 2]});
    new_index[a] = new_index[b] = new_index[c] = 0;
  }
  std::vector<std::uint32_t> old_of_new;
  for (std::uint32_t v = 0; v < mesh.num_vertices(); ++v) {
    if (new_index[v] == UINT32_MAX) continue;
    new_index[v] = static_cast<std::uint32_t>(old_of_new.size());
    old_of_new.push_back(v);
    out.positions.push_back(mesh.positions[v]);
  }
  for (std::size_t t = 0; t < kept_tris.size(); t += 3)
    out.faces.push_back({new_index[w.vertex[kept_tris[t]]], new_index[w.vertex[kept_tris[t + 1]]],
                         new_index[w.vertex[kept_tris[t + 2]]]});

  // 3. Channels: per-vertex copied, per-corner from each output corner's wedge.
  for (const AttributeChannel& c : mesh.channels) {
    if (c.storage == Storage::kPerFace) {
      result.dropped.push_back(c.name);
      continue;
    }
    AttributeChannel& o = out.add_channel(c.name, c.kind, c.storage, c.dim);
    if (c.storage == Storage::kPerVertex) {
      for (std::size_t v = 0; v < old_of_new.size(); ++v)
        std::copy(c.element(old_of_new[v]), c.element(old_of_new[v]) + c.dim, o.element(v));
    } else {
      for (std::size_t k = 0; k < kept_tris.size(); ++k) {
        const double* src = c.element(w.first_corner[kept_tris[k]]);
        std::copy(src, src + c.dim, o.element(k));
      }
    }
    result.kept.push_back(c.name);
  }
  result.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (collapsed > 0)
    result.message = std::to_string(collapsed) + " triangles on a repeated vertex dropped";
  std::size_t zero_area = 0;
  for (std::size_t f = 0; f < out.num_faces(); ++f) zero_area += face_area(out, f) == 0.0 ? 1 : 0;
  if (zero_area > 0)
    result.message += (result.message.empty() ? "" : "; ") + std::to_string(zero_area) +
                      " zero-area triangles in the output";
  if (!result.dropped.empty()) {
    std::string d = "per-face channels dropped:";
    for (const std::string& n : result.dropped) d += " " + n;
    result.message += (result.message.empty() ? "" : "; ") + d;
  }
  detail::set_status_from_counts(result);
  return result;
}

}  // namespace meshdev
