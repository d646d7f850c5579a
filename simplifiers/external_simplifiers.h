#pragma once
// Simplifiers that run an external program (simplifiers/external_process.h): the mesh is written
// to a fresh temporary folder, the program runs in its own process group with a timeout, and its
// output is read back with our validating reader.
//   meshlab-qec      meshlabserver "Quadric Edge Collapse Decimation" (vcglib, optimal placement)
//                    under xvfb-run -a
//   meshlab-qec-tex  the "(with texture)" variant: per-corner UVs kept (per-vertex UVs are sent as
//                    wedges and read back per vertex); a mesh without UVs runs the plain filter
//   vtk-quadric      VTK 9 vtkQuadricDecimation with its attribute error metric, through
//                    simplifiers/scripts/vtk_quadric.py and /usr/bin/python3
//   external         any program from a command template:
//                    command="qslim -t {faces} -o {output} {input}"
//                    placeholders {input} {output} {faces} {ratio} (fraction removed) {keep}
// Outcomes: crash / nonzero exit / timeout / no output / empty or unparsable output / NaN /
// no faces -> kFailed with the exit code or signal name and the last stderr lines; the program
// missing (PATH lookup) -> kUnavailable with the reason, also in `meshdev simplify --list`.
// Output faces with a repeated vertex are dropped and unreferenced vertices removed (both
// counted in the message); channels that came back with the input's name, kind, storage and
// dimension are kept, the others dropped.
#include <string>
#include <vector>

#include "simplifiers/external_process.h"
#include "simplifiers/simplifier.h"

namespace meshdev {

struct ExternalOptions {
  double timeout_seconds = 300;  // per run, then SIGTERM to the group
  double grace_seconds = 2;      // then SIGKILL
};

// What a backend hands to the common runner.
struct ExternalJob {
  std::vector<std::string> argv;
  std::vector<std::pair<std::string, std::string>> env;
  std::string output;  // the file the program must write
  std::string note;    // added to the result message
};

class ExternalSimplifier : public Simplifier {
 public:
  OutputGuarantees guarantees() const override { return {false, false, false}; }
  bool available() const override { return unavailable_reason().empty(); }
  std::vector<OptionInfo> options() const override;
  void set_option(const std::string& key, const std::string& value) override;

  // Writes the input, runs the program, reads and checks the output. O(program) + O(V + F).
  SimplifyResult simplify(const TriMesh& mesh, const SimplifyRequest& request) override;

  // The last run's process record (exit status, captured output, process group).
  const ProcessResult& last_process() const { return last_; }

 protected:
  // Writes the input into `folder` and says how to run the program.
  virtual ExternalJob prepare(const TriMesh& mesh, std::size_t target_faces,
                              const TempDir& folder) = 0;
  // Adjusts the mesh read back (e.g. wedge UVs back to per-vertex). Default: nothing.
  virtual void finish(const TriMesh& /*input*/, TriMesh& /*output*/) {}
  // Options of the backend itself, before the common timeout/grace.
  virtual std::vector<OptionInfo> own_options() const { return {}; }
  virtual bool set_own_option(const std::string& /*key*/, const std::string& /*value*/) {
    return false;
  }

  ExternalOptions external_;

 private:
  ProcessResult last_;
};

class MeshlabQec : public ExternalSimplifier {
 public:
  explicit MeshlabQec(bool texture) : texture_(texture) {}
  std::string name() const override { return texture_ ? "meshlab-qec-tex" : "meshlab-qec"; }
  std::string description() const override;
  std::string role() const override;
  std::string keeps() const override;
  std::string unavailable_reason() const override;

 protected:
  ExternalJob prepare(const TriMesh& mesh, std::size_t target_faces,
                      const TempDir& folder) override;
  void finish(const TriMesh& input, TriMesh& output) override;
  std::vector<OptionInfo> own_options() const override;
  bool set_own_option(const std::string& key, const std::string& value) override;

 private:
  bool texture_;
  bool optimal_ = true;
  bool preserve_boundary_ = true;
  bool preserve_normal_ = true;
  bool per_vertex_uv_sent_as_wedges_ = false;
};

class VtkQuadric : public ExternalSimplifier {
 public:
  std::string name() const override { return "vtk-quadric"; }
  std::string description() const override;
  std::string role() const override;
  std::string keeps() const override;
  std::string unavailable_reason() const override;

 protected:
  ExternalJob prepare(const TriMesh& mesh, std::size_t target_faces,
                      const TempDir& folder) override;
  std::vector<OptionInfo> own_options() const override;
  bool set_own_option(const std::string& key, const std::string& value) override;

 private:
  std::string python_ = "/usr/bin/python3";
  std::string script_;  // "" = the one shipped in simplifiers/scripts
  bool attributes_ = true;
  double color_weight_ = 0.1, normal_weight_ = 0.1, texcoord_weight_ = 0.1;
};

class ExternalCommand : public ExternalSimplifier {
 public:
  std::string name() const override { return "external"; }
  std::string description() const override;
  std::string role() const override;
  std::string keeps() const override;
  std::string unavailable_reason() const override;

 protected:
  ExternalJob prepare(const TriMesh& mesh, std::size_t target_faces,
                      const TempDir& folder) override;
  std::vector<OptionInfo> own_options() const override;
  bool set_own_option(const std::string& key, const std::string& value) override;

 private:
  std::string command_;
  std::string input_format_ = "ply";   // ply | obj
  std::string output_format_ = "ply";  // ply | obj | off (the output file's extension)
};

// Splits a command template into words (whitespace; '...' and "..." group) and replaces the
// placeholders in each word. Throws InvalidInput for an unterminated quote or an unknown {name}.
std::vector<std::string> expand_command(
    const std::string& command, const std::vector<std::pair<std::string, std::string>>& values);

}  // namespace meshdev
