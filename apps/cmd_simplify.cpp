// meshdev simplify IN OUT --method NAME (--ratio R | --faces N) [--option key=value ...]
// meshdev simplify --list
#include <CLI/CLI.hpp>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <memory>

#include "apps/commands.h"
#include "apps/exit_codes.h"
#include "metric/errors.h"
#include "metric/io/atomic_file.h"
#include "metric/io/mesh_io.h"
#include "metric/io/write_obj.h"
#include "metric/io/write_ply.h"
#include "simplifiers/registry.h"

namespace meshdev::app {
namespace {

struct SimplifyArgs {
  std::string input, output, method;
  double ratio = -1.0;
  std::size_t faces = 0;
  std::vector<std::string> options;
  bool list = false;
};

int run_list() {
  for (const auto& s : create_all_simplifiers()) {
    std::cout << std::left << std::setw(20) << s->name() << ' '
              << (s->available() ? "available" : "unavailable: " + s->unavailable_reason())
              << "\n    role:  " << s->role() << "\n    what:  " << s->description()
              << "\n    keeps: " << s->keeps() << '\n';
    for (const OptionInfo& o : s->options())
      std::cout << "    --option " << o.key << '=' << o.default_value << "  " << o.help << '\n';
  }
  return kOk;
}

bool ends_with(const std::string& s, const std::string& suffix) {
  if (s.size() < suffix.size()) return false;
  for (std::size_t i = 0; i < suffix.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(s[s.size() - suffix.size() + i])) != suffix[i])
      return false;
  return true;
}

int run_simplify(const SimplifyArgs& a) {
  if (a.list) return run_list();
  if (a.input.empty() || a.output.empty() || a.method.empty())
    throw CLI::ValidationError("simplify", "IN, OUT and --method are required (or --list)");
  if (std::isnan(a.ratio))  // (NaN passes CLI::Range and then read as "no --ratio")
    throw CLI::ValidationError("simplify", "--ratio must be a number in [0, 1)");
  if ((a.ratio >= 0.0) == (a.faces > 0))
    throw CLI::ValidationError("simplify", "give exactly one of --ratio and --faces");
  if (!ends_with(a.output, ".ply") && !ends_with(a.output, ".obj"))
    throw CLI::ValidationError("simplify", "OUT must end in .ply or .obj");

  std::unique_ptr<Simplifier> simplifier = create_simplifier(a.method);
  for (const std::string& kv : a.options) {
    std::size_t eq = kv.find('=');
    if (eq == std::string::npos || eq == 0)
      throw InvalidInput("--option '" + kv + "': expected key=value");
    simplifier->set_option(kv.substr(0, eq), kv.substr(eq + 1));
  }
  check_output_path(a.output);  // before the work (exit 5)
  TriMesh mesh = read_mesh(a.input);
  SimplifyRequest request =
      a.ratio >= 0.0 ? SimplifyRequest::reduction(a.ratio) : SimplifyRequest::faces(a.faces);
  SimplifyResult r = simplifier->simplify(mesh, request);
  if (r.status == SimplifyStatus::kFailed || r.status == SimplifyStatus::kUnavailable) {
    std::cerr << "meshdev: error: " << a.method << " " << status_name(r.status) << ": " << r.message
              << '\n';
    return kInvalidInput;
  }
  r.mesh.texture_file = mesh.texture_file;
  if (ends_with(a.output, ".obj"))
    write_obj(a.output, r.mesh);
  else
    write_ply(a.output, r.mesh);
  std::cout << a.method << ": " << r.input_faces << " -> " << r.reached_faces << " faces (target "
            << r.target_faces << ") in " << r.wall_seconds << " s, " << status_name(r.status)
            << '\n';
  if (!r.dropped.empty()) {
    std::cout << "dropped:";
    for (const std::string& d : r.dropped) std::cout << ' ' << d;
    std::cout << '\n';
  }
  if (r.status == SimplifyStatus::kTargetNotReached)
    std::cerr << "meshdev: warning: " << a.method << ": " << r.message << '\n';
  else if (!r.message.empty())
    std::cerr << "meshdev: note: " << r.message << '\n';
  return kOk;
}

}  // namespace

void add_simplify_command(CLI::App& root, int& exit_code) {
  auto* cmd =
      root.add_subcommand("simplify", "Simplify a mesh with one of the registered backends");
  auto args = std::make_shared<SimplifyArgs>();
  cmd->add_option("in", args->input, "input mesh (OBJ, PLY, OFF, STL)");
  cmd->add_option("out", args->output, "output mesh (.ply or .obj)");
  cmd->add_option("-m,--method", args->method, "backend name (see --list)");
  auto* ratio = cmd->add_option("-r,--ratio", args->ratio, "fraction of faces to remove, [0,1)")
                    ->check(CLI::Range(0.0, 1.0));
  auto* faces =
      cmd->add_option("-f,--faces", args->faces, "target face count")->check(CLI::PositiveNumber);
  ratio->excludes(faces);
  cmd->add_option("-o,--option", args->options, "backend option key=value (repeatable)");
  cmd->add_flag("-l,--list", args->list, "list the backends: name, role, what they keep");
  cmd->callback([args, &exit_code] { exit_code = run_simplify(*args); });
}

}  // namespace meshdev::app
