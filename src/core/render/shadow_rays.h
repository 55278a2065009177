// Shadow rays waiting for their answers, as structure of arrays, and the one way they are
// answered: four wide through the packet tracer where it serves the scene (testing only what a
// bundle towards one light can meet), else one by one; the same answers as occluded(). Used by
// the exact re-shade and the live path of a moved light (internal to core/render).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/accel/prepared_scene.h"
#include "core/packet/packet.h"

namespace phonglab {

struct ShadowRays {
  std::vector<double> ox, oy, oz, dx, dy, dz, t_max;

  std::size_t size() const { return t_max.size(); }
  void push(double x, double y, double z, double u, double v, double w, double t) {
    ox.push_back(x), oy.push_back(y), oz.push_back(z);
    dx.push_back(u), dy.push_back(v), dz.push_back(w);
    t_max.push_back(t);
  }
  void clear() {
    for (std::vector<double>* a : {&ox, &oy, &oz, &dx, &dy, &dz, &t_max}) a->clear();
  }
};

// blocked[i] for each of the rays towards `light` (one of the scene's), resized to whole groups of
// packet::kBatchLanes lanes; the rays are padded with idle lanes for the packet tracer (clear them before reuse).
inline void answer_shadow_rays(const PreparedScene& prepared, const Light& light, bool packets, ShadowRays& rays,
                               std::vector<std::uint8_t>& blocked) {
  const std::size_t n = rays.size();
  blocked.assign(static_cast<std::size_t>(packet::padded_lanes(static_cast<int>(n))), 0);
  if (n == 0) return;
  if (!packets) {
    for (std::size_t i = 0; i < n; ++i) {
      const Ray ray = make_ray(Vec3(rays.ox[i], rays.oy[i], rays.oz[i]), Vec3(rays.dx[i], rays.dy[i], rays.dz[i]));
      blocked[i] = occluded(prepared, ray, rays.t_max[i]);
    }
    return;
  }
  for (std::vector<double>* a : {&rays.ox, &rays.oy, &rays.oz, &rays.dx, &rays.dy, &rays.dz, &rays.t_max}) {
    a->resize(blocked.size(), 0.0);  // idle lanes: t_max 0 holds no ray
  }
  packet_tracer_for(prepared).occluded_towards(light, rays.ox.data(), rays.oy.data(), rays.oz.data(), rays.dx.data(),
                                               rays.dy.data(), rays.dz.data(), rays.t_max.data(), static_cast<int>(n),
                                               blocked.data());
}

}  // namespace phonglab
