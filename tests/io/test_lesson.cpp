// Lesson files: positioned errors, the embedded lessons' steps, the claims their captions make,
// and handouts that are the same bytes for any thread count.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <unistd.h>
#include <string>

#include "core/render/render.h"
#include "core/teaching/lesson.h"
#include "io/embedded_scenes.h"
#include "io/figure.h"
#include "io/handout.h"
#include "io/image_io.h"
#include "io/lesson_io.h"
#include "io/scene/scene_io.h"
#include "interaction/camera_control.h"

namespace phonglab {
namespace {

constexpr int kW = 160;  // small images: the claims hold at any size
constexpr int kH = 90;

Lesson embedded(const std::string& name) {
  const LessonLoad load = load_lesson_arg(name);
  EXPECT_TRUE(load.ok()) << load.error_text();
  return load.ok() ? *load.lesson : Lesson{};
}

std::string errors_of(const std::string& text) {
  const LessonLoad load = load_lesson_text(text, "bad.json");
  EXPECT_FALSE(load.ok());
  return load.error_text();
}

// The step whose title is `title`.
int step_titled(const Lesson& lesson, const std::string& title) {
  for (std::size_t i = 0; i < lesson.steps.size(); ++i) {
    if (lesson.steps[i].title == title) return static_cast<int>(i);
  }
  ADD_FAILURE() << "no step '" << title << "' in " << lesson.name;
  return 0;
}

// The image of `scene` as the plain renderer gives it (term, eye), kW x kH, 1 spp.
Image plain(const Scene& scene, Term term, const std::optional<Vec3>& eye = std::nullopt) {
  RenderOptions options;
  options.term = term;
  options.shading_eye = eye;
  Accumulator accum;
  accum.reset(kW, kH);
  render_pass(PreparedScene(scene), options, accum);
  return mean_image(accum);
}

HandoutOptions small() {
  HandoutOptions o;
  o.width = kW;
  o.height = kH;
  o.spp = 1;
  return o;
}

TEST(LessonFile, ErrorsArePositionedWithTheJsonPath) {
  EXPECT_EQ(errors_of("{\"title\": \"t\",\n \"stepz\": []}"),
            "bad.json:1:1: missing key \"steps\"\nbad.json:2:2: stepz: unknown key (did you mean \"steps\"?)");
  const std::string base = "{\"title\": \"t\", \"steps\": [\n";
  EXPECT_NE(errors_of(base + "{\"title\": \"a\", \"caption\": \"c\"}]}").find("bad.json:2:1: steps[0]: missing key \"scene\""),
            std::string::npos);
  EXPECT_NE(errors_of(base + "{\"title\": \"a\", \"caption\": \"c\", \"scene\": \"lectur\"}]}")
                .find("bad.json:2:41: steps[0].scene: the scene does not load: "),
            std::string::npos);
  EXPECT_NE(errors_of(base + "{\"title\": \"a\", \"caption\": \"c\", \"scene\": \"lectur\"}]}")
                .find("not an embedded scene either (did you mean \"lecture\"?)"),
            std::string::npos);
  const std::string step = "{\"title\": \"a\", \"caption\": \"c\", \"scene\": \"lecture\", ";
  EXPECT_NE(errors_of(base + step + "\"changes\": {\"materials\": {\"plastik\": {\"kd\": 1}}}}]}")
                .find("steps[0].changes.materials.plastik: unknown material \"plastik\" (did you mean \"plastic\"?)"),
            std::string::npos);
  EXPECT_NE(errors_of(base + step + "\"changes\": {\"materials\": {\"plastic\": {\"kd\": -1}}}}]}")
                .find("steps[0].changes.materials.plastic.kd: must be >= 0 (got -1)"),
            std::string::npos);
  EXPECT_NE(errors_of(base + step + "\"show\": {\"probe\": [960, 10]}}]}")
                .find("steps[0].show.probe[0]: must be an integer in 0..959 (got 960)"),
            std::string::npos);
  EXPECT_NE(errors_of(base + step + "\"show\": {\"ray_tree\": true}}]}").find("add \"probe\": [x, y]"), std::string::npos);
  EXPECT_NE(errors_of(base + step + "\"show\": {\"compare\": {\"against\": 5}}}]}").find("there is no step 5 (the lesson has 1)"),
            std::string::npos);
  EXPECT_NE(errors_of(base + step + "\"show\": {\"compare\": {\"against\": \"head\"}}}]}").find("needs \"head_angle_deg\""),
            std::string::npos);
  EXPECT_NE(errors_of(base + step + "\"question\": \"why?\"}]}").find("missing key \"answer\""), std::string::npos);
  EXPECT_NE(errors_of(base + step + "\"show\": {\"solo\": 2}}]}").find("steps[0].show.solo: must be an integer in 0..1 (got 2)"),
            std::string::npos);
  EXPECT_NE(errors_of(base + step + "\"show\": {\"term\": \"difuse\"}}]}").find("unknown term \"difuse\" (did you mean \"diffuse\"?)"),
            std::string::npos);
  EXPECT_EQ(errors_of("{\"title\": \"t\", \"steps\": [}"), "bad.json:1:26: syntax error: unexpected '}'; expected a value");
  EXPECT_NE(load_lesson_arg("shadin").error_text().find("not an embedded lesson either (did you mean \"shading\"?)"),
            std::string::npos);
}

TEST(LessonFile, StepsKeepTheirSceneAndApplyTheirChanges) {
  const LessonLoad load = load_lesson_text(R"({"title": "t", "steps": [
    {"title": "a", "caption": "c", "scene": "lecture", "changes": {"materials": {"plastic": {"ks": 0}}, "max_depth": 2,
     "camera": {"fov_y": 30}, "lights": [{"type": "point", "position": [0, 5, 0]}]}, "show": {"mute": [0]}},
    {"title": "b", "caption": "c", "show": {"solo": 1}}]})",
                                           "ok.json");
  ASSERT_TRUE(load.ok()) << load.error_text();
  const Lesson& l = *load.lesson;
  EXPECT_EQ(l.name, "ok");
  const Scene& a = l.steps[0].prepared_scene;
  const Scene lecture = *load_scene_arg("lecture").scene;
  EXPECT_EQ(a.max_depth, 2);
  EXPECT_EQ(a.camera.fov_y_deg, 30);
  EXPECT_EQ(a.camera.position, lecture.camera.position);
  ASSERT_EQ(a.lights.size(), 1U);
  EXPECT_FALSE(a.lights[0].enabled);
  EXPECT_EQ(a.materials[2].name, "plastic");
  EXPECT_EQ(a.materials[2].ks, Color(0));
  EXPECT_EQ(a.materials[2].kd, lecture.materials[2].kd);
  // The second step keeps the scene, not the changes.
  const Scene& b = l.steps[1].prepared_scene;
  EXPECT_EQ(l.steps[1].scene, "lecture");
  EXPECT_EQ(b.max_depth, lecture.max_depth);
  ASSERT_EQ(b.lights.size(), 2U);
  EXPECT_FALSE(b.lights[0].enabled);
  EXPECT_TRUE(b.lights[1].enabled);
}

TEST(LessonPlaces, QuestionsRevealBeforeTheNextStep) {
  Lesson l;
  l.steps.resize(3);
  l.steps[1].question = "q";
  LessonPlace p;
  p = lesson_next(l, p);
  EXPECT_EQ(p, (LessonPlace{1, false}));
  p = lesson_next(l, p);
  EXPECT_EQ(p, (LessonPlace{1, true}));
  p = lesson_next(l, p);
  EXPECT_EQ(p, (LessonPlace{2, false}));
  EXPECT_EQ(lesson_next(l, p), p) << "the last step stays";
  p = lesson_prev(l, {1, true});
  EXPECT_EQ(p, (LessonPlace{1, false}));
  EXPECT_EQ(lesson_prev(l, p), (LessonPlace{0, false}));
  EXPECT_EQ(lesson_prev(l, {0, false}), (LessonPlace{0, false}));
}

TEST(EmbeddedLessons, EveryStepRendersWithoutNaN) {
  for (const EmbeddedLesson& e : embedded_lessons()) {
    const Lesson lesson = embedded(std::string(e.name));
    ASSERT_GE(lesson.steps.size(), 5U) << e.name;
    EXPECT_FALSE(lesson.description.empty());
    for (int i = 0; i < static_cast<int>(lesson.steps.size()); ++i) {
      for (const bool revealed : {false, true}) {
        const LessonStep& step = lesson.steps[static_cast<std::size_t>(i)];
        if (revealed && !step.has_question()) continue;
        const StepView& view = view_at(step, revealed);
        RenderOptions options;
        options.term = view.term;
        const PreparedScene prepared(view_scene(step.prepared_scene, view));
        options.shading_eye = view_shading_eye(prepared, view, kW, kH);
        Accumulator accum;
        accum.reset(kW, kH);
        EXPECT_EQ(render_pass(prepared, options, accum).nan_count, 0U) << e.name << " step " << i + 1;
        const Image page = step_page(lesson, {i, revealed}, small());
        EXPECT_GT(page.height, kH) << "the caption is set below the image";
        for (const glm::vec3& p : page.pixels) ASSERT_TRUE(std::isfinite(p.x + p.y + p.z)) << e.name << " step " << i + 1;
      }
    }
  }
}

TEST(EmbeddedLessons, AmbientAloneIsOneColourPerMaterial) {
  const Lesson lesson = embedded("shading");
  const LessonStep& step = lesson.steps[static_cast<std::size_t>(step_titled(lesson, "Ambient alone"))];
  ASSERT_EQ(step.view.term, Term::kAmbient);
  const Image image = plain(step.prepared_scene, Term::kAmbient);
  std::set<std::array<float, 3>> colours;
  for (const glm::vec3& p : image.pixels) colours.insert({p.x, p.y, p.z});
  // Sample 0 is the pixel centre: no pixel mixes two objects, so only ka*Ia and 0 appear.
  std::set<std::array<float, 3>> expected = {{0, 0, 0}};
  for (const Material& m : step.prepared_scene.materials) {
    const Color c = m.ka * step.prepared_scene.ambient;
    expected.insert({static_cast<float>(c.x), static_cast<float>(c.y), static_cast<float>(c.z)});
  }
  for (const auto& c : colours) EXPECT_TRUE(expected.count(c)) << c[0] << " " << c[1] << " " << c[2];
}

TEST(EmbeddedLessons, TheDiffuseTermDoesNotChangeWithTheHead) {
  const Lesson lesson = embedded("shading");
  const int i = step_titled(lesson, "The diffuse term does not see the eye");
  const LessonStep& step = lesson.steps[static_cast<std::size_t>(i)];
  ASSERT_TRUE(step.view.head_angle_deg);
  const PreparedScene prepared(step.prepared_scene);
  const auto eye = view_shading_eye(prepared, step.view, kW, kH);
  ASSERT_TRUE(eye);
  EXPECT_NE(*eye, step.prepared_scene.camera.position);
  for (const double angle : {-60.0, 25.0, 80.0}) {
    StepView v = step.view;
    v.head_angle_deg = angle;
    const auto moved = view_shading_eye(prepared, v, kW, kH);
    EXPECT_EQ(plain(step.prepared_scene, Term::kDiffuse, moved).pixels, plain(step.prepared_scene, Term::kDiffuse).pixels)
        << angle;
  }
  // The step as the handout renders it: |moved - unmoved| is black everywhere but the probe's ring.
  const Image shown = render_step_view(lesson, {i, false}, small());
  const Image without_ring = [&] {
    HandoutOptions o = small();
    Lesson copy = lesson;
    copy.steps[static_cast<std::size_t>(i)].view.probe.reset();
    copy.steps[static_cast<std::size_t>(i)].view.head_angle_deg = step.view.head_angle_deg;
    return render_step_view(copy, {i, false}, o);
  }();
  for (const glm::vec3& p : without_ring.pixels) ASSERT_EQ(p, glm::vec3(0));
  EXPECT_NE(shown.pixels, without_ring.pixels) << "the probed pixel is marked";
  // ... while the specular term, and so the full image, does change: the highlight moves.
  const Image spec0 = plain(step.prepared_scene, Term::kSpecular);
  const Image spec1 = plain(step.prepared_scene, Term::kSpecular, eye);
  EXPECT_NE(spec0.pixels, spec1.pixels);
}

TEST(EmbeddedLessons, MovingTheHeadChangesOnlyTheHighlights) {
  const Lesson lesson = embedded("shading");
  const int i = step_titled(lesson, "Move your head");
  const LessonStep& step = lesson.steps[static_cast<std::size_t>(i)];
  ASSERT_TRUE(step.has_question());
  ASSERT_EQ(step.answer_view.compare, CompareView::kDifference);
  const PreparedScene prepared(step.prepared_scene);
  const auto eye = view_shading_eye(prepared, step.view, kW, kH);
  const Image full0 = plain(step.prepared_scene, Term::kFull);
  const Image full1 = plain(step.prepared_scene, Term::kFull, eye);
  const Image spec0 = plain(step.prepared_scene, Term::kSpecular);
  const Image spec1 = plain(step.prepared_scene, Term::kSpecular, eye);
  int changed = 0;
  for (std::size_t p = 0; p < full0.pixels.size(); ++p) {
    if (full0.pixels[p] == full1.pixels[p]) continue;
    ++changed;
    EXPECT_NE(spec0.pixels[p], spec1.pixels[p]) << "pixel " << p << " changed, but not its specular term";
  }
  EXPECT_GT(changed, 0) << "the highlights move";
}

TEST(EmbeddedLessons, NoLightLeavesOnlyTheAmbientTerm) {
  const Lesson lesson = embedded("shading");
  const LessonStep& step = lesson.steps[static_cast<std::size_t>(step_titled(lesson, "No light, no image"))];
  for (const Light& l : step.prepared_scene.lights) EXPECT_FALSE(l.enabled);
  const Image full = plain(step.prepared_scene, Term::kFull);
  const Image ambient = plain(step.prepared_scene, Term::kAmbient);
  const Image normal = plain(step.prepared_scene, Term::kNormal);  // 0 on a miss
  for (std::size_t p = 0; p < full.pixels.size(); ++p) {
    const bool miss = normal.pixels[p] == glm::vec3(0);
    EXPECT_EQ(full.pixels[p], miss ? glm::vec3(step.prepared_scene.background) : ambient.pixels[p]) << p;
  }
}

TEST(EmbeddedLessons, DepthCutStepsEqualTheCliMaxDepth) {
  int cut_steps = 0;
  for (const EmbeddedLesson& e : embedded_lessons()) {
    const Lesson lesson = embedded(std::string(e.name));
    for (int i = 0; i < static_cast<int>(lesson.steps.size()); ++i) {
      const LessonStep& step = lesson.steps[static_cast<std::size_t>(i)];
      if (!step.view.depth_cut || step.view.probe) continue;
      ++cut_steps;
      // `phonglab-cli render SCENE --max-depth D`: the scene file's own scene with max_depth = D.
      Scene cli = *load_scene_arg(step.scene).scene;
      cli.max_depth = *step.view.depth_cut;
      EXPECT_EQ(render_step_view(lesson, {i, false}, small()).pixels, plain(cli, Term::kFull).pixels) << e.name << " " << i + 1;
    }
  }
  EXPECT_GE(cut_steps, 3);
}

TEST(EmbeddedLessons, TheShadowStepsPointSeesNoLight) {
  const Lesson lesson = embedded("raytracing");
  const LessonStep& step = lesson.steps[static_cast<std::size_t>(step_titled(lesson, "Shadow rays"))];
  ASSERT_TRUE(step.view.probe);
  const Scene& s = step.prepared_scene;
  const PixelProbe probe = probe_pixel(PreparedScene(s), s.width, s.height, (*step.view.probe)[0], (*step.view.probe)[1]);
  ASSERT_TRUE(probe.root.hit);
  ASSERT_EQ(probe.root.lights.size(), s.lights.size());
  for (const auto& light : probe.root.lights) EXPECT_FALSE(light.visible);
  EXPECT_EQ(probe.root.total, probe.root.terms.ambient) << "only ka*Ia remains, as the answer says";
}

// In any window shape the previewer widens the field of view (ui::fit_to_view) and renders at
// the view's size: a step's probe still names the point the step's own image shows there, as
// `phonglab-cli probe` gives it at the scene's size: the same object, each light lit or not
// alike, and a ray within one shown pixel of the step's.
TEST(EmbeddedLessons, ProbedStepsNameTheSamePointAtAnyViewSize) {
  int checked = 0;
  for (const std::string name : {"shading", "raytracing"}) {
    const Lesson lesson = embedded(name);
    for (const LessonStep& step : lesson.steps) {
      for (const StepView* view : {&step.view, &step.answer_view}) {
        if (!view->probe) continue;
        const Scene& s = step.prepared_scene;
        const PixelProbe ref = probe_pixel(PreparedScene(s), s.width, s.height, (*view->probe)[0], (*view->probe)[1]);
        for (const auto& [w, h] : {std::pair{880, 720}, std::pair{1920, 1080}, std::pair{400, 900}}) {
          SCOPED_TRACE(name + ": " + step.title + " at " + std::to_string(w) + "x" + std::to_string(h));
          Scene shown = s;
          shown.camera = ui::fit_to_view(s.camera, static_cast<double>(s.width) / s.height, static_cast<double>(w) / h);
          const auto pixel = probe_in(s, shown.camera, *view, w, h);
          ASSERT_TRUE(pixel);
          const PixelProbe got = probe_pixel(PreparedScene(shown), w, h, (*pixel)[0], (*pixel)[1]);
          ASSERT_EQ(got.root.hit, ref.root.hit);
          const double pixel_angle = 2 * std::tan(glm::radians(shown.camera.fov_y_deg) / 2) / h;
          EXPECT_LT(std::acos(std::min(1.0, glm::dot(glm::normalize(got.root.dir), glm::normalize(ref.root.dir)))),
                    pixel_angle);
          if (!ref.root.hit) continue;
          EXPECT_EQ(got.root.object.kind, ref.root.object.kind);
          EXPECT_EQ(got.root.object.index, ref.root.object.index);
          ASSERT_EQ(got.root.lights.size(), ref.root.lights.size());
          for (std::size_t l = 0; l < ref.root.lights.size(); ++l) {
            EXPECT_EQ(got.root.lights[l].visible, ref.root.lights[l].visible) << "light " << l;
          }
          ++checked;
        }
      }
    }
  }
  EXPECT_GE(checked, 6);
}

std::string read_all(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(Handout, SameBytesForAnyThreadCountAndEveryImageInThePage) {
  const Lesson lesson = embedded("raytracing");
  const auto dir = std::filesystem::temp_directory_path() / ("phonglab_handout_" + std::to_string(::getpid()));
  std::vector<std::string> files[2];
  for (const int threads : {1, 2}) {
    HandoutOptions o = small();
    o.threads = threads;
    ASSERT_EQ(write_handout(lesson, (dir / std::to_string(threads)).string(), o, &files[threads - 1]), "");
  }
  ASSERT_EQ(files[0].size(), files[1].size());
  int questions = 0;
  for (const LessonStep& s : lesson.steps) questions += s.has_question() ? 1 : 0;
  EXPECT_EQ(files[0].size(), lesson.steps.size() + static_cast<std::size_t>(questions) + 1);
  for (std::size_t f = 0; f < files[0].size(); ++f) {
    EXPECT_EQ(read_all(files[0][f]), read_all(files[1][f])) << files[0][f];
  }
  EXPECT_TRUE(std::filesystem::exists(dir / "1" / "step-01.png"));
  const std::string html = read_all(dir / "1" / "index.html");
  std::size_t images = 0;
  for (std::size_t at = html.find("src=\"data:image/png;base64,"); at != std::string::npos;
       at = html.find("src=\"data:image/png;base64,", at + 1)) {
    ++images;
  }
  EXPECT_EQ(images, lesson.steps.size() + static_cast<std::size_t>(questions));
  std::filesystem::remove_all(dir);
}

TEST(Handout, CaptionsAreSpelledForThePngFontAndWrapped) {
  EXPECT_EQ(ascii_text("ka\xC2\xB7Ia + \xCE\xA3_l"), "ka*Ia + sum _l");
  EXPECT_EQ(ascii_text("caf\xC3\xA9"), "caf?");
  const auto lines = wrap_text("one two three four five six seven", 2, 100);
  EXPECT_GT(lines.size(), 1U);
  for (const auto& l : lines) EXPECT_LE(label_width(l, 2), 100);
}

}  // namespace
}  // namespace phonglab
