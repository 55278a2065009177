// The packet tracer's light loop (shade()'s, one light at a time over a level's hits), its
// shadow queries, and the culling of the spheres and loose triangles a batch of rays can meet.
#include <algorithm>
#include <cmath>
#include <cstring>

#include "core/packet/packet_driver.h"

namespace phonglab {

using namespace packet_driver;  // Level, Shadow, padded, at (packet_batches.h)

static_assert(sizeof(Shadow) == 1 && static_cast<int>(Shadow::kNone) == 0 && static_cast<int>(Shadow::kVisible) == 1 &&
              static_cast<int>(Shadow::kTest) == 2);

packet::Spheres PacketTracer::Impl::primary_spheres(const CameraFrame& f, int x0, int y0, int x1, int y1) {
  if (walk_hierarchy) return no_spheres();
  Vec3 corner[4];
  Vec3 sum(0);
  for (int c = 0; c < 4; ++c) {
    const double sx = 2.0 * (c & 1 ? x1 : x0) / f.width - 1;
    const double sy = 1 - 2.0 * (c & 2 ? y1 : y0) / f.height;
    corner[c] = glm::normalize(f.forward + sx * f.right + sy * f.up);
    sum += corner[c];
  }
  const Vec3 axis = glm::normalize(sum);
  double cos_theta = 1;
  for (const Vec3& c : corner) cos_theta = std::min(cos_theta, glm::dot(axis, c));
  const double theta = std::acos(clamp_unit(cos_theta));
  if (!(theta < 1.0)) return spheres;  // a wide region: no cone worth testing
  primary_tested.clear();
  for (std::size_t k = 0; k < scene.spheres.size(); ++k) {
    const Sphere& sp = scene.spheres[k];
    const Vec3 v = sp.center - f.origin;
    const double dist = glm::length(v);
    bool keep = !(dist > sp.radius * (1 + 1e-6));  // the eye inside or on the sphere
    if (!keep) {
      const double off_axis = std::acos(clamp_unit(glm::dot(axis, v) / dist));
      keep = !(off_axis > theta + std::asin(sp.radius / dist) + 1e-6);
    }
    if (keep) primary_tested.push_back(static_cast<std::int32_t>(k));
  }
  packet::Spheres view = spheres;
  view.tested = primary_tested.data();
  view.tested_count = static_cast<int>(primary_tested.size());
  return view;
}

namespace {

// Whether no ray from the eye along a direction in the convex hull of `corner` meets the
// triangle whose vertices, as seen from the eye, are v: the rays that meet it run inside the cone
// of v[0], v[1], v[2], so a hull that lies strictly outside one of the three planes through the
// eye and an edge holds none of them. Relative margins of 1e-9 stand far above the rounding of
// these products and of the watertight test, which starts from the same differences v.
bool tile_misses_triangle(const Vec3 v[3], const Vec3 corner[4]) {
  for (int e = 0; e < 3; ++e) {
    const Vec3 &p = v[e], &q = v[(e + 1) % 3], &r = v[(e + 2) % 3];
    const Vec3 m = glm::cross(p, q);
    const double scale = glm::length(p) * glm::length(q);
    const double inside = glm::dot(m, r);  // the same for every edge: the eye's side of the triangle
    if (!(std::abs(inside) > 1e-9 * scale * glm::length(r))) return false;  // the eye (nearly) in its plane
    int out = 0;
    for (int c = 0; c < 4; ++c) {
      out += std::copysign(1.0, inside) * glm::dot(m, corner[c]) < -1e-9 * scale * glm::length(corner[c]);
    }
    if (out == 4) return true;
  }
  return false;
}

}  // namespace

packet::LooseTriangles PacketTracer::Impl::primary_triangles(const CameraFrame& f, int x0, int y0, int x1, int y1) {
  packet::LooseTriangles view = loose;
  if (walk_hierarchy || loose.count == 0) return view;
  Vec3 corner[4];  // camera_ray's directions before normalising, at the region's corners
  for (int c = 0; c < 4; ++c) {
    const double sx = 2.0 * (c & 1 ? x1 : x0) / f.width - 1;
    const double sy = 1 - 2.0 * (c & 2 ? y1 : y0) / f.height;
    corner[c] = f.forward + sx * f.right + sy * f.up;
  }
  primary_triangles_tested.clear();
  for (int k = 0; k < loose.count; ++k) {
    const Triangle& t = scene.triangles[at(k)];
    // Every ray leaves the triangle's plane: the eye strictly on one side and every corner
    // direction pointing away from it (triangles_met's margins).
    const Vec3& n = loose_normal[at(k)];
    const double side = glm::dot(n, f.origin - t.v0);
    const double margin = 0x1p-42 * std::max(loose_magnitude[at(k)], max_abs(f.origin));
    int away = 0;
    for (const Vec3& d : corner) {
      const double cosine = glm::dot(n, d) / glm::length(d);
      away += (side > margin && cosine > 1e-12) || (side < -margin && cosine < -1e-12);
    }
    const Vec3 v[3] = {t.v0 - f.origin, t.v1 - f.origin, t.v2 - f.origin};
    if (away < 4 && !tile_misses_triangle(v, corner)) primary_triangles_tested.push_back(k);
  }
  view.tested = primary_triangles_tested.data();
  view.tested_count = static_cast<int>(primary_triangles_tested.size());
  return view;
}

packet::Spheres PacketTracer::Impl::shadow_spheres(const Vec3& b, double ball, const Light& light, const Vec3& l) {
  if (walk_hierarchy) return no_spheres();
  shadow_tested.clear();
  const bool point = light.type == LightType::kPoint;
  const Vec3 w = point ? light.position - b : l;
  const double ww = glm::dot(w, w);
  const double reach = point ? glm::length(w) : 0.0;
  for (std::size_t k = 0; k < scene.spheres.size(); ++k) {
    const Sphere& sp = scene.spheres[k];
    const Vec3 cb = sp.center - b;
    double s = ww > 0 ? glm::dot(cb, w) / ww : 0.0;
    s = point ? std::clamp(s, 0.0, 1.0) : std::max(s, 0.0);
    const double dist = glm::length(cb - s * w);
    const double margin = 1e-6 * (sp.radius + ball) + 1e-9 * (glm::length(cb) + reach + max_abs(b));
    if (!(dist > sp.radius + ball + margin)) shadow_tested.push_back(static_cast<std::int32_t>(k));
  }
  packet::Spheres view = spheres;
  view.tested = shadow_tested.data();
  view.tested_count = static_cast<int>(shadow_tested.size());
  return view;
}

packet::LooseTriangles PacketTracer::Impl::triangles_met(const packet::Rays& rays, const double* t_max, int lanes, const Light* light,
                                     const Aabb* origins) {
  packet::LooseTriangles view = loose;
  if (loose.count == 0) return view;
  triangles_tested.clear();
  // The batch's origins and directions as boxes, once for every triangle: over a box a plane's
  // signed distance (or a direction's cosine) lies within the centre's plus or minus |n|·half.
  double box[12];
  if (light && origins) {  // only the origins' box is read
    for (int c = 0; c < 3; ++c) box[c] = origins->lo[c], box[3 + c] = origins->hi[c];
  } else {
    packet::ray_bounds(rays, t_max, lanes, box);
  }
  const Vec3 olo(box[0], box[1], box[2]), ohi(box[3], box[4], box[5]);
  const Vec3 dlo(box[6], box[7], box[8]), dhi(box[9], box[10], box[11]);
  view.tested = triangles_tested.data();
  view.tested_count = 0;
  if (!(olo.x <= ohi.x)) return view;  // no ray
  const Vec3 centre = 0.5 * (olo + ohi), half = 0.5 * (ohi - olo);
  const Vec3 dcentre = 0.5 * (dlo + dhi), dhalf = 0.5 * (dhi - dlo);
  const double origins_size = std::max(max_abs(olo), max_abs(ohi));
  const bool point = light && light->type == LightType::kPoint;
  for (int k = 0; k < loose.count; ++k) {
    const Vec3& n = loose_normal[at(k)];
    const Vec3 an = glm::abs(n);
    const double d = glm::dot(n, centre - scene.triangles[at(k)].v0), spread = glm::dot(an, half);
    const double size = std::max(loose_magnitude[at(k)], origins_size);
    const double margin = 0x1p-42 * size;
    // The far ends' side: a point light's, the direction L from the plane, or the rays'.
    double end_lo = 0, end_hi = 0, end_margin = 1e-12;
    if (light) {
      end_lo = end_hi = point ? glm::dot(n, light->position - scene.triangles[at(k)].v0) : glm::dot(n, -light->direction);
      if (point) end_margin = 0x1p-42 * std::max(size, max_abs(light->position));
    } else {
      const double cosine = glm::dot(n, dcentre), cosine_spread = glm::dot(an, dhalf);
      end_lo = cosine - cosine_spread, end_hi = cosine + cosine_spread;
    }
    const bool above = d - spread > margin && end_lo > end_margin;
    const bool below = d + spread < -margin && end_hi < -end_margin;
    if (!above && !below) triangles_tested.push_back(k);
  }
  view.tested = triangles_tested.data();
  view.tested_count = static_cast<int>(triangles_tested.size());
  return view;
}

void PacketTracer::Impl::test_shadows(Level& lv, int lanes, const packet::Spheres& tested, const Light& light) {
  std::fill_n(lv.blocked.begin(), padded(lanes), std::uint8_t{0});
  const packet::Rays rays{lv.sox.data(), lv.soy.data(), lv.soz.data(), lv.sdx.data(), lv.sdy.data(), lv.sdz.data()};
  any_hits(rays, lv.st_max.data(), padded(lanes), tested, lv.blocked.data(), &light);
}

void PacketTracer::Impl::any_hits(const packet::Rays& rays, const double* t_max, int lanes, const packet::Spheres& tested,
              std::uint8_t* blocked, const Light* light, const Aabb* origins) {
  packet::occluded(tested, planes, rays, t_max, lanes, blocked);
  if (walk_hierarchy) {
    packet::hierarchy_occluded(hierarchy, rays, t_max, lanes, blocked);
    return;
  }
  if (scene.triangles.empty()) return;
  packet::triangles_occluded(light ? triangles_met(rays, t_max, lanes, light, origins) : loose, rays, t_max, lanes,
                             blocked);
}

void PacketTracer::Impl::shade_lights(Level& lv, int lanes, RayCounts& counts) {
  const packet::ShadedPoints pts{lv.px.data(), lv.py.data(), lv.pz.data(), lv.nx.data(), lv.ny.data(),
                                 lv.nz.data(), lv.gx.data(), lv.gy.data(), lv.gz.data(), lv.vx.data(),
                                 lv.vy.data(), lv.vz.data(), lv.offset.data(), lv.active.data()};
  const packet::LightOut out{lv.n_dot_l.data(), lv.cos_spec.data(), lv.sox.data(), lv.soy.data(), lv.soz.data(),
                             lv.sdx.data(),     lv.sdy.data(),      lv.sdz.data(), lv.st_max.data(),
                             reinterpret_cast<std::uint8_t*>(lv.shadow.data())};
  const bool blinn = scene.specular_model == SpecularModel::kBlinn;
  const std::size_t materials = scene.materials.size();
  for (std::size_t li = 0; li < scene.lights.size(); ++li) {
    const Light& light = scene.lights[li];
    if (!light.enabled && sink == nullptr) continue;
    packet::LightIn in{};
    in.point = light.type == LightType::kPoint;
    const Vec3 l = in.point ? light.position : -light.direction;
    in.x = l.x, in.y = l.y, in.z = l.z;
    in.shrink = in.point ? surface_offset(light.position, 0) : 0.0;
    in.blinn = blinn;
    // Lit points (N.L > 0, a material with kd or ks) cast a shadow ray, except where the
    // light is within rounding distance (visible without one). N.L is NaN for a point light
    // exactly at P.
    const packet::ShadowCounts shadows = packet::light(in, pts, padded(lanes), out);
    counts.shadow += static_cast<std::uint64_t>(shadows.lit);
    if (shadows.tested > 0) {
      // The rays start within max_offset of the hit points' bounding box.
      const double ball = (0.5 * glm::length(lv.hi - lv.lo) + lv.max_offset) * (1 + 1e-9);
      test_shadows(lv, lanes, shadow_spheres(0.5 * (lv.lo + lv.hi), ball, light, l), light);
    }
    if (sink != nullptr) record_light(lv, lanes, static_cast<int>(li));
    if (!light.enabled) continue;
    // The light's terms where it is seen. The specular factor (pow) is computed only there:
    // a blocked light's would be multiplied by vis = 0.
    if (mark_seen(lv, lanes) == 0) continue;
    packet::add_light(light_kd.from(li * materials), light_ks.from(li * materials), lv.material.data(),
                      lv.seen.data(), lv.n_dot_l.data(), lv.spec.data(), padded(lanes), lv.diffuse.lanes(),
                      lv.specular.lanes());
  }
}

int PacketTracer::Impl::mark_seen(Level& lv, int lanes) const {
  int count = 0;
  constexpr std::uint32_t kOnes = 0x01010101u;
  for (int h = 0; h < padded(lanes); h += 4) {
    std::uint32_t lit, shadow, blocked;
    std::memcpy(&lit, &lv.lit[at(h)], 4);
    std::memcpy(&shadow, &lv.shadow[at(h)], 4);
    std::memcpy(&blocked, &lv.blocked[at(h)], 4);
    const std::uint32_t seen = lit & ((shadow & kOnes) | ((shadow >> 1) & ~blocked & kOnes));
    std::memcpy(&lv.seen[at(h)], &seen, 4);
    count += static_cast<int>((seen * kOnes) >> 24);  // the four bytes' sum (each 0 or 1)
  }
  if (count == 0) return 0;
  // The specular factors: whole exponents four lanes at a time where the CPU can, std::pow for
  // the lanes that leaves.
  const std::uint8_t* left = lv.seen.data();
  if (!power.empty()) {
    packet::specular_powers(lv.cos_spec.data(), lv.material.data(), power.data(), lv.seen.data(), padded(lanes),
                            lv.spec.data(), lv.pending.data());
    left = lv.pending.data();
  }
  for (int h = 0; h < padded(lanes); h += 4) {
    std::uint32_t word;
    std::memcpy(&word, left + h, 4);
    if (word == 0) continue;
    for (int j = 0; j < 4; ++j) {
      if (!(word >> (8 * j) & 1)) continue;
      const std::size_t u = at(h + j);
      const MaterialInfo& mi = info[at(lv.material[u])];
      lv.spec[u] = mi.specular ? specular_factor(lv.cos_spec[u], mi.n) : 0.0;
    }
  }
  return count;
}

void PacketTracer::Impl::record_light(const Level& lv, int lanes, int li) {
  for (int h = 0; h < lanes; ++h) {
    const std::size_t u = at(h);
    if (lv.id[u] < 0) continue;
    const double n_dot_l = lv.n_dot_l[u];
    if (std::isnan(n_dot_l)) {  // a point light exactly at P: no direction
      sink->light(lv.node[u], li, LightSeen::kNoLight, 0, 0, 0);
    } else if (!(n_dot_l > 0)) {
      sink->light(lv.node[u], li, LightSeen::kNoLight, n_dot_l, 0, 0);
    } else {
      // A blocked light's specular factor is never read (every shading sum skips it, and an
      // edit that could unblock it moves the light, which takes the factor again): no pow.
      const bool blocked = lv.shadow[u] == Shadow::kTest && lv.blocked[u];
      const double cos_spec = lv.cos_spec[u];
      sink->light(lv.node[u], li, blocked ? LightSeen::kBlocked : LightSeen::kVisible, n_dot_l, cos_spec,
                  blocked ? 0.0 : specular_factor(cos_spec, info[at(lv.material[u])].n));
    }
  }
}
}  // namespace phonglab
