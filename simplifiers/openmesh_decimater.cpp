#include "simplifiers/openmesh_decimater.h"

#include <OpenMesh/Tools/Decimater/DecimaterT.hh>
#include <OpenMesh/Tools/Decimater/ModHausdorffT.hh>
#include <OpenMesh/Tools/Decimater/ModNormalDeviationT.hh>
#include <OpenMesh/Tools/Decimater/ModNormalFlippingT.hh>
#include <OpenMesh/Tools/Decimater/ModQuadricT.hh>
#include <OpenMesh/Tools/Decimater/Observer.hh>
#include <algorithm>
#include <chrono>
#include <functional>
#include <numeric>
#include <sstream>

#include "metric/errors.h"
#include "simplifiers/openmesh_convert.h"
#include "simplifiers/openmesh_modules.h"

namespace meshdev {
namespace {

using Decimater = OpenMesh::Decimater::DecimaterT<OmMesh>;
using Clock = std::chrono::steady_clock;

// Counts the faces removed so far (1 per boundary collapse, 2 otherwise), like DecimaterT does.
template <class MeshT>
class ModFaceCountT : public OpenMesh::Decimater::ModBaseT<MeshT> {
 public:
  DECIMATING_MODULE(ModFaceCountT, MeshT, MeshdevFaceCount);
  explicit ModFaceCountT(MeshT& mesh) : Base(mesh, true) {}
  void postprocess_collapse(const CollapseInfo& ci) override {
    removed += (ci.fl.is_valid() ? 1 : 0) + (ci.fr.is_valid() ? 1 : 0);
  }
  std::size_t removed = 0;
};

// Refuses a collapse that would turn a non-degenerate face around v0 into one of (near) zero
// area: twice its area below 1e-12 times its longest squared edge. ModQuadric alone happily
// makes such slivers on flat regions (every collapse there costs 0).
template <class MeshT>
class ModNoDegenerateT : public OpenMesh::Decimater::ModBaseT<MeshT> {
 public:
  DECIMATING_MODULE(ModNoDegenerateT, MeshT, MeshdevNoDegenerate);
  explicit ModNoDegenerateT(MeshT& mesh) : Base(mesh, true) {}

  float collapse_priority(const CollapseInfo& ci) override {
    MeshT& m = Base::mesh();
    for (auto f : m.vf_range(ci.v0)) {
      if (f == ci.fl || f == ci.fr) continue;
      typename MeshT::Point p[3];
      int i = 0, at = 0;
      for (auto v : m.fv_range(f)) {
        if (v == ci.v0) at = i;
        p[i++] = m.point(v);
      }
      if (degenerate(p)) continue;  // already degenerate in the input: not a new one
      p[at] = ci.p1;
      if (degenerate(p)) return float(Base::ILLEGAL_COLLAPSE);
    }
    return float(Base::LEGAL_COLLAPSE);
  }

 private:
  static bool degenerate(const typename MeshT::Point* p) {
    auto e0 = p[1] - p[0], e1 = p[2] - p[1], e2 = p[0] - p[2];
    double longest = std::max({e0.sqrnorm(), e1.sqrnorm(), e2.sqrnorm()});
    return OpenMesh::cross(e0, -e2).norm() <= 1e-12 * longest;
  }
};

// Calls back after every collapse; aborts the run once every snapshot is taken.
class StepObserver : public OpenMesh::Decimater::Observer {
 public:
  explicit StepObserver(std::function<bool()> step) : Observer(1), step_(std::move(step)) {}
  void notify(size_t /*step*/) override { done_ = step_(); }
  bool abort() const override { return done_; }

 private:
  std::function<bool()> step_;
  bool done_ = false;
};

double parse_angle(const std::string& key, const std::string& value) {
  double deg = detail::parse_double_option(key, value);
  if (!(deg > 0.0 && deg <= 180.0))
    throw InvalidInput("option " + key + ": must be in (0, 180] degrees, got " + value);
  return deg;
}

}  // namespace

OpenMeshDecimater::OpenMeshDecimater(OpenMeshVariant variant, OpenMeshDecimaterOptions options)
    : variant_(variant), options_(options) {}

std::string OpenMeshDecimater::name() const {
  switch (variant_) {
    case OpenMeshVariant::kQuadric:
      return "openmesh-quadric";
    case OpenMeshVariant::kHausdorff:
      return "openmesh-hausdorff";
    case OpenMeshVariant::kNormal:
      return "openmesh-normal";
  }
  return "openmesh-?";
}

std::string OpenMeshDecimater::description() const {
  switch (variant_) {
    case OpenMeshVariant::kQuadric:
      return "OpenMesh 9 Decimater, ModQuadric: halfedge collapse, endpoint placement";
    case OpenMeshVariant::kHausdorff:
      return "OpenMesh 9 Decimater, ModQuadric priority bounded by ModHausdorff (one-sided "
             "tolerance)";
    case OpenMeshVariant::kNormal:
      return "OpenMesh 9 Decimater, ModQuadric + ModNormalFlipping + ModNormalDeviation";
  }
  return {};
}

std::string OpenMeshDecimater::role() const {
  switch (variant_) {
    case OpenMeshVariant::kQuadric:
      return "ProgMesh-like";
    case OpenMeshVariant::kHausdorff:
      return "Jade-like";
    case OpenMeshVariant::kNormal:
      return "quadric with normal constraints";
  }
  return {};
}

std::string OpenMeshDecimater::keeps() const {
  return "all channels: per-vertex (surviving vertex's values), per-corner (seams kept: no "
         "collapse "
         "across a seam), per-face; vertex and face normals recomputed";
}

std::vector<OptionInfo> OpenMeshDecimater::options() const {
  switch (variant_) {
    case OpenMeshVariant::kQuadric:
      return {};
    case OpenMeshVariant::kHausdorff:
      return {{"tolerance", "0.5%",
               "Hausdorff bound: N% of the bbox diagonal, or an absolute distance"}};
    case OpenMeshVariant::kNormal:
      return {{"max_flip_deg", "45", "ModNormalFlipping: max turn of a one-ring face normal"},
              {"max_deviation_deg", "30", "ModNormalDeviation: max normal cone angle"}};
  }
  return {};
}

void OpenMeshDecimater::set_option(const std::string& key, const std::string& value) {
  if (variant_ == OpenMeshVariant::kHausdorff && key == "tolerance") {
    bool percent = !value.empty() && value.back() == '%';
    double v =
        detail::parse_double_option(key, percent ? value.substr(0, value.size() - 1) : value);
    if (!(v > 0.0)) throw InvalidInput("option tolerance: must be > 0, got " + value);
    options_.tolerance = v;
    options_.tolerance_percent = percent;
  } else if (variant_ == OpenMeshVariant::kNormal && key == "max_flip_deg") {
    options_.max_normal_flip_deg = parse_angle(key, value);
  } else if (variant_ == OpenMeshVariant::kNormal && key == "max_deviation_deg") {
    options_.max_normal_deviation_deg = parse_angle(key, value);
  } else {
    detail::throw_unknown_option(name(), key, options());
  }
}

SimplifyResult OpenMeshDecimater::simplify(const TriMesh& mesh, const SimplifyRequest& request) {
  return simplify_sweep(mesh, {request}).front();
}

std::vector<SimplifyResult> OpenMeshDecimater::simplify_sweep(
    const TriMesh& mesh, const std::vector<SimplifyRequest>& requests) {
  detail::check_input(mesh, name());
  const std::size_t n = requests.size();
  std::vector<SimplifyResult> results = detail::results_for(mesh, requests);
  if (n == 0) return results;
  const auto start = Clock::now();
  auto seconds = [&] { return std::chrono::duration<double>(Clock::now() - start).count(); };
  OpenMeshQuiet quiet;

  // 1. Convert (a face OpenMesh refuses makes the run fail) and request the status flags.
  OpenMeshConversion conv;
  if (!convert_for_decimation(mesh, conv, results)) return results;
  OmMesh& om = conv.mesh;
  bool vertex_normals = false, face_normals = false;
  std::vector<const OmChannelSlot*> corner_slots;
  for (const OmChannelSlot& s : conv.slots) {
    vertex_normals |= s.place == OmChannelSlot::Place::kVertexNormal;
    face_normals |= s.place == OmChannelSlot::Place::kFaceNormal;
    if (s.storage == Storage::kPerCorner) corner_slots.push_back(&s);
  }
  if (vertex_normals || variant_ == OpenMeshVariant::kNormal) {
    om.request_face_normals();
    om.update_face_normals();
  }

  // 3. The decimater and its modules.
  Decimater dec(om);
  OpenMesh::Decimater::ModQuadricT<OmMesh>::Handle quadric;
  dec.add(quadric);
  if (variant_ == OpenMeshVariant::kHausdorff) {
    OpenMesh::Decimater::ModHausdorffT<OmMesh>::Handle hausdorff;
    dec.add(hausdorff);
    double tol = options_.tolerance;
    if (options_.tolerance_percent) tol *= bounding_box(mesh).diagonal() / 100.0;
    dec.module(hausdorff).set_tolerance(tol);
  }
  if (variant_ == OpenMeshVariant::kNormal) {
    OpenMesh::Decimater::ModNormalFlippingT<OmMesh>::Handle flipping;
    OpenMesh::Decimater::ModNormalDeviationT<OmMesh>::Handle deviation;
    dec.add(flipping);
    dec.add(deviation);
    dec.module(flipping).set_max_normal_deviation(options_.max_normal_flip_deg);
    dec.module(deviation).set_normal_deviation(options_.max_normal_deviation_deg);
  }
  ModNoDegenerateT<OmMesh>::Handle no_degenerate;
  dec.add(no_degenerate);
  ModFaceCountT<OmMesh>::Handle counter;
  dec.add(counter);
  if (!corner_slots.empty()) {
    ModCornerSeamT<OmMesh>::Handle corner_seam;
    dec.add(corner_seam);
    dec.module(corner_seam).slots = corner_slots;
  }
  if (!dec.initialize()) {
    for (SimplifyResult& r : results) {
      r.status = SimplifyStatus::kFailed;
      r.message = "OpenMesh DecimaterT::initialize() failed (module set rejected)";
      r.wall_seconds = seconds();
    }
    return results;
  }

  // 4. Targets from the largest down; a snapshot is taken when the face count first reaches one.
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return results[a].target_faces > results[b].target_faces;
  });
  std::size_t next = 0;
  const std::size_t initial_faces = om.n_faces();
  auto snapshot = [&](SimplifyResult& r) {
    if (face_normals || vertex_normals) om.update_face_normals();
    if (vertex_normals) om.update_vertex_normals();
    r.mesh = from_openmesh(om, conv.slots);
    r.wall_seconds = seconds();
  };
  auto step = [&] {
    std::size_t faces = initial_faces - dec.module(counter).removed;
    while (next < n && faces <= results[order[next]].target_faces) snapshot(results[order[next++]]);
    return next == n;
  };
  StepObserver observer(step);
  dec.set_observer(&observer);

  // 5. Decimate to the smallest target; targets it could not reach get the final mesh.
  if (!step()) dec.decimate_to_faces(0, results[order.back()].target_faces);
  while (next < n) snapshot(results[order[next++]]);
  dec.set_observer(nullptr);

  for (SimplifyResult& r : results) {
    for (const AttributeChannel& c : mesh.channels) r.kept.push_back(c.name);
    detail::set_status_from_counts(r);
  }
  return results;
}

}  // namespace meshdev
