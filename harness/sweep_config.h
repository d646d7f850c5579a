#pragma once
// What a sweep runs: meshes x simplifiers (with options) x reduction ratios, and how each result
// is measured (sampling, seed, attributes). Read from a JSON config file; every key is optional
// except "meshes", so {"meshes": ["bunny00.off"]} is a complete config (docs/harness.md).
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "metric/compare.h"

namespace meshdev::harness {

// One simplifier run in the sweep: a registry name plus options (`key=value` as
// Simplifier::set_option takes them), kept in the order given.
struct SimplifierSpec {
  std::string name;                                          // e.g. "openmesh-hausdorff"
  std::vector<std::pair<std::string, std::string>> options;  // e.g. {"tolerance", "1%"}

  // "key=value;key=value" ("" without options): the options column of the CSV.
  std::string options_text() const;
};

struct SweepConfig {
  std::vector<std::string> meshes;  // paths as written (the CSV's mesh column)
  std::string base_dir;             // folder relative mesh paths are resolved against ("" = cwd)
  std::vector<SimplifierSpec> simplifiers;  // empty = every available backend, defaults
  std::vector<double> reduction_percent = {50, 75, 90, 95, 98, 99};  // faces removed, in %
  std::string sampling = "vertices,faces";  // kinds: vertices, edges, faces, montecarlo
  double step_fraction = 0;                 // Δ as a fraction of A's bbox diagonal; 0 = none
  std::size_t sample_count = 0;             // face samples per direction; 0 = metric default
                                            // (10 x the larger face count)
  std::uint64_t seed = 1;                   // Monte Carlo sampling seed
  std::vector<std::string> attributes;      // empty = automatic (geometry, normal, shared)
  std::string normals = "auto";             // auto, file, uniform, area, angle
  int jobs = 1;                             // (mesh, simplifier) groups run at once
  int threads = 0;                          // OpenMP threads per comparison; 0 = cores/jobs
  std::string output;                       // output folder ("" = results/<config stem>)
  bool plots = true;                        // draw the curves at the end
};

// Parses a JSON config. Keys: meshes (list of paths), simplifiers (list of names or of
// {"name": ..., "options": {key: value}}), ratios (percent, list of numbers in (0, 100)),
// sampling, step (e.g. "0.5%"), sample_count, seed, attributes (list or "auto"), normals,
// jobs, threads, output, plots. Relative mesh paths are resolved against `base_dir` ("" = as
// given). Throws InvalidInput naming `source` and the key for an unknown key or a bad value.
SweepConfig parse_sweep_config(const std::string& json_text, const std::string& base_dir,
                               const std::string& source);

// The path to open for mesh i: meshes[i] resolved against base_dir.
std::string resolve_mesh_path(const SweepConfig& config, std::size_t i);

// Reads and parses a config file (IoError if unreadable); mesh paths relative to its folder.
SweepConfig read_sweep_config(const std::string& path);

// The resolved config as JSON (what ran: written beside the CSV so a run can be repeated).
std::string config_to_json(const SweepConfig& config);

// The metric options a config asks for. Throws InvalidInput for a bad sampling kind or normals.
CompareOptions compare_options(const SweepConfig& config);

// "vertices,faces;step=0.5%;count=0;normals=auto;attributes=auto": the sampling column.
std::string sampling_text(const SweepConfig& config);

// Splits "a,b,c" (empty items dropped).
std::vector<std::string> split_list(const std::string& text, char separator = ',');

// Parses a ratio list "50,75,90" (percent). Throws InvalidInput for a value outside (0, 100).
std::vector<double> parse_ratio_list(const std::string& text);

// Parses "name" or "name:key=value:key=value". Throws InvalidInput for a malformed option.
SimplifierSpec parse_simplifier_spec(const std::string& text);

}  // namespace meshdev::harness
