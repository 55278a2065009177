// The teaching instruments (issue 4): the probe reproduces the rendered pixel, the term images
// add up to the full image, the slide figure is deterministic, undo/redo and solo restore what
// they should.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>
#include <regex>
#include <sstream>
#include <string>
#include <utility>

#include <gtest/gtest.h>

#include "io/embedded_scenes.h"
#include "core/scene/camera.h"
#include "io/figure.h"
#include "io/probe_report.h"
#include "core/render/render.h"
#include "io/scene/scene_io.h"
#include "tests/support/test_support.h"
#include "interaction/history.h"

namespace phonglab {
namespace {

constexpr int kWidth = 64;   // small images: every embedded scene, many pixels, still quick
constexpr int kHeight = 36;

Accumulator render_once(const PreparedScene& scene, Term term) {
  RenderOptions options;
  options.term = term;
  Accumulator accum;
  accum.reset(kWidth, kHeight);
  render_pass(scene, options, accum);
  return accum;
}

std::string read_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

TEST(PixelProbe, TotalEqualsTheRenderedLinearPixelInEveryEmbeddedScene) {
  for (const EmbeddedScene& embedded : embedded_scenes()) {
    const PreparedScene scene = load_prepared(embedded.name);
    const Accumulator image = render_once(scene, Term::kFull);
    for (int y = 0; y < kHeight; ++y) {
      for (int x = 0; x < kWidth; ++x) {
        const PixelProbe probe = probe_pixel(scene, kWidth, kHeight, x, y);
        const Color pixel = image.mean(x, y);
        ASSERT_EQ(probe.root.total, pixel) << embedded.name << " pixel " << x << "," << y;
      }
    }
  }
}

TEST(PixelProbe, TextWithFourDigitsHasNoLongerNumberAndTheCliDefaultIsUnchanged) {
  const PreparedScene prepared = load_prepared("lecture");
  const Scene& scene = prepared.scene();
  const PixelProbe probe = probe_pixel(prepared, 320, 180, 200, 120);
  const std::string four = probe_to_text(scene, probe, 4);
  // No number in the text carries more than four significant digits ("0.1234", "1.235e-07").
  const std::regex long_number("[0-9]\\.?[0-9]{4,}");
  std::smatch m;
  std::string rest = four;
  while (std::regex_search(rest, m, long_number)) {
    std::string digits;
    for (const char c : m.str()) {
      if (c != '.') digits += c;
    }
    digits.erase(0, digits.find_first_not_of('0'));
    EXPECT_LE(digits.size(), 4u) << m.str() << " in\n" << four;
    rest = m.suffix();
  }
  // phonglab-cli probe keeps its nine (and six) digits: more digits than the four-digit text.
  EXPECT_GT(probe_to_text(scene, probe).size(), four.size());
  EXPECT_EQ(probe_to_text(scene, probe), probe_to_text(scene, probe, 0));
}

TEST(PixelProbe, TermsAndLightsAddUpToTheTotal) {
  const PreparedScene scene = load_prepared("lights");
  const PixelProbe probe = probe_pixel(scene, kWidth, kHeight, kWidth / 2, kHeight / 2);
  ASSERT_TRUE(probe.root.hit);
  Color diffuse(0), specular(0);
  for (const ProbeLight& light : probe.root.lights) {
    diffuse += light.diffuse;
    specular += light.specular;
  }
  EXPECT_NEAR(glm::length(diffuse - probe.root.terms.diffuse), 0, 1e-12);
  EXPECT_NEAR(glm::length(specular - probe.root.terms.specular), 0, 1e-12);
  EXPECT_EQ(probe.root.terms.sum(), probe.root.total);
}

TEST(TermViews, FiveTermImagesAddUpToTheFullImageInEveryEmbeddedScene) {
  for (const EmbeddedScene& embedded : embedded_scenes()) {
    const PreparedScene scene = load_prepared(embedded.name);
    const Accumulator full = render_once(scene, Term::kFull);
    Accumulator sum;
    sum.reset(kWidth, kHeight);
    for (const Term term : {Term::kAmbient, Term::kDiffuse, Term::kSpecular, Term::kReflection, Term::kRefraction}) {
      const Accumulator part = render_once(scene, term);
      for (std::size_t i = 0; i < sum.sum.size(); ++i) sum.sum[i] += part.sum[i];
    }
    for (int y = 0; y < kHeight; ++y) {
      for (int x = 0; x < kWidth; ++x) {
        const std::size_t i = static_cast<std::size_t>(y) * kWidth + static_cast<std::size_t>(x);
        const PixelProbe probe = probe_pixel(scene, kWidth, kHeight, x, y);
        if (!probe.root.hit) continue;  // term images are 0 on a miss, the full image is the background
        EXPECT_NEAR(glm::length(sum.sum[i] - full.sum[i]), 0, 1e-12) << embedded.name << " pixel " << x << "," << y;
      }
    }
  }
}

TEST(TermViews, MutingALightRemovesItsDiffuseAndSoloKeepsOnlyIt) {
  Scene scene = load_scene_or_fail("lights");
  ASSERT_GE(scene.lights.size(), 2u);
  ui::LightSolo solo;
  ui::toggle_solo(scene.lights, solo, 1);
  const PixelProbe probe = probe_pixel(PreparedScene(scene), kWidth, kHeight, kWidth / 2, kHeight / 2);
  for (const ProbeLight& light : probe.root.lights) EXPECT_EQ(light.index, 1) << "only the soloed light shades";
}

TEST(Figure, IsDeterministicAndHasTheGridSize) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "phonglab_test_figure";
  std::filesystem::create_directories(dir);
  const std::string a = (dir / "a.png").string();
  const std::string b = (dir / "b.png").string();
  const std::string cli = PHONGLAB_CLI;
  ASSERT_EQ(std::system((cli + " figure lecture -o " + a + " --width 96 --height 54 --threads 1").c_str()), 0);
  ASSERT_EQ(std::system((cli + " figure lecture -o " + b + " --width 96 --height 54 --threads 3").c_str()), 0);
  const std::string bytes_a = read_bytes(a);
  ASSERT_GT(bytes_a.size(), 24u);
  EXPECT_EQ(bytes_a, read_bytes(b)) << "two runs (and thread counts) give the same bytes";
  // PNG IHDR: big-endian width and height at offsets 16 and 20.
  const auto be32 = [&](std::size_t at) {
    return (static_cast<unsigned>(static_cast<unsigned char>(bytes_a[at])) << 24) |
           (static_cast<unsigned>(static_cast<unsigned char>(bytes_a[at + 1])) << 16) |
           (static_cast<unsigned>(static_cast<unsigned char>(bytes_a[at + 2])) << 8) |
           static_cast<unsigned>(static_cast<unsigned char>(bytes_a[at + 3]));
  };
  const auto gutter = static_cast<unsigned>(figure_gutter());
  EXPECT_EQ(be32(16), 3u * 96u + 2u * gutter);
  EXPECT_EQ(be32(20), 2u * (54u + static_cast<unsigned>(figure_label_height())) + gutter);
  std::filesystem::remove_all(dir);
}

TEST(Figure, CellsAreTheTermImagesAndLabelsAreDrawn) {
  const PreparedScene scene = load_prepared("lecture");
  FigureOptions options;
  options.cell_width = kWidth;
  options.cell_height = kHeight;
  const Image figure = make_figure(scene, options);
  const int row_h = kHeight + figure_label_height();
  const int gutter = figure_gutter();
  ASSERT_GE(gutter, 2);
  const glm::vec3 background = figure.at(0, kHeight);  // the label strip's
  for (std::size_t cell = 0; cell < kFigureTerms.size(); ++cell) {
    const Accumulator term = render_once(scene, kFigureTerms[cell]);
    const int x0 = static_cast<int>(cell % 3) * (kWidth + gutter);
    const int y0 = static_cast<int>(cell / 3) * (row_h + gutter);
    // The gutters: background between the cells, across and down.
    if (cell % 3 < 2) {
      for (int y = y0; y < y0 + kHeight; ++y) ASSERT_EQ(figure.at(x0 + kWidth, y), background) << "cell " << cell;
    }
    if (cell < 3) {
      for (int x = x0; x < x0 + kWidth; ++x) ASSERT_EQ(figure.at(x, y0 + row_h), background) << "cell " << cell;
    }
    for (int y = 0; y < kHeight; y += 5) {
      for (int x = 0; x < kWidth; x += 5) {
        ASSERT_EQ(figure.at(x0 + x, y0 + y), glm::vec3(term.mean(x, y))) << "cell " << cell;
      }
    }
    int lit = 0;  // label pixels in the strip under the cell
    for (int y = y0 + kHeight; y < y0 + row_h; ++y) {
      for (int x = x0; x < x0 + kWidth; ++x) lit += figure.at(x, y).x > 0.5f ? 1 : 0;
    }
    EXPECT_GT(lit, 20) << "cell " << cell << " has a label";
  }
}

TEST(Figure, OneLabelSizeAndTheSymbolsSpelledOut) {
  // The large font only where every label fits a cell; else every label is small.
  EXPECT_EQ(figure_label_scale(480), 2);
  EXPECT_EQ(figure_label_scale(160), 1);
  for (const Term t : kFigureTerms) {
    EXPECT_LE(label_width(figure_label(t), 2), 480 - 8) << figure_label(t);
  }
  EXPECT_EQ(figure_label(Term::kAmbient), "ambient ka*I_a");
  EXPECT_NE(figure_label(Term::kDiffuse).find("sum_l vis*I_l*kd"), std::string_view::npos);
  EXPECT_NE(figure_label(Term::kSpecular).find("sum_l vis*I_l*ks"), std::string_view::npos);
  // A small label is broken into lines that fit the cell.
  const auto lines = wrap_text(figure_label(Term::kSpecular), 1, 160 - 8);
  EXPECT_EQ(lines.size(), 2U);
  for (const auto& l : lines) EXPECT_LE(label_width(l, 1), 160 - 8) << l;
}

TEST(Figure, BadUsageExitsTwo) {
  const std::string cli = PHONGLAB_CLI;
  EXPECT_NE(std::system((cli + " figure lecture >/dev/null 2>&1").c_str()), 0) << "missing -o";
}

TEST(UndoHistory, UndoAndRedoWalkTheCommittedStatesAndKeepTheCamera) {
  ui::SceneHistory history;
  Scene scene;
  scene.materials.push_back(Material{});
  history.reset(scene);
  EXPECT_FALSE(history.undo(scene));
  scene.materials[0].kd = Color(0.5);
  history.commit(scene);
  scene.materials[0].kd = Color(0.25);
  history.commit(scene);
  scene.camera.position = Vec3(1, 2, 3);  // navigation between edits
  std::optional<Scene> back = history.undo(scene);
  ASSERT_TRUE(back);
  EXPECT_EQ(back->materials[0].kd, Color(0.5));
  EXPECT_EQ(back->camera.position, Vec3(1, 2, 3));
  back = history.undo(*back);
  ASSERT_TRUE(back);
  EXPECT_EQ(back->materials[0].kd, Color(0));
  EXPECT_FALSE(history.undo(*back));
  std::optional<Scene> forward = history.redo(*back);
  ASSERT_TRUE(forward);
  EXPECT_EQ(forward->materials[0].kd, Color(0.5));
  forward->materials[0].kd = Color(1);
  history.commit(*forward);
  EXPECT_EQ(history.redo_count(), 0u) << "a new edit drops the redo states";
}

TEST(UndoHistory, KeepsAtMostAHundredStates) {
  ui::SceneHistory history;
  Scene scene;
  history.reset(scene);
  for (int i = 0; i < 250; ++i) {
    scene.max_depth = i;
    history.commit(scene);
  }
  EXPECT_EQ(history.undo_count(), ui::SceneHistory::kMaxStates);
}

TEST(LightSolo, SoloThenUnsoloRestoresEveryFlag) {
  std::vector<Light> lights(3);
  lights[2].enabled = false;
  ui::LightSolo solo;
  ui::toggle_solo(lights, solo, 0);
  EXPECT_TRUE(lights[0].enabled);
  EXPECT_FALSE(lights[1].enabled);
  ui::toggle_solo(lights, solo, 1);  // moving the solo keeps the original flags
  EXPECT_FALSE(lights[0].enabled);
  EXPECT_TRUE(lights[1].enabled);
  ui::toggle_solo(lights, solo, 1);
  EXPECT_TRUE(lights[0].enabled);
  EXPECT_TRUE(lights[1].enabled);
  EXPECT_FALSE(lights[2].enabled);
  EXPECT_EQ(solo.soloed, -1);
}

// "Move your head": the eye used for V at the primary hit, rotated `degrees` about the camera's
// up axis around the look-at point (the view rays stay the camera's).
Vec3 moved_eye(const Camera& camera, double degrees) {
  const Vec3 up = glm::normalize(camera.up);
  const Vec3 d = camera.position - camera.look_at;
  const double a = degrees * 3.14159265358979323846 / 180;
  // Rodrigues' rotation of d about `up`.
  const Vec3 rotated = d * std::cos(a) + glm::cross(up, d) * std::sin(a) + up * glm::dot(up, d) * (1 - std::cos(a));
  return camera.look_at + rotated;
}

Accumulator render_with_eye(const PreparedScene& scene, Term term, const std::optional<Vec3>& eye) {
  RenderOptions options;
  options.term = term;
  options.shading_eye = eye;
  Accumulator accum;
  accum.reset(kWidth, kHeight);
  render_pass(scene, options, accum);
  return accum;
}

TEST(MoveYourHead, EyeOnlyMovesKeepDiffuseExactlyAndChangeSpecular) {
  for (const SpecularModel model : {SpecularModel::kPhong, SpecularModel::kBlinn}) {
    Scene data = load_scene_or_fail("lecture");
    data.specular_model = model;
    const Vec3 eye = moved_eye(data.camera, 35);
    const PreparedScene scene(std::move(data));
    for (const Term term : {Term::kAmbient, Term::kDiffuse}) {
      const Accumulator still = render_with_eye(scene, term, std::nullopt);
      const Accumulator moved = render_with_eye(scene, term, eye);
      ASSERT_EQ(still.sum, moved.sum) << term_name(term);
    }
    const Accumulator still = render_with_eye(scene, Term::kSpecular, std::nullopt);
    const Accumulator moved = render_with_eye(scene, Term::kSpecular, eye);
    int changed = 0;
    for (std::size_t i = 0; i < still.sum.size(); ++i) changed += still.sum[i] != moved.sum[i] ? 1 : 0;
    EXPECT_GT(changed, 20) << "specular pixels changed by the head move";
    // The probe sees the same moved eye: its total is the rendered pixel.
    const Accumulator full = render_with_eye(scene, Term::kFull, eye);
    for (int y = 0; y < kHeight; y += 5) {
      for (int x = 0; x < kWidth; x += 7) {
        const PixelProbe probe = probe_pixel(scene, kWidth, kHeight, x, y, eye);
        ASSERT_EQ(probe.root.total, full.mean(x, y)) << x << "," << y;
      }
    }
  }
}

TEST(MoveYourHead, NoOverrideIsBitIdenticalToThePlainRender) {
  for (const EmbeddedScene& embedded : embedded_scenes()) {
    const PreparedScene scene = load_prepared(embedded.name);
    for (const Term term : {Term::kFull, Term::kSpecular, Term::kReflection, Term::kRays}) {
      const Accumulator plain = render_once(scene, term);
      const Accumulator defaulted = render_with_eye(scene, term, std::nullopt);
      ASSERT_EQ(plain.sum, defaulted.sum) << embedded.name << " " << term_name(term);
      // Each pixel is render_sample's value without an eye.
      const CameraFrame frame = make_camera_frame(scene.scene().camera, kWidth, kHeight);
      RayCounts counts;
      for (int y = 0; y < kHeight; y += 3) {
        for (int x = 0; x < kWidth; x += 3) {
          ASSERT_EQ(render_sample(scene, frame, term, x, y, 0, counts), plain.mean(x, y))
              << embedded.name << " " << x << "," << y;
        }
      }
    }
    // The eye at the camera's own position gives -D up to rounding: the same image, nearly.
    const Accumulator plain = render_once(scene, Term::kFull);
    const Accumulator at_camera = render_with_eye(scene, Term::kFull, scene.scene().camera.position);
    for (std::size_t i = 0; i < plain.sum.size(); ++i) {
      ASSERT_NEAR(plain.sum[i].x, at_camera.sum[i].x, 1e-6) << embedded.name << " " << i;
    }
  }
}

}  // namespace
}  // namespace phonglab
