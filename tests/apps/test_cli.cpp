// phonglab-cli end to end: exit codes, image formats and orientation, stats, probe (README).
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <sys/wait.h>
#include <filesystem>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <set>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "io/embedded_scenes.h"
#include "io/image_io.h"
#include "io/scene/scene_io.h"
#include "tests/support/pfm_reader.h"
#include "tests/support/run_cli.h"
#include "core/packet/packet.h"

namespace fs = std::filesystem;
using phonglab::Image;

namespace {

using phonglab::test::RunResult;
using phonglab::test::run_cli;
using phonglab::test::run_cli_stdout;

// A fresh temporary directory per test.
class CliTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("phonglab_cli_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(path(name)) << text;
    return path(name);
  }
  fs::path dir_;
};

// Lower half: a lit white floor; upper half: a red background. Camera level, looking along -z.
constexpr const char* kHalfScene = R"({
  "camera": {"position": [0, 1, 0], "look_at": [0, 1, -1], "up": [0, 1, 0], "fov_y": 90},
  "image": {"width": 8, "height": 6},
  "background": [1, 0, 0],
  "lights": [{"type": "directional", "direction": [0, -1, 0], "intensity": 1}],
  "materials": {"white": {"kd": 0.5}},
  "objects": [{"type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0], "material": "white"}]
})";

}  // namespace

TEST_F(CliTest, VersionAndHelpExitZero) {
  EXPECT_EQ(run_cli("--version").exit_code, 0);
  const RunResult help = run_cli("--help");
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_NE(help.out.find("render"), std::string::npos);
}

TEST_F(CliTest, HelpStatesEveryDefaultWithinEightyColumns) {
  const RunResult help = run_cli("--help");
  ASSERT_EQ(help.exit_code, 0);
  for (const char* words : {"default: the scene's image size",  // render, probe: --width/--height
                            "default 16, anti-aliased", "--spp 1 renders the pixel centres only",
                            "default: the scene's max_depth", "field of view (default: the scene's",
                            "full (default)", "default: none",                            // --term, --stats
                            "(default 320 x 180) at N samples per pixel (default 16)",    // figure
                            "(default: its scene's image size);\n      N: samples per pixel (default 4)",  // lesson
                            "(default bench-out/)", "default 15; 1 spp each", "(default 1280 x 720",
                            "(default 0: all hardware threads)", "default: lecture"}) {
    EXPECT_NE(help.out.find(words), std::string::npos) << words << "\n" << help.out;
  }
  std::istringstream lines(help.out);
  for (std::string line; std::getline(lines, line);) EXPECT_LE(line.size(), 80u) << line;
}

TEST_F(CliTest, RenderAndFigureDefaultToSixteenSamplesAndSpp1IsThePixelCentres) {
  ASSERT_EQ(run_cli("render lecture --width 16 --height 9 -o " + path("d.pfm") + " --stats " + path("d.json")).exit_code, 0);
  std::ifstream in(path("d.json"));
  EXPECT_EQ(nlohmann::json::parse(in)["samples_per_pixel"], 16);
  ASSERT_EQ(run_cli("render lecture --width 16 --height 9 --spp 16 -o " + path("16.pfm")).exit_code, 0);
  ASSERT_EQ(run_cli("render lecture --width 16 --height 9 --spp 1 -o " + path("1.pfm")).exit_code, 0);
  const Image by_default = phonglab::read_pfm(path("d.pfm"));
  const Image sixteen = phonglab::read_pfm(path("16.pfm"));
  const Image centres = phonglab::read_pfm(path("1.pfm"));
  ASSERT_EQ(by_default.pixels.size(), 16u * 9u);
  EXPECT_EQ(by_default.pixels, sixteen.pixels);
  EXPECT_NE(by_default.pixels, centres.pixels) << "the edges are anti-aliased";
  // --spp 1 is the pixel centres: what the probe traces.
  const RunResult probe = run_cli("probe lecture --width 16 --height 9 --json --pixel 8,5");
  ASSERT_EQ(probe.exit_code, 0) << probe.out;
  const nlohmann::json j = nlohmann::json::parse(probe.out);
  EXPECT_FLOAT_EQ(static_cast<float>(j["total"][0].get<double>()), centres.at(8, 5).x);
  // figure: the same default.
  const std::string figure = "figure lecture --width 24 --height 16 -o ";
  ASSERT_EQ(run_cli(figure + path("fd.png")).exit_code, 0);
  ASSERT_EQ(run_cli(figure + path("f16.png") + " --spp 16").exit_code, 0);
  ASSERT_EQ(run_cli(figure + path("f1.png") + " --spp 1").exit_code, 0);
  const auto bytes = [&](const std::string& name) {
    std::ifstream f(path(name), std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(f), {});
  };
  EXPECT_EQ(bytes("fd.png"), bytes("f16.png"));
  EXPECT_NE(bytes("fd.png"), bytes("f1.png"));
}

TEST_F(CliTest, MisspeltTermGetsASuggestion) {
  const RunResult typo = run_cli("render lecture -o " + path("x.pfm") + " --term specualr");
  EXPECT_EQ(typo.exit_code, 2);
  EXPECT_NE(typo.out.find("unknown --term 'specualr' (did you mean \"specular\"?)"), std::string::npos) << typo.out;
  const RunResult far = run_cli("render lecture -o " + path("x.pfm") + " --term glossy");
  EXPECT_EQ(far.exit_code, 2);
  EXPECT_NE(far.out.find("(expected one of: full, ambient, diffuse, specular, reflection, refraction, indirect, normal, depth, rays)"),
            std::string::npos)
      << far.out;
  EXPECT_FALSE(fs::exists(path("x.pfm")));
}

TEST_F(CliTest, ValidateCountsOneInTheSingular) {
  const std::string scene = write("half.json", kHalfScene);
  const RunResult r = run_cli("validate " + scene);
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find(": ok (0 spheres, 1 plane, 0 triangles, 1 light, 1 material)"), std::string::npos) << r.out;
  const RunResult lecture = run_cli("validate lecture");
  EXPECT_NE(lecture.out.find(" spheres, 1 plane, 0 triangles, 2 lights, "), std::string::npos) << lecture.out;
}

// A lesson file given to validate is checked as a lesson and said to be one (not "title: unknown
// key" as a scene); a broken lesson gives the lesson's diagnostics, exit 1.
TEST_F(CliTest, ValidateRecognisesALessonFile) {
  const std::string lesson = write("my-lesson.json", R"({
  "title": "One step",
  "steps": [{"title": "Ambient", "caption": "ka only.", "scene": "lecture", "show": {"term": "ambient"}}]
})");
  const RunResult r = run_cli("validate " + lesson);
  EXPECT_EQ(r.exit_code, 0) << r.out;
  EXPECT_NE(r.out.find(": ok, a lesson (1 step"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("unknown key"), std::string::npos) << r.out;
  const std::string broken = write("broken-lesson.json", R"({"title": "x", "steps": [{"title": "a", "scene": "nowhere"}]})");
  const RunResult bad = run_cli("validate " + broken);
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_NE(bad.out.find("is a lesson file"), std::string::npos) << bad.out;
  EXPECT_NE(bad.out.find("broken-lesson.json:"), std::string::npos) << bad.out;
}

// The man page says what --help says: every option --help names is in the man page and every
// option the man page names is in --help (bench's own options are bench --help's), and its
// probe example hits a pixel some light reaches.
TEST_F(CliTest, TheManPageNamesTheOptionsHelpNames) {
  const auto options = [](const std::string& text, const std::string& dash) {
    std::set<std::string> out;
    for (std::size_t at = text.find(dash); at != std::string::npos; at = text.find(dash, at + 1)) {
      std::size_t end = at + dash.size();
      std::string name = "--";
      while (end < text.size() && (std::isalnum(static_cast<unsigned char>(text[end])) || text[end] == '-' ||
                                   text.compare(end, 2, "\\-") == 0)) {
        if (text.compare(end, 2, "\\-") == 0) {
          name += '-';
          end += 2;
        } else {
          name += text[end++];
        }
      }
      if (name.size() > 2) out.insert(name);
    }
    return out;
  };
  std::ifstream in(std::string(PHONGLAB_SOURCE_DIR) + "/docs/man/phonglab-cli.1");
  std::stringstream man;
  man << in.rdbuf();
  std::set<std::string> in_man = options(man.str(), "\\-\\-");
  in_man.erase("--install");  // "cmake --install", where the page says how it was installed
  const std::set<std::string> in_help = options(run_cli("--help").out, "--");
  const std::set<std::string> in_bench = options(run_cli("bench --help").out, "--");
  for (const std::string& o : in_help) EXPECT_TRUE(in_man.count(o)) << o << " is in --help, not in the man page";
  for (const std::string& o : in_man) EXPECT_TRUE(in_help.count(o) || in_bench.count(o)) << o << " is in the man page, not in --help";
  EXPECT_GT(in_help.size(), 10u);
  const std::size_t example = man.str().find("phonglab-cli probe lecture \\-\\-pixel ");
  ASSERT_NE(example, std::string::npos);
  const std::string pixel = man.str().substr(example + 37, man.str().find('\n', example) - example - 37);
  const RunResult probe = run_cli("probe lecture --pixel " + pixel + " --json");
  ASSERT_EQ(probe.exit_code, 0) << probe.out;
  const nlohmann::json j = nlohmann::json::parse(probe.out);
  double lit = 0;
  for (const auto& light : j["lights"]) lit += light.value("visible", false) && light.value("n_dot_l", 0.0) > 0 ? 1 : 0;
  EXPECT_GT(lit, 0) << "the example's pixel (" << pixel << ") is lit: " << probe.out.substr(0, 400);
}

TEST_F(CliTest, BenchUsageNamesItself) {
  const RunResult help = run_cli("bench --help");
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_EQ(help.out.rfind("usage: phonglab-bench ", 0), 0u) << help.out;
  EXPECT_NE(help.out.find("default 15"), std::string::npos) << help.out;
  const RunResult bad = run_cli("bench --reshade colour lecture");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_EQ(bad.out.rfind("phonglab-bench: ", 0), 0u) << bad.out;
  EXPECT_NE(bad.out.find("(see phonglab-bench --help)"), std::string::npos) << bad.out;
  EXPECT_EQ(bad.out.find("phonglab-cli"), std::string::npos) << bad.out;
}

// PHONGLAB_SIMD chooses the packet kernels' instance ("off": the scalar renderer); a key this CPU
// cannot run is said on stderr, and the render goes on with the best instance.
TEST_F(CliTest, TheKernelsInstanceIsChosenAndABadChoiceIsSaid) {
  const auto render_with = [&](const char* simd, const std::string& stats) {
    setenv("PHONGLAB_SIMD", simd, 1);
    RunResult r = run_cli("render lecture -o " + path("k.pfm") + " --width 16 --height 8 --spp 1 --stats " + path(stats));
    unsetenv("PHONGLAB_SIMD");
    return r;
  };
  ASSERT_EQ(render_with("off", "off.json").exit_code, 0);
  std::ifstream off(path("off.json"));
  EXPECT_EQ(nlohmann::json::parse(off)["tracer"], "scalar");
  const RunResult bad = render_with("avx9", "bad.json");
  EXPECT_EQ(bad.exit_code, 0);
  EXPECT_NE(bad.out.find("PHONGLAB_SIMD=avx9: expected one of "), std::string::npos) << bad.out;
  std::ifstream bad_stats(path("bad.json"));
  EXPECT_EQ(nlohmann::json::parse(bad_stats)["tracer"], phonglab::packet_cpu_supported() ? "packet" : "scalar");
}

TEST_F(CliTest, BadUsageExitsTwo) {
  EXPECT_EQ(run_cli("").exit_code, 2);
  EXPECT_EQ(run_cli("frobnicate").exit_code, 2);
  EXPECT_EQ(run_cli("render lecture").exit_code, 2) << "missing -o";
  EXPECT_EQ(run_cli("render lecture -o x.pfm --spp zero").exit_code, 2);
  EXPECT_EQ(run_cli("render lecture -o x.pfm --term glossy").exit_code, 2);
  EXPECT_EQ(run_cli("probe lecture --pixel 5").exit_code, 2);
  EXPECT_EQ(run_cli("render lecture -o x.pfm --bogus").exit_code, 2);
}

TEST_F(CliTest, BadSceneExitsOneWithPositionedMessage) {
  const std::string scene = write("bad.json", R"({
  "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": -1, "material": "m"}],
  "materials": {"m": {}}
})");
  const RunResult r = run_cli("render " + scene + " -o " + path("out.pfm"));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.out.find("bad.json:2:"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("objects[0].radius"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(path("out.pfm")));
  EXPECT_EQ(run_cli("validate " + scene).exit_code, 1);
  EXPECT_EQ(run_cli("validate " + path("missing.json")).exit_code, 1);
}

TEST_F(CliTest, PfmRowsAreStoredBottomToTop) {
  const std::string scene = write("half.json", kHalfScene);
  ASSERT_EQ(run_cli("render " + scene + " -o " + path("half.pfm")).exit_code, 0);
  std::ifstream in(path("half.pfm"), std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string bytes = ss.str();
  ASSERT_EQ(bytes.rfind("PF\n8 6\n-1.0\n", 0), 0u) << "standard header, little-endian";
  const std::size_t header = std::string("PF\n8 6\n-1.0\n").size();
  ASSERT_EQ(bytes.size(), header + 8 * 6 * 3 * 4);
  auto value = [&](int file_row, int x, int c) {
    float f;
    std::memcpy(&f, bytes.data() + header + ((file_row * 8 + x) * 3 + c) * 4, 4);
    return f;
  };
  // First row in the file is the image's bottom row: the floor, lit at N.L = 1: kd * I = 0.5.
  EXPECT_FLOAT_EQ(value(0, 3, 0), 0.5f);
  EXPECT_FLOAT_EQ(value(0, 3, 1), 0.5f);
  // Last row in the file is the top row: the red background.
  EXPECT_FLOAT_EQ(value(5, 3, 0), 1.0f);
  EXPECT_FLOAT_EQ(value(5, 3, 1), 0.0f);
}

TEST_F(CliTest, PngIsSrgbOfClampedMean) {
  const std::string scene = write("half.json", kHalfScene);
  ASSERT_EQ(run_cli("render " + scene + " -o " + path("half.png")).exit_code, 0);
  std::ifstream in(path("half.png"), std::ios::binary);
  char sig[8] = {};
  in.read(sig, 8);
  EXPECT_EQ(std::string(sig + 1, 3), "PNG");
  EXPECT_EQ(phonglab::linear_to_srgb8(0.5), 188);  // sRGB of linear 0.5
  EXPECT_EQ(phonglab::linear_to_srgb8(7.0), 255);
  EXPECT_EQ(phonglab::linear_to_srgb8(-1.0), 0);
}

TEST_F(CliTest, WidthHeightOverridesAndStatsFile) {
  ASSERT_EQ(run_cli("render lecture -o " + path("l.pfm") + " --width 40 --height 30 --spp 2 --stats " +
                    path("stats.json"))
                .exit_code,
            0);
  std::string err;
  const Image img = phonglab::read_pfm(path("l.pfm"), &err);
  ASSERT_EQ(img.width, 40) << err;
  ASSERT_EQ(img.height, 30);
  std::ifstream in(path("stats.json"));
  const nlohmann::json j = nlohmann::json::parse(in);
  for (const char* key : {"load_ms", "build_ms", "render_ms", "samples_per_pixel", "rays", "mrays_per_s", "nan_count"}) {
    EXPECT_TRUE(j.contains(key)) << key;
  }
  EXPECT_EQ(j["samples_per_pixel"], 2);
  EXPECT_EQ(j["rays"]["primary"], 40 * 30 * 2);
  EXPECT_EQ(j["nan_count"], 0);
  // lecture's full image goes to the packet tracer wherever the CPU runs the packet kernels.
  EXPECT_EQ(j["tracer"], phonglab::packet_cpu_supported() ? "packet" : "scalar");
  ASSERT_EQ(run_cli("render lecture -o " + path("d.pfm") + " --width 8 --height 8 --term diffuse --stats " +
                    path("stats_term.json"))
                .exit_code,
            0);
  std::ifstream term_in(path("stats_term.json"));
  EXPECT_EQ(nlohmann::json::parse(term_in)["tracer"], phonglab::packet_cpu_supported() ? "packet" : "scalar");
  ASSERT_EQ(run_cli("render lecture -o " + path("n.pfm") + " --width 8 --height 8 --term normal --stats " +
                    path("stats_normal.json"))
                .exit_code,
            0);
  std::ifstream normal_in(path("stats_normal.json"));
  EXPECT_EQ(nlohmann::json::parse(normal_in)["tracer"], "scalar");  // debug views are traced ray by ray
}

TEST_F(CliTest, ProbeTotalEqualsRenderedPixel) {
  // --spp 1: the pixel centres, the rays the probe traces.
  ASSERT_EQ(run_cli("render lecture -o " + path("l.pfm") + " --width 64 --height 36 --spp 1").exit_code, 0);
  const Image img = phonglab::read_pfm(path("l.pfm"));
  ASSERT_EQ(img.width, 64);
  for (auto [x, y] : {std::pair{32, 20}, {10, 30}, {50, 5}, {40, 25}}) {
    const RunResult r = run_cli("probe lecture --width 64 --height 36 --json --pixel " + std::to_string(x) + "," +
                                std::to_string(y));
    ASSERT_EQ(r.exit_code, 0) << r.out;
    const nlohmann::json j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["pixel"][0], x);
    for (const char* key : {"hit", "total", "terms", "lights"}) EXPECT_TRUE(j.contains(key)) << key;
    for (int c = 0; c < 3; ++c) {
      EXPECT_FLOAT_EQ(static_cast<float>(j["total"][c].get<double>()), img.at(x, y)[c]) << x << "," << y;
      double sum = 0;
      for (const char* t : {"ambient", "diffuse", "specular", "reflection", "refraction"}) sum += j["terms"][t][c].get<double>();
      if (j["hit"]) {
        EXPECT_NEAR(sum, j["total"][c].get<double>(), 1e-12);
      }
    }
    if (j["hit"]) {
      for (const auto& l : j["lights"]) {
        for (const char* key : {"visible", "n_dot_l", "diffuse", "specular"}) EXPECT_TRUE(l.contains(key)) << key;
      }
    }
  }
  const RunResult text = run_cli("probe lecture --width 64 --height 36 --pixel 32,20");
  EXPECT_EQ(text.exit_code, 0);
  EXPECT_NE(text.out.find("N.L"), std::string::npos);
}

TEST_F(CliTest, TermImagesMatchTermFlag) {
  for (const char* term : {"ambient", "diffuse", "specular", "reflection", "refraction", "normal", "depth", "rays"}) {
    EXPECT_EQ(run_cli(std::string("render lecture --width 16 --height 9 --term ") + term + " -o " + path("t.pfm")).exit_code, 0)
        << term;
  }
}

TEST_F(CliTest, RaysPngIsAHeatMapScaledToTheImageMaximumWhileThePfmKeepsTheCounts) {
  const RunResult png = run_cli("render glass --width 32 --height 18 --spp 1 --term rays -o " + path("heat.png"));
  ASSERT_EQ(png.exit_code, 0) << png.out;
  EXPECT_TRUE(fs::file_size(path("heat.png")) > 0);
  double printed_max = 0;
  ASSERT_EQ(std::sscanf(png.out.c_str(), "heat map: 0 (black) .. %lf (pale yellow) rays per pixel", &printed_max), 1)
      << png.out;
  ASSERT_EQ(run_cli("render glass --width 32 --height 18 --spp 1 --term rays -o " + path("rays.pfm")).exit_code, 0);
  const Image counts = phonglab::read_pfm(path("rays.pfm"));
  ASSERT_EQ(counts.width, 32);
  float max = 0;
  for (const auto& p : counts.pixels) {
    EXPECT_EQ(p.x, std::floor(p.x)) << "whole rays at 1 spp";
    EXPECT_GE(p.x, 1.0f) << "at least the primary ray";
    max = std::max(max, p.x);
  }
  EXPECT_EQ(printed_max, static_cast<double>(max));
}

TEST_F(CliTest, ScenesListsEveryEmbeddedScene) {
  const RunResult r = run_cli("scenes");
  EXPECT_EQ(r.exit_code, 0);
  for (const char* name : {"lecture", "shininess", "lights", "mirrors", "glass"}) {
    EXPECT_NE(r.out.find(name), std::string::npos) << name;
    EXPECT_EQ(run_cli(std::string("validate ") + name).exit_code, 0) << name;
  }
}

TEST_F(CliTest, UnwritableOutputIsBadInput) {
  EXPECT_EQ(run_cli("render lecture --width 4 --height 4 -o /nonexistent-dir/x.pfm").exit_code, 1);
  EXPECT_EQ(run_cli("render lecture --width 4 --height 4 -o " + path("x.exr")).exit_code, 2) << "unknown format";
}

TEST_F(CliTest, MistypedEmbeddedSceneNameGetsASuggestion) {
  const RunResult r = run_cli("render lectur -o " + path("x.png"));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.out.find("did you mean \"lecture\"?"), std::string::npos) << r.out;
}

TEST_F(CliTest, BenchOnlyAcceptsTheAccelSectionAndNoScene) {
  EXPECT_EQ(run_cli("bench --only speed").exit_code, 2);
  EXPECT_EQ(run_cli("bench lecture --only accel").exit_code, 2);
}

TEST_F(CliTest, LessonsListsTheEmbeddedLessonsAndLessonWritesTheHandout) {
  const RunResult list = run_cli("lessons");
  EXPECT_EQ(list.exit_code, 0);
  EXPECT_NE(list.out.find("shading "), std::string::npos) << list.out;
  EXPECT_NE(list.out.find("raytracing "), std::string::npos) << list.out;
  EXPECT_EQ(run_cli("lesson shading").exit_code, 2) << "missing -o";
  EXPECT_EQ(run_cli("lesson -o " + path("h")).exit_code, 2) << "missing LESSON";
  const RunResult typo = run_cli("lesson shadin -o " + path("h"));
  EXPECT_EQ(typo.exit_code, 1);
  EXPECT_NE(typo.out.find("did you mean \"shading\"?"), std::string::npos) << typo.out;
  const std::string bad = write("bad.json", "{\"title\": \"t\",\n \"steps\": [{\"title\": 1}]}");
  const RunResult broken = run_cli("lesson " + bad + " -o " + path("h"));
  EXPECT_EQ(broken.exit_code, 1);
  EXPECT_NE(broken.out.find(bad + ":2:22: steps[0].title: (step 1) must be a string (got 1)"), std::string::npos) << broken.out;
  const RunResult ok = run_cli("lesson raytracing -o " + path("h") + " --width 64 --height 36 --spp 1");
  EXPECT_EQ(ok.exit_code, 0) << ok.out;
  EXPECT_TRUE(fs::exists(path("h/step-01.png")));
  EXPECT_TRUE(fs::exists(path("h/answer-03.png"))) << "the shadow step's question";
  EXPECT_TRUE(fs::exists(path("h/index.html")));
  EXPECT_NE(ok.out.find("index.html"), std::string::npos);
  int steps = 0;
  for (const auto& entry : fs::directory_iterator(path("h"))) {
    const std::string name = entry.path().filename().string();
    if (name.rfind("step-", 0) == 0) ++steps;
  }
  EXPECT_EQ(steps, 8) << "one step-NN.png per step of raytracing, the answers apart";
}

// --ambient indirect, --term indirect and --bounces (docs/cli.md): a floor under a red sky with
// no light but the sky: with one bounce its indirect term is kd times the sky (the floor sees
// nothing else), its full image the same (no direct light reaches it: the light is below).
TEST_F(CliTest, AmbientIndirectRendersTheLightTheAmbientTermStandsFor) {
  const std::string scene = write("sky.json", R"({
  "camera": {"position": [0, 1, 0], "look_at": [0, 1, -1], "up": [0, 1, 0], "fov_y": 90},
  "image": {"width": 8, "height": 6},
  "background": [1, 0, 0],
  "materials": {"white": {"ka": 0.1, "kd": 0.5}},
  "objects": [{"type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0], "material": "white"}]
})");
  ASSERT_EQ(run_cli("render " + scene + " -o " + path("c.pfm") + " --spp 1").exit_code, 0);
  ASSERT_EQ(run_cli("render " + scene + " -o " + path("i.pfm") + " --spp 3 --ambient indirect --bounces 1").exit_code, 0);
  ASSERT_EQ(run_cli("render " + scene + " -o " + path("t.pfm") + " --spp 2 --term indirect").exit_code, 0);
  const auto pixel = [&](const std::string& name, int x, int y) {
    const Image image = phonglab::read_pfm(path(name));
    return image.pixels[static_cast<std::size_t>(y) * 8 + x];
  };
  EXPECT_NEAR(pixel("c.pfm", 4, 5).x, 0.1, 1e-6);  // ka·Ia, bottom row (the floor)
  EXPECT_NEAR(pixel("i.pfm", 4, 5).x, 0.5, 1e-6);  // kd ⊙ sky
  EXPECT_NEAR(pixel("i.pfm", 4, 5).y, 0.0, 1e-6);
  EXPECT_NEAR(pixel("t.pfm", 4, 5).x, 0.5, 1e-6);
  EXPECT_NEAR(pixel("i.pfm", 4, 0).x, 1.0, 1e-6);  // the sky itself in the full image
  EXPECT_EQ(pixel("t.pfm", 4, 0).x, 0.0f);         // and 0 in the term image

  const RunResult bad = run_cli("render " + scene + " -o " + path("x.pfm") + " --ambient indirect --bounces 65");
  EXPECT_EQ(bad.exit_code, 2) << bad.out;
  const RunResult typo = run_cli("render " + scene + " -o " + path("x.pfm") + " --ambient indirekt");
  EXPECT_EQ(typo.exit_code, 2);
  EXPECT_NE(typo.out.find("did you mean \"indirect\""), std::string::npos) << typo.out;

  const RunResult probe = run_cli("probe " + scene + " --pixel 4,5 --json --ambient indirect --bounces 1 --spp 64");
  ASSERT_EQ(probe.exit_code, 0) << probe.out;
  const nlohmann::json j = nlohmann::json::parse(probe.out);
  EXPECT_EQ(j["indirect"]["samples"], 64);
  EXPECT_NEAR(j["indirect"]["estimate"][0].get<double>(), 0.5, 1e-9);
  EXPECT_NEAR(j["indirect"]["standard_error"][0].get<double>(), 0.0, 1e-9);
  EXPECT_NEAR(j["indirect"]["ambient"][0].get<double>(), 0.1, 1e-9);
  EXPECT_NEAR(j["indirect"]["fitted_ka"][0].get<double>(), 0.5, 1e-9);
  EXPECT_EQ(run_cli("probe " + scene + " --pixel 4,5 --spp 4").exit_code, 2);  // --spp only with indirect
}

// ----- scene --plain -----------------------------------------------------------------------------

namespace {

// The numbers of a JSON text as written (outside its strings).
std::vector<std::string> number_tokens(const std::string& text) {
  std::vector<std::string> out;
  bool in_string = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (c == '\\') {
        ++i;
      } else if (c == '"') {
        in_string = false;
      }
      continue;
    }
    if (c == '"') {
      in_string = true;
      continue;
    }
    if (c == '-' || std::isdigit(static_cast<unsigned char>(c))) {
      std::size_t j = i;
      while (j < text.size() && std::strchr("+-.eE0123456789", text[j]) != nullptr) ++j;
      out.push_back(text.substr(i, j - i));
      i = j - 1;
    }
  }
  return out;
}

// Plain decimal: an optional minus, digits, optionally a point and digits; no exponent.
bool plain_decimal(const std::string& token) {
  std::size_t i = token[0] == '-' ? 1 : 0;
  const std::size_t digits = i;
  while (i < token.size() && std::isdigit(static_cast<unsigned char>(token[i]))) ++i;
  if (i == digits) return false;
  if (i == token.size()) return true;
  if (token[i] != '.') return false;
  const std::size_t decimals = ++i;
  while (i < token.size() && std::isdigit(static_cast<unsigned char>(token[i]))) ++i;
  return i > decimals && i == token.size();
}

void expect_same_scene(const phonglab::Scene& a, const phonglab::Scene& b, const std::string& what) {
  EXPECT_TRUE(a.camera == b.camera) << what;
  EXPECT_EQ(a.width, b.width) << what;
  EXPECT_EQ(a.height, b.height) << what;
  EXPECT_EQ(a.ambient, b.ambient) << what;
  EXPECT_EQ(a.background, b.background) << what;
  EXPECT_EQ(a.max_depth, b.max_depth) << what;
  EXPECT_EQ(a.min_weight, b.min_weight) << what;
  EXPECT_EQ(a.specular_model, b.specular_model) << what;
  EXPECT_EQ(a.indirect_bounces, b.indirect_bounces) << what;
  EXPECT_TRUE(a.lights == b.lights) << what;
  EXPECT_TRUE(a.materials == b.materials) << what;
  EXPECT_TRUE(a.spheres == b.spheres) << what;
  EXPECT_TRUE(a.planes == b.planes) << what;
  EXPECT_TRUE(a.triangles == b.triangles) << what;
  ASSERT_EQ(a.meshes.size(), b.meshes.size()) << what;
  for (std::size_t i = 0; i < a.meshes.size(); ++i) {
    EXPECT_EQ(a.meshes[i].file, b.meshes[i].file) << what;
    EXPECT_EQ(a.meshes[i].material_override, b.meshes[i].material_override) << what;
    EXPECT_TRUE(a.meshes[i].transform == b.meshes[i].transform) << what;
    EXPECT_EQ(a.meshes[i].ns, b.meshes[i].ns) << what;
  }
  EXPECT_EQ(a.sphere_object, b.sphere_object) << what;
  EXPECT_EQ(a.plane_object, b.plane_object) << what;
  EXPECT_EQ(a.triangle_object, b.triangle_object) << what;
  EXPECT_EQ(a.mesh_object, b.mesh_object) << what;
  EXPECT_EQ(a.object_names, b.object_names) << what;
}

// Every key a student's reader needs is written out, colours as three numbers.
void expect_every_key(const nlohmann::json& j, const std::string& what) {
  const auto triple = [&](const nlohmann::json& v, const std::string& key) {
    EXPECT_TRUE(v.is_array() && v.size() == 3) << what << ": " << key << " is " << v.dump();
  };
  ASSERT_TRUE(j.is_object()) << what;
  for (const char* key : {"position", "look_at", "up"}) triple(j["camera"][key], std::string("camera.") + key);
  EXPECT_TRUE(j["camera"]["fov_y"].is_number()) << what;
  EXPECT_TRUE(j["image"]["width"].is_number_integer()) << what;
  EXPECT_TRUE(j["image"]["height"].is_number_integer()) << what;
  triple(j["ambient"], "ambient");
  triple(j["background"], "background");
  EXPECT_TRUE(j["max_depth"].is_number_integer()) << what;
  EXPECT_TRUE(j["min_weight"].is_number()) << what;
  EXPECT_TRUE(j["specular_model"].is_string()) << what;
  for (const auto& light : j["lights"]) {
    const bool point = light["type"] == "point";
    EXPECT_TRUE(point || light["type"] == "directional") << what << ": " << light.dump();
    triple(light[point ? "position" : "direction"], "a light's position or direction");
    triple(light["intensity"], "a light's intensity");
    EXPECT_TRUE(light["enabled"].is_boolean()) << what << ": " << light.dump();
  }
  for (const auto& [name, m] : j["materials"].items()) {
    EXPECT_EQ(m.size(), 8u) << what << ": " << name << " " << m.dump();
    for (const char* key : {"ka", "kd", "ks", "kr", "kt"}) triple(m[key], name + "." + key);
    EXPECT_TRUE(m["n"].is_number()) << what << ": " << name;
    EXPECT_TRUE(m["ior"].is_number()) << what << ": " << name;
    EXPECT_TRUE(m["fresnel"].is_boolean()) << what << ": " << name;
  }
  EXPECT_TRUE(j["objects"].is_array()) << what;
}

}  // namespace

// scene --plain for every embedded scene: JSON with every key, plain decimal numbers, and it
// reads back to the same scene (mesh objects as their OBJ files, which load again).
TEST_F(CliTest, ScenePlainWritesEveryKeyInPlainDecimalAndReadsBackForEveryEmbeddedScene) {
  for (const phonglab::EmbeddedScene& embedded : phonglab::embedded_scenes()) {
    const std::string name(embedded.name);
    const RunResult r = run_cli_stdout("scene " + name + " --plain");
    ASSERT_EQ(r.exit_code, 0) << name;
    nlohmann::json j;
    ASSERT_NO_THROW(j = nlohmann::json::parse(r.out)) << name << "\n" << r.out;
    expect_every_key(j, name);
    const std::vector<std::string> numbers = number_tokens(r.out);
    EXPECT_GT(numbers.size(), 20u) << name;
    for (const std::string& number : numbers) EXPECT_TRUE(plain_decimal(number)) << name << ": " << number;
    const phonglab::LoadResult original = phonglab::load_scene_arg(name);
    const phonglab::LoadResult again = phonglab::load_scene_text(r.out, name + ".json", ".", true);
    ASSERT_TRUE(original.ok()) << original.error_text();
    ASSERT_TRUE(again.ok()) << name << ": " << again.error_text() << "\n" << r.out;
    expect_same_scene(*original.scene, *again.scene, name);
  }
}

// Defaults are filled in, numbers that the shortest text would write with an exponent come out
// plain and read back to the same doubles; -o writes the file (and nothing to stdout).
TEST_F(CliTest, ScenePlainFillsInDefaultsAndWritesAwkwardNumbersPlain) {
  const std::string scene = write("awkward.json", R"({
  "camera": {"fov_y": 0.00001},
  "min_weight": 1e-6,
  "ambient": [0.30000000000000004, 1e22, 5e-324],
  "lights": [{"type": "directional", "direction": [0, -1, 0]}],
  "materials": {"m": {"kd": 0.5}},
  "objects": [{"type": "sphere", "name": "tiny", "center": [-1e-7, 123456789.125, 0], "radius": 2.5e-5, "material": "m"}]
})");
  const RunResult r = run_cli_stdout("scene " + scene + " --plain");
  ASSERT_EQ(r.exit_code, 0) << r.out;
  for (const char* text : {"\"fov_y\": 0.00001", "\"min_weight\": 0.000001", "0.30000000000000004",
                           "10000000000000000000000", "\"radius\": 0.000025", "-0.0000001", "123456789.125",
                           "\"width\": 960", "\"height\": 540", "\"max_depth\": 5", "\"specular_model\": \"phong\"",
                           "\"background\": [0, 0, 0]", "\"intensity\": [1, 1, 1]", "\"enabled\": true", "\"n\": 32",
                           "\"ior\": 1.5", "\"fresnel\": false", "\"kr\": [0, 0, 0]", "\"name\": \"tiny\""}) {
    EXPECT_NE(r.out.find(text), std::string::npos) << text << "\n" << r.out;
  }
  for (const std::string& number : number_tokens(r.out)) EXPECT_TRUE(plain_decimal(number)) << number;
  const phonglab::LoadResult original = phonglab::load_scene_file(scene);
  const phonglab::LoadResult again = phonglab::load_scene_text(r.out, "plain.json");
  ASSERT_TRUE(original.ok()) << original.error_text();
  ASSERT_TRUE(again.ok()) << again.error_text() << "\n" << r.out;
  expect_same_scene(*original.scene, *again.scene, "awkward.json");
  EXPECT_EQ(again.scene->ambient.z, 5e-324);

  // -o: the same text in the file, nothing printed.
  const RunResult to_file = run_cli("scene " + scene + " --plain -o " + path("full.json"));
  EXPECT_EQ(to_file.exit_code, 0) << to_file.out;
  EXPECT_TRUE(to_file.out.empty()) << to_file.out;
  std::ifstream in(path("full.json"));
  const std::string written((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(written, r.out);
  // Without --plain: the scene file's shortest numbers, the same scene.
  const RunResult shortest = run_cli_stdout("scene " + scene);
  ASSERT_EQ(shortest.exit_code, 0);
  EXPECT_NE(shortest.out.find("\"min_weight\": 1e-06"), std::string::npos) << shortest.out;
  EXPECT_EQ(shortest.out, phonglab::scene_to_json(*original.scene));
}

TEST_F(CliTest, SceneReportsBadScenesAndBadUsage) {
  const RunResult missing = run_cli("scene " + path("missing.json") + " --plain");
  EXPECT_EQ(missing.exit_code, 1);
  EXPECT_NE(missing.out.find("missing.json"), std::string::npos) << missing.out;
  EXPECT_EQ(run_cli("scene lecture --plain --bogus").exit_code, 2);
  EXPECT_EQ(run_cli("scene lecture glass --plain").exit_code, 2);
  EXPECT_EQ(run_cli("scene lecture --plain -o /nonexistent-dir/x.json").exit_code, 1);
  EXPECT_NE(run_cli("--help").out.find("scene [SCENE] [--plain] [-o OUT.json]"), std::string::npos);
}
