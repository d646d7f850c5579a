// meshdev compare A B: the attribute deviation metric between two meshes, both directions.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <iostream>
#include <sstream>

#include "apps/commands.h"
#include "apps/exit_codes.h"
#include "metric/colorbar.h"
#include "metric/colored_mesh.h"
#include "metric/colormap.h"
#include "metric/compare.h"
#include "metric/deviation_atlas.h"
#include "metric/errors.h"
#include "metric/io/atomic_file.h"
#include "metric/io/mesh_io.h"
#include "metric/io/write_atlas.h"
#include "metric/io/write_obj.h"
#include "metric/io/write_ply.h"
#include "metric/io/write_png.h"
#include "metric/report.h"

namespace meshdev::app {
namespace {

struct CompareArgs {
  std::string a, b;
  std::string sampling = "vertices,faces";
  std::string step;
  std::size_t sample_count = 0;
  std::uint64_t seed = 1;
  std::string attributes = "auto";
  std::string normals = "auto";
  std::string direction = "both";
  std::string index = "bvh";
  int threads = 0;
  std::string json, csv, samples, colored, samples_ply, colorbar, atlas;
  std::string color_measure = "geometry", color_scale = "paper";
  std::vector<double> range;
  bool quiet = false;
};

std::vector<std::string> split(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ','))
    if (!item.empty()) out.push_back(item);
  return out;
}

CompareOptions to_options(const CompareArgs& args) {
  CompareOptions o;
  try {
    set_sample_kinds(o.sampling, args.sampling);
  } catch (const InvalidInput& e) {
    throw CLI::ValidationError("--sampling", e.what());
  }
  if (!args.step.empty()) {
    const bool percent = args.step.back() == '%';
    const std::string number = percent ? args.step.substr(0, args.step.size() - 1) : args.step;
    double value = 0;
    try {
      std::size_t used = 0;
      value = std::stod(number, &used);
      if (used != number.size()) throw std::invalid_argument("trailing characters");
    } catch (const std::exception&) {
      throw CLI::ValidationError("--step", "'" + args.step + "' is not a number or a percentage");
    }
    if (!(value > 0.0)) throw CLI::ValidationError("--step", "must be positive");
    (percent ? o.sampling.step_fraction : o.sampling.step) = percent ? value / 100.0 : value;
  }
  o.sampling.target_count = args.sample_count;
  o.sampling.seed = args.seed;
  if (args.attributes != "auto") o.attributes.attributes = split(args.attributes);
  o.attributes.normals = parse_normal_source(args.normals);
  o.direction = args.direction == "forward"    ? Direction::kForward
                : args.direction == "backward" ? Direction::kBackward
                                               : Direction::kBoth;
  o.index = args.index == "brute"  ? IndexKind::kBruteForce
            : args.index == "grid" ? IndexKind::kGrid
                                   : IndexKind::kBvh;
  o.threads = args.threads;
  o.keep_samples = !args.samples.empty() || !args.colored.empty() || !args.samples_ply.empty() ||
                   !args.atlas.empty();
  return o;
}

int run_compare(const CompareArgs& args) {
  const CompareOptions options = to_options(args);
  if (!args.range.empty()) check_color_range(args.range[0], args.range[1]);  // before the work
  // Where the results go, also before the work: a comparison of millions of samples is not lost
  // to a mistyped folder (exit 5). The atlas's folder is made.
  for (const std::string* path :
       {&args.json, &args.csv, &args.samples, &args.colored, &args.samples_ply, &args.colorbar})
    if (!path->empty()) check_output_path(*path);
  if (!args.atlas.empty()) make_output_folder(args.atlas);
  const TriMesh a = read_mesh(args.a, args.threads);
  const TriMesh b = read_mesh(args.b, args.threads);
  const ComparisonResult result = compare_meshes(a, b, options, args.a, args.b);

  if (!args.quiet) std::cout << format_report(result) << std::flush;
  if (!args.json.empty())
    write_file_atomically(args.json, [&](std::ostream& out) { out << to_json(result); });
  if (!args.csv.empty())
    write_file_atomically(args.csv, [&](std::ostream& out) { out << to_summary_csv(result); });
  if (!args.samples.empty())
    write_file_atomically(args.samples, [&](std::ostream& out) { write_samples_csv(out, result); });
  const bool visual = !args.colored.empty() || !args.samples_ply.empty() ||
                      !args.colorbar.empty() || !args.atlas.empty();
  if (!visual) return kOk;
  if (!result.forward)
    throw InvalidInput(
        "--colored, --samples-ply, --colorbar and --atlas show mesh A's A -> B deviation: use "
        "--direction forward or both");
  const DirectionResult& forward = *result.forward;

  // The measures to show (--color-by: one, a comma-separated list, or "all").
  std::vector<std::size_t> shown;
  for (const std::string& name : split(args.color_measure)) {
    const std::size_t before = shown.size();
    for (std::size_t m = 0; m < result.measures.size(); ++m)
      if (name == "all" || result.measures[m].name == name) shown.push_back(m);
    if (shown.size() == before)
      throw InvalidInput("--color-by '" + name + "' is not a measured attribute");
  }
  if (shown.empty()) throw InvalidInput("--color-by names no measure");
  // With several measures, each output gets "_<measure>" before its extension.
  auto output_for = [&](const std::string& path, std::size_t m) {
    if (shown.size() == 1) return path;
    const std::size_t slash = path.find_last_of('/');
    const std::size_t dot = path.find_last_of('.');
    const bool has_ext = dot != std::string::npos && (slash == std::string::npos || dot > slash);
    const std::string stem = has_ext ? path.substr(0, dot) : path;
    return stem + "_" + result.measures[m].name + (has_ext ? path.substr(dot) : "");
  };
  const ColorScale scale = parse_color_scale(args.color_scale);
  auto coloring = [&](std::size_t m) {
    ColoringOptions co;
    co.scale = scale;
    co.measure = m;
    if (!args.range.empty()) {
      co.fixed_range = true;
      co.lo = args.range[0];
      co.hi = args.range[1];
    }
    return co;
  };
  auto bar = [&](std::size_t m) {
    const ColoringOptions co = coloring(m);
    ColorBarOptions legend;
    legend.scale = scale;
    legend.lo = co.fixed_range ? co.lo : forward.stats[m].min;
    legend.hi = co.fixed_range ? co.hi : forward.stats[m].max;
    legend.title = result.measures[m].name + " (" + result.measures[m].unit + "), A -> B";
    if (legend.title.size() > 70) legend.title = result.measures[m].name + ", A -> B";
    return legend;
  };
  auto write_bar = [&](const std::string& png, std::size_t m) {
    const ColorBarOptions legend = bar(m);
    write_png(png, colorbar_image(legend));
    const std::size_t dot = png.find_last_of('.');
    const std::size_t slash = png.find_last_of('/');
    const std::string stem = dot != std::string::npos && (slash == std::string::npos || dot > slash)
                                 ? png.substr(0, dot)
                                 : png;
    write_file_atomically(stem + ".svg", [&](std::ostream& out) { out << colorbar_svg(legend); });
  };
  auto ends_with = [](const std::string& s, const std::string& e) {
    return s.size() >= e.size() && s.compare(s.size() - e.size(), e.size(), e) == 0;
  };

  for (std::size_t m : shown) {
    if (!args.colored.empty()) {
      TriMesh colored = color_by_deviation(a, forward, coloring(m));
      colored.texture_file.clear();  // viewers should show the deviation colours, not A's texture
      const std::string path = output_for(args.colored, m);
      if (ends_with(path, ".obj") || ends_with(path, ".OBJ"))
        write_obj(path, colored);
      else
        write_ply(path, colored);
    }
    if (!args.colorbar.empty()) write_bar(output_for(args.colorbar, m), m);
    if (!args.atlas.empty()) {
      AtlasOptions ao;
      ao.measure = m;
      ao.scale = scale;
      const ColoringOptions co = coloring(m);
      ao.fixed_range = co.fixed_range;
      ao.lo = co.lo;
      ao.hi = co.hi;
      const DeviationAtlas atlas = build_deviation_atlas(a, forward, ao);
      std::string stem = args.a;
      if (stem.find_last_of('/') != std::string::npos)
        stem = stem.substr(stem.find_last_of('/') + 1);
      if (stem.find_last_of('.') != std::string::npos)
        stem = stem.substr(0, stem.find_last_of('.'));
      stem = args.atlas + "/" + stem + "_" + result.measures[m].name + "_atlas";
      write_deviation_atlas(stem, atlas);
      write_bar(stem + "_colorbar.png", m);
      if (!args.quiet)
        std::printf(
            "atlas %s: %d x %d texels, %zu sample texels = %.1f %% of the texture, face "
            "rectangles %.1f %%, built in %.3f s -> %s.{png,obj,mtl,ply}\n",
            result.measures[m].name.c_str(), atlas.size, atlas.size, atlas.sample_texels,
            100.0 * atlas.sample_efficiency, 100.0 * atlas.rectangle_efficiency, atlas.seconds,
            stem.c_str());
    }
  }
  if (!args.samples_ply.empty()) {
    // A's samples as a point cloud: colour of the first --color-by measure, every deviation.
    const std::size_t first = shown.front();
    const ColorBarOptions legend = bar(first);
    const SampleSet& set = forward.sample_set;
    TriMesh cloud;
    cloud.positions.reserve(set.samples.size());
    for (const Sample& smp : set.samples) cloud.positions.push_back(smp.point);
    cloud.add_channel("color", AttributeKind::kColor, Storage::kPerVertex, 3);
    for (const Measure& m : result.measures)
      cloud.add_channel("dev_" + m.name, AttributeKind::kScalar, Storage::kPerVertex, 1);
    cloud.add_channel("kind", AttributeKind::kScalar, Storage::kPerVertex, 1);
    cloud.add_channel("face", AttributeKind::kScalar, Storage::kPerVertex, 1);
    cloud.add_channel("weight", AttributeKind::kScalar, Storage::kPerVertex, 1);
    AttributeChannel& color = *cloud.channel("color");
    for (std::size_t i = 0; i < set.samples.size(); ++i) {
      const Vec3 c = map_color(forward.deviations.values[first][i], legend.lo, legend.hi, scale);
      color.values[3 * i] = c.x;
      color.values[3 * i + 1] = c.y;
      color.values[3 * i + 2] = c.z;
    }
    for (std::size_t m = 0; m < result.measures.size(); ++m) {
      AttributeChannel& ch = *cloud.channel("dev_" + result.measures[m].name);
      ch.values.assign(forward.deviations.values[m].begin(), forward.deviations.values[m].end());
    }
    AttributeChannel& kind = *cloud.channel("kind");
    AttributeChannel& face = *cloud.channel("face");
    AttributeChannel& weight = *cloud.channel("weight");
    for (std::size_t i = 0; i < set.samples.size(); ++i) {
      kind.values[i] = static_cast<double>(set.samples[i].kind);
      face.values[i] = set.samples[i].face == kNoFace ? -1.0 : set.samples[i].face;
      weight.values[i] = set.samples[i].weight;
    }
    PlyWriteOptions po;
    po.double_attributes = true;
    write_ply(args.samples_ply, cloud, po);
  }
  return kOk;
}

}  // namespace

void add_compare_command(CLI::App& root, int& exit_code) {
  auto args = std::make_shared<CompareArgs>();
  auto* cmd = root.add_subcommand(
      "compare", "Attribute deviation between mesh A (reference) and mesh B, in both directions");
  cmd->footer(
      "Examples:\n"
      "  meshdev compare bunny.off bunny_simplified.off\n"
      "  meshdev compare a.ply b.ply --sampling vertices --json report.json\n"
      "  meshdev compare a.ply b.ply --step 0.5% --attributes geometry,color --colored a_dev.ply\n"
      "  meshdev compare a.obj b.obj --sampling montecarlo --sample-count 1000000 --seed 7\n"
      "Exit codes: 0 ok, 2 usage, 3 unreadable or malformed input, 4 unusable input,\n"
      "5 output not written, 70 internal error.");
  cmd->add_option("a", args->a, "reference mesh A (OBJ, PLY, OFF, STL)")->required();
  cmd->add_option("b", args->b, "compared mesh B")->required();
  cmd->add_option("--sampling", args->sampling,
                  "sample kinds, comma-separated: vertices, edges, faces (scan conversion, paper "
                  "Eq. 5-6), montecarlo")
      ->capture_default_str();
  cmd->add_option("--step", args->step,
                  "sampling step Δ: absolute (0.01) or % of A's bbox diagonal (0.5%); default: "
                  "chosen to give --sample-count face samples");
  cmd->add_option("--sample-count", args->sample_count,
                  "face samples per direction (default 10 x the larger face count)");
  cmd->add_option("--seed", args->seed, "seed of the Monte Carlo sampling")->capture_default_str();
  cmd->add_option("--attributes", args->attributes,
                  "attributes: auto, or a list of geometry, normal, color, texcoord, <channel>, "
                  "cohen (Cohen's texture deviation, paper Eq. 2), texture (texture colours)")
      ->capture_default_str();
  cmd->add_option("--normals", args->normals, "normals: auto, file, uniform, area, angle")
      ->check(CLI::IsMember({"auto", "file", "uniform", "average", "area", "angle"}))
      ->capture_default_str();
  cmd->add_option("--direction", args->direction, "both, forward (A->B) or backward (B->A)")
      ->check(CLI::IsMember({"both", "forward", "backward"}))
      ->capture_default_str();
  cmd->add_option("--index", args->index,
                  "nearest-point index: bvh, grid (hashed grid + BVH) or brute (the oracle)")
      ->check(CLI::IsMember({"bvh", "grid", "brute"}))
      ->capture_default_str();
  cmd->add_option("--threads", args->threads,
                  "OpenMP threads (0 = all, at most 1024); results do not change")
      ->check(CLI::Range(0, meshdev::kMaxThreads));
  cmd->add_option("--json", args->json, "write the full report as JSON (schema meshdev.compare/1)");
  cmd->add_option("--csv", args->csv, "write summary rows as CSV");
  cmd->add_option("--samples", args->samples, "write one CSV row per sample");
  cmd->add_option("--colored", args->colored,
                  "write A coloured by its deviation: PLY (colour + vertex quality) or, if the "
                  "name ends in .obj, OBJ (v x y z r g b)");
  cmd->add_option("--color-by", args->color_measure,
                  "measure(s) shown by --colored, --colorbar, --atlas, --samples-ply: a name, a "
                  "comma-separated list or 'all' (several: '_<measure>' is added to file names)")
      ->capture_default_str();
  cmd->add_option("--samples-ply", args->samples_ply,
                  "write A's samples as a point-cloud PLY: colour of the (first) --color-by "
                  "measure, every deviation as a property dev_<measure>, kind, face, weight");
  cmd->add_option("--colorbar", args->colorbar,
                  "write the colour bar with its numbers as PNG, and as SVG beside it");
  cmd->add_option("--atlas", args->atlas,
                  "folder: write the deviation texture atlas (paper §4; needs face samples): "
                  "<A>_<measure>_atlas.png, .obj + .mtl, .ply, and its colour bar");
  cmd->add_option("--color-scale", args->color_scale, "paper (blue-green-red), viridis, turbo")
      ->check(CLI::IsMember({"paper", "viridis", "turbo"}))
      ->capture_default_str();
  cmd->add_option("--range", args->range, "fix the colour range: --range LO HI")->expected(2);
  cmd->add_flag("--quiet,-q", args->quiet, "print nothing on success");
  cmd->callback([args, &exit_code] { exit_code = run_compare(*args); });
}

}  // namespace meshdev::app
