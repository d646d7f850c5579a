#include "simplifiers/external_simplifiers.h"

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <deque>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>

#include "metric/errors.h"
#include "metric/io/mesh_io.h"
#include "metric/io/write_obj.h"
#include "metric/io/write_ply.h"

#ifndef MESHDEV_SIMPLIFIER_SCRIPTS_DIR
#define MESHDEV_SIMPLIFIER_SCRIPTS_DIR "simplifiers/scripts"
#endif

namespace meshdev {
namespace {

using Clock = std::chrono::steady_clock;

std::string format_number(double x) {
  std::ostringstream s;
  s.precision(17);
  s << x;
  return s.str();
}

double positive_seconds(const std::string& key, const std::string& value) {
  double s = detail::parse_double_option(key, value);
  if (!(s > 0.0)) throw InvalidInput("option " + key + ": must be > 0 seconds, got " + value);
  return s;
}

double non_negative(const std::string& key, const std::string& value) {
  double w = detail::parse_double_option(key, value);
  if (!(w >= 0.0)) throw InvalidInput("option " + key + ": must be >= 0, got " + value);
  return w;
}

bool has_channel(const TriMesh& m, AttributeKind kind, Storage storage) {
  return std::any_of(m.channels.begin(), m.channels.end(), [&](const AttributeChannel& c) {
    return c.kind == kind && c.storage == storage;
  });
}

// PLY for external tools: float positions (every reader takes them), binary little-endian.
void write_input_ply(const std::string& path, const TriMesh& mesh) {
  PlyWriteOptions o;
  o.binary = true;
  o.double_positions = false;
  write_ply(path, mesh, o);
}

// Removes faces with a repeated vertex and vertices no face uses (with their per-vertex values).
// Returns {faces dropped, vertices dropped}.
std::pair<std::size_t, std::size_t> clean_output(TriMesh& m) {
  std::size_t bad_faces = 0;
  std::vector<std::size_t> keep_faces;
  for (std::size_t f = 0; f < m.num_faces(); ++f) {
    const Triangle& t = m.faces[f];
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2])
      ++bad_faces;
    else
      keep_faces.push_back(f);
  }
  if (bad_faces > 0) {
    std::vector<Triangle> faces;
    for (std::size_t f : keep_faces) faces.push_back(m.faces[f]);
    for (AttributeChannel& c : m.channels) {
      if (c.storage == Storage::kPerVertex) continue;
      const std::size_t per = (c.storage == Storage::kPerCorner ? 3 : 1) * std::size_t(c.dim);
      std::vector<double> values;
      for (std::size_t f : keep_faces)
        values.insert(values.end(), c.values.begin() + f * per, c.values.begin() + (f + 1) * per);
      c.values = std::move(values);
    }
    m.faces = std::move(faces);
  }
  std::vector<bool> used = referenced_vertices(m);
  std::vector<std::uint32_t> remap(m.num_vertices(), 0);
  std::size_t next = 0;
  for (std::size_t v = 0; v < used.size(); ++v)
    if (used[v]) remap[v] = std::uint32_t(next++);
  const std::size_t unused = m.num_vertices() - next;
  if (unused > 0) {
    std::vector<Vec3> positions;
    for (std::size_t v = 0; v < used.size(); ++v)
      if (used[v]) positions.push_back(m.positions[v]);
    for (AttributeChannel& c : m.channels) {
      if (c.storage != Storage::kPerVertex) continue;
      std::vector<double> values;
      for (std::size_t v = 0; v < used.size(); ++v)
        if (used[v]) values.insert(values.end(), c.element(v), c.element(v) + c.dim);
      c.values = std::move(values);
    }
    m.positions = std::move(positions);
    for (Triangle& t : m.faces)
      for (auto& i : t) i = remap[i];
  }
  return {bad_faces, unused};
}

std::size_t zero_area_faces(const TriMesh& m) {
  std::size_t n = 0;
  for (std::size_t f = 0; f < m.num_faces(); ++f) n += face_area(m, f) <= 0.0 ? 1 : 0;
  return n;
}

// The mlx script: every parameter of the filter listed (meshlabserver aborts otherwise).
std::string meshlab_script(bool texture, std::size_t target, bool optimal, bool boundary,
                           bool normal) {
  auto b = [](bool x) { return x ? "true" : "false"; };
  std::ostringstream s;
  s << "<!DOCTYPE FilterScript>\n<FilterScript>\n";
  if (texture) {
    s << " <filter name=\"Simplification: Quadric Edge Collapse Decimation (with texture)\">\n"
      << "  <Param type=\"RichInt\" value=\"" << target << "\" name=\"TargetFaceNum\"/>\n"
      << "  <Param type=\"RichFloat\" value=\"0\" name=\"TargetPerc\"/>\n"
      << "  <Param type=\"RichFloat\" value=\"0.3\" name=\"QualityThr\"/>\n"
      << "  <Param type=\"RichFloat\" value=\"1\" name=\"Extratcoordw\"/>\n"
      << "  <Param type=\"RichBool\" value=\"" << b(boundary) << "\" name=\"PreserveBoundary\"/>\n"
      << "  <Param type=\"RichFloat\" value=\"1\" name=\"BoundaryWeight\"/>\n"
      << "  <Param type=\"RichBool\" value=\"" << b(optimal) << "\" name=\"OptimalPlacement\"/>\n"
      << "  <Param type=\"RichBool\" value=\"" << b(normal) << "\" name=\"PreserveNormal\"/>\n"
      << "  <Param type=\"RichBool\" value=\"false\" name=\"PlanarQuadric\"/>\n"
      << "  <Param type=\"RichBool\" value=\"false\" name=\"Selected\"/>\n";
  } else {
    s << " <filter name=\"Simplification: Quadric Edge Collapse Decimation\">\n"
      << "  <Param type=\"RichInt\" value=\"" << target << "\" name=\"TargetFaceNum\"/>\n"
      << "  <Param type=\"RichFloat\" value=\"0\" name=\"TargetPerc\"/>\n"
      << "  <Param type=\"RichFloat\" value=\"0.3\" name=\"QualityThr\"/>\n"
      << "  <Param type=\"RichBool\" value=\"" << b(boundary) << "\" name=\"PreserveBoundary\"/>\n"
      << "  <Param type=\"RichFloat\" value=\"1\" name=\"BoundaryWeight\"/>\n"
      << "  <Param type=\"RichBool\" value=\"" << b(normal) << "\" name=\"PreserveNormal\"/>\n"
      << "  <Param type=\"RichBool\" value=\"true\" name=\"PreserveTopology\"/>\n"
      << "  <Param type=\"RichBool\" value=\"" << b(optimal) << "\" name=\"OptimalPlacement\"/>\n"
      << "  <Param type=\"RichBool\" value=\"false\" name=\"PlanarQuadric\"/>\n"
      << "  <Param type=\"RichFloat\" value=\"0.001\" name=\"PlanarWeight\"/>\n"
      << "  <Param type=\"RichBool\" value=\"false\" name=\"QualityWeight\"/>\n"
      << "  <Param type=\"RichBool\" value=\"true\" name=\"AutoClean\"/>\n"
      << "  <Param type=\"RichBool\" value=\"false\" name=\"Selected\"/>\n";
  }
  s << " </filter>\n</FilterScript>\n";
  return s.str();
}

void write_text(const std::string& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
  if (!out.flush()) throw IoError("cannot write " + path);
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// The common runner.

std::vector<OptionInfo> ExternalSimplifier::options() const {
  std::vector<OptionInfo> all = own_options();
  all.push_back({"timeout", "300", "seconds before SIGTERM to the program's process group"});
  all.push_back({"grace", "2", "seconds between SIGTERM and SIGKILL"});
  return all;
}

void ExternalSimplifier::set_option(const std::string& key, const std::string& value) {
  if (key == "timeout") {
    external_.timeout_seconds = positive_seconds(key, value);
  } else if (key == "grace") {
    external_.grace_seconds = positive_seconds(key, value);
  } else if (!set_own_option(key, value)) {
    detail::throw_unknown_option(name(), key, options());
  }
}

SimplifyResult ExternalSimplifier::simplify(const TriMesh& mesh, const SimplifyRequest& request) {
  detail::check_input(mesh, name());
  SimplifyResult r;
  r.input_faces = mesh.num_faces();
  r.target_faces = resolve_target_faces(request, mesh.num_faces());
  const auto start = Clock::now();
  auto seconds = [&] { return std::chrono::duration<double>(Clock::now() - start).count(); };
  auto fail = [&](const std::string& why) {
    r.status = SimplifyStatus::kFailed;
    r.message = name() + ": " + why;
    r.mesh = TriMesh{};
    r.reached_faces = 0;
    r.wall_seconds = seconds();
    for (const AttributeChannel& c : mesh.channels) r.dropped.push_back(c.name);
    return r;
  };
  last_ = ProcessResult{};
  const std::string reason = unavailable_reason();
  if (!reason.empty()) {
    r.status = SimplifyStatus::kUnavailable;
    r.message = name() + " is unavailable: " + reason;
    return r;
  }

  // 1. A fresh folder with the input; 2. the program in its own process group.
  std::unique_ptr<TempDir> folder;
  ExternalJob job;
  try {
    folder = std::make_unique<TempDir>("meshdev-" + name() + "-");
    job = prepare(mesh, r.target_faces, *folder);
  } catch (const IoError& e) {
    return fail(std::string("cannot write its input: ") + e.what());
  }
  ProcessOptions po;
  po.argv = job.argv;
  po.env = job.env;
  po.working_dir = folder->path();
  po.timeout_seconds = external_.timeout_seconds;
  po.grace_seconds = external_.grace_seconds;
  last_ = run_process(po);
  const ProcessResult& p = last_;
  auto with_stderr = [&](std::string what) {
    std::string err = last_lines(p.stderr_tail, 3), out = last_lines(p.stdout_tail, 2);
    if (!err.empty()) what += "; stderr: " + err;
    if (!out.empty()) what += "; stdout: " + out;
    return what;
  };
  if (!p.started) return fail(p.describe());
  if (!p.ok()) return fail(with_stderr(p.describe()));

  // 3. The output, through our validating reader.
  struct stat st {};
  if (::stat(job.output.c_str(), &st) != 0)
    return fail(with_stderr("exited with 0 but wrote no output file"));
  if (st.st_size == 0) return fail(with_stderr("wrote an empty output file"));
  TriMesh out;
  try {
    out = read_mesh(job.output);
    validate(out, "output");
  } catch (const std::exception& e) {
    return fail(std::string("output is not a valid mesh: ") + e.what());
  }
  finish(mesh, out);
  auto [bad_faces, unused] = clean_output(out);
  if (out.num_faces() == 0) return fail("output has no faces");

  // 4. Channels: kept if they came back as they went in; everything else dropped.
  std::deque<AttributeChannel> channels;
  for (const AttributeChannel& c : mesh.channels) {
    const AttributeChannel* o = out.channel(c.name);
    if (o != nullptr && o->kind == c.kind && o->storage == c.storage && o->dim == c.dim) {
      channels.push_back(*o);
      r.kept.push_back(c.name);
    } else {
      r.dropped.push_back(c.name);
    }
  }
  out.channels = std::move(channels);
  out.source_file.clear();
  r.mesh = std::move(out);

  std::vector<std::string> notes;
  if (!job.note.empty()) notes.push_back(job.note);
  if (bad_faces > 0)
    notes.push_back(std::to_string(bad_faces) + " faces with a repeated vertex removed");
  if (unused > 0) notes.push_back(std::to_string(unused) + " unreferenced vertices removed");
  std::size_t zero = zero_area_faces(r.mesh);
  if (zero > 0) notes.push_back(std::to_string(zero) + " zero-area faces in the output");
  if (p.killed_leftovers) notes.push_back("processes it left running were terminated");
  for (const std::string& n : notes) r.message += (r.message.empty() ? "" : "; ") + n;
  detail::set_status_from_counts(r);
  r.wall_seconds = seconds();
  return r;
}

// ---------------------------------------------------------------------------------------------
// meshlab-qec / meshlab-qec-tex

std::string MeshlabQec::description() const {
  return texture_ ? "meshlabserver 2020.09 Quadric Edge Collapse Decimation (with texture), "
                    "under xvfb-run"
                  : "meshlabserver 2020.09 Quadric Edge Collapse Decimation (vcglib), under "
                    "xvfb-run";
}

std::string MeshlabQec::role() const {
  return texture_ ? "QSlim-like with UV seams (external process)"
                  : "QSlim-like, optimal placement (external process)";
}

std::string MeshlabQec::keeps() const {
  return texture_ ? "per-corner UVs (seams kept; per-vertex UVs go as wedges), per-vertex "
                    "colour/normal/quality of the surviving vertex; per-face dropped"
                  : "per-vertex colour, normal, UV and 'quality' of the surviving vertex (not "
                    "in the metric); per-corner and per-face dropped";
}

std::string MeshlabQec::unavailable_reason() const {
  std::string missing;
  for (const char* p : {"meshlabserver", "xvfb-run", "xauth"})
    if (find_program(p).empty()) missing += (missing.empty() ? "" : ", ") + std::string(p);
  if (missing.empty()) return {};
  return "not found in PATH: " + missing + " (apt-get install meshlab xvfb xauth)";
}

std::vector<OptionInfo> MeshlabQec::own_options() const {
  return {{"optimal", "true", "OptimalPlacement (false: endpoint placement)"},
          {"preserve_boundary", "true", "PreserveBoundary"},
          {"preserve_normal", "true", "PreserveNormal (refuse collapses that flip faces)"}};
}

bool MeshlabQec::set_own_option(const std::string& key, const std::string& value) {
  if (key == "optimal") return optimal_ = detail::parse_bool_option(key, value), true;
  if (key == "preserve_boundary")
    return preserve_boundary_ = detail::parse_bool_option(key, value), true;
  if (key == "preserve_normal")
    return preserve_normal_ = detail::parse_bool_option(key, value), true;
  return false;
}

ExternalJob MeshlabQec::prepare(const TriMesh& mesh, std::size_t target_faces,
                                const TempDir& folder) {
  ExternalJob job;
  TriMesh sent = mesh;
  per_vertex_uv_sent_as_wedges_ = false;
  bool texture = texture_;
  if (texture_ && !has_channel(mesh, AttributeKind::kTexCoord, Storage::kPerCorner)) {
    const AttributeChannel* uv = mesh.channel("texcoord");
    if (uv != nullptr && uv->storage == Storage::kPerVertex && uv->dim == 2) {
      AttributeChannel wedges;
      wedges.name = "texcoord";
      wedges.kind = AttributeKind::kTexCoord;
      wedges.storage = Storage::kPerCorner;
      wedges.dim = 2;
      for (const Triangle& t : mesh.faces)
        for (std::uint32_t v : t)
          wedges.values.insert(wedges.values.end(), uv->element(v), uv->element(v) + 2);
      for (AttributeChannel& c : sent.channels)
        if (c.name == "texcoord") c = wedges;
      per_vertex_uv_sent_as_wedges_ = true;
    } else {
      texture = false;
      job.note = "no texture coordinates: ran the plain Quadric Edge Collapse filter";
    }
  }
  write_input_ply(folder.file("input.ply"), sent);
  write_text(folder.file("qec.mlx"),
             meshlab_script(texture, target_faces, optimal_, preserve_boundary_, preserve_normal_));
  job.output = folder.file("output.ply");
  // -m (what to save) belongs to the -o before it; -s comes last.
  job.argv = {"xvfb-run", "-a", "meshlabserver", "-i", folder.file("input.ply"), "-o", job.output};
  std::vector<std::string> mask;
  if (has_channel(sent, AttributeKind::kColor, Storage::kPerVertex)) mask.push_back("vc");
  if (has_channel(sent, AttributeKind::kNormal, Storage::kPerVertex)) mask.push_back("vn");
  if (has_channel(sent, AttributeKind::kTexCoord, Storage::kPerVertex)) mask.push_back("vt");
  if (has_channel(sent, AttributeKind::kTexCoord, Storage::kPerCorner)) mask.push_back("wt");
  const AttributeChannel* q = sent.channel("quality");
  if (q != nullptr && q->storage == Storage::kPerVertex && q->dim == 1) mask.push_back("vq");
  if (!mask.empty()) {
    job.argv.push_back("-m");
    job.argv.insert(job.argv.end(), mask.begin(), mask.end());
  }
  job.argv.push_back("-s");
  job.argv.push_back(folder.file("qec.mlx"));
  // MeshLab writes its settings under $HOME: keep them in the job's folder.
  job.env = {{"HOME", folder.path()}, {"XDG_CONFIG_HOME", folder.path()}};
  return job;
}

void MeshlabQec::finish(const TriMesh& /*input*/, TriMesh& output) {
  if (!per_vertex_uv_sent_as_wedges_) return;
  AttributeChannel* wedges = output.channel("texcoord");
  if (wedges == nullptr || wedges->storage != Storage::kPerCorner) return;
  AttributeChannel uv;
  uv.name = "texcoord";
  uv.kind = AttributeKind::kTexCoord;
  uv.storage = Storage::kPerVertex;
  uv.dim = 2;
  uv.values.assign(output.num_vertices() * 2, 0.0);
  for (std::size_t f = 0; f < output.num_faces(); ++f)
    for (int k = 0; k < 3; ++k)
      std::copy(wedges->element(3 * f + k), wedges->element(3 * f + k) + 2,
                uv.element(output.faces[f][k]));
  *wedges = std::move(uv);
}

// ---------------------------------------------------------------------------------------------
// vtk-quadric

std::string VtkQuadric::description() const {
  return "VTK 9 vtkQuadricDecimation with the attribute error metric (python3-vtk9 script)";
}

std::string VtkQuadric::role() const {
  return "attribute-aware quadric, optimal placement (Hoppe 1999 style, external process)";
}

std::string VtkQuadric::keeps() const {
  return "per-vertex colour, normal and UV (in the metric, interpolated); other channels, "
         "per-corner and per-face dropped";
}

std::string VtkQuadric::unavailable_reason() const {
  if (find_program(python_).empty()) return python_ + " not found (apt-get install python3)";
  std::string script =
      script_.empty() ? std::string(MESHDEV_SIMPLIFIER_SCRIPTS_DIR) + "/vtk_quadric.py" : script_;
  if (::access(script.c_str(), R_OK) != 0) return "script not found: " + script;
  // Whether VTK imports: checked once per interpreter and process.
  static std::map<std::string, std::string> checked;
  auto it = checked.find(python_);
  if (it == checked.end()) {
    ProcessOptions po;
    po.argv = {python_, "-c", "import vtkmodules.vtkFiltersCore, vtkmodules.vtkIOPLY"};
    po.timeout_seconds = 60;
    ProcessResult p = run_process(po);
    std::string why =
        p.ok() ? ""
               : python_ + " cannot import VTK (apt-get install python3-vtk9): " +
                     (last_lines(p.stderr_tail, 1).empty() ? p.describe()
                                                           : last_lines(p.stderr_tail, 1));
    it = checked.emplace(python_, why).first;
  }
  return it->second;
}

std::vector<OptionInfo> VtkQuadric::own_options() const {
  return {{"python", "/usr/bin/python3", "interpreter with python3-vtk9 (not pyenv's)"},
          {"script", "", "vtk_quadric.py to run (default: the one in simplifiers/scripts)"},
          {"attributes", "true", "AttributeErrorMetricOn (false: VTK drops all point data)"},
          {"color_weight", "0.1", "ScalarsWeight (colour)"},
          {"normal_weight", "0.1", "NormalsWeight"},
          {"texcoord_weight", "0.1", "TCoordsWeight"}};
}

bool VtkQuadric::set_own_option(const std::string& key, const std::string& value) {
  if (key == "python") {
    if (find_program(value).empty())
      throw InvalidInput("option python: '" + value + "' is not an executable (PATH lookup)");
    return python_ = value, true;
  }
  if (key == "script") {
    if (!value.empty() && ::access(value.c_str(), R_OK) != 0)
      throw InvalidInput("option script: cannot read '" + value + "'");
    return script_ = value, true;
  }
  if (key == "attributes") return attributes_ = detail::parse_bool_option(key, value), true;
  if (key == "color_weight") return color_weight_ = non_negative(key, value), true;
  if (key == "normal_weight") return normal_weight_ = non_negative(key, value), true;
  if (key == "texcoord_weight") return texcoord_weight_ = non_negative(key, value), true;
  return false;
}

ExternalJob VtkQuadric::prepare(const TriMesh& mesh, std::size_t target_faces,
                                const TempDir& folder) {
  ExternalJob job;
  write_input_ply(folder.file("input.ply"), mesh);
  job.output = folder.file("output.ply");
  std::string script =
      script_.empty() ? std::string(MESHDEV_SIMPLIFIER_SCRIPTS_DIR) + "/vtk_quadric.py" : script_;
  job.argv = {python_,
              script,
              folder.file("input.ply"),
              job.output,
              "--faces",
              std::to_string(target_faces),
              "--color-weight",
              format_number(color_weight_),
              "--normal-weight",
              format_number(normal_weight_),
              "--texcoord-weight",
              format_number(texcoord_weight_)};
  if (!attributes_) job.argv.push_back("--no-attributes");
  return job;
}

// ---------------------------------------------------------------------------------------------
// external

std::string ExternalCommand::description() const {
  return "any QSlim-style program from a command template ({input} {output} {faces} {ratio} "
         "{keep})";
}

std::string ExternalCommand::role() const {
  return "user-supplied external simplifier";
}

std::string ExternalCommand::keeps() const {
  return "whatever the program writes back under the input's channel names";
}

std::string ExternalCommand::unavailable_reason() const {
  if (command_.empty())
    return "no command set (--option command=\"prog -t {faces} -o {output} {input}\")";
  std::vector<std::string> words;
  try {
    words = expand_command(
        command_,
        {{"input", "i"}, {"output", "o"}, {"faces", "1"}, {"ratio", "0.5"}, {"keep", "0.5"}});
  } catch (const InvalidInput& e) {
    return e.what();
  }
  if (words.empty()) return "empty command";
  if (find_program(words[0]).empty()) return "program '" + words[0] + "' not found (PATH lookup)";
  return {};
}

std::vector<OptionInfo> ExternalCommand::own_options() const {
  return {{"command", "", "template, e.g. \"qslim -t {faces} -o {output} {input}\""},
          {"input_format", "ply", "file given as {input}: ply or obj"},
          {"output_format", "ply", "extension of {output}: ply, obj or off"}};
}

bool ExternalCommand::set_own_option(const std::string& key, const std::string& value) {
  if (key == "command") {
    expand_command(value, {{"input", "i"},
                           {"output", "o"},
                           {"faces", "1"},
                           {"ratio", "0.5"},
                           {"keep", "0.5"}});  // throws on a malformed template
    command_ = value;
    return true;
  }
  if (key == "input_format" || key == "output_format") {
    bool ok = value == "ply" || value == "obj" || (key == "output_format" && value == "off");
    if (!ok) throw InvalidInput("option " + key + ": unsupported format '" + value + "'");
    (key == "input_format" ? input_format_ : output_format_) = value;
    return true;
  }
  return false;
}

ExternalJob ExternalCommand::prepare(const TriMesh& mesh, std::size_t target_faces,
                                     const TempDir& folder) {
  ExternalJob job;
  const std::string input = folder.file("input." + input_format_);
  if (input_format_ == "obj")
    write_obj(input, mesh);
  else
    write_input_ply(input, mesh);
  job.output = folder.file("output." + output_format_);
  const double faces = double(mesh.num_faces());
  const double keep = double(target_faces) / faces;
  job.argv = expand_command(command_, {{"input", input},
                                       {"output", job.output},
                                       {"faces", std::to_string(target_faces)},
                                       {"ratio", format_number(1.0 - keep)},
                                       {"keep", format_number(keep)}});
  return job;
}

std::vector<std::string> expand_command(
    const std::string& command, const std::vector<std::pair<std::string, std::string>>& values) {
  std::vector<std::string> words;
  std::string word;
  bool in_word = false;
  char quote = 0;
  for (std::size_t i = 0; i < command.size(); ++i) {
    char c = command[i];
    if (quote != 0) {
      if (c == quote)
        quote = 0;
      else
        word += c;
    } else if (c == '\'' || c == '"') {
      quote = c;
      in_word = true;
    } else if (c == ' ' || c == '\t' || c == '\n') {
      if (in_word) words.push_back(word), word.clear(), in_word = false;
    } else {
      word += c;
      in_word = true;
    }
  }
  if (quote != 0) throw InvalidInput("command template: unterminated quote in '" + command + "'");
  if (in_word) words.push_back(word);
  for (std::string& w : words) {
    std::string out;
    for (std::size_t i = 0; i < w.size(); ++i) {
      if (w[i] != '{') {
        out += w[i];
        continue;
      }
      std::size_t end = w.find('}', i);
      if (end == std::string::npos)
        throw InvalidInput("command template: unmatched '{' in '" + w + "'");
      std::string key = w.substr(i + 1, end - i - 1);
      auto it = std::find_if(values.begin(), values.end(),
                             [&](const auto& kv) { return kv.first == key; });
      if (it == values.end())
        throw InvalidInput("command template: unknown placeholder {" + key +
                           "} (known: {input} {output} {faces} {ratio} {keep})");
      out += it->second;
      i = end;
    }
    w = out;
  }
  return words;
}

}  // namespace meshdev
