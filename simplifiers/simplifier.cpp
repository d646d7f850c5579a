#include "simplifiers/simplifier.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "metric/errors.h"

namespace meshdev {

std::size_t resolve_target_faces(const SimplifyRequest& request, std::size_t input_faces) {
  if (request.ratio < 0.0) {
    if (request.target_faces == 0)
      throw InvalidInput("simplify request: target face count must be at least 1");
    return request.target_faces;
  }
  if (!(request.ratio < 1.0))
    throw InvalidInput("simplify request: reduction ratio must be in [0, 1), got " +
                       std::to_string(request.ratio));
  double keep = (1.0 - request.ratio) * static_cast<double>(input_faces);
  return std::max<std::size_t>(1, static_cast<std::size_t>(std::llround(keep)));
}

bool target_reached(std::size_t reached_faces, std::size_t target_faces) {
  std::size_t slack = std::max<std::size_t>(2, target_faces / 100);
  return reached_faces <= target_faces + slack;
}

const char* status_name(SimplifyStatus status) {
  switch (status) {
    case SimplifyStatus::kOk:
      return "ok";
    case SimplifyStatus::kTargetNotReached:
      return "target-not-reached";
    case SimplifyStatus::kFailed:
      return "failed";
    case SimplifyStatus::kUnavailable:
      return "unavailable";
  }
  return "?";
}

void Simplifier::set_option(const std::string& key, const std::string& /*value*/) {
  detail::throw_unknown_option(name(), key, options());
}

std::vector<SimplifyResult> Simplifier::simplify_sweep(
    const TriMesh& mesh, const std::vector<SimplifyRequest>& requests) {
  std::vector<SimplifyResult> results;
  results.reserve(requests.size());
  for (const SimplifyRequest& r : requests) results.push_back(simplify(mesh, r));
  return results;
}

UnavailableSimplifier::UnavailableSimplifier(std::string name, std::string description,
                                             std::string role, std::string keeps,
                                             std::string reason)
    : name_(std::move(name)),
      description_(std::move(description)),
      role_(std::move(role)),
      keeps_(std::move(keeps)),
      reason_(std::move(reason)) {}

void UnavailableSimplifier::set_option(const std::string& /*key*/, const std::string& /*value*/) {
  // Options of a compiled-out backend are accepted and ignored: simplify() reports why.
}

SimplifyResult UnavailableSimplifier::simplify(const TriMesh& mesh,
                                               const SimplifyRequest& request) {
  SimplifyResult result;
  result.input_faces = mesh.num_faces();
  result.target_faces = resolve_target_faces(request, mesh.num_faces());
  result.status = SimplifyStatus::kUnavailable;
  result.message = name_ + " is unavailable: " + reason_;
  return result;
}

namespace detail {

std::vector<SimplifyResult> results_for(const TriMesh& mesh,
                                        const std::vector<SimplifyRequest>& requests) {
  std::vector<SimplifyResult> results(requests.size());
  for (std::size_t i = 0; i < requests.size(); ++i) {
    results[i].input_faces = mesh.num_faces();
    results[i].target_faces = resolve_target_faces(requests[i], mesh.num_faces());
  }
  return results;
}

void check_input(const TriMesh& mesh, const std::string& backend) {
  if (mesh.num_faces() == 0) throw InvalidInput(backend + ": the input mesh has no faces");
  validate(mesh, backend + " input");
}

void set_status_from_counts(SimplifyResult& result) {
  result.reached_faces = result.mesh.num_faces();
  if (target_reached(result.reached_faces, result.target_faces)) {
    result.status = SimplifyStatus::kOk;
    return;
  }
  result.status = SimplifyStatus::kTargetNotReached;
  std::ostringstream msg;
  msg << "stopped at " << result.reached_faces << " faces, target " << result.target_faces;
  if (!result.message.empty()) msg << "; " << result.message;
  result.message = msg.str();
}

double parse_double_option(const std::string& key, const std::string& value) {
  const char* begin = value.c_str();
  char* end = nullptr;
  errno = 0;
  double v = std::strtod(begin, &end);
  if (value.empty() || end != begin + value.size() || errno != 0 || !std::isfinite(v))
    throw InvalidInput("option " + key + ": '" + value + "' is not a finite number");
  return v;
}

bool parse_bool_option(const std::string& key, const std::string& value) {
  if (value == "1" || value == "true" || value == "on" || value == "yes") return true;
  if (value == "0" || value == "false" || value == "off" || value == "no") return false;
  throw InvalidInput("option " + key + ": '" + value + "' is not a boolean (true/false)");
}

void throw_unknown_option(const std::string& backend, const std::string& key,
                          const std::vector<OptionInfo>& known) {
  std::string msg = backend + ": unknown option '" + key + "'";
  if (known.empty()) {
    msg += " (this backend takes no options)";
  } else {
    msg += "; known options:";
    for (const OptionInfo& o : known) msg += " " + o.key;
  }
  throw InvalidInput(msg);
}

}  // namespace detail
}  // namespace meshdev
