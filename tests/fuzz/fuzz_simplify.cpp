// libFuzzer target: bytes -> a small valid-but-weird mesh (optionally with colour, normals and
// per-corner UVs) -> every available in-process simplifier at reduction ratios 0, 0.5 and 0.9.
// Only InvalidInput may escape a backend; every result must validate, report its face count
// truthfully and keep only channels the input had.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "metric/errors.h"
#include "simplifiers/registry.h"
#include "tests/fuzz/fuzz_input.h"
#ifdef MESHDEV_HAVE_EXTERNAL
#include "simplifiers/external_simplifiers.h"
#endif

namespace {

using namespace meshdev;

void require(bool condition, const std::string& backend, const char* what) {
  if (!condition) {
    std::fprintf(stderr, "fuzz_simplify: %s: %s\n", backend.c_str(), what);
    std::abort();
  }
}

std::vector<std::unique_ptr<Simplifier>>& backends() {
  static std::vector<std::unique_ptr<Simplifier>> list = [] {
    std::vector<std::unique_ptr<Simplifier>> in_process;
    for (auto& s : create_all_simplifiers()) {
#ifdef MESHDEV_HAVE_EXTERNAL
      if (dynamic_cast<ExternalSimplifier*>(s.get())) continue;  // separate processes
#endif
      if (s->available()) in_process.push_back(std::move(s));
    }
    return in_process;
  }();
  return list;
}

void add_channels(TriMesh& m, std::uint8_t flags, fuzz::ByteReader& in) {
  if (flags & 1) {
    AttributeChannel& c = m.add_channel("color", AttributeKind::kColor, Storage::kPerVertex, 3);
    for (double& v : c.values) v = in.byte() / 255.0;
  }
  if (flags & 2) {
    AttributeChannel& n = m.add_channel("normal", AttributeKind::kNormal, Storage::kPerVertex, 3);
    for (double& v : n.values) v = (in.byte() - 128.0) / 64.0;  // zero-length normals included
  }
  if (flags & 4) {
    AttributeChannel& uv =
        m.add_channel("texcoord", AttributeKind::kTexCoord, Storage::kPerCorner, 2);
    for (double& v : uv.values) v = in.byte() / 64.0;
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  fuzz::ByteReader in(data, size);
  const std::uint8_t flags = in.byte();
  TriMesh mesh = fuzz::small_mesh(in);
  add_channels(mesh, flags, in);
  for (auto& backend : backends()) {
    const std::string name = backend->name();
    for (double ratio : {0.0, 0.5, 0.9}) {
      SimplifyResult r;
      try {
        r = backend->simplify(mesh, SimplifyRequest::reduction(ratio));
      } catch (const InvalidInput&) {
        continue;
      }
      require(r.status != SimplifyStatus::kUnavailable, name, "available but kUnavailable");
      require(r.reached_faces == r.mesh.num_faces(), name, "reached_faces != output faces");
      require(r.input_faces == mesh.num_faces(), name, "input_faces != input faces");
      if (r.status == SimplifyStatus::kFailed) continue;
      try {
        validate(r.mesh, name + " output");
      } catch (const InvalidInput& e) {
        std::fprintf(stderr, "%s\n", e.what());
        require(false, name, "output does not validate");
      }
      for (const AttributeChannel& c : r.mesh.channels)
        require(mesh.channel(c.name) != nullptr, name, "output has a channel the input lacks");
    }
  }
  return 0;
}
