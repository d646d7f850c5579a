// Sweep runner: job list, resume keys, locked append-only CSV, worker threads, status rows.
#include "harness/sweep.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <sstream>
#include <thread>

#include "harness/progress.h"
#include "harness/results_csv.h"
#include "metric/errors.h"
#include "metric/io/atomic_file.h"
#include "metric/io/mesh_io.h"
#include "simplifiers/registry.h"

#ifndef MESHDEV_VERSION
#define MESHDEV_VERSION "unknown"
#endif

namespace meshdev::harness {
namespace {

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

std::string errno_text() {
  return std::strerror(errno);
}

// The CSV's lock (a separate file, so the CSV itself may be replaced by rename) and its
// append-only descriptor.
class CsvWriter {
 public:
  explicit CsvWriter(const std::string& csv) : csv_(csv) {
    const std::string lock_path = csv + ".lock";
    lock_fd_ = ::open(lock_path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (lock_fd_ < 0)
      throw WriteError(lock_path + ": cannot create the lock file (" + errno_text() + ")");
    if (::flock(lock_fd_, LOCK_EX | LOCK_NB) != 0) {
      ::close(lock_fd_);
      throw WriteError(csv + ": another meshdev sweep is writing it (lock held on " + lock_path +
                       ")");
    }
  }
  ~CsvWriter() {
    if (fd_ >= 0) ::close(fd_);
    ::close(lock_fd_);  // releases the flock
  }
  CsvWriter(const CsvWriter&) = delete;
  CsvWriter& operator=(const CsvWriter&) = delete;

  void open_append() {
    fd_ = ::open(csv_.c_str(), O_WRONLY | O_APPEND | O_CLOEXEC);
    if (fd_ < 0) throw WriteError(csv_ + ": cannot open for appending (" + errno_text() + ")");
  }
  void close_append() {
    if (fd_ >= 0 && ::close(fd_) != 0) {
      fd_ = -1;
      throw WriteError(csv_ + ": close failed (" + errno_text() + ")");
    }
    fd_ = -1;
  }
  // One job's rows in one write(): a crash leaves either all of them or a torn tail, which the
  // reader drops.
  void append(const std::string& text) {
    std::lock_guard<std::mutex> lock(mutex_);
    std::size_t done = 0;
    while (done < text.size()) {
      const ssize_t n = ::write(fd_, text.data() + done, text.size() - done);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) throw WriteError(csv_ + ": write failed (" + errno_text() + ")");
      done += static_cast<std::size_t>(n);
    }
    if (::fdatasync(fd_) != 0 && errno != EINVAL && errno != EROFS)
      throw WriteError(csv_ + ": fdatasync failed (" + errno_text() + ")");
  }

 private:
  std::string csv_;
  int lock_fd_ = -1, fd_ = -1;
  std::mutex mutex_;
};

void write_rows_atomically(const std::string& path, const std::vector<ResultRow>& rows) {
  write_file_atomically(path, [&](std::ostream& out) {
    out << format_header();
    for (const ResultRow& r : rows) out << format_row(r);
  });
}

std::string percent_text(double p) {
  std::ostringstream s;
  s << p << '%';
  return s.str();
}

bool is_failure(const std::string& status) {
  return status != "ok" && status != "target-not-reached";
}

// Meshes shared between the groups that use them at the same time; freed when none does.
class MeshCache {
 public:
  std::shared_ptr<const TriMesh> get(std::size_t index, const std::string& path) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (auto m = cache_[index].lock()) return m;
    }
    auto mesh = std::make_shared<const TriMesh>(read_mesh(path));  // outside the lock
    std::lock_guard<std::mutex> lock(mutex_);
    if (auto m = cache_[index].lock()) return m;
    cache_[index] = mesh;
    return mesh;
  }

 private:
  std::mutex mutex_;
  std::map<std::size_t, std::weak_ptr<const TriMesh>> cache_;
};

struct Group {
  std::size_t mesh = 0, simplifier = 0;
  std::vector<const Job*> jobs;  // missing ones, in ratio order
};

}  // namespace

std::string tool_version() {
  return MESHDEV_VERSION;
}

std::string fnv1a_hex(const std::string& bytes) {
  std::uint64_t h = 14695981039346656037ull;
  for (unsigned char c : bytes) {
    h ^= c;
    h *= 1099511628211ull;
  }
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return buf;
}

std::string hash_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError(path + ": cannot open the mesh (" + errno_text() + ")");
  std::uint64_t h = 14695981039346656037ull;
  char buf[1 << 16];
  while (in) {
    in.read(buf, sizeof buf);
    for (std::streamsize i = 0; i < in.gcount(); ++i) {
      h ^= static_cast<unsigned char>(buf[i]);
      h *= 1099511628211ull;
    }
  }
  if (in.bad()) throw IoError(path + ": read failed");
  char out[17];
  std::snprintf(out, sizeof out, "%016llx", static_cast<unsigned long long>(h));
  return out;
}

std::vector<Job> make_jobs(const SweepConfig& config,
                           const std::vector<SimplifierSpec>& simplifiers,
                           const std::vector<std::string>& mesh_hashes) {
  std::vector<Job> jobs;
  const std::string common =
      sampling_text(config) + '\n' + std::to_string(config.seed) + '\n' + tool_version();
  for (std::size_t m = 0; m < config.meshes.size(); ++m)
    for (std::size_t s = 0; s < simplifiers.size(); ++s)
      for (double r : config.reduction_percent) {
        Job j;
        j.ordinal = jobs.size();
        j.mesh = m;
        j.simplifier = s;
        j.reduction_percent = r;
        j.key = fnv1a_hex("meshdev-sweep/1\n" + mesh_hashes[m] + '\n' + simplifiers[s].name + '\n' +
                          simplifiers[s].options_text() + '\n' + format_number(r) + '\n' + common);
        jobs.push_back(j);
      }
  return jobs;
}

std::vector<SimplifierSpec> resolve_simplifiers(const SweepConfig& config,
                                                const SweepOptions& options) {
  if (!config.simplifiers.empty()) return config.simplifiers;
  std::vector<SimplifierSpec> out;
  if (!options.available_names.empty()) {
    for (const std::string& n : options.available_names) out.push_back({n, {}});
    return out;
  }
  for (const std::string& n : simplifier_names())
    if (create_simplifier(n)->available()) out.push_back({n, {}});
  return out;
}

SweepSummary run_sweep(const SweepConfig& config, const SweepOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  SweepSummary summary;
  std::ostream* log = options.log;
  const SimplifierFactory factory =
      options.factory
          ? options.factory
          : SimplifierFactory([](const std::string& n) { return create_simplifier(n); });

  // 1. What to run: simplifiers checked (names, options) and meshes hashed before any work.
  const std::vector<SimplifierSpec> specs = resolve_simplifiers(config, options);
  if (specs.empty()) throw InvalidInput("no simplifier to run (none is available in this build)");
  for (const SimplifierSpec& spec : specs) {
    std::unique_ptr<Simplifier> s = factory(spec.name);
    for (const auto& [k, v] : spec.options) s->set_option(k, v);
  }
  const CompareOptions base_compare = compare_options(config);
  std::vector<std::string> hashes;
  for (std::size_t m = 0; m < config.meshes.size(); ++m)
    hashes.push_back(hash_file(resolve_mesh_path(config, m)));
  const std::vector<Job> all_jobs = make_jobs(config, specs, hashes);
  summary.jobs_total = all_jobs.size();
  std::map<std::string, const Job*> shard_jobs;
  for (const Job& j : all_jobs)
    if (in_shard(j.ordinal, options.shard)) shard_jobs.emplace(j.key, &j);
  summary.jobs_in_shard = shard_jobs.size();

  // 2. The output: lock, then keep the complete rows of this shard's jobs.
  std::filesystem::create_directories(options.output_dir);
  summary.csv_path = (std::filesystem::path(options.output_dir) / "sweep.csv").string();
  summary.json_path = (std::filesystem::path(options.output_dir) / "sweep.json").string();
  CsvWriter writer(summary.csv_path);
  ParsedResults existing = read_results_file(summary.csv_path, /*missing_ok=*/true);
  std::vector<std::string> warnings = existing.warnings;
  std::vector<ResultRow> kept = keep_complete_jobs(existing.rows, warnings);
  std::vector<ResultRow> current, stale;
  for (ResultRow& r : kept) (shard_jobs.count(r.get("job_key")) ? current : stale).push_back(r);
  summary.rows_dropped = existing.rows.size() + existing.dropped_lines - current.size();
  std::set<std::string> done;
  for (const ResultRow& r : current) done.insert(r.get("job_key"));
  summary.jobs_present = done.size();
  if (!stale.empty()) {
    const std::string stale_path = summary.csv_path + ".stale";
    write_rows_atomically(stale_path, stale);
    warnings.push_back(std::to_string(stale.size()) +
                       " rows from another config, tool version or input file moved to " +
                       stale_path);
  }
  if (log)
    for (const std::string& w : warnings) *log << "sweep: warning: " << w << '\n';
  const bool exists = std::filesystem::exists(summary.csv_path);
  if (!exists || summary.rows_dropped > 0 || std::filesystem::file_size(summary.csv_path) == 0)
    write_rows_atomically(summary.csv_path, current);

  // The config, tool version and seed beside the CSV, so the run can be repeated exactly.
  {
    nlohmann::json j = nlohmann::json::parse(config_to_json(config));
    j["schema"] = "meshdev.sweep/1";
    j["tool_version"] = tool_version();
    j["shard"] = std::to_string(options.shard.index) + "/" + std::to_string(options.shard.count);
    nlohmann::json sims = nlohmann::json::array();
    for (const SimplifierSpec& s : specs)
      sims.push_back(s.name + (s.options.empty() ? "" : ":") + s.options_text());
    j["resolved_simplifiers"] = sims;
    nlohmann::json mh = nlohmann::json::object();
    for (std::size_t m = 0; m < config.meshes.size(); ++m) mh[config.meshes[m]] = hashes[m];
    j["mesh_hashes"] = mh;
    write_file_atomically(summary.json_path, [&](std::ostream& out) { out << j.dump(2) << '\n'; });
  }

  // 3. The missing jobs, grouped by (mesh, simplifier) so one decimation run serves all ratios.
  std::vector<Group> groups;
  std::map<std::pair<std::size_t, std::size_t>, std::size_t> group_of;
  std::size_t missing = 0;
  for (const Job& j : all_jobs) {
    if (!in_shard(j.ordinal, options.shard) || done.count(j.key)) continue;
    auto [it, added] = group_of.emplace(std::make_pair(j.mesh, j.simplifier), groups.size());
    if (added) groups.push_back({j.mesh, j.simplifier, {}});
    groups[it->second].jobs.push_back(&j);
    ++missing;
  }
  const int workers = std::max(1, std::min<int>(config.jobs, static_cast<int>(groups.size())));
  CompareOptions compare = base_compare;
  if (compare.threads == 0 && workers > 1)
    compare.threads = std::max(1, static_cast<int>(std::thread::hardware_concurrency()) / workers);

  writer.open_append();
  Progress progress(log ? *log : std::cerr, options.tty, missing);
  MeshCache meshes;
  std::atomic<std::size_t> next{0}, failed{0}, ran{0};
  std::mutex error_mutex;
  std::exception_ptr fatal;

  auto emit = [&](const Job& job, const std::vector<ResultRow>& rows, const std::string& detail) {
    std::string text;
    for (const ResultRow& r : rows) text += format_row(r);
    writer.append(text);
    if (is_failure(rows.front().get("status"))) ++failed;
    ++ran;
    if (log)
      progress.job_done(config.meshes[job.mesh] + " " + specs[job.simplifier].name + " " +
                            percent_text(job.reduction_percent),
                        detail);
  };

  auto base_row = [&](const Job& job) {
    ResultRow r;
    r.set("job_key", job.key);
    r.set("mesh", config.meshes[job.mesh]);
    r.set("mesh_hash", hashes[job.mesh]);
    r.set("simplifier", specs[job.simplifier].name);
    r.set("options", specs[job.simplifier].options_text());
    r.set_number("reduction_percent", job.reduction_percent);
    r.set("measure_index", "0");
    r.set("measure_count", "1");
    r.set("sampling", sampling_text(config));
    r.set("seed", std::to_string(config.seed));
    r.set("tool_version", tool_version());
    return r;
  };

  auto status_row = [&](const Job& job, const std::string& status, const std::string& message) {
    ResultRow r = base_row(job);
    r.set("status", status);
    r.set("message", message);
    emit(job, {r}, status + ": " + message);
  };

  auto run_group = [&](const Group& g) {
    const std::string path = resolve_mesh_path(config, g.mesh);
    std::shared_ptr<const TriMesh> mesh;
    try {
      mesh = meshes.get(g.mesh, path);
    } catch (const std::exception& e) {
      for (const Job* j : g.jobs) status_row(*j, "input-error", e.what());
      return;
    }
    std::vector<SimplifyRequest> requests;
    for (const Job* j : g.jobs)
      requests.push_back(SimplifyRequest::reduction(j->reduction_percent / 100.0));
    std::vector<SimplifyResult> results;
    std::string error;
    try {
      std::unique_ptr<Simplifier> s = factory(specs[g.simplifier].name);
      for (const auto& [k, v] : specs[g.simplifier].options) s->set_option(k, v);
      results = s->simplify_sweep(*mesh, requests);
      if (results.size() != requests.size()) error = "the backend returned a wrong result count";
    } catch (const std::exception& e) {
      error = e.what();
    }
    // The mesh checked, summarised and (by the first comparison) indexed and sampled once for
    // all the group's ratios: the same results as comparing it anew each time.
    std::optional<ComparisonReference> reference;
    for (std::size_t i = 0; i < g.jobs.size(); ++i) {
      const Job& job = *g.jobs[i];
      ResultRow head = base_row(job);
      head.set_count("input_vertices", mesh->num_vertices());
      head.set_count("input_faces", mesh->num_faces());
      if (!error.empty()) {
        head.set("status", "failed");
        head.set("message", error);
        emit(job, {head}, "failed: " + error);
        continue;
      }
      SimplifyResult& res = results[i];
      head.set("status", status_name(res.status));
      head.set("message", res.message);
      head.set_count("target_faces", res.target_faces);
      head.set_count("reached_faces", res.reached_faces);
      head.set_number("simplify_seconds", res.wall_seconds);
      if (res.status == SimplifyStatus::kFailed || res.status == SimplifyStatus::kUnavailable) {
        emit(job, {head}, std::string(status_name(res.status)) + ": " + res.message);
        continue;
      }
      ComparisonResult cmp;
      try {
        if (!reference) reference.emplace(*mesh, config.meshes[job.mesh], compare.threads);
        cmp = compare_meshes(*reference, res.mesh, compare,
                             specs[g.simplifier].name + " " + percent_text(job.reduction_percent));
      } catch (const std::exception& e) {
        head.set("status", "metric-failed");
        head.set("message", e.what());
        emit(job, {head}, std::string("metric-failed: ") + e.what());
        continue;
      }
      res.mesh = TriMesh();  // free it early
      std::vector<ResultRow> rows;
      for (std::size_t m = 0; m < cmp.measures.size(); ++m) {
        ResultRow r = head;
        const Statistics& f = cmp.forward->stats[m];
        const Statistics& b = cmp.backward->stats[m];
        const SymmetricStats& s = cmp.symmetric[m];
        r.set_number("metric_seconds", cmp.seconds);
        r.set("measure", cmp.measures[m].name);
        r.set("unit", cmp.measures[m].unit);
        r.set_count("measure_index", m);
        r.set_count("measure_count", cmp.measures.size());
        r.set_number("diagonal", cmp.diagonal);
        r.set_count("samples_forward", cmp.forward->samples);
        r.set_count("samples_backward", cmp.backward->samples);
        const std::pair<const char*, double> values[] = {
            {"forward_mean", f.mean},  {"forward_rms", f.rms},    {"forward_max", f.max},
            {"forward_p95", f.p95},    {"backward_mean", b.mean}, {"backward_rms", b.rms},
            {"backward_max", b.max},   {"backward_p95", b.p95},   {"symmetric_mean", s.mean},
            {"symmetric_rms", s.rms},  {"symmetric_max", s.max},  {"symmetric_p95", s.p95},
            {"hausdorff", s.hausdorff}};
        const bool geometric = cmp.measures[m].name == "geometry" && cmp.diagonal > 0;
        for (const auto& [name, v] : values) {
          r.set_number(name, v);
          if (geometric) r.set_number(std::string(name) + "_rel", v / cmp.diagonal);
        }
        rows.push_back(std::move(r));
      }
      std::ostringstream detail;
      detail << head.get("status") << ", " << res.reached_faces << " faces";
      if (!rows.empty())
        detail << ", " << rows.front().get("measure") << " mean " << std::setprecision(4)
               << rows.front().number("symmetric_mean");
      emit(job, rows, detail.str());
    }
  };

  // 4. Workers take groups in canonical order.
  auto worker = [&] {
    for (;;) {
      {
        std::lock_guard<std::mutex> lock(error_mutex);
        if (fatal) return;
      }
      const std::size_t i = next++;
      if (i >= groups.size()) return;
      try {
        run_group(groups[i]);
      } catch (...) {  // a write error or a bug: stop everything, keep the rows written so far
        std::lock_guard<std::mutex> lock(error_mutex);
        if (!fatal) fatal = std::current_exception();
        return;
      }
    }
  };
  std::vector<std::thread> threads;
  for (int t = 1; t < workers; ++t) threads.emplace_back(worker);
  worker();
  for (std::thread& t : threads) t.join();
  if (log) progress.finish();
  writer.close_append();
  if (fatal) std::rethrow_exception(fatal);
  summary.jobs_run = ran;
  summary.jobs_failed = failed;

  // 5. Canonical order once every job of the shard is there (byte-comparable between runs).
  ParsedResults final_rows = read_results_file(summary.csv_path);
  std::vector<std::string> w;
  std::vector<ResultRow> rows = keep_complete_jobs(final_rows.rows, w);
  std::set<std::string> have;
  for (const ResultRow& r : rows) have.insert(r.get("job_key"));
  summary.complete = have.size() == shard_jobs.size();
  if (summary.complete) {
    sort_rows(rows);
    write_rows_atomically(summary.csv_path, rows);
  }
  summary.seconds = seconds_since(start);
  return summary;
}

}  // namespace meshdev::harness
