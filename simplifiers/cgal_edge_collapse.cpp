#include "simplifiers/cgal_edge_collapse.h"

#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/GarlandHeckbert_plane_policies.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/LindstromTurk_cost.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/LindstromTurk_placement.h>
#include <CGAL/Surface_mesh_simplification/edge_collapse.h>

#include <chrono>

#include "metric/errors.h"

namespace meshdev {
namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using SurfaceMesh = CGAL::Surface_mesh<Kernel::Point_3>;
namespace SMS = CGAL::Surface_mesh_simplification;

// Stops when the mesh has at most `target` faces (CGAL 5.5 only counts edges).
struct FaceCountStop {
  const SurfaceMesh* mesh;
  std::size_t target;
  template <class FT, class Profile>
  bool operator()(const FT&, const Profile&, std::size_t, std::size_t) const {
    return mesh->number_of_faces() <= target;
  }
};

}  // namespace

CgalEdgeCollapse::CgalEdgeCollapse(CgalPolicy policy, CgalEdgeCollapseOptions options)
    : policy_(policy), options_(options) {}

std::string CgalEdgeCollapse::name() const {
  return policy_ == CgalPolicy::kGarlandHeckbert ? "cgal-gh" : "cgal-lt";
}

std::string CgalEdgeCollapse::description() const {
  return policy_ == CgalPolicy::kGarlandHeckbert
             ? "CGAL 5.5 edge_collapse, GarlandHeckbert_plane_policies: plane quadrics, optimal "
               "placement"
             : "CGAL 5.5 edge_collapse, Lindstrom-Turk cost and placement";
}

std::string CgalEdgeCollapse::role() const {
  return policy_ == CgalPolicy::kGarlandHeckbert ? "QSlim-like" : "Lindstrom-Turk (memoryless)";
}

std::string CgalEdgeCollapse::keeps() const {
  return "per-vertex channels from the surviving vertex (approximate: it moves), normals "
         "recomputed; per-corner and per-face channels dropped";
}

OutputGuarantees CgalEdgeCollapse::guarantees() const {
  OutputGuarantees g;
  g.vertices_fixed = false;
  return g;
}

std::vector<OptionInfo> CgalEdgeCollapse::options() const {
  if (policy_ == CgalPolicy::kLindstromTurk) return {};
  return {{"boundary_weight", "100", "weight of the boundary quadrics (GH dm)"}};
}

void CgalEdgeCollapse::set_option(const std::string& key, const std::string& value) {
  if (policy_ == CgalPolicy::kGarlandHeckbert && key == "boundary_weight") {
    double v = detail::parse_double_option(key, value);
    if (!(v >= 0.0)) throw InvalidInput("option boundary_weight: must be >= 0, got " + value);
    options_.boundary_weight = v;
  } else {
    detail::throw_unknown_option(name(), key, options());
  }
}

SimplifyResult CgalEdgeCollapse::simplify(const TriMesh& mesh, const SimplifyRequest& request) {
  detail::check_input(mesh, name());
  SimplifyResult result;
  result.input_faces = mesh.num_faces();
  result.target_faces = resolve_target_faces(request, mesh.num_faces());
  const auto start = std::chrono::steady_clock::now();
  auto seconds = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };

  // 1. Surface_mesh with the same vertex indices; a refused face fails the run.
  SurfaceMesh sm;
  for (const Vec3& p : mesh.positions) sm.add_vertex(Kernel::Point_3(p.x, p.y, p.z));
  std::size_t refused = 0;
  for (const Triangle& t : mesh.faces) {
    bool repeated = t[0] == t[1] || t[1] == t[2] || t[0] == t[2];
    if (repeated || sm.add_face(SurfaceMesh::Vertex_index(t[0]), SurfaceMesh::Vertex_index(t[1]),
                                SurfaceMesh::Vertex_index(t[2])) == SurfaceMesh::null_face())
      ++refused;
  }
  if (refused > 0) {
    result.status = SimplifyStatus::kFailed;
    result.message = "CGAL Surface_mesh refused " + std::to_string(refused) + " of " +
                     std::to_string(mesh.num_faces()) +
                     " faces (non-manifold edge or vertex, or a repeated vertex index)";
    result.wall_seconds = seconds();
    return result;
  }

  // 2. Collapse to the face target.
  if (result.target_faces < mesh.num_faces()) {
    FaceCountStop stop{&sm, result.target_faces};
    if (policy_ == CgalPolicy::kGarlandHeckbert) {
      SMS::GarlandHeckbert_plane_policies<SurfaceMesh, Kernel> gh(sm, options_.boundary_weight);
      SMS::edge_collapse(
          sm, stop, CGAL::parameters::get_cost(gh.get_cost()).get_placement(gh.get_placement()));
    } else {
      SMS::edge_collapse(sm, stop,
                         CGAL::parameters::get_cost(SMS::LindstromTurk_cost<SurfaceMesh>())
                             .get_placement(SMS::LindstromTurk_placement<SurfaceMesh>()));
    }
  }

  // 3. Back to TriMesh without collect_garbage (indices of survivors = input indices).
  TriMesh& out = result.mesh;
  std::vector<std::uint32_t> new_index(sm.number_of_vertices() + sm.number_of_removed_vertices(),
                                       UINT32_MAX);
  std::vector<std::uint32_t> old_of_new;
  for (SurfaceMesh::Vertex_index v : sm.vertices()) {
    if (sm.is_isolated(v)) continue;
    new_index[v.idx()] = static_cast<std::uint32_t>(old_of_new.size());
    old_of_new.push_back(static_cast<std::uint32_t>(v.idx()));
    const Kernel::Point_3& p = sm.point(v);
    out.positions.push_back({p.x(), p.y(), p.z()});
  }
  for (SurfaceMesh::Face_index f : sm.faces()) {
    Triangle t{};
    int k = 0;
    for (SurfaceMesh::Vertex_index v : sm.vertices_around_face(sm.halfedge(f)))
      if (k < 3) t[k++] = new_index[v.idx()];
    out.faces.push_back(t);
  }

  // 4. Channels: per-vertex from the survivor, normals recomputed; the rest dropped.
  for (const AttributeChannel& c : mesh.channels) {
    if (c.storage != Storage::kPerVertex) {
      result.dropped.push_back(c.name);
      continue;
    }
    AttributeChannel& o = out.add_channel(c.name, c.kind, c.storage, c.dim);
    if (c.kind == AttributeKind::kNormal && c.dim == 3) {
      for (const Triangle& t : out.faces) {
        Vec3 n = cross(out.positions[t[1]] - out.positions[t[0]],
                       out.positions[t[2]] - out.positions[t[0]]);  // area weighted
        for (std::uint32_t v : t)
          for (int d = 0; d < 3; ++d) o.element(v)[d] += n[d];
      }
      for (std::size_t v = 0; v < out.num_vertices(); ++v) {
        Vec3 n{o.element(v)[0], o.element(v)[1], o.element(v)[2]};
        double len = norm(n);
        for (int d = 0; d < 3; ++d) o.element(v)[d] = len > 0 ? n[d] / len : 0.0;
      }
    } else {
      for (std::size_t v = 0; v < old_of_new.size(); ++v)
        std::copy(c.element(old_of_new[v]), c.element(old_of_new[v]) + c.dim, o.element(v));
    }
    result.kept.push_back(c.name);
  }
  if (!result.dropped.empty()) {
    result.message = "dropped:";
    for (const std::string& n : result.dropped) result.message += " " + n;
  }
  result.wall_seconds = seconds();
  detail::set_status_from_counts(result);
  return result;
}

}  // namespace meshdev
