// What differs between two snapshots of a scene, field by field: one comparison for an edit's
// scope, for what a re-shade brings up to date at each stored hit, for which pixels it shades
// again, and for which edits the image is a linear function of the edited coefficients (the
// live path of a slider). Internal to core/render; every field of Material, Light and Scene is
// classified here (scene_changes.cpp fails to compile when one is added and not).
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "core/render/ray_trees.h"
#include "core/scene/scene.h"

namespace phonglab {

inline bool any(const std::vector<bool>& flags) { return std::find(flags.begin(), flags.end(), true) != flags.end(); }

struct Changes {
  bool retrace = false;                // camera, geometry, a table's length, a light's type
  std::vector<bool> light_moved;       // its shadow rays are cast again
  std::vector<bool> light_shading;     // its intensity or mute
  std::vector<bool> material_shading;  // its ka, kd, ks or n
  std::vector<bool> coefficients;      // its ka, kd or ks: the image is linear in them
  std::vector<bool> n_changed;         // the specular factor of its hits is taken again
  std::vector<bool> bounce_changed;    // kr, kt, ior or Fresnel: its hits' F is taken again
  std::vector<bool> ior_changed;       // its hits' refracted rays go elsewhere: traced again
  bool limits_changed = false;         // the depth limit or the pruning weight
  bool depth_grew = false;             // hits that had no children may now: their F is taken
  bool eye_moved = false;              // V at the primary hits: their specular cosines are taken again
  bool model_changed = false;          // every specular cosine is computed again
  bool ambient_changed = false, background_changed = false;
  // The indirect light's bounces: no pixel of the lecture's image changes (the indirect view,
  // which reads them, is traced again after any edit but of ka and Ia: progressive.h).
  bool indirect_bounces_changed = false;

  // Something stored at the hits must be brought up to date.
  bool stale_hits() const {
    return any(light_moved) || any(n_changed) || any(bounce_changed) || model_changed || depth_grew || eye_moved;
  }
  EditScope scope() const {
    if (retrace) return EditScope::kRetrace;
    if (limits_changed || any(bounce_changed)) return EditScope::kBounces;
    if (any(light_moved)) return EditScope::kLights;
    if (any(light_shading) || any(material_shading) || model_changed || eye_moved || ambient_changed ||
        background_changed) {
      return EditScope::kShading;
    }
    return EditScope::kNothing;
  }
  // The reach bits of the pixels whose values change: those of the materials whose shading or
  // bounce changed and the background's, when it changed; every pixel for anything else.
  std::uint64_t dirty_reach(bool other_term) const {
    if (other_term || any(light_moved) || any(light_shading) || model_changed || eye_moved || ambient_changed ||
        limits_changed) {
      return ~std::uint64_t{0};
    }
    std::uint64_t dirty = background_changed ? RayTrees::kBackground : 0;
    for (std::size_t i = 0; i < material_shading.size(); ++i) {
      if (material_shading[i] || bounce_changed[i]) dirty |= RayTrees::reach_bit(static_cast<int>(i));
    }
    return dirty;
  }
  // The edits the live path of a slider or a drag shows, one family at a time. The image is
  // linear in some materials' ka, kd, ks; or in Ia; or in some lights' intensities (a muted
  // light's is 0); a product of two edited coefficients is not. kMovedLight: one light moved
  // (its intensity or mute may change with it): the image is the rest of each pixel's value plus
  // that light's share over the stored hits, cast again. Nothing else may differ. The family
  // (kMaterials when nothing at all changed), or kNone.
  enum class Linear : std::uint8_t { kNone, kMaterials, kAmbient, kLights, kMovedLight };
  Linear linear() const;
};

Changes changes_between(const Scene& a, const Scene& b);

// Whether the indirect light's images (its full image, its term) are the same for a and b: they
// read neither ka nor Ia, so an edit of those alone leaves them as they are.
bool indirect_unchanged(const Scene& a, const Scene& b);

}  // namespace phonglab
