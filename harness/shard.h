#pragma once
// Splitting a sweep over machines and joining the pieces: `--shard I/N` keeps the jobs whose
// position in the canonical job order is I modulo N (0 <= I < N), so N shards are disjoint, cover
// every job, and differ in size by at most one; merge_results joins their CSVs.
#include <cstddef>
#include <string>
#include <vector>

#include "harness/results_csv.h"

namespace meshdev::harness {

struct ShardSpec {
  std::size_t index = 0;  // I, 0-based (Slurm: --array=0-(N-1) and $SLURM_ARRAY_TASK_ID)
  std::size_t count = 1;  // N
};

// Parses "I/N". Throws InvalidInput unless 0 <= I < N. O(1).
ShardSpec parse_shard(const std::string& text);

// Whether job number `ordinal` (0-based, canonical order) belongs to `shard`. O(1).
inline bool in_shard(std::size_t ordinal, const ShardSpec& shard) {
  return ordinal % shard.count == shard.index;
}

struct MergeResult {
  std::vector<ResultRow> rows;        // canonical order (sort_rows)
  std::vector<std::string> warnings;  // dropped torn lines, incomplete jobs, repeats
  std::size_t inputs = 0, jobs = 0;
};

// Reads every shard CSV (IoError/ParseError when one is unreadable or not a results CSV), keeps
// complete jobs, and joins them in canonical order. The same job in two inputs is kept once when
// the rows agree except for timings; otherwise throws InvalidInput naming the job key.
// O(total rows log total rows).
MergeResult merge_results(const std::vector<std::string>& paths);

}  // namespace meshdev::harness
