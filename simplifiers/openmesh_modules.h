#pragma once
// OpenMesh Decimater modules shared by the OpenMesh-based backends (openmesh_decimater.cpp,
// openmesh_appearance.cpp). Binary modules: they only allow or refuse collapses.
#include <OpenMesh/Tools/Decimater/ModBaseT.hh>
#include <vector>

#include "simplifiers/openmesh_convert.h"

namespace meshdev {

// Keeps per-corner (halfedge) attributes consistent and UV/normal seams in place. OpenMesh
// redirects the halfedges that pointed to v0 onto v1 but leaves v0's corner values on them.
// Before the collapse, each surviving face around v0 takes the value v1 has in the removed face
// fl or fr of the same chart (the one whose v0 corner has the same value). A collapse where some
// face around v0 belongs to neither chart (v0 on a seam the edge does not follow) is illegal, so
// every corner keeps a value its vertex had in the input.
template <class MeshT>
class ModCornerSeamT : public OpenMesh::Decimater::ModBaseT<MeshT> {
 public:
  DECIMATING_MODULE(ModCornerSeamT, MeshT, MeshdevCornerSeam);
  explicit ModCornerSeamT(MeshT& mesh) : Base(mesh, true) {}

  float collapse_priority(const CollapseInfo& ci) override {
    bool ok = true;
    for (const OmChannelSlot* s : slots) ok = ok && visit(*s, ci, /*apply=*/false);
    return ok ? float(Base::LEGAL_COLLAPSE) : float(Base::ILLEGAL_COLLAPSE);
  }

  void preprocess_collapse(const CollapseInfo& ci) override {
    for (const OmChannelSlot* s : slots) visit(*s, ci, /*apply=*/true);
  }

  std::vector<const OmChannelSlot*> slots;

 private:
  bool visit(const OmChannelSlot& s, const CollapseInfo& ci, bool apply) {
    MeshT& m = Base::mesh();
    switch (s.place) {
      case OmChannelSlot::Place::kHalfedgeTexCoord:
        return charts(
            ci, apply, [&](auto h) { return m.texcoord2D(h); },
            [&](auto h, const auto& x) { m.set_texcoord2D(h, x); });
      case OmChannelSlot::Place::kHalfedgeNormal:
        return charts(
            ci, apply, [&](auto h) { return m.normal(h); },
            [&](auto h, const auto& x) { m.set_normal(h, x); });
      case OmChannelSlot::Place::kHalfedgeProperty:
        return charts(
            ci, apply, [&](auto h) { return m.property(s.hprop, h); },
            [&](auto h, const auto& x) { m.property(s.hprop, h) = x; });
      default:
        return true;
    }
  }

  // Checks (apply = false) or performs (apply = true) the reassignment; false = a third chart.
  template <class Get, class Set>
  bool charts(const CollapseInfo& ci, bool apply, Get get, Set set) {
    MeshT& m = Base::mesh();
    const bool left = ci.fl.is_valid(), right = ci.fr.is_valid();
    // v0 and v1 corner values in the two faces that disappear.
    decltype(get(ci.v0v1)) a0{}, a1{}, b0{}, b1{};
    if (left) a0 = get(m.prev_halfedge_handle(ci.v0v1)), a1 = get(ci.v0v1);
    if (right) b0 = get(ci.v1v0), b1 = get(m.prev_halfedge_handle(ci.v1v0));
    for (auto h : m.vih_range(ci.v0)) {
      auto f = m.face_handle(h);
      if (!f.is_valid() || f == ci.fl || f == ci.fr) continue;
      auto value = get(h);
      if (left && value == a0) {
        if (apply) set(h, a1);
      } else if (right && value == b0) {
        if (apply) set(h, b1);
      } else {
        return false;
      }
    }
    return true;
  }
};

}  // namespace meshdev
