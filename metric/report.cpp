#include "metric/report.h"

#include <cstdio>
#include <nlohmann/json.hpp>
#include <sstream>

#include "metric/errors.h"

namespace meshdev {
namespace {

using nlohmann::json;

// Round-trip formatting, independent of the locale.
std::string num(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

std::string short_num(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", x);
  return buf;
}

std::string with_commas(std::size_t n) {
  std::string s = std::to_string(n);
  for (int i = static_cast<int>(s.size()) - 3; i > 0; i -= 3)
    s.insert(static_cast<std::size_t>(i), ",");
  return s;
}

const char* direction_name(const ComparisonResult& r, const DirectionResult& d) {
  return &d == &*r.forward ? "forward" : "backward";
}

std::vector<const DirectionResult*> directions(const ComparisonResult& r) {
  std::vector<const DirectionResult*> out;
  if (r.forward) out.push_back(&*r.forward);
  if (r.backward) out.push_back(&*r.backward);
  return out;
}

json stats_json(const Statistics& s, double relative_divisor) {
  json j = {{"count", s.count},
            {"weight_sum", s.weight_sum},
            {"area_weighted", s.area_weighted},
            {"min", s.min},
            {"max", s.max},
            {"mean", s.mean},
            {"variance", s.variance},
            {"stddev", s.stddev},
            {"rms", s.rms},
            {"p50", s.p50},
            {"p90", s.p90},
            {"p95", s.p95},
            {"p99", s.p99}};
  if (relative_divisor > 0.0)
    j["relative"] = {{"min", s.min / relative_divisor},       {"max", s.max / relative_divisor},
                     {"mean", s.mean / relative_divisor},     {"rms", s.rms / relative_divisor},
                     {"stddev", s.stddev / relative_divisor}, {"p95", s.p95 / relative_divisor}};
  j["histogram"] = {{"edges", s.histogram.edges},
                    {"counts", s.histogram.counts},
                    {"weight_fraction", s.histogram.weight_fraction}};
  return j;
}

json vec_json(const Vec3& v) {
  return json::array({v.x, v.y, v.z});
}

json mesh_json(const MeshSummary& m) {
  return {{"file", m.label},
          {"vertices", m.vertices},
          {"referenced_vertices", m.referenced_vertices},
          {"faces", m.faces},
          {"polygons", m.polygons},
          {"area", m.area},
          {"bbox_min", vec_json(m.box.min)},
          {"bbox_max", vec_json(m.box.max)},
          {"bbox_diagonal", m.box.diagonal()},
          {"attributes", m.channels}};
}

const char* face_sampling_name(FaceSampling f) {
  switch (f) {
    case FaceSampling::kNone:
      return "none";
    case FaceSampling::kScanConversion:
      return "scan-conversion";
    case FaceSampling::kMonteCarlo:
      return "monte-carlo";
  }
  return "?";
}

}  // namespace

std::string format_report(const ComparisonResult& r) {
  std::ostringstream o;
  char line[512];
  o << "meshdev " << MESHDEV_VERSION << ": attribute deviation (Roy, Foufou & Truchetet 2004)\n\n";
  std::snprintf(line, sizeof line, "%-16s %18s %18s\n", "", "Mesh A", "Mesh B");
  o << line;
  auto row = [&](const char* name, const std::string& a, const std::string& b) {
    std::snprintf(line, sizeof line, "%-16s %18s %18s\n", name, a.c_str(), b.c_str());
    o << line;
  };
  row("vertices", with_commas(r.a.vertices), with_commas(r.b.vertices));
  row("faces", with_commas(r.a.faces), with_commas(r.b.faces));
  row("area", short_num(r.a.area), short_num(r.b.area));
  row("bbox diagonal", short_num(r.a.box.diagonal()), short_num(r.b.box.diagonal()));
  o << "A = " << r.a.label << "\nB = " << r.b.label << '\n';
  if (!r.normal_source.empty()) o << "normals: " << r.normal_source << '\n';

  for (const DirectionResult* d : directions(r)) {
    o << '\n'
      << (d == &*r.forward ? "A -> B" : "B -> A") << ": " << d->sampling << " ("
      << with_commas(d->samples) << " samples"
      << (d->stats[0].area_weighted ? ", face samples area-weighted" : "") << ")\n";
    std::snprintf(line, sizeof line, "  %-14s %12s %12s %12s %12s %12s %12s\n", "measure", "min",
                  "max", "mean", "variance", "rms", "p95");
    o << line;
    for (std::size_t m = 0; m < r.measures.size(); ++m) {
      const Statistics& s = d->stats[m];
      std::snprintf(line, sizeof line, "  %-14s %12.6g %12.6g %12.6g %12.6g %12.6g %12.6g\n",
                    r.measures[m].name.c_str(), s.min, s.max, s.mean, s.variance, s.rms, s.p95);
      o << line;
    }
    const double n = static_cast<double>(d->samples);
    std::snprintf(line, sizeof line,
                  "  nearest point on a vertex %.1f %%, an edge %.1f %%, a face interior %.1f %%; "
                  "%s samples with equidistant ties\n",
                  100.0 * static_cast<double>(d->nearest_feature[0]) / n,
                  100.0 * static_cast<double>(d->nearest_feature[1]) / n,
                  100.0 * static_cast<double>(d->nearest_feature[2]) / n,
                  with_commas(d->samples_with_ties).c_str());
    o << line;
    for (const Measure& m : r.measures)
      if (m.kind == MeasureKind::kCohenTexture) {
        std::snprintf(line, sizeof line,
                      "  texcoord_cohen: %s samples whose UV lies at several points of the other "
                      "mesh (smallest distance kept), %s on none of its faces (UV-nearest point "
                      "used, UV gap up to %.3g)\n",
                      with_commas(d->cohen_multiple).c_str(), with_commas(d->cohen_outside).c_str(),
                      d->cohen_max_uv_gap);
        o << line;
      }
    const Location& at = d->max_location[0];
    o << "  max geometric deviation at (" << short_num(at.point.x) << ", " << short_num(at.point.y)
      << ", " << short_num(at.point.z) << "), a " << sample_kind_name(at.kind)
      << " sample; nearest point on the " << feature_name(at.feature) << " of face "
      << at.nearest_face << '\n';
  }
  if (!r.symmetric.empty()) {
    o << "\nsymmetric (average of A -> B and B -> A, paper §3.3; Hausdorff = larger maximum)\n";
    std::snprintf(line, sizeof line, "  %-14s %12s %12s %12s %12s %12s\n", "measure", "mean", "rms",
                  "max", "p95", "hausdorff");
    o << line;
    for (std::size_t m = 0; m < r.measures.size(); ++m) {
      const SymmetricStats& s = r.symmetric[m];
      std::snprintf(line, sizeof line, "  %-14s %12.6g %12.6g %12.6g %12.6g %12.6g\n",
                    r.measures[m].name.c_str(), s.mean, s.rms, s.max, s.p95, s.hausdorff);
      o << line;
    }
    if (r.diagonal > 0.0) {
      const SymmetricStats& g = r.symmetric[0];
      std::snprintf(line, sizeof line,
                    "  geometry relative to the bbox diagonal of A (%.6g): mean %.4g %%, rms %.4g "
                    "%%, hausdorff %.4g %%\n",
                    r.diagonal, 100 * g.mean / r.diagonal, 100 * g.rms / r.diagonal,
                    100 * g.hausdorff / r.diagonal);
      o << line;
    }
  }
  o << "\nunits: ";
  for (std::size_t m = 0; m < r.measures.size(); ++m)
    o << (m ? "; " : "") << r.measures[m].name << " = " << r.measures[m].unit;
  std::snprintf(line, sizeof line, "\ntime: %.3f s\n", r.seconds);
  o << line;
  return o.str();
}

std::string to_json(const ComparisonResult& r) {
  json j;
  j["schema"] = kCompareSchema;
  j["tool"] = {{"name", "meshdev"}, {"version", MESHDEV_VERSION}};
  j["meshes"] = {{"a", mesh_json(r.a)}, {"b", mesh_json(r.b)}};
  const CompareOptions& o = r.options;
  j["options"] = {
      {"sampling",
       {{"vertices", o.sampling.vertices},
        {"edges", o.sampling.edges},
        {"faces", face_sampling_name(o.sampling.faces)},
        {"step", o.sampling.step},
        {"step_fraction", o.sampling.step_fraction},
        {"target_count", o.sampling.target_count},
        {"seed", o.sampling.seed}}},
      {"index", o.index == IndexKind::kBvh    ? "bvh"
                : o.index == IndexKind::kGrid ? "grid"
                                              : "brute-force"},
      {"ties", {{"relative", o.ties.relative}, {"absolute_fraction", o.ties.absolute_fraction}}},
      {"threads", o.threads}};
  j["normal_source"] = r.normal_source;
  j["relative_to"] = {{"what", "bounding-box diagonal of mesh A"}, {"value", r.diagonal}};
  json measures = json::array();
  for (const Measure& m : r.measures) measures.push_back({{"name", m.name}, {"unit", m.unit}});
  j["measures"] = measures;
  json dirs = json::object();
  for (const DirectionResult* d : directions(r)) {
    json dj = {{"from", d->from},
               {"to", d->to},
               {"sampling", d->sampling},
               {"step", d->step},
               {"samples", d->samples},
               {"index", d->index},
               {"nearest_feature",
                {{"vertex", d->nearest_feature[0]},
                 {"edge", d->nearest_feature[1]},
                 {"face", d->nearest_feature[2]}}},
               {"samples_with_ties", d->samples_with_ties},
               {"seconds",
                {{"sampling", d->seconds_sampling},
                 {"index", d->seconds_index},
                 {"query", d->seconds_query}}}};
    for (const Measure& m : r.measures)
      if (m.kind == MeasureKind::kCohenTexture)
        dj["cohen"] = {{"multiple", d->cohen_multiple},
                       {"outside", d->cohen_outside},
                       {"max_uv_gap", d->cohen_max_uv_gap}};
    json stats = json::object();
    for (std::size_t m = 0; m < r.measures.size(); ++m) {
      json sj = stats_json(d->stats[m], m == 0 ? r.diagonal : 0.0);
      const Location& at = d->max_location[m];
      sj["max_at"] = {{"sample", at.sample},
                      {"point", vec_json(at.point)},
                      {"kind", sample_kind_name(at.kind)},
                      {"face", at.face == kNoFace ? json(nullptr) : json(at.face)},
                      {"nearest_point", vec_json(at.nearest)},
                      {"nearest_face", at.nearest_face},
                      {"nearest_feature", feature_name(at.feature)}};
      stats[r.measures[m].name] = sj;
    }
    dj["stats"] = stats;
    dirs[direction_name(r, *d)] = dj;
  }
  j["directions"] = dirs;
  if (!r.symmetric.empty()) {
    json sym = json::object();
    for (std::size_t m = 0; m < r.measures.size(); ++m) {
      const SymmetricStats& s = r.symmetric[m];
      json sj = {{"min", s.min},       {"max", s.max},
                 {"mean", s.mean},     {"rms", s.rms},
                 {"stddev", s.stddev}, {"p50", s.p50},
                 {"p90", s.p90},       {"p95", s.p95},
                 {"p99", s.p99},       {"hausdorff", s.hausdorff}};
      if (m == 0 && r.diagonal > 0.0)
        sj["relative"] = {{"mean", s.mean / r.diagonal},
                          {"rms", s.rms / r.diagonal},
                          {"max", s.max / r.diagonal},
                          {"hausdorff", s.hausdorff / r.diagonal}};
      sym[r.measures[m].name] = sj;
    }
    j["symmetric"] = sym;
  }
  j["seconds"] = r.seconds;
  return j.dump(2) + "\n";
}

std::string to_summary_csv(const ComparisonResult& r) {
  std::ostringstream o;
  o << "direction,measure,unit,samples,min,max,mean,variance,stddev,rms,p50,p90,p95,p99,hausdorff,"
       "mean_rel,rms_rel,max_rel\n";
  auto rel = [&](std::size_t m, double x) {
    return m == 0 && r.diagonal > 0.0 ? num(x / r.diagonal) : std::string();
  };
  for (const DirectionResult* d : directions(r))
    for (std::size_t m = 0; m < r.measures.size(); ++m) {
      const Statistics& s = d->stats[m];
      o << direction_name(r, *d) << ',' << r.measures[m].name << ",\"" << r.measures[m].unit
        << "\"," << s.count << ',' << num(s.min) << ',' << num(s.max) << ',' << num(s.mean) << ','
        << num(s.variance) << ',' << num(s.stddev) << ',' << num(s.rms) << ',' << num(s.p50) << ','
        << num(s.p90) << ',' << num(s.p95) << ',' << num(s.p99) << ",," << rel(m, s.mean) << ','
        << rel(m, s.rms) << ',' << rel(m, s.max) << '\n';
    }
  for (std::size_t m = 0; m < r.symmetric.size(); ++m) {
    const SymmetricStats& s = r.symmetric[m];
    o << "symmetric," << r.measures[m].name << ",\"" << r.measures[m].unit << "\",," << num(s.min)
      << ',' << num(s.max) << ',' << num(s.mean) << ",," << num(s.stddev) << ',' << num(s.rms)
      << ',' << num(s.p50) << ',' << num(s.p90) << ',' << num(s.p95) << ',' << num(s.p99) << ','
      << num(s.hausdorff) << ',' << rel(m, s.mean) << ',' << rel(m, s.rms) << ','
      << rel(m, s.hausdorff) << '\n';
  }
  return o.str();
}

void write_samples_csv(std::ostream& out, const ComparisonResult& r) {
  out << "direction,sample,kind,x,y,z,face,nearest_x,nearest_y,nearest_z,nearest_face,feature,ties,"
         "weight";
  for (const Measure& m : r.measures) out << ',' << m.name;
  out << '\n';
  for (const DirectionResult* d : directions(r)) {
    if (d->sample_set.samples.size() != d->samples)
      throw InvalidInput("per-sample data was not kept (CompareOptions::keep_samples)");
    const char* name = direction_name(r, *d);
    for (std::size_t i = 0; i < d->samples; ++i) {
      const Sample& s = d->sample_set.samples[i];
      const SurfaceHit& h = d->deviations.nearest[i];
      out << name << ',' << i << ',' << sample_kind_name(s.kind) << ',' << num(s.point.x) << ','
          << num(s.point.y) << ',' << num(s.point.z) << ','
          << (s.face == kNoFace ? std::string() : std::to_string(s.face)) << ',' << num(h.point.x)
          << ',' << num(h.point.y) << ',' << num(h.point.z) << ',' << h.face << ','
          << feature_name(h.feature) << ',' << d->deviations.tie_count[i] << ',' << num(s.weight);
      for (std::size_t m = 0; m < r.measures.size(); ++m)
        out << ',' << num(d->deviations.values[m][i]);
      out << '\n';
    }
  }
}

}  // namespace meshdev
