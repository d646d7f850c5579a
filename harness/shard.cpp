// Shards (I/N round-robin over the canonical job order) and merging shard CSVs.
#include "harness/shard.h"

#include <cstdlib>
#include <map>

#include "metric/errors.h"

namespace meshdev::harness {

ShardSpec parse_shard(const std::string& text) {
  const std::size_t slash = text.find('/');
  auto parse = [&](const std::string& part, std::size_t& out) {
    char* end = nullptr;
    const unsigned long long v = std::strtoull(part.c_str(), &end, 10);
    if (part.empty() || part[0] == '-' || end != part.c_str() + part.size()) return false;
    out = static_cast<std::size_t>(v);
    return true;
  };
  ShardSpec s;
  if (slash == std::string::npos || !parse(text.substr(0, slash), s.index) ||
      !parse(text.substr(slash + 1), s.count) || s.count == 0 || s.index >= s.count)
    throw InvalidInput("--shard '" + text + "': use I/N with 0 <= I < N (e.g. 0/4)");
  return s;
}

MergeResult merge_results(const std::vector<std::string>& paths) {
  MergeResult out;
  std::map<std::string, std::vector<ResultRow>> jobs;  // key -> its rows (from the first input)
  for (const std::string& path : paths) {
    ParsedResults parsed = read_results_file(path);
    out.warnings.insert(out.warnings.end(), parsed.warnings.begin(), parsed.warnings.end());
    std::vector<std::string> w;
    const std::vector<ResultRow> rows = keep_complete_jobs(parsed.rows, w);
    for (const std::string& s : w) out.warnings.push_back(path + ": " + s);
    std::map<std::string, std::vector<ResultRow>> here;
    for (const ResultRow& r : rows) here[r.get("job_key")].push_back(r);
    for (auto& [key, job_rows] : here) {
      auto it = jobs.find(key);
      if (it == jobs.end()) {
        jobs.emplace(key, std::move(job_rows));
        continue;
      }
      bool same = it->second.size() == job_rows.size();
      for (std::size_t i = 0; same && i < job_rows.size(); ++i)
        same = same_except_timing(it->second[i], job_rows[i]);
      if (!same)
        throw InvalidInput(path + ": job " + key +
                           " is also in an earlier input with different results");
      out.warnings.push_back(path + ": job " + key + " repeated in several inputs, kept once");
    }
    ++out.inputs;
  }
  for (auto& [key, job_rows] : jobs)
    for (ResultRow& r : job_rows) out.rows.push_back(std::move(r));
  out.jobs = jobs.size();
  sort_rows(out.rows);
  return out;
}

}  // namespace meshdev::harness
