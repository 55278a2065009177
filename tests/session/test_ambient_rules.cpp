// What ambient stands in for, on the Cornell box (the GUI test's ambient session drives the same through the window): the probe's
// indirect light on the back wall beside the red wall is red, and the ka that matches it; "best
// ka" and "best Iₐ" as the Materials panel applies them (Sidebar::sidebar_ambient_fit: fit_ambient
// over the view at a quarter of its size, 4 samples a pixel, the result tidied, one edit each).
#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

#include "core/render/indirect_probe.h"
#include "interaction/numbers.h"
#include "session/session.h"

namespace phonglab {
namespace {

constexpr int kProbeSamples = 256;  // the probe's gathers (Instruments::refresh_probe)

int material_named(const Scene& scene, const std::string& part) {
  for (std::size_t i = 0; i < scene.materials.size(); ++i) {
    if (scene.materials[i].name.find(part) != std::string::npos) return static_cast<int>(i);
  }
  return -1;
}

struct AmbientOnTheCornellBox : ::testing::Test {
  Session session{""};  // no recovery files
  void SetUp() override { ASSERT_TRUE(session.open("cornell")); }
};

// The probe in a 64x36 view (16:9, as the window with the panels hidden): pixel (22, 14) is the
// back wall between the red wall and the tall box, above the box. The red wall's bleed: its
// indirect light is redder than green by more than three standard errors, and ka·Iₐ with the ka
// it offers is that estimate.
TEST_F(AmbientOnTheCornellBox, TheBackWallBesideTheRedWallReceivesRedderIndirectLight) {
  const Scene& scene = session.scene();
  const IndirectProbe probe = probe_indirect(PreparedScene(scene), 64, 36, 22, 14, kProbeSamples);
  ASSERT_TRUE(probe.hit);
  ASSERT_GE(probe.material, 0);
  const Material& wall = scene.materials.at(static_cast<std::size_t>(probe.material));
  ASSERT_NE(wall.name.find("backWall"), std::string::npos) << wall.name;
  EXPECT_EQ(probe.samples, kProbeSamples);
  EXPECT_GT(probe.standard_error.x, 0);
  EXPECT_GT(probe.mean.x, probe.mean.y + 3 * (probe.standard_error.x + probe.standard_error.y))
      << "indirect " << probe.mean.x << " " << probe.mean.y << " " << probe.mean.z;
  ASSERT_EQ(scene.ambient, Color(0.12));
  for (int c = 0; c < 3; ++c) {
    EXPECT_DOUBLE_EQ(probe.ambient[c], wall.ka[c] * scene.ambient[c]) << c;
    EXPECT_GT(probe.fitted_ka[c], 0) << c;
    EXPECT_NEAR(probe.fitted_ka[c] * scene.ambient[c], probe.mean[c], 1e-12) << c;
  }
}

// "best ka" on the back wall (the material a click at the middle of the view selects): the fit
// wants more than a surface reflects, so ka is raised to at most 1 and the panel says so; then
// "best Iₐ", fitted again over the scene as it now is, raises the scene's one Iₐ below 1 and
// keeps every material's ka.
TEST_F(AmbientOnTheCornellBox, BestKaStopsAtOneAndBestIaRaisesTheScenesAmbientKeepingKa) {
  const int wall = material_named(session.scene(), "backWall");
  ASSERT_GE(wall, 0);
  const auto w = static_cast<std::size_t>(wall);
  const Color ka_before = session.scene().materials[w].ka;
  // A quarter of the 880x720 view's size (the panel fits 220x180; the same aspect, smaller).
  AmbientFit fit = fit_ambient(PreparedScene(session.scene()), 55, 45, 4);
  ASSERT_GT(fit.hits.at(w), 0U);
  EXPECT_TRUE(ka_over_one(fit.wanted_ka[w])) << "the panel's warning: ka wanted over 1, raise Ia instead";
  Material fitted = session.scene().materials[w];
  fitted.ka = ui::tidy_color(fit.fitted_ka[w]);
  EXPECT_TRUE(session.apply({edit::SetMaterial{wall, fitted}}).changed);
  session.settle(false);  // the frame's end, as the shell settles every frame
  EXPECT_EQ(session.undo_count(), 1U);
  const Color ka = session.scene().materials[w].ka;
  EXPECT_GT(ka.x, ka_before.x);
  for (int c = 0; c < 3; ++c) EXPECT_LE(ka[c], 1) << c;

  const std::vector<Material> materials = session.scene().materials;
  fit = fit_ambient(PreparedScene(session.scene()), 55, 45, 4);
  Scene whole = session.scene();
  whole.ambient = ui::tidy_color(fit.fitted_ia);
  EXPECT_TRUE(session.apply({edit::SetScene{std::move(whole)}}).changed);
  EXPECT_GT(session.scene().ambient.x, 0.12);
  EXPECT_LT(session.scene().ambient.x, 1);
  EXPECT_EQ(session.scene().materials, materials);
  session.settle(false);
  EXPECT_EQ(session.undo_count(), 2U);
}

}  // namespace
}  // namespace phonglab
