// Lesson files: positioned errors, the embedded lessons' steps, the claims their captions make,
// and handouts that are the same bytes for any thread count.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <unistd.h>
#include <string>

#include "core/render/render.h"
#include "core/scene/camera.h"
#include "core/scene/math.h"
#include "core/teaching/ray_tree_view.h"
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
  EXPECT_NE(errors_of(base + "{\"title\": \"a\", \"caption\": \"c\"}]}").find("bad.json:2:1: steps[0]: (step 1) missing key \"scene\""),
            std::string::npos);
  EXPECT_NE(errors_of(base + "{\"title\": \"a\", \"caption\": \"c\", \"scene\": \"lectur\"}]}")
                .find("bad.json:2:41: steps[0].scene: (step 1) the scene does not load: "),
            std::string::npos);
  EXPECT_NE(errors_of(base + "{\"title\": \"a\", \"caption\": \"c\", \"scene\": \"lectur\"}]}")
                .find("not an embedded scene either (did you mean \"lecture\"?)"),
            std::string::npos);
  const std::string step = "{\"title\": \"a\", \"caption\": \"c\", \"scene\": \"lecture\", ";
  EXPECT_NE(errors_of(base + step + "\"changes\": {\"materials\": {\"plastik\": {\"kd\": 1}}}}]}")
                .find("steps[0].changes.materials.plastik: (step 1) unknown material \"plastik\" (did you mean \"plastic\"?)"),
            std::string::npos);
  EXPECT_NE(errors_of(base + step + "\"changes\": {\"materials\": {\"plastic\": {\"kd\": -1}}}}]}")
                .find("steps[0].changes.materials.plastic.kd: (step 1) must be >= 0 (got -1)"),
            std::string::npos);
  EXPECT_NE(errors_of(base + step + "\"show\": {\"probe\": [960, 10]}}]}")
                .find("steps[0].show.probe[0]: (step 1) must be an integer in 0..959 (got 960)"),
            std::string::npos);
  EXPECT_NE(errors_of(base + step + "\"show\": {\"ray_tree\": true}}]}").find("add \"probe\": [x, y]"), std::string::npos);
  EXPECT_NE(errors_of(base + step + "\"show\": {\"compare\": {\"against\": 5}}}]}").find("there is no step 5 (the lesson has 1)"),
            std::string::npos);
  EXPECT_NE(errors_of(base + step + "\"show\": {\"compare\": {\"against\": \"head\"}}}]}").find("needs \"head_angle_deg\""),
            std::string::npos);
  EXPECT_NE(errors_of(base + step + "\"question\": \"why?\"}]}").find("missing key \"answer\""), std::string::npos);
  EXPECT_NE(errors_of(base + step + "\"show\": {\"solo\": 2}}]}").find("steps[0].show.solo: (step 1) must be an integer in 0..1 (got 2)"),
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
        const Image page = render_step_view(lesson, {i, revealed}, small());
        EXPECT_EQ(page.height, kH) << "the image only: its text is the HTML page's";
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
    copy.steps[static_cast<std::size_t>(i)].view.light_markers = false;
    copy.steps[static_cast<std::size_t>(i)].view.head_angle_deg = step.view.head_angle_deg;
    return render_step_view(copy, {i, false}, o);
  }();
  for (const glm::vec3& p : without_ring.pixels) ASSERT_EQ(p, glm::vec3(0));
  EXPECT_NE(shown.pixels, without_ring.pixels) << "the probed pixel and the lights are marked";
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
      // `phonglab-cli render SCENE --max-depth D`: the scene file's own scene with max_depth = D
      // (the step's image without its light markers).
      Scene cli = *load_scene_arg(step.scene).scene;
      cli.max_depth = *step.view.depth_cut;
      Lesson unmarked = lesson;
      unmarked.steps[static_cast<std::size_t>(i)].view.light_markers = false;
      EXPECT_EQ(render_step_view(unmarked, {i, false}, small()).pixels, plain(cli, Term::kFull).pixels) << e.name << " " << i + 1;
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

// The caption is written once, in the page (Unicode, with the step's number and title); the
// PNG is the image alone.
TEST(Handout, TheTextIsThePagesAndThePngIsTheImage) {
  const Lesson lesson = embedded("shading");
  const auto dir = std::filesystem::temp_directory_path() / ("phonglab_handout_text_" + std::to_string(::getpid()));
  ASSERT_EQ(write_handout(lesson, dir.string(), small()), "");
  const std::string png = read_all(dir / "step-01.png");
  ASSERT_GT(png.size(), 24U);
  const auto be32 = [&](std::size_t at) {
    return static_cast<unsigned>(static_cast<unsigned char>(png[at])) << 24 | static_cast<unsigned>(static_cast<unsigned char>(png[at + 1])) << 16 |
           static_cast<unsigned>(static_cast<unsigned char>(png[at + 2])) << 8 | static_cast<unsigned>(static_cast<unsigned char>(png[at + 3]));
  };
  EXPECT_EQ(be32(16), static_cast<unsigned>(kW));
  EXPECT_EQ(be32(20), static_cast<unsigned>(kH)) << "no text below the image";
  const std::string html = read_all(dir / "index.html");
  EXPECT_NE(html.find("<h2>1. Ambient alone <span class=\"of\">(step 1 of 16)</span></h2>"), std::string::npos);
  EXPECT_NE(html.find("I = ka\xC2\xB7I\xE2\x82\x90. The ambient term"), std::string::npos) << "Ia as the panels write it";
  EXPECT_NE(html.find("This is the end of the lesson."), std::string::npos);
  std::filesystem::remove_all(dir);
}

// The lessons write the equation's symbols as the panels do (src/ui/widgets.cpp i_a(), i_l():
// I with a subscript a or l), never "Ia" (which reads as "la" in a sans-serif font); the last
// step says that the lesson has ended.
TEST(EmbeddedLessons, CaptionsWriteTheSubscriptsAndTheLastStepEndsTheLesson) {
  for (const EmbeddedLesson& e : embedded_lessons()) {
    const Lesson lesson = embedded(std::string(e.name));
    for (const LessonStep& step : lesson.steps) {
      for (const std::string* text : {&step.title, &step.caption, &step.question, &step.answer}) {
        EXPECT_EQ(text->find("Ia"), std::string::npos) << e.name << ": " << *text;
        EXPECT_EQ(text->find("I_l"), std::string::npos) << e.name << ": " << *text;
        EXPECT_EQ(text->find("I_a"), std::string::npos) << e.name << ": " << *text;
      }
    }
    EXPECT_NE(lesson.steps.back().caption.find("end of the lesson"), std::string::npos) << e.name;
  }
}

// The shadow step asks "Is this point lit?" over the probed point alone; its answer shows what
// the question hid: the ray tree, the shadow rays red (blocked) and ending at the red sphere.
TEST(Handout, TheShadowAnswerShowsTheBlockedShadowRaysTheQuestionHides) {
  const Lesson lesson = embedded("raytracing");
  const int i = step_titled(lesson, "Shadow rays");
  const LessonStep& step = lesson.steps[static_cast<std::size_t>(i)];
  ASSERT_TRUE(step.has_question());
  EXPECT_FALSE(step.view.ray_tree) << "the question does not give the answer away";
  EXPECT_TRUE(step.answer_view.ray_tree);
  HandoutOptions o = small();
  o.width = 480;
  o.height = 270;
  const auto dir = std::filesystem::temp_directory_path() / ("phonglab_handout_shadow_" + std::to_string(::getpid()));
  ASSERT_EQ(write_handout(lesson, dir.string(), o), "");
  char name[2][32];
  std::snprintf(name[0], sizeof name[0], "step-%02d.png", i + 1);
  std::snprintf(name[1], sizeof name[1], "answer-%02d.png", i + 1);
  EXPECT_NE(read_all(dir / name[0]), read_all(dir / name[1]));
  std::filesystem::remove_all(dir);

  const Image question = render_step_view(lesson, {i, false}, o);
  const Image answer = render_step_view(lesson, {i, true}, o);
  // The overlay's red (sRGB 255, 55, 45) in linear RGB: no rendered pixel of this scene is that colour.
  const auto red = [](const glm::vec3& p) { return p.x > 0.9f && p.y < 0.06f && p.z < 0.05f; };
  EXPECT_EQ(std::count_if(question.pixels.begin(), question.pixels.end(), red), 0) << "no shadow ray in the question";
  // Each blocked shadow ray is drawn red up to the occluder, where it stops (its cross).
  const Scene& s = step.prepared_scene;
  const PreparedScene prepared(s);
  const auto pixel = probe_in(s, s.camera, step.answer_view, o.width, o.height);
  ASSERT_TRUE(pixel);
  const PixelProbe probe = probe_pixel(prepared, o.width, o.height, (*pixel)[0], (*pixel)[1]);
  const auto segments = project_ray_tree(make_camera_frame(s.camera, o.width, o.height), ray_tree_segments(s, probe.root),
                                         ray_tree_near(s, probe.root));
  int blocked = 0;
  for (const ScreenSegment& seg : segments) {
    if (seg.kind != TreeSegmentKind::kShadowBlocked) continue;
    ++blocked;
    ASSERT_TRUE(seg.to_visible);
    // The occluder: the red sphere (the probe's own test says both rays meet it).
    const int x = static_cast<int>(seg.to.x), y = static_cast<int>(seg.to.y);
    int red_near_end = 0, red_beyond = 0;
    const double dx = seg.to.x - seg.from.x, dy = seg.to.y - seg.from.y, len = std::hypot(dx, dy);
    for (int oy = -2; oy <= 2; ++oy) {
      for (int ox = -2; ox <= 2; ++ox) red_near_end += red(answer.at(x + ox, y + oy)) ? 1 : 0;
    }
    // Well past the occluder along the ray: not red (the ray stops there).
    const int bx = static_cast<int>(seg.to.x + dx / len * 20), by = static_cast<int>(seg.to.y + dy / len * 20);
    if (bx >= 0 && by >= 0 && bx < answer.width && by < answer.height) red_beyond = red(answer.at(bx, by)) ? 1 : 0;
    EXPECT_GT(red_near_end, 3) << "the blocked ray is red where it meets the occluder";
    EXPECT_EQ(red_beyond, 0) << "and does not go on";
    // Half way along it too (over the L arrow it runs along).
    const int mx = static_cast<int>(seg.from.x + dx * 0.6), my = static_cast<int>(seg.from.y + dy * 0.6);
    int red_mid = 0;
    for (int oy = -1; oy <= 1; ++oy) {
      for (int ox = -1; ox <= 1; ++ox) red_mid += red(answer.at(mx + ox, my + oy)) ? 1 : 0;
    }
    EXPECT_GT(red_mid, 0) << "the blocked ray is drawn over its L arrow";
  }
  EXPECT_EQ(blocked, 2);
}

// "light_markers": false hides the lights' markers in the question; the answer shows them, at
// each point light's projected position in its colour.
TEST(Handout, LightMarkersAreHiddenByTheQuestionAndShownByTheAnswer) {
  const Lesson lesson = embedded("shading");
  const int i = step_titled(lesson, "Diffuse: kd\xC2\xB7max(0, N\xC2\xB7L)");
  const LessonStep& step = lesson.steps[static_cast<std::size_t>(i)];
  ASSERT_FALSE(step.view.light_markers);
  ASSERT_TRUE(step.answer_view.light_markers);
  HandoutOptions o = small();
  o.width = 480;
  o.height = 270;
  const Image question = render_step_view(lesson, {i, false}, o);
  const Image answer = render_step_view(lesson, {i, true}, o);
  EXPECT_NE(question.pixels, answer.pixels);
  const CameraFrame frame = make_camera_frame(step.prepared_scene.camera, o.width, o.height);
  // The marker's place: the light's projection, or for one outside the picture (the lecture's
  // main light is, up and to the right) the edge point towards it, where an arrowhead points at it.
  const double r = std::max(5.0, o.height / 77.0), inset = 2.5 * r;
  int markers = 0;
  std::vector<ImagePoint> places;
  for (const Light& light : step.prepared_scene.lights) {
    if (light.type != LightType::kPoint) continue;
    const auto at = project_point(frame, light.position);
    if (!at) continue;  // behind the eye
    ++markers;
    const ImagePoint p{std::clamp(at->x, inset, o.width - inset), std::clamp(at->y, inset, o.height - inset)};
    const double dx = at->x - p.x, dy = at->y - p.y, len = std::hypot(dx, dy);
    const double ux = len > 0 ? dx / len : 0, uy = len > 0 ? dy / len : 0;
    const int x = static_cast<int>(p.x + ux * 0.5 * r), y = static_cast<int>(p.y + uy * 0.5 * r);
    const double m = max_channel(light.intensity);
    const glm::vec3 colour(static_cast<float>(light.intensity.x / m), static_cast<float>(light.intensity.y / m),
                           static_cast<float>(light.intensity.z / m));
    EXPECT_EQ(answer.at(x, y), colour) << "the answer's marker in the light's colour at " << x << ", " << y;
    EXPECT_NE(question.at(x, y), colour) << "none in the question";
    places.push_back(p);
  }
  EXPECT_GE(markers, 1) << "the lecture's main light is in front of the eye";
  // Everywhere away from the markers (and their labels) the two images are the same.
  for (int y = 0; y < o.height; ++y) {
    for (int x = 0; x < o.width; ++x) {
      if (question.at(x, y) == answer.at(x, y)) continue;
      const bool near = std::any_of(places.begin(), places.end(), [&](const ImagePoint& p) { return std::hypot(x - p.x, y - p.y) < 8 * r; });
      ASSERT_TRUE(near) << x << ", " << y << " differs, away from every marker";
    }
  }
}

TEST(LessonFile, ErrorsNumberTheStepFromOneAndSuggestTheScene) {
  const std::string base = "{\"title\": \"t\", \"steps\": [\n";
  const std::string step = "{\"title\": \"a\", \"caption\": \"c\", \"scene\": \"lecture\"}";
  EXPECT_NE(errors_of(base + step + ",\n" + step + ",\n{\"title\": \"a\", \"caption\": \"c\", \"show\": {\"solo\": 2}}]}")
                .find("bad.json:4:49: steps[2].show.solo: (step 3) must be an integer in 0..1 (got 2)"),
            std::string::npos);
  // A misspelt file next to the lesson: the file of the nearest name in that folder.
  const auto dir = std::filesystem::temp_directory_path() / ("phonglab_lesson_scene_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir / "scenes");
  std::ofstream(dir / "scenes" / "mirrors-2.json") << "{}";
  std::ofstream(dir / "scenes" / "other.json") << "{}";
  const LessonLoad load = load_lesson_text(base + "{\"title\": \"a\", \"caption\": \"c\", \"scene\": \"scenes/mirors-2.json\"}]}",
                                           "bad.json", dir.string());
  EXPECT_NE(load.error_text().find("(step 1) the scene does not load: "), std::string::npos) << load.error_text();
  EXPECT_NE(load.error_text().find("(did you mean \"scenes/mirrors-2.json\"?)"), std::string::npos) << load.error_text();
  // A file name that is nothing like the folder's: the embedded scene its stem is nearest.
  EXPECT_NE(load_lesson_text(base + "{\"title\": \"a\", \"caption\": \"c\", \"scene\": \"scenes/lectur.json\"}]}", "bad.json",
                             dir.string())
                .error_text()
                .find("(did you mean \"lecture\"?)"),
            std::string::npos);
  std::filesystem::remove_all(dir);
}

// A step may show the indirect light ("ambient": "indirect"); a misspelt choice is named.
TEST(LessonFile, AStepShowsTheIndirectLightWithAmbientIndirect) {
  const std::string base = "{\"title\": \"t\", \"steps\": [\n{\"title\": \"a\", \"caption\": \"c\", \"scene\": \"lecture\", ";
  EXPECT_NE(errors_of(base + "\"show\": {\"ambient\": \"indirekt\"}}]}").find("(did you mean \"indirect\"?)"),
            std::string::npos);
  const LessonLoad load = load_lesson_text(base + "\"show\": {\"ambient\": \"indirect\"}}]}", "good.json");
  ASSERT_TRUE(load.lesson) << load.error_text();
  EXPECT_EQ(load.lesson->steps[0].view.ambient, Ambient::kIndirect);
}

// The shading lesson ends on what ambient stands in for: the Cornell box with ka·Ia left of the
// wipe (the previous step's image, bit for bit) and the indirect light right of it.
// The last answer's picture is indirect - ka·Ia on the signed ramp: the ceiling (lit only by the
// other surfaces) is orange, more light than ka·Ia says, on average over its pixels.
TEST(EmbeddedLessons, TheLastAnswerShowsTheCeilingAboveTheConstant) {
  const Lesson lesson = embedded("shading");
  const int last = step_titled(lesson, "The light it stands in for");  // the lecture's last, before the exercises
  const Image gap = render_step_view(lesson, LessonPlace{last, true}, small());
  double red = 0, blue = 0;
  for (int y = 0; y < kH / 10; ++y) {  // the top tenth: the ceiling
    for (int x = kW / 3; x < 2 * kW / 3; ++x) {
      const glm::vec3 p = gap.pixels[static_cast<std::size_t>(y) * kW + static_cast<std::size_t>(x)];
      red += p.x;
      blue += p.z;
    }
  }
  EXPECT_GT(red, 2 * blue) << "orange: the indirect light is above ka·Ia there";
  EXPECT_GT(red, 0);
}

TEST(EmbeddedLessons, TheLastStepWipesFromTheConstantToTheIndirectLight) {
  const Lesson lesson = embedded("shading");
  const int last = step_titled(lesson, "The light it stands in for");  // the lecture's last, before the exercises
  const StepView& view = lesson.steps[static_cast<std::size_t>(last)].view;
  ASSERT_EQ(view.ambient, Ambient::kIndirect);
  ASSERT_EQ(view.compare, CompareView::kWipe);
  ASSERT_EQ(view.compare_against, last - 1);
  // The answer: indirect - ka·Ia on the signed ramp, from one image (no A to wait for).
  ASSERT_EQ(lesson.steps[static_cast<std::size_t>(last)].answer_view.compare, CompareView::kNone);
  ASSERT_EQ(lesson.steps[static_cast<std::size_t>(last)].answer_view.ambient_shown, AmbientShown::kDifference);
  const Image constant = render_step_view(lesson, LessonPlace{last - 1, false}, small());
  const Image wiped = render_step_view(lesson, LessonPlace{last, false}, small());
  ASSERT_EQ(constant.pixels.size(), wiped.pixels.size());
  int left_same = 0, right_differs = 0, hits = 0;
  for (int y = 0; y < kH; ++y) {
    for (int x = 0; x < kW; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * kW + static_cast<std::size_t>(x);
      if (x < kW / 2 - 2) left_same += constant.pixels[i] == wiped.pixels[i] ? 1 : 0;
      if (x > kW / 2 + 2 && glm::length(constant.pixels[i]) > 0) {
        ++hits;
        right_differs += constant.pixels[i] != wiped.pixels[i] ? 1 : 0;
      }
    }
  }
  EXPECT_EQ(left_same, kH * (kW / 2 - 2));
  EXPECT_GT(right_differs, hits * 9 / 10);
}

// With a live page, each step of an embedded lesson links to it at that step (the web page's
// address #lesson=NAME&step=K); without one, no links.
TEST(Handout, EachStepLinksToTheLivePage) {
  const Lesson lesson = embedded("raytracing");
  const auto dir = std::filesystem::temp_directory_path() / ("phonglab_handout_live_" + std::to_string(::getpid()));
  HandoutOptions o = small();
  o.live_page = "phonglab.html";
  ASSERT_EQ(write_handout(lesson, (dir / "live").string(), o), "");
  const std::string html = read_all(dir / "live" / "index.html");
  for (std::size_t i = 1; i <= lesson.steps.size(); ++i) {
    EXPECT_NE(html.find("href=\"phonglab.html#lesson=raytracing&amp;step=" + std::to_string(i) + "\""), std::string::npos) << i;
  }
  ASSERT_EQ(write_handout(lesson, (dir / "plain").string(), small()), "");
  EXPECT_EQ(read_all(dir / "plain" / "index.html").find("Open this step live"), std::string::npos);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace phonglab

// A lesson file is told from a scene by a top-level "steps", read without building the document.
TEST(LessonFiles, ALessonIsToldFromASceneByItsTopLevelSteps) {
  using phonglab::is_lesson_file;
  using phonglab::looks_like_lesson;
  EXPECT_TRUE(looks_like_lesson(R"({"title": "x", "steps": []})"));
  EXPECT_TRUE(looks_like_lesson(R"({"title": {"a": [1, {"b": 2}]}, "steps": [{"title": "a"}]})"));
  EXPECT_FALSE(looks_like_lesson(R"({"camera": {"fov_y": 40}, "objects": []})"));
  EXPECT_FALSE(looks_like_lesson(R"({"materials": {"steps": {"kd": 0.5}}})")) << "a material named steps";
  EXPECT_FALSE(looks_like_lesson(R"([{"steps": []}])"));
  EXPECT_TRUE(looks_like_lesson(R"({"title": "x", "steps")")) << "found before the error: a broken lesson";
  EXPECT_FALSE(looks_like_lesson(R"({"title": "x", "step)"));
  EXPECT_FALSE(looks_like_lesson(""));
  EXPECT_FALSE(is_lesson_file("/no/such/file.json"));
}

namespace phonglab {
namespace {

TEST(LessonFile, ExerciseStepsAreReadWithTheirSlotTaskStarterAndHints) {
  const LessonLoad load = load_lesson_text(R"({"title": "t", "steps": [
    {"title": "a", "caption": "c", "scene": "lecture",
     "exercise": {"slot": "specular", "task": "write it", "starter": "R = ", "hints": ["one", "two"]}}]})",
                                           "ok.json");
  ASSERT_TRUE(load.ok()) << load.error_text();
  const LessonStep& step = load.lesson->steps.at(0);
  ASSERT_TRUE(step.exercise.has_value());
  EXPECT_EQ(step.exercise->slot, "specular");
  EXPECT_EQ(step.exercise->task, "write it");
  EXPECT_EQ(step.exercise->starter, "R = ");
  EXPECT_EQ(step.exercise->hints, (std::vector<std::string>{"one", "two"}));
  // The embedded shading lesson ends with three exercises: diffuse, specular, and "play with n".
  const LessonLoad shading = load_lesson_arg("shading");
  ASSERT_TRUE(shading.ok()) << shading.error_text();
  std::vector<std::string> slots;
  for (const LessonStep& s : shading.lesson->steps) {
    if (s.exercise) slots.push_back(s.exercise->slot + "@" + s.scene);
  }
  EXPECT_EQ(slots, (std::vector<std::string>{"diffuse@lecture", "specular@lecture", "specular@shininess"}));
}

TEST(LessonFile, ExerciseErrorsArePositioned) {
  const std::string base = "{\"title\": \"t\",\n\"steps\": [{\"title\": \"a\", \"caption\": \"c\", \"scene\": \"lecture\", ";
  const auto errors = [&](const std::string& rest) {
    const LessonLoad load = load_lesson_text(base + rest, "bad.json");
    return load.ok() ? std::string() : load.error_text();
  };
  EXPECT_NE(errors("\"exercise\": {\"slot\": \"specualr\", \"task\": \"t\"}}]}")
                .find("steps[0].exercise.slot: (step 1) unknown slot \"specualr\" (did you mean \"specular\"?)"),
            std::string::npos)
      << errors("\"exercise\": {\"slot\": \"specualr\", \"task\": \"t\"}}]}");
  EXPECT_NE(errors("\"exercise\": {\"slot\": \"diffuse\"}}]}").find("missing key \"task\""), std::string::npos);
  EXPECT_NE(errors("\"exercise\": {\"slot\": \"diffuse\", \"task\": \"t\", \"hint\": []}}]}").find("hint"), std::string::npos);
  EXPECT_NE(errors("\"question\": \"q\", \"answer\": {\"caption\": \"a\"}, \"exercise\": {\"slot\": \"diffuse\", \"task\": \"t\"}}]}")
                .find("a step is a question or an exercise, not both"),
            std::string::npos);
  EXPECT_NE(errors("\"exercise\": {\"slot\": \"diffuse\", \"task\": \"t\", \"hints\": [1]}}]}").find("steps[0].exercise.hints[0]"),
            std::string::npos);
}

}  // namespace
}  // namespace phonglab
