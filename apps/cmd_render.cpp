// meshdev render MESH --out view.png: a headless picture of a (coloured or textured) mesh from a
// few standard views, with an optional colour bar (metric/render.h says why a software
// rasteriser).
#include <CLI/CLI.hpp>
#include <algorithm>
#include <iostream>

#include "apps/commands.h"
#include "apps/exit_codes.h"
#include "metric/colorbar.h"
#include "metric/colormap.h"
#include "metric/draw_text.h"
#include "metric/errors.h"
#include "metric/io/atomic_file.h"
#include "metric/io/mesh_io.h"
#include "metric/io/write_png.h"
#include "metric/render.h"

namespace meshdev::app {
namespace {

struct RenderArgs {
  std::string mesh, out;
  std::string views = "front,right,back,left";
  int size = 480;
  int supersample = 2;
  std::string up = "y";
  std::string shade = "auto";
  double ambient = 0.45;
  bool flat = false, no_labels = false;
  bool legend = false;
  std::vector<double> range;
  std::string color_scale = "paper";
  std::string title;
};

// The picture with `below` appended under it (centred), on white.
Image stack(const Image& top, const Image& below) {
  Image out(std::max(top.width, below.width), top.height + below.height, {1, 1, 1});
  for (int y = 0; y < top.height; ++y)
    for (int x = 0; x < top.width; ++x) out.set(x, y, top.pixel(x, y));
  const int ox = (out.width - below.width) / 2;
  for (int y = 0; y < below.height; ++y)
    for (int x = 0; x < below.width; ++x) out.set(ox + x, top.height + y, below.pixel(x, y));
  return out;
}

int run_render(const RenderArgs& args) {
  check_output_path(args.out);  // before the work (exit 5)
  const TriMesh mesh = read_mesh(args.mesh);
  RenderOptions o;
  o.views = parse_views(args.views);
  o.size = args.size;
  o.supersample = args.supersample;
  o.up = args.up == "z" ? 'z' : 'y';
  o.ambient = args.ambient;
  o.flat = args.flat;
  o.labels = !args.no_labels;

  // Colour source: texture (auto: when the mesh has texcoord and a readable texture_file),
  // else vertex colours, else plain grey.
  Image texture;
  const bool has_uv = mesh.channel("texcoord") != nullptr && !mesh.texture_file.empty();
  if (args.shade == "texture" && !has_uv)
    throw InvalidInput(args.mesh + " has no texture coordinates with a texture image");
  if (args.shade == "color" && mesh.channel("color") == nullptr)
    throw InvalidInput(args.mesh + " has no colours");
  if (has_uv && (args.shade == "auto" || args.shade == "texture"))
    texture = load_image(mesh.texture_file);
  o.use_texture = !texture.empty();
  TriMesh shown = mesh;
  if (args.shade == "plain") {
    o.use_texture = false;
    shown.channels.erase(
        std::remove_if(shown.channels.begin(), shown.channels.end(),
                       [](const AttributeChannel& c) { return c.name == "color"; }),
        shown.channels.end());
  }
  Image picture = render_mesh(shown, texture.empty() ? nullptr : &texture, o);
  if (!args.title.empty()) {
    Image header(picture.width, 40, {1, 1, 1});
    draw_text(header, 10, 10, args.title, {0, 0, 0}, 2);
    picture = stack(header, picture);
  }
  if (args.legend) {
    ColorBarOptions b;
    b.scale = parse_color_scale(args.color_scale);
    if (args.range.size() == 2) {
      check_color_range(args.range[0], args.range[1]);
      b.lo = args.range[0];
      b.hi = args.range[1];
    } else {
      const AttributeChannel* q = mesh.channel("quality");
      if (q == nullptr || q->values.empty())
        throw InvalidInput("--legend needs --range LO HI or a 'quality' channel on " + args.mesh);
      b.lo = *std::min_element(q->values.begin(), q->values.end());
      b.hi = *std::max_element(q->values.begin(), q->values.end());
    }
    b.width = std::min(picture.width, 720);
    picture = stack(picture, colorbar_image(b));
  }
  write_png(args.out, picture);
  return kOk;
}

}  // namespace

void add_render_command(CLI::App& root, int& exit_code) {
  auto args = std::make_shared<RenderArgs>();
  auto* cmd = root.add_subcommand(
      "render", "Headless picture of a mesh (vertex colours or texture) from standard views");
  cmd->footer(
      "Examples:\n"
      "  meshdev render a_dev.ply --out a_dev.png --legend\n"
      "  meshdev render a_geometry_atlas.obj --out atlas_view.png --views front,iso\n"
      "Software rasteriser: orthographic views, z-buffer, Gouraud-interpolated colours or\n"
      "bilinear texture, two-sided headlight (docs/visualisation.md).");
  cmd->add_option("mesh", args->mesh, "mesh to render (OBJ, PLY, OFF, STL)")->required();
  cmd->add_option("--out,-o", args->out, "PNG to write")->required();
  cmd->add_option("--views", args->views,
                  "comma-separated: front, back, left, right, top, bottom, iso, all")
      ->capture_default_str();
  cmd->add_option("--size", args->size, "tile side in pixels")->capture_default_str();
  cmd->add_option("--supersample", args->supersample, "anti-aliasing factor 1-4")
      ->capture_default_str();
  cmd->add_option("--up", args->up, "the mesh's up axis")
      ->check(CLI::IsMember({"y", "z"}))
      ->capture_default_str();
  cmd->add_option("--shade", args->shade, "auto (texture, else colours), texture, color, plain")
      ->check(CLI::IsMember({"auto", "texture", "color", "plain"}))
      ->capture_default_str();
  cmd->add_option("--ambient", args->ambient, "ambient light in [0,1] (1 = unlit colours)")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  cmd->add_flag("--flat", args->flat, "flat shading (face normals)");
  cmd->add_flag("--no-labels", args->no_labels, "no view names in the tiles");
  cmd->add_flag("--legend", args->legend,
                "append a colour bar: range from --range or the mesh's 'quality' min/max");
  cmd->add_option("--range", args->range, "colour bar range: --range LO HI")->expected(2);
  cmd->add_option("--color-scale", args->color_scale, "colour bar scale: paper, viridis, turbo")
      ->check(CLI::IsMember({"paper", "viridis", "turbo"}))
      ->capture_default_str();
  cmd->add_option("--title", args->title, "a line of text above the picture");
  cmd->callback([args, &exit_code] { exit_code = run_render(*args); });
}

}  // namespace meshdev::app
