// The ray tree overlay, the depth cut and the heat map (issue 4, item 3): the overlay's
// geometry matches the probed tree and the renderer's camera, the image cut at depth d is the
// render with max_depth = d, and the heat map's ramp rises in luminance.
#include <cmath>
#include <cstdint>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/scene/camera.h"
#include "io/embedded_scenes.h"
#include "core/teaching/heat_map.h"
#include "core/teaching/ray_tree_view.h"
#include "core/render/render.h"
#include "io/scene/scene_io.h"
#include "tests/support/test_support.h"

namespace phonglab {
namespace {

constexpr int kWidth = 48;  // small images: every embedded scene, every pixel, still quick
constexpr int kHeight = 27;

std::string describe(const Camera& c) {
  std::ostringstream s;
  s << "camera (" << c.position.x << "," << c.position.y << "," << c.position.z << ") -> (" << c.look_at.x << ","
    << c.look_at.y << "," << c.look_at.z << ") up (" << c.up.x << "," << c.up.y << "," << c.up.z << ") fov "
    << c.fov_y_deg;
  return s.str();
}

// Cameras of every kind: the embedded scenes', tilted ones, narrow and wide, far from the origin.
std::vector<Camera> test_cameras() {
  std::vector<Camera> cameras;
  for (const EmbeddedScene& e : embedded_scenes()) cameras.push_back(load_scene_or_fail(e.name).camera);
  cameras.push_back(Camera{{3, 4, -5}, {0, 0.5, 0}, {0.2, 1, 0.1}, 60});
  cameras.push_back(Camera{{0, 10, 0.5}, {0, 0, 0}, {0, 1, 0}, 10});
  cameras.push_back(Camera{{-2, 0.3, 1}, {1, 0.2, -3}, {0, 0, 1}, 150});
  cameras.push_back(Camera{{1e5, 1e5 + 1, 1e5 + 6}, {1e5, 1e5 + 0.8, 1e5}, {0, 1, 0}, 40});
  return cameras;
}

// Walks a probe tree and counts what the overlay should show.
struct TreeCounts {
  int shadow_visible = 0;
  int shadow_blocked = 0;
  int reflections = 0;
  int refractions = 0;
  int deepest = 0;
};
void count_tree(const ProbeNode& node, TreeCounts& c) {
  c.deepest = std::max(c.deepest, node.depth);
  for (const ProbeLight& l : node.lights) {
    if (!l.lit_side) continue;
    if (l.visible) ++c.shadow_visible;
    else ++c.shadow_blocked;
  }
  if (node.reflection) {
    ++c.reflections;
    count_tree(*node.reflection, c);
  }
  if (node.refraction) {
    ++c.refractions;
    count_tree(*node.refraction, c);
  }
}

int count_kind(const std::vector<TreeSegment>& segments, TreeSegmentKind kind) {
  int n = 0;
  for (const TreeSegment& s : segments) n += s.kind == kind ? 1 : 0;
  return n;
}

TEST(RayTreeProjection, PrimaryHitProjectsOntoThePixelCentreForManyPixelsAndCameras) {
  Scene scene = load_scene_or_fail("lecture");
  for (const Camera& camera : test_cameras()) {
    scene.camera = camera;
    const PreparedScene prepared(scene);
    for (const auto& [w, h] : {std::pair{kWidth, kHeight}, std::pair{31, 64}}) {
      const CameraFrame frame = make_camera_frame(camera, w, h);
      int hits = 0;
      for (int y = 0; y < h; y += 2) {
        for (int x = 0; x < w; x += 2) {
          const PixelProbe probe = probe_pixel(prepared, w, h, x, y);
          if (!probe.root.hit) continue;
          ++hits;
          const std::optional<ImagePoint> p = project_point(frame, probe.root.p);
          ASSERT_TRUE(p.has_value()) << describe(camera) << " pixel " << x << "," << y;
          // The hit point is rounded (and re-projected onto the surface): a millionth of a pixel.
          EXPECT_NEAR(p->x, x + 0.5, 1e-6) << describe(camera) << " pixel " << x << "," << y;
          EXPECT_NEAR(p->y, y + 0.5, 1e-6) << describe(camera) << " pixel " << x << "," << y;
        }
      }
      if (camera.position.x < 1e4) {
        EXPECT_GT(hits, 0) << describe(camera);
      }
    }
  }
}

TEST(RayTreeProjection, AnyPointAlongACameraRayLandsOnItsImagePoint) {
  for (const Camera& camera : test_cameras()) {
    const CameraFrame frame = make_camera_frame(camera, 37, 20);
    for (int i = 0; i < 200; ++i) {
      const int x = (i * 7) % 37, y = (i * 3) % 20;
      double u, v;
      sample_offset(x, y, static_cast<std::uint32_t>(i), u, v);
      const Ray ray = camera_ray(frame, x, y, u, v);
      const double t = std::ldexp(1.0, i % 20 - 6);  // 1/64 .. 8192 world units
      const std::optional<ImagePoint> p = project_point(frame, ray.origin + t * ray.dir);
      ASSERT_TRUE(p.has_value());
      EXPECT_NEAR(p->x, x + u, 1e-7) << describe(camera) << " t " << t;
      EXPECT_NEAR(p->y, y + v, 1e-7) << describe(camera) << " t " << t;
    }
  }
}

TEST(RayTreeProjection, PointsBehindTheCameraDoNotProject) {
  const Camera camera{{0, 0, 5}, {0, 0, 0}, {0, 1, 0}, 40};
  const CameraFrame frame = make_camera_frame(camera, 16, 9);
  EXPECT_FALSE(project_point(frame, Vec3(0, 0, 6)).has_value());
  EXPECT_FALSE(project_point(frame, Vec3(1, 0, 5)).has_value()) << "on the camera plane";
  EXPECT_TRUE(project_point(frame, Vec3(0, 0, 4)).has_value());
}

TEST(RayTreeProjection, SegmentCrossingTheCameraPlaneIsCutAtTheNearPlane) {
  const Camera camera{{0, 0, 5}, {0, 0, 0}, {0, 1, 0}, 40};
  const CameraFrame frame = make_camera_frame(camera, 160, 90);
  // From the view centre's line, 4 units in front, to a point behind the camera and up: the
  // visible part runs from the image centre upwards and leaves through the top edge.
  const auto ends = project_segment(frame, Vec3(0, 0, 1), Vec3(0, 3, 8), 0.01);
  ASSERT_TRUE(ends.has_value());
  EXPECT_NEAR((*ends)[0].x, 80, 1e-9);
  EXPECT_NEAR((*ends)[0].y, 45, 1e-9);
  EXPECT_NEAR((*ends)[1].x, 80, 1e-9);
  EXPECT_NEAR((*ends)[1].y, 0, 1e-9) << "clipped to the top edge";
  EXPECT_FALSE(project_segment(frame, Vec3(0, 0, 6), Vec3(1, 1, 9), 0.01).has_value()) << "wholly behind";
  EXPECT_FALSE(project_segment(frame, Vec3(100, 0, 0), Vec3(100, 1, 0), 0.01).has_value()) << "wholly outside";
}

TEST(RayTreeProjection, EveryProjectedSegmentLiesInsideTheImage) {
  const PreparedScene prepared = load_prepared("glass");
  const Scene& scene = prepared.scene();
  const CameraFrame frame = make_camera_frame(scene.camera, kWidth, kHeight);
  for (int y = 0; y < kHeight; y += 3) {
    for (int x = 0; x < kWidth; x += 3) {
      const PixelProbe probe = probe_pixel(prepared, kWidth, kHeight, x, y);
      const auto screen =
          project_ray_tree(frame, ray_tree_segments(scene, probe.root), ray_tree_near(scene, probe.root));
      for (const ScreenSegment& s : screen) {
        for (const ImagePoint& p : {s.from, s.to}) {
          ASSERT_TRUE(std::isfinite(p.x) && std::isfinite(p.y));
          EXPECT_GE(p.x, 0);
          EXPECT_LE(p.x, kWidth);
          EXPECT_GE(p.y, 0);
          EXPECT_LE(p.y, kHeight);
        }
      }
    }
  }
}

TEST(RayTreeProjection, EndsInsideTheImageAreMarkedVisibleAndExact) {
  const PreparedScene prepared = load_prepared("lecture");
  const Scene& scene = prepared.scene();
  const CameraFrame frame = make_camera_frame(scene.camera, kWidth, kHeight);
  const PixelProbe probe = probe_pixel(prepared, kWidth, kHeight, kWidth / 2, kHeight / 2);
  ASSERT_TRUE(probe.root.hit);
  const auto screen = project_ray_tree(frame, ray_tree_segments(scene, probe.root), ray_tree_near(scene, probe.root));
  ASSERT_FALSE(screen.empty());
  ASSERT_EQ(screen[0].kind, TreeSegmentKind::kPrimary);
  EXPECT_TRUE(screen[0].to_visible) << "the primary hit is on screen";
  EXPECT_NEAR(screen[0].to.x, kWidth / 2 + 0.5, 1e-6);
  EXPECT_NEAR(screen[0].to.y, kHeight / 2 + 0.5, 1e-6);
}

TEST(RayTreeSegments, KindsAndCountsMatchTheProbedTreeInEveryEmbeddedScene) {
  for (const EmbeddedScene& e : embedded_scenes()) {
    const PreparedScene prepared = load_prepared(e.name);
    const Scene& scene = prepared.scene();
    for (int y = 0; y < kHeight; y += 2) {
      for (int x = 0; x < kWidth; x += 2) {
        const PixelProbe probe = probe_pixel(prepared, kWidth, kHeight, x, y);
        const std::vector<TreeSegment> segments = ray_tree_segments(scene, probe.root);
        TreeCounts c;
        count_tree(probe.root, c);
        int lit = 0;
        for (const ProbeLight& l : probe.root.lights) lit += l.lit_side ? 1 : 0;
        const std::string where = std::string(e.name) + " pixel " + std::to_string(x) + "," + std::to_string(y);
        EXPECT_EQ(count_kind(segments, TreeSegmentKind::kPrimary), 1) << where;
        EXPECT_EQ(count_kind(segments, TreeSegmentKind::kShadowVisible), c.shadow_visible) << where;
        EXPECT_EQ(count_kind(segments, TreeSegmentKind::kShadowBlocked), c.shadow_blocked) << where;
        EXPECT_EQ(count_kind(segments, TreeSegmentKind::kReflection), c.reflections) << where;
        EXPECT_EQ(count_kind(segments, TreeSegmentKind::kRefraction), c.refractions) << where;
        EXPECT_EQ(static_cast<std::uint64_t>(c.reflections), probe.rays.reflection) << where;
        EXPECT_EQ(static_cast<std::uint64_t>(c.refractions), probe.rays.refraction) << where;
        EXPECT_EQ(static_cast<std::uint64_t>(c.shadow_visible + c.shadow_blocked), probe.rays.shadow) << where;
        EXPECT_EQ(count_kind(segments, TreeSegmentKind::kArrowN), probe.root.hit ? 1 : 0) << where;
        EXPECT_EQ(count_kind(segments, TreeSegmentKind::kArrowV), probe.root.hit ? 1 : 0) << where;
        EXPECT_EQ(count_kind(segments, TreeSegmentKind::kArrowL), lit) << where;
        EXPECT_EQ(count_kind(segments, TreeSegmentKind::kArrowR), lit) << where;
        for (const TreeSegment& s : segments) {
          EXPECT_LE(s.depth, c.deepest) << where;
          EXPECT_TRUE(all_finite(s.from) && all_finite(s.to)) << where;
          if (s.kind == TreeSegmentKind::kReflection || s.kind == TreeSegmentKind::kRefraction) {
            EXPECT_GE(s.depth, 1) << where;
          }
        }
      }
    }
  }
}

TEST(RayTreeSegments, OptionsLeaveOutShadowsSecondaryRaysAndArrows) {
  const PreparedScene prepared = load_prepared("lecture");
  const Scene& scene = prepared.scene();
  const PixelProbe probe = probe_pixel(prepared, kWidth, kHeight, kWidth / 2, kHeight / 2);
  RayTreeViewOptions options;
  options.shadow_rays = options.secondary_rays = options.arrows = false;
  const std::vector<TreeSegment> segments = ray_tree_segments(scene, probe.root, options);
  ASSERT_EQ(segments.size(), 1u);
  EXPECT_EQ(segments[0].kind, TreeSegmentKind::kPrimary);
}

// A sphere between a floor point and a point light, a second light beside it that sees the
// point, and a directional light from the side; every position times `scale`.
PreparedScene shadow_scene(double scale = 1) {
  Scene scene;
  scene.camera = Camera{Vec3(0, 3, 8) * scale, {0, 0, 0}, {0, 1, 0}, 40};
  Material floor;
  floor.kd = Color(0.5);
  floor.ks = Color(0.25);
  scene.materials.push_back(floor);
  scene.planes.push_back(Plane{Vec3(0), Vec3(0, 1, 0), 0});
  scene.plane_object.push_back(0);
  scene.spheres.push_back(Sphere{Vec3(0, 2, 0) * scale, 0.5 * scale, 0});
  scene.sphere_object.push_back(1);
  Light above;
  above.position = Vec3(0, 4, 0) * scale;
  Light beside;
  beside.position = Vec3(4, 4, 0) * scale;
  Light sun;
  sun.type = LightType::kDirectional;
  sun.direction = Vec3(0, -1, -1);
  scene.lights = {above, beside, sun};
  return PreparedScene(std::move(scene));
}

TEST(RayTreeSegments, ShadowRaysEndAtTheLightOrAtTheOccluder) {
  const PreparedScene prepared = shadow_scene();
  const Scene& scene = prepared.scene();
  const CameraFrame frame = make_camera_frame(scene.camera, 320, 180);
  // The pixel whose ray hits the floor at the origin, right under the sphere.
  const std::optional<ImagePoint> origin = project_point(frame, Vec3(0));
  ASSERT_TRUE(origin.has_value());
  const PixelProbe probe = probe_pixel(prepared, 320, 180, static_cast<int>(origin->x), static_cast<int>(origin->y));
  ASSERT_TRUE(probe.root.hit);
  ASSERT_LT(glm::length(probe.root.p), 0.1);
  const std::vector<TreeSegment> segments = ray_tree_segments(scene, probe.root);
  const double reference = probe.root.t;
  int blocked = 0, visible = 0;
  for (const TreeSegment& s : segments) {
    if (s.kind == TreeSegmentKind::kShadowBlocked) {
      ++blocked;
      EXPECT_EQ(s.light, 0);
      EXPECT_NEAR(glm::length(s.to - Vec3(0, 2, 0)), 0.5, 1e-9) << "ends on the sphere";
      EXPECT_LT(s.to.y, 2.0) << "on its underside";
    } else if (s.kind == TreeSegmentKind::kShadowVisible && s.light == 1) {
      ++visible;
      EXPECT_NEAR(glm::length(s.to - Vec3(4, 4, 0)), 0, 1e-9) << "ends at the point light";
      EXPECT_FALSE(s.escapes);
    } else if (s.kind == TreeSegmentKind::kShadowVisible && s.light == 2) {
      ++visible;
      EXPECT_NEAR(glm::length(s.to - s.from), 0.6 * reference, 1e-9) << "a directional light: a fixed length";
      EXPECT_GT(glm::dot(s.to - s.from, Vec3(0, 1, 1)), 0) << "towards the light";
    }
  }
  EXPECT_EQ(blocked, 1);
  EXPECT_EQ(visible, 2);
}

TEST(RayTreeSegments, ArrowsAreUnitVectorsScaledByTheHitDistance) {
  for (const double scale : {1e-4, 1.0, 1e5}) {
    const PreparedScene prepared = shadow_scene(scale);
    const Scene& scene = prepared.scene();
    const PixelProbe probe = probe_pixel(prepared, 64, 36, 20, 30);
    ASSERT_TRUE(probe.root.hit) << scale;
    for (const TreeSegment& s : ray_tree_segments(scene, probe.root)) {
      if (s.kind < TreeSegmentKind::kArrowN) continue;
      EXPECT_EQ(s.from, probe.root.p);
      EXPECT_NEAR(glm::length(s.to - s.from) / probe.root.t, 0.15, 1e-9) << scale;
      if (s.kind == TreeSegmentKind::kArrowN) {
        EXPECT_NEAR(glm::dot(glm::normalize(s.to - s.from), probe.root.n), 1, 1e-12);
      }
      if (s.kind == TreeSegmentKind::kArrowV) {
        EXPECT_NEAR(glm::dot(glm::normalize(s.to - s.from), probe.root.v), 1, 1e-12);
      }
    }
  }
}

// The pixel of 'mirrors' with the longest chain of reflections (several bounces between the
// facing mirrors).
PixelProbe deepest_mirror_pixel(const PreparedScene& scene) {
  PixelProbe best = probe_pixel(scene, kWidth, kHeight, 0, 0);
  int best_depth = -1;
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      PixelProbe probe = probe_pixel(scene, kWidth, kHeight, x, y);
      TreeCounts c;
      count_tree(probe.root, c);
      if (c.deepest > best_depth && c.refractions == 0) {
        best_depth = c.deepest;
        best = std::move(probe);
      }
    }
  }
  return best;
}

TEST(RayTreeSegments, ReflectionsChainFromHitToHit) {
  const PreparedScene prepared = load_prepared("mirrors");
  const Scene& scene = prepared.scene();
  const PixelProbe probe = deepest_mirror_pixel(prepared);
  ASSERT_TRUE(probe.root.reflection);
  RayTreeViewOptions options;
  options.shadow_rays = options.arrows = false;
  const std::vector<TreeSegment> segments = ray_tree_segments(scene, probe.root, options);
  const ProbeNode* node = &probe.root;
  std::size_t i = 0;
  for (; node != nullptr && i < segments.size(); ++i, node = node->reflection.get()) {
    EXPECT_EQ(segments[i].depth, node->depth);
    EXPECT_EQ(segments[i].from, node->origin);
    if (node->hit) {
      EXPECT_EQ(segments[i].to, node->p);
    } else {
      EXPECT_TRUE(segments[i].escapes);
    }
  }
  EXPECT_GE(i, 3u) << "several bounces between the facing mirrors";
}

TEST(DepthCut, ImageCutAtDepthDIsTheRenderWithMaxDepthD) {
  for (const char* name : {"mirrors", "glass", "lecture"}) {
    const Scene scene = load_scene_or_fail(name);
    std::vector<Color> previous;
    for (int cut = 0; cut <= scene.max_depth + 1; ++cut) {
      Scene shown = scene;
      apply_depth_cut(shown, cut);
      Scene limited = scene;
      limited.max_depth = std::min(cut, scene.max_depth);
      Accumulator a, b;
      a.reset(kWidth, kHeight);
      b.reset(kWidth, kHeight);
      render_pass(PreparedScene(shown), RenderOptions{}, a);
      render_pass(PreparedScene(limited), RenderOptions{}, b);
      ASSERT_EQ(a.sum, b.sum) << name << " cut " << cut;  // bit-exact
      if (std::string_view(name) == "mirrors" && cut >= 1 && cut <= scene.max_depth) {
        EXPECT_NE(a.sum, previous) << "one more bounce shows in the facing mirrors at cut " << cut;
      }
      previous = a.sum;
    }
  }
}

TEST(DepthCut, NoCutKeepsTheScenesDepthAndACutNeverDeepens) {
  EXPECT_EQ(cut_max_depth(5, std::nullopt), 5);
  EXPECT_EQ(cut_max_depth(5, 2), 2);
  EXPECT_EQ(cut_max_depth(5, 0), 0);
  EXPECT_EQ(cut_max_depth(3, 7), 3);
  EXPECT_EQ(cut_max_depth(3, -1), 0);
}

TEST(DepthCut, ProbedTreeAtCutDHasNoRayDeeperThanD) {
  const Scene scene = load_scene_or_fail("mirrors");
  for (int cut = 0; cut <= 3; ++cut) {
    Scene shown = scene;
    apply_depth_cut(shown, cut);
    const PixelProbe probe = deepest_mirror_pixel(PreparedScene(shown));
    TreeCounts c;
    count_tree(probe.root, c);
    EXPECT_EQ(c.deepest, cut) << "some pixel of 'mirrors' bounces at least 3 times";
  }
}

double luminance(const Color& linear) { return 0.2126 * linear.x + 0.7152 * linear.y + 0.0722 * linear.z; }

TEST(HeatMap, RampRisesInLuminanceFromNearBlackToPaleYellow) {
  double previous = -1;
  for (int i = 0; i <= 1000; ++i) {
    const double lum = luminance(heat_color(i, 1000));
    EXPECT_GT(lum, previous) << "t = " << i / 1000.0;
    previous = lum;
  }
  EXPECT_LT(luminance(heat_color(0, 1)), 0.001) << "zero is near black";
  EXPECT_GT(luminance(heat_color(1, 1)), 0.8) << "the maximum is bright";
  EXPECT_EQ(heat_color(2, 1), heat_color(1, 1)) << "clamped above the scale";
  EXPECT_EQ(heat_color(-1, 1), heat_color(0, 1)) << "clamped below";
  EXPECT_EQ(heat_color(5, 0), heat_color(0, 1)) << "an empty scale maps to its bottom";
}

TEST(HeatMap, ScaleTopIsTheLargestRayCountOfTheImage) {
  const PreparedScene scene = load_prepared("glass");
  RenderOptions options;
  options.term = Term::kRays;
  Accumulator accum;
  accum.reset(kWidth, kHeight);
  render_pass(scene, options, accum);
  std::vector<glm::vec3> rays;
  double expected = 0;
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      rays.emplace_back(accum.mean(x, y));
      expected = std::max(expected, accum.mean(x, y).x);
    }
  }
  EXPECT_EQ(heat_max(rays), expected);
  EXPECT_GT(expected, 3) << "glass needs shadow, reflection and refraction rays";
  const std::vector<glm::vec3> heat = heat_map_pixels(rays, expected);
  ASSERT_EQ(heat.size(), rays.size());
  for (std::size_t i = 0; i < rays.size(); ++i) {
    EXPECT_EQ(heat[i], glm::vec3(heat_color(rays[i].x, expected)));
  }
}

// The raytracing lesson's shadow step: a floor point behind the red sphere sees neither light.
// Its L (and R) arrows are grey, not the yellow of "light seen" (a student read yellow L arrows
// through the sphere as "lit"); at a lit point they keep their colours.
TEST(RayTreeSegments, ArrowsTowardsABlockedLightAreGrey) {
  const PreparedScene prepared = load_prepared("lecture");
  const Scene& scene = prepared.scene();
  const auto arrows_at = [&](int x, int y, bool& any_blocked, bool& any_seen) {
    const PixelProbe probe = probe_pixel(prepared, scene.width, scene.height, x, y);
    any_blocked = any_seen = false;
    for (const TreeSegment& s : ray_tree_segments(scene, probe.root)) {
      if (s.kind != TreeSegmentKind::kArrowL && s.kind != TreeSegmentKind::kArrowR) continue;
      for (const ProbeLight& pl : probe.root.lights) {
        if (pl.index != s.light) continue;
        EXPECT_EQ(s.blocked, !pl.visible);
        const auto c = segment_srgb8(s);
        const std::array<std::uint8_t, 3> grey{150, 150, 150};
        if (!pl.visible) {
          EXPECT_EQ(c, grey);
          any_blocked = true;
        } else {
          EXPECT_NE(c, grey);
          any_seen = true;
        }
      }
    }
  };
  bool blocked = false, seen = false;
  arrows_at(300, 360, blocked, seen);  // the lesson's probed pixel: the floor in the red sphere's shadow
  EXPECT_TRUE(blocked);
  arrows_at(390, 270, blocked, seen);  // the red sphere's lit top
  EXPECT_TRUE(seen);
  EXPECT_EQ(segment_srgb8(TreeSegmentKind::kArrowL, 0), segment_srgb8(TreeSegmentKind::kShadowVisible, 0));
}

}  // namespace
}  // namespace phonglab

