#include "io/probe_report.h"

#include <cstdarg>
#include <cstdio>
#include <limits>

#include <nlohmann/json.hpp>

#include "core/accel/accel.h"
#include "io/image_io.h"

namespace phonglab {

using nlohmann::json;

std::string object_name(const Scene& scene, ObjectRef ref) {
  const std::vector<int>* map = nullptr;
  const char* kind = "";
  switch (ref.kind) {
    case ObjectRef::Kind::kSphere: map = &scene.sphere_object; kind = "sphere"; break;
    case ObjectRef::Kind::kPlane: map = &scene.plane_object; kind = "plane"; break;
    case ObjectRef::Kind::kTriangle: map = &scene.triangle_object; kind = "triangle"; break;
    case ObjectRef::Kind::kMesh: map = &scene.mesh_object; kind = "mesh"; break;
    case ObjectRef::Kind::kNone: return "";
  }
  if (ref.index >= 0 && static_cast<std::size_t>(ref.index) < map->size()) {
    std::string name = "objects[" + std::to_string((*map)[static_cast<std::size_t>(ref.index)]) + "]";
    if (ref.kind == ObjectRef::Kind::kMesh && ref.prim >= 0) {
      const MeshGeometry& g = *scene.meshes[static_cast<std::size_t>(ref.index)].geometry;
      // Counted from 1 in file order, as OBJ indices and the loader's messages count.
      name += " face " + std::to_string(g.source_face[static_cast<std::size_t>(ref.prim)] + 1);
    }
    return name;
  }
  return std::string(kind) + "#" + std::to_string(ref.index);
}

namespace {

json vec_json(const Vec3& v) { return json::array({v.x, v.y, v.z}); }

// Infinity is not JSON: distances to directional lights are written as null.
json number_json(double x) { return std::isfinite(x) ? json(x) : json(nullptr); }

json terms_json(const Terms& t) {
  return {{"ambient", vec_json(t.ambient)},   {"diffuse", vec_json(t.diffuse)},
          {"specular", vec_json(t.specular)}, {"reflection", vec_json(t.reflection)},
          {"refraction", vec_json(t.refraction)}};
}

json node_json(const Scene& scene, const ProbeNode& node) {
  json j;
  j["depth"] = node.depth;
  j["weight"] = node.weight;
  j["origin"] = vec_json(node.origin);
  j["direction"] = vec_json(node.dir);
  j["hit"] = node.hit;
  j["total"] = vec_json(node.total);
  if (!node.hit) {
    j["background"] = vec_json(scene.background);
    return j;
  }
  j["t"] = node.t;
  j["object"] = object_name(scene, node.object);
  j["material"] = scene.materials[static_cast<std::size_t>(node.material)].name;
  j["P"] = vec_json(node.p);
  j["Ng"] = vec_json(node.ng);
  j["N"] = vec_json(node.n);
  j["V"] = vec_json(node.v);
  j["entering"] = node.entering;
  j["terms"] = terms_json(node.terms);
  const bool blinn = scene.specular_model == SpecularModel::kBlinn;
  json lights = json::array();
  for (const ProbeLight& pl : node.lights) {
    const Light& light = scene.lights[static_cast<std::size_t>(pl.index)];
    json l;
    l["index"] = pl.index;
    l["type"] = light.type == LightType::kPoint ? "point" : "directional";
    l["intensity"] = vec_json(light.intensity);
    l["L"] = vec_json(pl.l);
    l["distance"] = number_json(pl.distance);
    l["n_dot_l"] = pl.n_dot_l;
    l[blinn ? "H" : "R"] = vec_json(pl.r);
    l[blinn ? "n_dot_h" : "r_dot_v"] = pl.r_dot_v;
    l["spec_factor"] = pl.spec_factor;
    l["shadow_ray"] = pl.lit_side;
    l["visible"] = pl.visible;
    if (pl.lit_side && !pl.visible) {
      l["occluder"] = object_name(scene, pl.occluder);
      l["occluder_distance"] = pl.occluder_distance;
    }
    l["diffuse"] = vec_json(pl.diffuse);
    l["specular"] = vec_json(pl.specular);
    lights.push_back(std::move(l));
  }
  j["lights"] = std::move(lights);
  j["kr_eff"] = vec_json(node.kr_eff);
  j["kt_eff"] = vec_json(node.kt_eff);
  j["fresnel"] = node.fresnel;
  j["tir"] = node.tir;
  j["eta"] = node.eta;
  j["reflection"] = node.reflection ? node_json(scene, *node.reflection) : json(nullptr);
  j["refraction"] = node.refraction ? node_json(scene, *node.refraction) : json(nullptr);
  return j;
}

std::string fmt(const char* format, ...) __attribute__((format(printf, 1, 2)));
std::string fmt(const char* format, ...) {
  char buf[512];
  va_list args;
  va_start(args, format);
  std::vsnprintf(buf, sizeof buf, format, args);
  va_end(args);
  return buf;
}

// Significant digits: of scalars (t, dot products, F) and of vectors and colours.
struct Digits {
  int scalar = 9;
  int vector = 6;
};

std::string rgb(const Vec3& c, const Digits& d) { return fmt("(%.*g, %.*g, %.*g)", d.vector, c.x, d.vector, c.y, d.vector, c.z); }

void node_text(const Scene& scene, const ProbeNode& node, const std::string& label, const Digits& d, std::string& out) {
  const auto rgb = [&](const Vec3& c) { return phonglab::rgb(c, d); };
  const std::string pad(static_cast<std::size_t>(node.depth) * 4, ' ');
  out += pad + label + fmt(" ray, depth %d, path weight %.*g\n", node.depth, d.vector, node.weight);
  out += pad + "  O = " + rgb(node.origin) + "  D = " + rgb(node.dir) + "\n";
  if (!node.hit) {
    out += pad + "  misses everything: background " + rgb(node.total) + "\n";
    return;
  }
  const Material& m = scene.materials[static_cast<std::size_t>(node.material)];
  const bool blinn = scene.specular_model == SpecularModel::kBlinn;
  out += pad + fmt("  hits %s (material \"%s\") at t = %.*g, %s\n", object_name(scene, node.object).c_str(),
                   m.name.c_str(), d.scalar, node.t, node.entering ? "from outside" : "from inside");
  out += pad + "  P = " + rgb(node.p) + "\n";
  out += pad + "  N = " + rgb(node.n) + "  V = " + rgb(node.v) + "\n";
  out += pad + "  ambient   ka*Ia = " + rgb(m.ka) + " * " + rgb(scene.ambient) + " = " + rgb(node.terms.ambient) + "\n";
  for (const ProbeLight& pl : node.lights) {
    out += pad + fmt("  light %d: L = ", pl.index) + rgb(pl.l) + fmt("  N.L = %.*g", d.scalar, pl.n_dot_l);
    if (!pl.lit_side) {
      out += " <= 0: behind the surface, adds nothing\n";
      continue;
    }
    out += fmt("\n%s    %s = ", pad.c_str(), blinn ? "H" : "R") + rgb(pl.r) +
           fmt("  %s = %.*g  max(0, %s)^n = %.*g (n = %g)\n", blinn ? "N.H" : "R.V", d.scalar, pl.r_dot_v,
               blinn ? "N.H" : "R.V", d.scalar, pl.spec_factor, m.n);
    if (pl.visible) {
      out += pad + "    visible: diffuse I*kd*N.L = " + rgb(pl.diffuse) + "  specular I*ks*spec = " + rgb(pl.specular) + "\n";
    } else {
      out += pad + "    in shadow of " + object_name(scene, pl.occluder) + ": adds nothing\n";
    }
  }
  out += pad + "  diffuse    = " + rgb(node.terms.diffuse) + "\n";
  out += pad + "  specular   = " + rgb(node.terms.specular) + "\n";
  if (!is_zero(m.kr) || !is_zero(m.kt)) {
    out += pad + "  kr' = " + rgb(node.kr_eff) + "  kt' = " + rgb(node.kt_eff);
    if (m.fresnel) out += fmt("  Fresnel F = %.*g", d.scalar, node.fresnel);
    if (node.tir) out += "  total internal reflection";
    out += "\n";
  }
  out += pad + "  reflection = " + rgb(node.terms.reflection) + "\n";
  out += pad + "  refraction = " + rgb(node.terms.refraction) + "\n";
  out += pad + "  I = ambient + diffuse + specular + reflection + refraction = " + rgb(node.total) + "\n";
  if (node.reflection) node_text(scene, *node.reflection, "reflection", d, out);
  if (node.refraction) node_text(scene, *node.refraction, node.tir ? "refraction (TIR, mirror direction)" : "refraction", d, out);
}

}  // namespace

std::string probe_to_json(const Scene& scene, const PixelProbe& probe, const IndirectProbe* indirect) {
  json j = node_json(scene, probe.root);
  json out;
  out["pixel"] = json::array({probe.x, probe.y});
  out["hit"] = probe.root.hit;
  out["total"] = vec_json(probe.root.total);
  const Color& t = probe.root.total;
  out["srgb8"] = json::array({linear_to_srgb8(t.x), linear_to_srgb8(t.y), linear_to_srgb8(t.z)});
  out["terms"] = probe.root.hit ? terms_json(probe.root.terms) : terms_json(Terms{});
  out["lights"] = probe.root.hit ? j["lights"] : json::array();
  out["rays"] = {{"primary", probe.rays.primary},
                 {"shadow", probe.rays.shadow},
                 {"reflection", probe.rays.reflection},
                 {"refraction", probe.rays.refraction}};
  out["specular_model"] = scene.specular_model == SpecularModel::kBlinn ? "blinn" : "phong";
  out["ray"] = std::move(j);
  if (indirect) {
    out["indirect"] = {{"hit", indirect->hit},
                       {"bounces", indirect->bounces},
                       {"samples", indirect->samples},
                       {"ambient", vec_json(indirect->ambient)},
                       {"estimate", vec_json(indirect->mean)},
                       {"standard_error", vec_json(indirect->standard_error)},
                       {"fitted_ka", vec_json(indirect->fitted_ka)}};
  }
  return out.dump(2) + "\n";
}

std::string indirect_probe_text(const IndirectProbe& indirect, int digits) {
  const Digits d = digits > 0 ? Digits{digits, digits} : Digits{};
  if (!indirect.hit) return "what ambient stands in for: the centre ray meets nothing (indirect term 0)\n";
  std::string out = fmt("what ambient stands in for (%d bounces, %d samples):\n", indirect.bounces, indirect.samples);
  out += "  ka*Ia                  = " + rgb(indirect.ambient, d) + "\n";
  out += "  indirect kd*E          = " + rgb(indirect.mean, d) + "\n";
  out += "  its standard error     = " + rgb(indirect.standard_error, d) + "\n";
  out += "  ka for ka*Ia = indirect = " + rgb(indirect.fitted_ka, d) + "\n";
  return out;
}

std::string probe_to_text(const Scene& scene, const PixelProbe& probe, int digits) {
  const Digits d = digits > 0 ? Digits{digits, digits} : Digits{};
  std::string out = fmt("pixel (%d, %d), centre ray\n", probe.x, probe.y);
  out += "I = ka*Ia + sum_l vis_l*I_l*(kd*max(0,N.L) + ks*spec) + kr'*I_reflected + kt'*I_refracted\n";
  node_text(scene, probe.root, "primary", d, out);
  const Color& t = probe.root.total;
  out += "pixel value (linear) = " + rgb(t, d) +
         fmt("  displayed sRGB8 = (%d, %d, %d)\n", linear_to_srgb8(t.x), linear_to_srgb8(t.y), linear_to_srgb8(t.z));
  return out;
}

}  // namespace phonglab
