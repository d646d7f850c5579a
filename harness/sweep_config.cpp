// Sweep configuration: JSON (nlohmann-json) with defaults for every key but "meshes".
#include "harness/sweep_config.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "metric/attributes.h"
#include "metric/errors.h"

namespace meshdev::harness {
namespace {

using nlohmann::json;

std::string value_text(const json& v) {
  if (v.is_string()) return v.get<std::string>();
  if (v.is_boolean()) return v.get<bool>() ? "true" : "false";
  return v.dump();
}

double parse_percent_or_fraction(const std::string& text, const std::string& what) {
  const bool percent = !text.empty() && text.back() == '%';
  const std::string number = percent ? text.substr(0, text.size() - 1) : text;
  char* end = nullptr;
  const double v = std::strtod(number.c_str(), &end);
  if (number.empty() || end != number.c_str() + number.size() || !(v > 0) || !std::isfinite(v))
    throw InvalidInput(what + ": '" + text + "' is not a positive number or percentage");
  return percent ? v / 100.0 : v;
}

}  // namespace

std::string SimplifierSpec::options_text() const {
  std::string out;
  for (const auto& [key, value] : options) {
    if (!out.empty()) out += ';';
    out += key + '=' + value;
  }
  return out;
}

std::vector<std::string> split_list(const std::string& text, char separator) {
  std::vector<std::string> out;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, separator))
    if (!item.empty()) out.push_back(item);
  return out;
}

std::vector<double> parse_ratio_list(const std::string& text) {
  std::vector<double> out;
  for (std::string item : split_list(text)) {
    if (!item.empty() && item.back() == '%') item.pop_back();
    char* end = nullptr;
    const double v = std::strtod(item.c_str(), &end);
    if (item.empty() || end != item.c_str() + item.size() || !(v > 0 && v < 100))
      throw InvalidInput("ratio '" + item + "': give the reduction in percent, in (0, 100)");
    out.push_back(v);
  }
  return out;
}

SimplifierSpec parse_simplifier_spec(const std::string& text) {
  const std::vector<std::string> parts = split_list(text, ':');
  if (parts.empty()) throw InvalidInput("empty simplifier name");
  SimplifierSpec spec;
  spec.name = parts[0];
  for (std::size_t i = 1; i < parts.size(); ++i) {
    const std::size_t eq = parts[i].find('=');
    if (eq == std::string::npos || eq == 0)
      throw InvalidInput("simplifier '" + text + "': option '" + parts[i] + "' is not key=value");
    spec.options.emplace_back(parts[i].substr(0, eq), parts[i].substr(eq + 1));
  }
  return spec;
}

SweepConfig parse_sweep_config(const std::string& json_text, const std::string& base_dir,
                               const std::string& source) {
  json j;
  try {
    j = json::parse(json_text);
  } catch (const json::parse_error& e) {
    throw ParseError(source, "", e.what());
  }
  if (!j.is_object()) throw InvalidInput(source + ": the config must be a JSON object");
  SweepConfig c;
  c.base_dir = base_dir;
  static const std::set<std::string> known = {
      "meshes",     "simplifiers", "ratios", "sampling", "step",   "sample_count", "seed",
      "attributes", "normals",     "jobs",   "threads",  "output", "plots"};
  for (auto it = j.begin(); it != j.end(); ++it)
    if (!known.count(it.key()))
      throw InvalidInput(source + ": unknown key '" + it.key() +
                         "' (known: meshes, simplifiers, ratios, sampling, step, sample_count, "
                         "seed, attributes, normals, jobs, threads, output, plots)");
  auto fail = [&](const std::string& key, const std::string& what) -> InvalidInput {
    return InvalidInput(source + ": \"" + key + "\": " + what);
  };
  try {
    if (!j.contains("meshes") || !j["meshes"].is_array() || j["meshes"].empty())
      throw fail("meshes", "a non-empty list of mesh paths is required");
    for (const json& m : j["meshes"]) {
      if (!m.is_string()) throw fail("meshes", "every entry must be a path string");
      c.meshes.push_back(m.get<std::string>());
    }
    if (j.contains("simplifiers")) {
      const json& s = j["simplifiers"];
      if (s.is_string() && s.get<std::string>() == "all") {
        // all available: leave empty
      } else if (!s.is_array()) {
        throw fail("simplifiers", "a list of names or {\"name\", \"options\"} objects, or \"all\"");
      } else {
        for (const json& e : s) {
          if (e.is_string()) {
            c.simplifiers.push_back(parse_simplifier_spec(e.get<std::string>()));
          } else if (e.is_object() && e.contains("name") && e["name"].is_string()) {
            SimplifierSpec spec;
            spec.name = e["name"].get<std::string>();
            if (e.contains("options")) {
              if (!e["options"].is_object()) throw fail("simplifiers", "options must be an object");
              for (auto o = e["options"].begin(); o != e["options"].end(); ++o)
                spec.options.emplace_back(o.key(), value_text(o.value()));
            }
            c.simplifiers.push_back(spec);
          } else {
            throw fail("simplifiers", "each entry is a name or {\"name\": ..., \"options\": {}}");
          }
        }
      }
    }
    if (j.contains("ratios")) {
      c.reduction_percent.clear();
      if (!j["ratios"].is_array() || j["ratios"].empty())
        throw fail("ratios", "a non-empty list of reductions in percent");
      for (const json& r : j["ratios"]) {
        const std::string text = r.is_number() ? r.dump() : value_text(r);
        for (double v : parse_ratio_list(text)) c.reduction_percent.push_back(v);
      }
    }
    if (j.contains("sampling")) c.sampling = j["sampling"].get<std::string>();
    if (j.contains("step")) {
      const json& s = j["step"];
      const std::string text = s.is_string() ? s.get<std::string>() : s.dump();
      if (text.empty() || text.back() != '%')
        throw fail("step", "give the step as a percentage of the bbox diagonal, e.g. \"0.5%\"");
      c.step_fraction = parse_percent_or_fraction(text, "step");
    }
    if (j.contains("sample_count")) c.sample_count = j["sample_count"].get<std::size_t>();
    if (j.contains("seed")) c.seed = j["seed"].get<std::uint64_t>();
    if (j.contains("attributes")) {
      const json& a = j["attributes"];
      if (a.is_string()) {
        if (a.get<std::string>() != "auto") c.attributes = split_list(a.get<std::string>());
      } else {
        c.attributes = a.get<std::vector<std::string>>();
      }
    }
    if (j.contains("normals")) c.normals = j["normals"].get<std::string>();
    if (j.contains("jobs")) c.jobs = j["jobs"].get<int>();
    if (j.contains("threads")) c.threads = j["threads"].get<int>();
    if (j.contains("output")) c.output = j["output"].get<std::string>();
    if (j.contains("plots")) c.plots = j["plots"].get<bool>();
  } catch (const json::exception& e) {
    throw InvalidInput(source + ": " + e.what());
  }
  if (c.jobs < 1) throw fail("jobs", "must be at least 1");
  if (c.threads < 0 || c.threads > kMaxThreads)
    throw fail("threads", "must be 0 (automatic) to " + std::to_string(kMaxThreads));
  compare_options(c);  // validates sampling and normals
  return c;
}

std::string resolve_mesh_path(const SweepConfig& config, std::size_t i) {
  std::filesystem::path p = config.meshes.at(i);
  if (p.is_relative() && !config.base_dir.empty()) p = std::filesystem::path(config.base_dir) / p;
  return p.lexically_normal().string();
}

SweepConfig read_sweep_config(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError(path + ": cannot open the sweep config");
  std::ostringstream buf;
  buf << in.rdbuf();
  const std::string base = std::filesystem::path(path).parent_path().string();
  return parse_sweep_config(buf.str(), base, path);
}

std::string config_to_json(const SweepConfig& c) {
  json j;
  j["meshes"] = c.meshes;
  json sims = json::array();
  for (const SimplifierSpec& s : c.simplifiers) {
    json o = json::object();
    for (const auto& [k, v] : s.options) o[k] = v;
    sims.push_back({{"name", s.name}, {"options", o}});
  }
  j["simplifiers"] = sims;
  j["ratios"] = c.reduction_percent;
  j["sampling"] = c.sampling;
  if (c.step_fraction > 0) {
    std::ostringstream s;
    s.precision(17);
    s << c.step_fraction * 100 << '%';
    j["step"] = s.str();
  }
  j["sample_count"] = c.sample_count;
  j["seed"] = c.seed;
  j["attributes"] = c.attributes.empty() ? json("auto") : json(c.attributes);
  j["normals"] = c.normals;
  j["jobs"] = c.jobs;
  j["threads"] = c.threads;
  j["output"] = c.output;
  j["plots"] = c.plots;
  return j.dump(2) + "\n";
}

CompareOptions compare_options(const SweepConfig& c) {
  CompareOptions o;
  set_sample_kinds(o.sampling, c.sampling);
  if (!o.sampling.vertices && !o.sampling.edges && o.sampling.faces == FaceSampling::kNone)
    throw InvalidInput("sampling: nothing to sample");
  o.sampling.step_fraction = c.step_fraction;
  o.sampling.target_count = c.sample_count;
  o.sampling.seed = c.seed;
  check_sampling_options(o.sampling);
  o.attributes.attributes = c.attributes;
  o.attributes.normals = parse_normal_source(c.normals);
  o.threads = c.threads;
  return o;
}

std::string sampling_text(const SweepConfig& c) {
  std::ostringstream s;
  s.precision(17);
  s << c.sampling << ";step=" << c.step_fraction * 100 << "%;count=" << c.sample_count
    << ";normals=" << c.normals << ";attributes=";
  if (c.attributes.empty()) s << "auto";
  for (std::size_t i = 0; i < c.attributes.size(); ++i) s << (i ? "+" : "") << c.attributes[i];
  return s.str();
}

}  // namespace meshdev::harness
