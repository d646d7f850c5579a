#pragma once
// Running a sweep: every mesh x simplifier x reduction ratio of a config, each result compared
// with its input by the attribute deviation metric, one tidy CSV row per measure.
//
//   jobs = meshes x simplifiers x ratios (canonical order), keys = hash(input file contents,
//          simplifier name + options, ratio, sampling, seed, tool version); keep this shard's
//   lock <csv>.lock (flock, exclusive); read <csv>: drop torn lines, incomplete and stale jobs
//   for each (mesh, simplifier) group with missing jobs, on `jobs` threads:
//     simplify_sweep(mesh, missing ratios)          (one decimation run where supported)
//     compare_meshes(mesh, simplified) per ratio    (OpenMP inside; the mesh's checks, summary,
//                                                    samples and BVH made once per group:
//                                                    ComparisonReference, metric/compare.h)
//     append the job's rows with ONE write() on an O_APPEND descriptor, fdatasync
//   rewrite <csv> in canonical order (atomically) when every job of the shard is present
//
// A failing simplifier or metric gives a status row and the sweep goes on. Re-running an
// interrupted sweep computes only the missing jobs; the final CSV equals an uninterrupted run's
// except for the timing columns.
#include <cstdint>
#include <functional>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include "harness/shard.h"
#include "harness/sweep_config.h"
#include "simplifiers/simplifier.h"

namespace meshdev::harness {

// The tool version recorded in every row and hashed into job keys.
std::string tool_version();

// 64-bit FNV-1a of bytes, as 16 hex digits. O(n).
std::string fnv1a_hex(const std::string& bytes);

// The hash of a file's contents (IoError if unreadable). O(size).
std::string hash_file(const std::string& path);

struct Job {
  std::size_t ordinal = 0;  // position in the canonical order (shards split on it)
  std::size_t mesh = 0;     // index into config.meshes
  std::size_t simplifier = 0;
  double reduction_percent = 0;
  std::string key;  // the resume key
};

// The canonical job list: meshes outer, then simplifiers, then ratios, in config order.
// `mesh_hashes` are the meshes' content hashes. O(jobs).
std::vector<Job> make_jobs(const SweepConfig& config,
                           const std::vector<SimplifierSpec>& simplifiers,
                           const std::vector<std::string>& mesh_hashes);

// Creates a simplifier by name (tests inject fakes); default: the registry.
using SimplifierFactory = std::function<std::unique_ptr<Simplifier>(const std::string& name)>;

struct SweepOptions {
  std::string output_dir;  // holds sweep.csv, sweep.json (and plots, made by the caller)
  ShardSpec shard;
  std::ostream* log = nullptr;               // progress and warnings; nullptr = silent
  bool tty = false;                          // progress bar instead of log lines
  SimplifierFactory factory;                 // empty = create_simplifier
  std::vector<std::string> available_names;  // for an empty simplifier list; empty = registry's
                                             // available backends
};

struct SweepSummary {
  std::string csv_path, json_path;
  std::size_t jobs_total = 0;     // all jobs of the config
  std::size_t jobs_in_shard = 0;  // this shard's
  std::size_t jobs_present = 0;   // complete in the CSV before this run
  std::size_t jobs_run = 0;       // computed now
  std::size_t jobs_failed = 0;    // of those, with a failure status
  std::size_t rows_dropped = 0;   // torn / incomplete / stale rows removed at start
  bool complete = false;          // every job of the shard is in the CSV
  double seconds = 0;
};

// The simplifiers a config runs: its list, or every available backend with default options.
std::vector<SimplifierSpec> resolve_simplifiers(const SweepConfig& config,
                                                const SweepOptions& options);

// Runs (or resumes) the sweep. Throws InvalidInput for an unknown simplifier or option, IoError
// for an unreadable mesh listed in the config (checked before any computation), WriteError when
// the CSV cannot be written or another sweep holds its lock. Failures of single jobs are rows.
SweepSummary run_sweep(const SweepConfig& config, const SweepOptions& options);

}  // namespace meshdev::harness
