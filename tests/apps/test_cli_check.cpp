// phonglab-cli check and render --formula end to end (docs/checking.md): the verdict's lines,
// --json's keys, the exit codes (0 match, 3 differs, 1 bad input, 2 bad usage), each formula
// mistake named as a student would type it, a student's image with its format's errors.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <nlohmann/json.hpp>

#include "tests/support/run_cli.h"

namespace fs = std::filesystem;

namespace {

using Ran = phonglab::test::RunResult;
Ran cli(const std::string& args) { return phonglab::test::run_cli(args); }

std::string first_line(const std::string& s) { return s.substr(0, s.find('\n')); }

std::string temp_dir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("phonglab_cli_check_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir.string();
}

// A small view of the lecture: every formula check below renders it twice.
const std::string kSmall = " --width 160 --height 90";

TEST(CliCheck, TheReferenceFormulasMatchOnEveryEmbeddedScene) {
  const char* formulas[] = {"ambient=ka * Ia", "diffuse=kd * dot(N, L)",
                            "specular=R = reflect(-L, N); ks * pow(max(0, dot(R, V)), n)"};
  for (const char* scene : {"lecture", "shininess", "lights", "mirrors", "glass"}) {
    std::string args = std::string("check ") + scene + kSmall;
    for (const char* f : formulas) args += std::string(" --formula '") + f + "'";
    const Ran r = cli(args);
    EXPECT_EQ(r.exit_code, 0) << scene << ": " << r.out;
    EXPECT_EQ(first_line(r.out), "match") << scene;
    EXPECT_NE(r.out.find("\nnan 0\n"), std::string::npos) << r.out;
  }
}

TEST(CliCheck, EachFormulaMistakeIsNamed) {
  const struct {
    const char* formula;
    const char* named;
  } cases[] = {
      {"R = reflect(-L, N); ks * pow(dot(R, V), n)", "specular-unclamped"},
      {"R = reflect(L, N); ks * pow(max(0, dot(R, V)), n)", "reflect-sign or view-reversed"},
      {"H = normalize(L + V); ks * pow(max(0, dot(N, H)), n)", "blinn-for-phong"},
      {"R = reflect(-L, N); ks * pow(max(0, dot(R, -V)), n)", "reflect-sign or view-reversed"},
      {"R = reflect(-L, N); pow(ks * max(0, dot(R, V)), n)", "exponent-outside"},
  };
  for (const auto& c : cases) {
    const Ran r = cli("check lecture" + kSmall + " --formula 'specular=" + c.formula + "'");
    EXPECT_EQ(r.exit_code, 3) << c.formula << ": " << r.out;
    EXPECT_EQ(first_line(r.out), "differs");
    EXPECT_NE(r.out.find(std::string("nearest mistake: ") + c.named + " (explains 100 % of the differing pixels)"),
              std::string::npos)
        << c.formula << ":\n" << r.out;
  }
  // A mistake the catalogue does not hold: none, and the exit status still says it differs.
  const Ran none = cli("check lecture" + kSmall + " --formula 'diffuse=kd * dot(N, L) * 0.5'");
  EXPECT_EQ(none.exit_code, 3);
  EXPECT_NE(none.out.find("nearest mistake: none"), std::string::npos) << none.out;
}

TEST(CliCheck, JsonHasTheContractsKeys) {
  const Ran r = cli("check lecture" + kSmall + " --json --formula 'specular=R = reflect(-L, N); ks * pow(dot(R, V), n)'");
  ASSERT_EQ(r.exit_code, 3) << r.out;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  for (const char* key : {"verdict", "pixels", "differing", "max_difference", "worst_pixel", "nan", "mistake", "explained"}) {
    EXPECT_TRUE(j.contains(key)) << key;
  }
  EXPECT_EQ(j["verdict"], "differs");
  EXPECT_EQ(j["pixels"], 160 * 90);
  EXPECT_EQ(j["mistake"], "specular-unclamped");
  EXPECT_EQ(j["explained"], 100.0);
  EXPECT_GT(j["differing"].get<int>(), 0);
}

TEST(CliCheck, ANanIsTheStudentsAndCounted) {
  // A fractional n and no clamp: a negative base to the power n is NaN.
  const Ran r = cli("check shininess" + kSmall + " --formula 'specular=R = reflect(-L, N); ks * pow(dot(R, V), n + 0.5)'");
  EXPECT_EQ(r.exit_code, 3) << r.out;
  const std::size_t at = r.out.find("\nnan ");
  ASSERT_NE(at, std::string::npos) << r.out;
  EXPECT_GT(std::stoi(r.out.substr(at + 5)), 0) << r.out;
}

TEST(CliCheck, FormulaErrorsAndUsage) {
  const Ran unknown = cli("check lecture" + kSmall + " --formula 'diffuse=kd * max(0, dot(normalize(P), nrm))'");
  EXPECT_EQ(unknown.exit_code, 1);
  EXPECT_NE(unknown.out.find("formula:1:31: unknown name \"nrm\" (did you mean \"N\"?)"), std::string::npos) << unknown.out;
  const Ran types = cli("check lecture" + kSmall + " --formula 'diffuse=kd * dot(n, L)'");
  EXPECT_EQ(types.exit_code, 1);
  EXPECT_NE(types.out.find("formula:1:6: dot() takes two vectors (got a number)"), std::string::npos) << types.out;
  const std::string dir = temp_dir("file");
  std::ofstream(dir + "/mine.txt") << "R = reflect(-L, N)\nks * pow(max(0, dot(R, V), n)\n";
  const Ran file = cli("check lecture" + kSmall + " --formula specular=@" + dir + "/mine.txt");
  EXPECT_EQ(file.exit_code, 1);
  EXPECT_EQ(file.out.rfind(dir + "/mine.txt:2:", 0), 0U) << file.out;  // the file named, line 2
  EXPECT_EQ(cli("check lecture --formula 'specualr=ks'").exit_code, 2);
  EXPECT_EQ(cli("check lecture").exit_code, 2);  // neither an image nor a formula
  EXPECT_EQ(cli("check lecture --formula specular=@/nonexistent/f.txt").exit_code, 1);
}

// A formula file the Formula panel saved: checked as --formula's; its problems positioned; a
// --formula after it replaces a slot.
TEST(CliCheck, AFormulaFile) {
  const std::string dir = temp_dir("formulas");
  std::ofstream(dir + "/mine.formulas.json")
      << "{\n  \"diffuse\": \"kd * dot(N, L)\",\n  \"specular\": \"R = reflect(L, N)\\nks * pow(max(0, dot(R, V)), n)\"\n}\n";
  const Ran wrong = cli("check lecture" + kSmall + " --formulas " + dir + "/mine.formulas.json");
  EXPECT_EQ(wrong.exit_code, 3) << wrong.out;
  EXPECT_NE(wrong.out.find("nearest mistake: reflect-sign or view-reversed"), std::string::npos) << wrong.out;
  const Ran fixed = cli("check lecture" + kSmall + " --formulas " + dir +
                        "/mine.formulas.json --formula 'specular=R = reflect(-L, N); ks * pow(max(0, dot(R, V)), n)'");
  EXPECT_EQ(fixed.exit_code, 0) << fixed.out;
  std::ofstream(dir + "/bad.json") << "{\n  \"difuse\": \"kd\"\n}\n";
  const Ran bad = cli("check lecture --formulas " + dir + "/bad.json");
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_EQ(first_line(bad.out), dir + "/bad.json:2:3: difuse: unknown slot (did you mean \"diffuse\"?)") << bad.out;
  std::ofstream(dir + "/typo.json") << "{\"specular\": \"ks * pow(\"}";
  const Ran typo = cli("check lecture --formulas " + dir + "/typo.json");
  EXPECT_EQ(typo.exit_code, 1);
  EXPECT_EQ(typo.out.rfind(dir + "/typo.json: specular: formula:1:10: ", 0), 0U) << typo.out;
}

TEST(CliCheck, RenderWithTheReferenceFormulasIsTheRendersImage) {
  const std::string dir = temp_dir("render");
  ASSERT_EQ(cli("render lecture" + kSmall + " --spp 1 -o " + dir + "/ref.png").exit_code, 0);
  const Ran r = cli("render lecture" + kSmall + " --spp 1 -o " + dir + "/mine.png --formula 'diffuse=kd * dot(N, L)' "
                    "--formula 'specular=R = reflect(-L, N); ks * pow(max(0, dot(R, V)), n)'");
  ASSERT_EQ(r.exit_code, 0) << r.out;
  // The formulas' 8-bit image checked as a student's: the reference's, at the image's size.
  const Ran c = cli("check lecture " + dir + "/mine.png");
  EXPECT_EQ(c.exit_code, 0) << c.out;
  EXPECT_EQ(first_line(c.out), "match");
  std::ifstream a(dir + "/ref.png", std::ios::binary), b(dir + "/mine.png", std::ios::binary);
  const std::string ref((std::istreambuf_iterator<char>(a)), {}), mine((std::istreambuf_iterator<char>(b)), {});
  EXPECT_EQ(ref, mine);  // the same bytes: the formulas differ from the built-in terms only in the last bits
}

}  // namespace
