#pragma once
// The Simplifier interface: one decimation backend behind a name, with its own options, taking a
// TriMesh and a target and returning the simplified mesh with whatever attributes it can keep.
// Missing the target is a status (kTargetNotReached), not an exception; bad input (an empty mesh,
// a ratio outside [0,1), an unknown option) throws InvalidInput (metric/errors.h).
#include <cstddef>
#include <string>
#include <vector>

#include "metric/mesh.h"

namespace meshdev {

// What to simplify to: either an absolute face count or a reduction ratio.
struct SimplifyRequest {
  // Target number of triangles; used when ratio < 0. Must be >= 1 when used.
  std::size_t target_faces = 0;
  // Fraction of the faces to REMOVE, in [0, 1): 0.9 keeps 10 % of them. Negative = use
  // target_faces instead.
  double ratio = -1.0;

  static SimplifyRequest faces(std::size_t n) { return {n, -1.0}; }
  static SimplifyRequest reduction(double r) { return {0, r}; }
};

// The target face count for a mesh with `input_faces` triangles: target_faces, or
// round((1 - ratio) * input_faces) clamped to at least 1. Throws InvalidInput if the ratio is
// not in [0, 1) or target_faces is 0. O(1).
std::size_t resolve_target_faces(const SimplifyRequest& request, std::size_t input_faces);

// The tolerance rule for "reached": the result has at most target + max(2, 1 % of target)
// faces. Being below the target is fine (backends may overshoot by a face or two, and a sloppy
// one by more). O(1).
bool target_reached(std::size_t reached_faces, std::size_t target_faces);

enum class SimplifyStatus {
  kOk,                // the target was reached (target_reached() is true)
  kTargetNotReached,  // the backend stopped above the target (constraint, topology); mesh valid
  kFailed,            // the backend failed or refused the input; mesh may be empty
  kUnavailable,       // the backend's library or program is not present in this build
};

// "ok", "target-not-reached", "failed", "unavailable".
const char* status_name(SimplifyStatus status);

struct SimplifyResult {
  TriMesh mesh;                   // the simplified mesh, with the channels it kept
  std::size_t input_faces = 0;    // faces of the input
  std::size_t target_faces = 0;   // the resolved target
  std::size_t reached_faces = 0;  // == mesh.num_faces()
  double wall_seconds = 0.0;      // time of the backend call (conversions included)
  SimplifyStatus status = SimplifyStatus::kFailed;
  std::string message;               // why it failed / stopped, warnings ("" when all is fine)
  std::vector<std::string> kept;     // names of the input channels carried into mesh
  std::vector<std::string> dropped;  // names of the input channels the backend could not keep
  double backend_error = -1.0;       // the backend's own error estimate if it has one, else -1
};

// One option a backend accepts on the command line (`--option key=value`).
struct OptionInfo {
  std::string key;
  std::string default_value;
  std::string help;
};

// What a backend promises about its output; the conformance suite checks every claim.
struct OutputGuarantees {
  bool manifold = true;           // an edge-manifold input gives an edge-manifold output
  bool no_new_degenerate = true;  // no zero-area triangle that the input did not have
  bool vertices_fixed = true;     // output vertices are input vertices, unmoved, with their exact
                                  // per-vertex values (per-corner values: ones they had)
};

class Simplifier {
 public:
  virtual ~Simplifier() = default;

  // Registry name, e.g. "openmesh-quadric".
  virtual std::string name() const = 0;
  // One line: what it does.
  virtual std::string description() const = 0;
  // The role it plays in the comparison, e.g. "ProgMesh-like".
  virtual std::string role() const = 0;
  // What it keeps, in words ("per-vertex channels (copied from the surviving vertex), ...").
  virtual std::string keeps() const = 0;

  // The output properties it guarantees (default: both).
  virtual OutputGuarantees guarantees() const { return {}; }

  // False when the backend's library was not built in; unavailable_reason() then says why.
  virtual bool available() const { return true; }
  virtual std::string unavailable_reason() const { return {}; }

  // The options this backend understands, and setting one from text. set_option throws
  // InvalidInput for an unknown key or an unparsable / out-of-range value.
  virtual std::vector<OptionInfo> options() const { return {}; }
  virtual void set_option(const std::string& key, const std::string& value);

  // Simplifies `mesh` to the request. Throws InvalidInput for a bad request or an empty mesh;
  // every other outcome comes back in the result's status and message.
  virtual SimplifyResult simplify(const TriMesh& mesh, const SimplifyRequest& request) = 0;

  // One result per request, in the same order. The default runs simplify() once per request;
  // backends that can take snapshots during one run override it (same meshes, less time).
  virtual std::vector<SimplifyResult> simplify_sweep(const TriMesh& mesh,
                                                     const std::vector<SimplifyRequest>& requests);
};

// A backend compiled out of this build: listed by the registry, available() false, and
// simplify() returns kUnavailable with the reason.
class UnavailableSimplifier : public Simplifier {
 public:
  UnavailableSimplifier(std::string name, std::string description, std::string role,
                        std::string keeps, std::string reason);
  std::string name() const override { return name_; }
  std::string description() const override { return description_; }
  std::string role() const override { return role_; }
  std::string keeps() const override { return keeps_; }
  bool available() const override { return false; }
  std::string unavailable_reason() const override { return reason_; }
  void set_option(const std::string& key, const std::string& value) override;
  SimplifyResult simplify(const TriMesh& mesh, const SimplifyRequest& request) override;

 private:
  std::string name_, description_, role_, keeps_, reason_;
};

namespace detail {
// Helpers shared by the backends (not part of the public surface).

// Throws InvalidInput unless the mesh has at least one face and is valid (metric validate()).
void check_input(const TriMesh& mesh, const std::string& backend);
// One result per request with input_faces and the resolved target_faces filled in. Throws
// InvalidInput for a bad request (see resolve_target_faces).
std::vector<SimplifyResult> results_for(const TriMesh& mesh,
                                        const std::vector<SimplifyRequest>& requests);
// kOk or kTargetNotReached from the counts, with a message for the latter.
void set_status_from_counts(SimplifyResult& result);
// Parses option values; throw InvalidInput naming the key on failure.
double parse_double_option(const std::string& key, const std::string& value);
bool parse_bool_option(const std::string& key, const std::string& value);
[[noreturn]] void throw_unknown_option(const std::string& backend, const std::string& key,
                                       const std::vector<OptionInfo>& known);
}  // namespace detail

}  // namespace meshdev
