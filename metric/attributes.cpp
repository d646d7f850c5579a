#include "metric/attributes.h"

#include <algorithm>
#include <cmath>

#include "metric/color_space.h"
#include "metric/errors.h"
#include "metric/nearest_point.h"
#include "metric/vertex_normals.h"

namespace meshdev {
namespace {

constexpr int kMaxDim = 16;

AttributeChannel computed_normals(const TriMesh& m, NormalWeighting w, int threads) {
  AttributeChannel c{"normal", AttributeKind::kNormal, Storage::kPerVertex, 3,
                     std::vector<double>(3 * m.positions.size())};
  compute_vertex_normals(m, w, threads, c.values.data());
  return c;
}

// A's computed normals: from the cache where it has them for `w`, else computed (and kept there).
AttributeChannel a_normals(const TriMesh& a, NormalWeighting w, int threads,
                           ReferenceAttributes* cache) {
  if (cache == nullptr) return computed_normals(a, w, threads);
  for (const auto& [weighting, channel] : cache->normals)
    if (weighting == w) return channel;
  cache->normals.emplace_back(w, computed_normals(a, w, threads));
  return cache->normals.back().second;
}

void add_channel_measures(const AttributeChannel& c, std::vector<Measure>& out) {
  switch (c.kind) {
    case AttributeKind::kNormal:
      out.push_back({"normal", MeasureKind::kNormalEuclidean, c.name, "unit-normal distance"});
      out.push_back({"normal_angle", MeasureKind::kNormalAngle, c.name, "degrees"});
      break;
    case AttributeKind::kColor:
      out.push_back({c.name, MeasureKind::kColorRgb, c.name, "sRGB distance, components in [0,1]"});
      out.push_back({c.name + "_de76", MeasureKind::kColorDeltaE76, c.name, "CIE76 delta E"});
      out.push_back(
          {c.name + "_de2000", MeasureKind::kColorDeltaE2000, c.name, "CIEDE2000 delta E"});
      break;
    case AttributeKind::kTexCoord:
      out.push_back({c.name, MeasureKind::kTexCoord, c.name, "UV units"});
      break;
    case AttributeKind::kScalar:
      out.push_back({c.name, MeasureKind::kScalar, c.name, "attribute units"});
      break;
  }
}

void add_cohen_measure(std::vector<Measure>& out) {
  out.push_back({"texcoord_cohen", MeasureKind::kCohenTexture, "texcoord",
                 "mesh units (Cohen: distance to the point of the other mesh with the same UV)"});
}

void add_texture_measures(std::vector<Measure>& out) {
  out.push_back({"texture_color", MeasureKind::kTextureColorRgb, "texcoord",
                 "texture sRGB distance, components in [0,1]"});
  out.push_back(
      {"texture_color_de76", MeasureKind::kTextureColorDeltaE76, "texcoord", "CIE76 delta E"});
  out.push_back({"texture_color_de2000", MeasureKind::kTextureColorDeltaE2000, "texcoord",
                 "CIEDE2000 delta E"});
}

// The "texcoord" channel of both meshes, 2-D, or InvalidInput naming what is missing.
void require_texcoords(const TriMesh& a, const TriMesh& b, const std::string& what,
                       const std::string& label_a, const std::string& label_b) {
  for (int k = 0; k < 2; ++k) {
    const AttributeChannel* c = (k == 0 ? a : b).channel("texcoord");
    if (c == nullptr || c->dim != 2)
      throw InvalidInput("'" + what + "' was requested but " + (k == 0 ? label_a : label_b) +
                         " has no 2-D texture coordinates");
  }
}

}  // namespace

bool is_texture_color(MeasureKind kind) {
  return kind == MeasureKind::kTextureColorRgb || kind == MeasureKind::kTextureColorDeltaE76 ||
         kind == MeasureKind::kTextureColorDeltaE2000;
}

const AttributeChannel* PreparedMesh::channel(std::string_view name) const {
  for (const AttributeChannel& c : computed)
    if (c.name == name) return &c;
  return mesh->channel(name);
}

NormalSource parse_normal_source(const std::string& text) {
  if (text == "auto") return NormalSource::kAuto;
  if (text == "file") return NormalSource::kFile;
  if (text == "uniform" || text == "average") return NormalSource::kUniform;
  if (text == "area") return NormalSource::kArea;
  if (text == "angle") return NormalSource::kAngle;
  throw InvalidInput("unknown normal source '" + text + "' (use auto, file, uniform, area, angle)");
}

AttributePlan plan_attributes(const TriMesh& a, const TriMesh& b, const AttributeOptions& options,
                              const std::string& label_a, const std::string& label_b,
                              ReferenceAttributes* a_cache) {
  AttributePlan plan;
  plan.a.mesh = &a;
  plan.b.mesh = &b;
  plan.measures.push_back({"geometry", MeasureKind::kGeometry, "", "mesh units"});

  std::vector<std::string> wanted = options.attributes;
  const bool automatic = wanted.empty();
  if (automatic) {
    wanted.push_back("normal");
    for (const AttributeChannel& c : a.channels) {
      const AttributeChannel* other = b.channel(c.name);
      if (c.name != "normal" && other != nullptr && other->dim == c.dim && other->kind == c.kind)
        wanted.push_back(c.name);
    }
  }

  std::vector<std::string> done;
  for (const std::string& name : wanted) {
    if (name == "geometry" || std::find(done.begin(), done.end(), name) != done.end()) continue;
    done.push_back(name);
    if (name == "normal") {
      const bool both_have = a.channel("normal") != nullptr && b.channel("normal") != nullptr;
      NormalSource source = options.normals;
      if (source == NormalSource::kAuto)
        source = both_have ? NormalSource::kFile : NormalSource::kUniform;
      if (source == NormalSource::kFile) {
        if (!both_have)
          throw InvalidInput("normals from the file were requested but " +
                             (a.channel("normal") ? label_b : label_a) + " has none");
        plan.normal_source = "file";
      } else {
        const NormalWeighting w = source == NormalSource::kArea    ? NormalWeighting::kArea
                                  : source == NormalSource::kAngle ? NormalWeighting::kAngle
                                                                   : NormalWeighting::kUniform;
        plan.a.computed.push_back(a_normals(a, w, options.threads, a_cache));
        plan.b.computed.push_back(computed_normals(b, w, options.threads));
        plan.normal_source = source == NormalSource::kArea ? "computed (area-weighted)"
                             : source == NormalSource::kAngle
                                 ? "computed (angle-weighted)"
                                 : "computed (uniform average, as the paper)";
      }
      add_channel_measures(*plan.a.channel("normal"), plan.measures);
      continue;
    }
    if (name == "cohen" || name == "texcoord_cohen") {
      require_texcoords(a, b, name, label_a, label_b);
      done.insert(done.end(), {"cohen", "texcoord_cohen"});
      if (std::find(done.begin(), done.end(), "texcoord") == done.end()) {
        done.push_back("texcoord");
        add_channel_measures(*a.channel("texcoord"), plan.measures);
      }
      add_cohen_measure(plan.measures);
      continue;
    }
    if (name == "texture" || name == "texture_color") {
      require_texcoords(a, b, name, label_a, label_b);
      done.insert(done.end(), {"texture", "texture_color"});
      for (int k = 0; k < 2; ++k) {
        const TriMesh& m = k == 0 ? a : b;
        if (m.texture_file.empty())
          throw InvalidInput("'texture' was requested but " + (k == 0 ? label_a : label_b) +
                             " names no texture image (OBJ map_Kd or PLY comment TextureFile)");
        if (k == 0 && a_cache != nullptr && a_cache->texture) {
          plan.a.texture = a_cache->texture;
          continue;
        }
        (k == 0 ? plan.a : plan.b).texture =
            std::make_shared<const Image>(load_image(m.texture_file));
        if (k == 0 && a_cache != nullptr) a_cache->texture = plan.a.texture;
      }
      add_texture_measures(plan.measures);
      continue;
    }
    const AttributeChannel* ca = a.channel(name);
    const AttributeChannel* cb = b.channel(name);
    if (ca == nullptr || cb == nullptr)
      throw InvalidInput("attribute '" + name + "' was requested but " +
                         (ca == nullptr ? label_a : label_b) + " has no such attribute");
    if (ca->dim != cb->dim || ca->kind != cb->kind)
      throw InvalidInput("attribute '" + name + "' has dimension " + std::to_string(ca->dim) +
                         " on " + label_a + " but " + std::to_string(cb->dim) + " on " + label_b);
    if (ca->dim > kMaxDim)
      throw InvalidInput("attribute '" + name + "' has " + std::to_string(ca->dim) +
                         " components; at most 16 are supported");
    add_channel_measures(*ca, plan.measures);
  }
  return plan;
}

ValueForm value_form(MeasureKind kind) {
  switch (kind) {
    case MeasureKind::kNormalEuclidean:
    case MeasureKind::kNormalAngle:
      return ValueForm::kUnit;
    case MeasureKind::kColorDeltaE76:
    case MeasureKind::kColorDeltaE2000:
    case MeasureKind::kTextureColorDeltaE76:
    case MeasureKind::kTextureColorDeltaE2000:
      return ValueForm::kLab;
    case MeasureKind::kGeometry:
    case MeasureKind::kCohenTexture:
    case MeasureKind::kTextureColorRgb:
    case MeasureKind::kColorRgb:
    case MeasureKind::kTexCoord:
    case MeasureKind::kScalar:
      break;
  }
  return ValueForm::kRaw;
}

void to_form(ValueForm form, const double* x, int dim, double* out) {
  Vec3 v;
  switch (form) {
    case ValueForm::kUnit:
      v = unit_normal({x[0], x[1], x[2]});
      break;
    case ValueForm::kLab:
      v = srgb_to_lab({x[0], x[1], x[2]});
      break;
    case ValueForm::kRaw:
      for (int k = 0; k < dim; ++k) out[k] = x[k];
      return;
  }
  out[0] = v.x;
  out[1] = v.y;
  out[2] = v.z;
}

double form_distance(MeasureKind kind, const double* x, const double* y, int dim) {
  // Unit normals and CIELAB colours have three components.
  auto vec = [](const double* v) { return Vec3{v[0], v[1], v[2]}; };
  switch (kind) {
    case MeasureKind::kNormalEuclidean:
    case MeasureKind::kNormalAngle:
      return unit_normal_distance(kind, vec(x), vec(y));
    case MeasureKind::kColorDeltaE76:
    case MeasureKind::kTextureColorDeltaE76:
      return delta_e76(vec(x), vec(y));
    case MeasureKind::kColorDeltaE2000:
    case MeasureKind::kTextureColorDeltaE2000:
      return delta_e2000(vec(x), vec(y));
    case MeasureKind::kGeometry:
    case MeasureKind::kCohenTexture:
    case MeasureKind::kTextureColorRgb:
    case MeasureKind::kColorRgb:
    case MeasureKind::kTexCoord:
    case MeasureKind::kScalar:
      break;
  }
  double s = 0.0;
  for (int k = 0; k < dim; ++k) s += (x[k] - y[k]) * (x[k] - y[k]);
  return std::sqrt(s);
}

double attribute_distance(MeasureKind kind, const double* x, const double* y, int dim) {
  const ValueForm form = value_form(kind);
  if (form == ValueForm::kRaw) return form_distance(kind, x, y, dim);
  double fx[3], fy[3];
  to_form(form, x, dim, fx);
  to_form(form, y, dim, fy);
  return form_distance(kind, fx, fy, dim);
}

}  // namespace meshdev
