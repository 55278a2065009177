// The Formula panel's logic as the previewer runs it: a student's specular term with the sign of R wrong is checked against the reference and
// the mistake named (FormulaShell::poll_check: check_formulas of the view's scene with the
// session's rules), the probe shows yours, the reference and R's value (formula_probe_text), an
// unfinished text shows its error while the last good formula keeps rendering, undo gives the text
// back, the reference's own term matches, a misspelt name is positioned with its suggestion, the
// formulas' own file is written, refused with its position, opened as one undo step; and a formula
// edit reaches the renderer as a new snapshot whose first image is re-shaded from the stored ray
// trees at full size (RenderSchedule::set_rules, as FormulaShell::sync_rules calls it). The
// difference view's colours stay in the GUI test (pixels on the screen).
#include <gtest/gtest.h>

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>

#include "check/check.h"
#include "core/render/render.h"
#include "interaction/scene_objects.h"
#include "io/formula_file.h"
#include "session/render_schedule.h"
#include "session/session.h"
#include "tests/support/test_folder.h"

namespace phonglab {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

constexpr const char* kWrong = "R = reflect(L, N); ks * pow(max(0, dot(R, V)), n)";
constexpr const char* kRight = "R = reflect(-L, N); ks * pow(max(0, dot(R, V)), n)";
constexpr const char* kUnfinished = "R = reflect(L, N) ks * pow(";

struct FormulaPanel : ::testing::Test {
  Session session{""};
  test::TestFolder temp{"phonglab-formula-panel"};
  const fs::path dir = temp.path();
  void SetUp() override {
    ASSERT_TRUE(session.open("lecture"));
  }
  const FormulaBook::Slot& slot(FormulaSlot s) const { return session.formulas().slot(s); }
  // The check beside the renderer, at a reduced size of the view (the previewer's is at most
  // 480 wide; phonglab-cli check's tests use 160 x 90).
  CheckResult check() const {
    Scene scene = session.scene();
    scene.width = 160;
    scene.height = 90;
    return check_formulas(scene, session.formulas().rules());
  }
  static std::string read(const std::string& path) {
    std::stringstream text;
    text << std::ifstream(path).rdbuf();
    return text.str();
  }
};

TEST_F(FormulaPanel, TheWrongSignOfRIsNamed) {
  EXPECT_TRUE(session.set_formula(FormulaSlot::kSpecular, kWrong));
  const CheckResult r = check();
  EXPECT_FALSE(r.match);
  EXPECT_GT(r.differing, 0U);
  EXPECT_EQ(r.mistake, "reflect-sign or view-reversed") << check_report_text(r);
}

TEST_F(FormulaPanel, TheReferencesOwnTermMatches) {
  session.set_formula(FormulaSlot::kSpecular, kWrong);
  session.set_formula(FormulaSlot::kSpecular, kRight);
  const CheckResult r = check();
  EXPECT_TRUE(r.match) << check_report_text(r);
  EXPECT_EQ(r.differing, 0U);
}

// The probe at a lit pixel of the plastic sphere: yours against the reference for the point light,
// and the value of R as the student wrote it, reflect(L, N) = L - 2 (N.L) N.
TEST_F(FormulaPanel, TheProbeGivesYoursAgainstTheReferenceWithRsValue) {
  session.set_formula(FormulaSlot::kSpecular, kWrong);
  Scene scene = session.scene();
  scene.width = 96;
  scene.height = 54;
  const PreparedScene prepared(scene);
  const int plastic = ui::find_material(scene, "plastic");
  ASSERT_GE(plastic, 0);
  std::optional<PixelProbe> probed;
  for (int y = 0; y < scene.height && !probed; ++y) {
    for (int x = 0; x < scene.width && !probed; ++x) {
      PixelProbe p = probe_pixel(prepared, scene.width, scene.height, x, y);
      const ProbeNode& root = p.root;
      if (root.hit && root.material == plastic && !root.lights.empty() && root.lights[0].lit_side && root.lights[0].visible) {
        probed = std::move(p);
      }
    }
  }
  ASSERT_TRUE(probed) << "no pixel of the plastic sphere lit by the first light";
  const ProbeNode& hit = probed->root;
  const ProbeLight& light = hit.lights[0];
  const std::string text = formula_probe_text(scene, hit, session.formulas().rules());
  EXPECT_EQ(text.rfind("at the primary hit (plastic):\n", 0), 0U) << text;
  EXPECT_NE(text.find("light " + std::to_string(light.index) + " (N\xC2\xB7L "), std::string::npos) << text;
  EXPECT_NE(text.find("\n  specular: yours ("), std::string::npos) << text;
  EXPECT_NE(text.find("), reference ("), std::string::npos) << text;
  const Vec3 n = hit.n, l = light.l;
  const double twice = 2 * (n.x * l.x + n.y * l.y + n.z * l.z);
  const Vec3 r = l - twice * n;
  char expected[128];
  std::snprintf(expected, sizeof expected, "\n    R = (%.6g, %.6g, %.6g)\n", r.x, r.y, r.z);
  EXPECT_NE(text.find(expected), std::string::npos) << "expected" << expected << "in\n" << text;
}

TEST_F(FormulaPanel, AnUnfinishedTextShowsItsErrorAndTheLastGoodFormulaKeepsRendering) {
  session.set_formula(FormulaSlot::kSpecular, kWrong);
  const std::shared_ptr<const Formula> rendering = slot(FormulaSlot::kSpecular).formula;
  ASSERT_NE(rendering, nullptr);
  const std::uint64_t version = session.formulas().version();
  EXPECT_FALSE(session.set_formula(FormulaSlot::kSpecular, kUnfinished)) << "nothing new renders";
  ASSERT_TRUE(slot(FormulaSlot::kSpecular).error.has_value());
  EXPECT_EQ(slot(FormulaSlot::kSpecular).error->text(), "formula:1:19: expected an operator, \";\" or a new line (got \"ks\")");
  EXPECT_EQ(slot(FormulaSlot::kSpecular).text, kUnfinished) << "the text as typed";
  EXPECT_EQ(slot(FormulaSlot::kSpecular).formula, rendering);
  EXPECT_EQ(session.formulas().rules().formulas[static_cast<std::size_t>(FormulaSlot::kSpecular)], rendering);
  EXPECT_EQ(session.formulas().version(), version) << "the check is not run again: its verdict stays";
}

TEST_F(FormulaPanel, UndoGivesBackTheTextBeforeTheError) {
  session.set_formula(FormulaSlot::kSpecular, kWrong);
  session.set_formula(FormulaSlot::kSpecular, kUnfinished);
  ASSERT_TRUE(session.undo());
  EXPECT_EQ(slot(FormulaSlot::kSpecular).text, kWrong);
  EXPECT_FALSE(slot(FormulaSlot::kSpecular).error.has_value());
  ASSERT_NE(slot(FormulaSlot::kSpecular).formula, nullptr);
  EXPECT_EQ(slot(FormulaSlot::kSpecular).formula->text(), kWrong);
}

TEST_F(FormulaPanel, AMisspeltNameIsPositionedWithItsSuggestion) {
  session.set_formula(FormulaSlot::kDiffuse, "kd * dot(nrm, L)");
  ASSERT_TRUE(slot(FormulaSlot::kDiffuse).error.has_value());
  EXPECT_EQ(slot(FormulaSlot::kDiffuse).error->text(), "formula:1:10: unknown name \"nrm\" (did you mean \"N\"?)");
}

TEST_F(FormulaPanel, TheFormulasAreSavedInAFileOfTheirOwn) {
  session.set_formula(FormulaSlot::kSpecular, kRight);
  const std::string path = (dir / "mine.formulas.json").string();
  ASSERT_EQ(save_formula_file(path, session.formulas().texts()), "");
  EXPECT_NE(read(path).find("\"specular\": \"R = reflect(-L, N); ks * pow(max(0, dot(R, V)), n)\""), std::string::npos)
      << read(path);
}

// FormulaShell::open_formulas shows the file's first error and changes nothing.
TEST_F(FormulaPanel, ABadFormulaFileSaysWhereAndChangesNothing) {
  const std::string bad = (dir / "bad.json").string();
  std::ofstream(bad) << "{\n  \"specular\": 1\n}\n";
  const FormulaBook::Texts before = session.formulas().texts();
  const FormulaFileLoad loaded = load_formula_file(bad);
  ASSERT_FALSE(loaded.ok());
  ASSERT_FALSE(loaded.errors.empty());
  EXPECT_EQ(loaded.errors.front().to_string(), bad + ":2:15: specular: expected the formula's text as a string (got a number)");
  EXPECT_FALSE(loaded.texts.has_value());
  EXPECT_EQ(session.formulas().texts(), before);
}

// Saved, the panel cleared, the file opened again: its texts render (and match), and undo takes
// the whole file back in one step.
TEST_F(FormulaPanel, TheFileOpenedGivesTheTextsBackAndUndoTakesItBackInOneStep) {
  session.set_formula(FormulaSlot::kSpecular, kRight);
  const std::string path = (dir / "mine.formulas.json").string();
  ASSERT_EQ(save_formula_file(path, session.formulas().texts()), "");
  session.set_formula(FormulaSlot::kDiffuse, "kd * dot(nrm, L)");
  session.set_formula(FormulaSlot::kSpecular, "");
  session.set_formula(FormulaSlot::kDiffuse, "");
  EXPECT_FALSE(session.formulas().any());
  const FormulaFileLoad loaded = load_formula_file(path);
  ASSERT_TRUE(loaded.ok()) << loaded.error_text();
  session.set_formulas(*loaded.texts);
  EXPECT_EQ(slot(FormulaSlot::kSpecular).text, kRight);
  EXPECT_EQ(slot(FormulaSlot::kDiffuse).text, "");
  const CheckResult r = check();
  EXPECT_TRUE(r.match) << check_report_text(r);
  ASSERT_TRUE(session.undo());
  EXPECT_EQ(slot(FormulaSlot::kSpecular).text, "");
  EXPECT_FALSE(session.formulas().any());
}

// A formula edit changes no ray: once the renderer has the view's exact image (and its trees), the
// snapshot with the student's formula is shown at full size at once, re-shaded, bit for bit the
// image traced with the formula.
TEST(FormulaEditReshade, TheFirstImageOfAFormulaEditIsReshadedFromTheStoredTreesAtFullSize) {
  ProgressiveSettings settings;
  settings.target_spp = 2;
  settings.tree_budget_bytes = std::size_t{64} << 20;
  settings.live_images_per_s = 0;  // no live recombination: the re-shade itself
  ProgressiveRenderer renderer(settings);
  RenderSchedule schedule(renderer);
  Session session("");
  ASSERT_TRUE(session.open("lecture"));
  const auto send = [&](bool edited, double now) {
    return schedule.send_scene({edited, false, false, 40, 30, now, std::nullopt, std::nullopt}, session.scene(),
                               session.document().version());
  };
  ASSERT_TRUE(send(false, 0.0).scene);
  ASSERT_TRUE(renderer.wait_idle(60s));
  ASSERT_TRUE(session.set_formula(FormulaSlot::kSpecular, kWrong));
  schedule.set_rules(session.formulas().rules());  // FormulaShell::sync_rules
  renderer.set_interacting(true);                   // the first image only
  ASSERT_TRUE(send(true, 1.0).scene);
  ASSERT_TRUE(renderer.wait_idle(60s));
  ProgressiveFrame frame;
  ASSERT_TRUE(renderer.take_frame(frame));
  EXPECT_EQ(frame.divisor, 1);
  EXPECT_FALSE(frame.quads);
  EXPECT_TRUE(frame.stats.reshaded);
  Accumulator traced;
  traced.reset(40, 30);
  render_pass(*schedule.snapshot(), RenderOptions{}, traced);
  ASSERT_EQ(frame.pixels.size(), traced.sum.size());
  for (std::size_t i = 0; i < frame.pixels.size(); ++i) ASSERT_EQ(frame.pixels[i], glm::vec3(traced.sum[i])) << i;
  renderer.set_interacting(false);
}

}  // namespace
}  // namespace phonglab
