#include "simplifiers/registry.h"

#include <functional>

#include "metric/errors.h"
#ifdef MESHDEV_HAVE_OPENMESH
#include "simplifiers/openmesh_appearance.h"
#include "simplifiers/openmesh_decimater.h"
#endif
#ifdef MESHDEV_HAVE_MESHOPT
#include "simplifiers/meshopt_simplify.h"
#endif
#ifdef MESHDEV_HAVE_CGAL
#include "simplifiers/cgal_edge_collapse.h"
#endif
#ifdef MESHDEV_HAVE_EXTERNAL
#include "simplifiers/external_simplifiers.h"
#endif

namespace meshdev {
namespace {

struct Entry {
  std::string name;
  std::function<std::unique_ptr<Simplifier>()> create;
};

// A backend whose library is not in this build.
[[maybe_unused]] std::function<std::unique_ptr<Simplifier>()> missing(std::string name,
                                                                      std::string description,
                                                                      std::string role,
                                                                      std::string reason) {
  return
      [=] { return std::make_unique<UnavailableSimplifier>(name, description, role, "-", reason); };
}

const std::vector<Entry>& entries() {
  static const std::vector<Entry> list = {
#ifdef MESHDEV_HAVE_OPENMESH
      {"openmesh-quadric",
       [] { return std::make_unique<OpenMeshDecimater>(OpenMeshVariant::kQuadric); }},
      {"openmesh-hausdorff",
       [] { return std::make_unique<OpenMeshDecimater>(OpenMeshVariant::kHausdorff); }},
      {"openmesh-normal",
       [] { return std::make_unique<OpenMeshDecimater>(OpenMeshVariant::kNormal); }},
      {"openmesh-appearance", [] { return std::make_unique<OpenMeshAppearance>(); }},
#else
      {"openmesh-quadric", missing("openmesh-quadric", "OpenMesh Decimater, ModQuadric",
                                   "ProgMesh-like", "built without MESHDEV_WITH_OPENMESH")},
      {"openmesh-hausdorff",
       missing("openmesh-hausdorff", "OpenMesh Decimater, ModQuadric + ModHausdorff", "Jade-like",
               "built without MESHDEV_WITH_OPENMESH")},
      {"openmesh-normal",
       missing("openmesh-normal", "OpenMesh Decimater, ModQuadric + normal constraints",
               "quadric with normal constraints", "built without MESHDEV_WITH_OPENMESH")},
      {"openmesh-appearance",
       missing("openmesh-appearance", "OpenMesh halfedge collapses, generalized quadric (GH98)",
               "appearance-preserving quadric (GH98)", "built without MESHDEV_WITH_OPENMESH")},
#endif
#ifdef MESHDEV_HAVE_MESHOPT
      {"meshopt", [] { return std::make_unique<MeshoptSimplifier>(MeshoptVariant::kSimplify); }},
      {"meshopt-sloppy",
       [] { return std::make_unique<MeshoptSimplifier>(MeshoptVariant::kSloppy); }},
#else
      {"meshopt", missing("meshopt", "meshoptimizer meshopt_simplify",
                          "fast vertex-subset quadric (game-engine LOD)",
                          "built without MESHDEV_WITH_MESHOPT (libmeshoptimizer-dev)")},
      {"meshopt-sloppy",
       missing("meshopt-sloppy", "meshoptimizer meshopt_simplifySloppy", "fast clustering baseline",
               "built without MESHDEV_WITH_MESHOPT (libmeshoptimizer-dev)")},
#endif
#ifdef MESHDEV_HAVE_CGAL
      {"cgal-gh", [] { return std::make_unique<CgalEdgeCollapse>(CgalPolicy::kGarlandHeckbert); }},
      {"cgal-lt", [] { return std::make_unique<CgalEdgeCollapse>(CgalPolicy::kLindstromTurk); }},
#else
      {"cgal-gh", missing("cgal-gh", "CGAL edge_collapse, Garland-Heckbert plane policies",
                          "QSlim-like", "built without MESHDEV_WITH_CGAL (libcgal-dev)")},
      {"cgal-lt",
       missing("cgal-lt", "CGAL edge_collapse, Lindstrom-Turk", "Lindstrom-Turk (memoryless)",
               "built without MESHDEV_WITH_CGAL (libcgal-dev)")},
#endif
#ifdef MESHDEV_HAVE_EXTERNAL
      {"meshlab-qec", [] { return std::make_unique<MeshlabQec>(false); }},
      {"meshlab-qec-tex", [] { return std::make_unique<MeshlabQec>(true); }},
      {"vtk-quadric", [] { return std::make_unique<VtkQuadric>(); }},
      {"external", [] { return std::make_unique<ExternalCommand>(); }},
#else
      {"meshlab-qec", missing("meshlab-qec", "meshlabserver Quadric Edge Collapse",
                              "QSlim-like (external process)", "needs a POSIX build")},
      {"meshlab-qec-tex",
       missing("meshlab-qec-tex", "meshlabserver Quadric Edge Collapse (with texture)",
               "QSlim-like with UV seams (external process)", "needs a POSIX build")},
      {"vtk-quadric", missing("vtk-quadric", "VTK vtkQuadricDecimation",
                              "attribute-aware quadric (external process)", "needs a POSIX build")},
      {"external", missing("external", "command template", "user-supplied external simplifier",
                           "needs a POSIX build")},
#endif
  };
  return list;
}

}  // namespace

std::vector<std::string> simplifier_names() {
  std::vector<std::string> names;
  for (const Entry& e : entries()) names.push_back(e.name);
  return names;
}

std::unique_ptr<Simplifier> create_simplifier(const std::string& name) {
  for (const Entry& e : entries())
    if (e.name == name) return e.create();
  std::string known;
  for (const Entry& e : entries()) known += (known.empty() ? "" : ", ") + e.name;
  throw InvalidInput("unknown simplifier '" + name + "'; known: " + known);
}

std::vector<std::unique_ptr<Simplifier>> create_all_simplifiers() {
  std::vector<std::unique_ptr<Simplifier>> all;
  for (const Entry& e : entries()) all.push_back(e.create());
  return all;
}

}  // namespace meshdev
