#pragma once
// Headless pictures of a mesh: a small software rasteriser (orthographic camera, z-buffer,
// per-vertex colours or a texture interpolated across faces, two-sided Lambert lighting from a
// headlight), so reports and the paper's Fig. 5-7 can be regenerated without a GUI or a GPU.
// Why not an offscreen OpenGL (OSMesa) or a ray tracer from Debian: a z-buffer over triangles is
// ~200 lines, has no driver, display or version dependencies, and is exact and deterministic
// (the same image on every machine); the pictures only need colours, depth and a little shading.
#include <string>
#include <vector>

#include "metric/mesh.h"
#include "metric/texture_image.h"

namespace meshdev {

enum class View { kFront, kBack, kLeft, kRight, kTop, kBottom, kIso };

struct RenderOptions {
  std::vector<View> views{View::kFront, View::kRight, View::kBack, View::kLeft};  // one tile each
  int size = 480;           // tile side in pixels
  int supersample = 2;      // rendered at size x supersample, box-filtered down (anti-aliasing)
  char up = 'y';            // the mesh's up axis: 'y' (default) or 'z'
  double ambient = 0.45;    // light = ambient + (1 - ambient) |n . l|; 1 = unlit colours
  bool flat = false;        // face normals instead of interpolated vertex normals
  bool use_texture = true;  // with "texcoord" and a texture image: texture instead of colours
  bool labels = true;       // the view's name in each tile's corner
  Vec3 background{1, 1, 1};
  Vec3 plain{0.8, 0.8, 0.8};  // the colour of a mesh with neither colours nor texture
};

// Renders `mesh` from each view into one image (tiles in a grid of up to 3 columns per row for
// 1-3 views, else ceil(n/2) columns). Colour source, first available: `texture` (if not null and
// the mesh has "texcoord"), the "color" channel (per vertex, corner or face; Gouraud-interpolated),
// options.plain. Throws InvalidInput for a mesh without faces or a bad size.
// O(views x (F + pixels x supersample^2)).
Image render_mesh(const TriMesh& mesh, const Image* texture, const RenderOptions& options);

// Parses a comma-separated list of front, back, left, right, top, bottom, iso, all. Throws
// InvalidInput for an unknown name.
std::vector<View> parse_views(const std::string& text);
const char* view_name(View view);

}  // namespace meshdev
