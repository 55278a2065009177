// The formulas' own file (src/io/formula_file.h): what is written reads back to the same texts
// (a seeded property over texts with new lines, quotes, backslashes and UTF-8), a text that does
// not compile is kept as typed, every error is positioned, a save replaces the file whole; and
// the session takes a file's texts as one undo step.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>

#include "io/formula_file.h"
#include "session/session.h"

namespace phonglab {
namespace {

TEST(FormulaFile, WhatIsWrittenReadsBackToTheSameTexts) {
  std::mt19937 rng(7);
  // Texts of whole UTF-8 characters (the panel's and the page's boxes give nothing else; other
  // bytes are written as U+FFFD, never thrown on: the next test).
  const std::vector<std::string> alphabet = {"a", "b", "R", "L", "N", "V", "(", ")", "*", "+", "-", "/", ";", "=", ".",
                                             ",", "0", "9", " ", "\n", "\t", "\"", "\\", "\xc2\xb7", "{", "}", "[", "]", ":"};
  for (int round = 0; round < 300; ++round) {
    FormulaTexts texts{};
    for (std::string& t : texts) {
      if (rng() % 3 == 0) continue;  // a slot left to the equation
      const std::size_t n = 1 + rng() % 60;
      for (std::size_t i = 0; i < n; ++i) t += alphabet[rng() % alphabet.size()];
    }
    const std::string file = formula_file_text(texts);
    const FormulaFileLoad back = load_formula_text(file, "f.json");
    ASSERT_TRUE(back.ok()) << back.error_text() << "\n" << file;
    EXPECT_EQ(*back.texts, texts) << file;
  }
}

TEST(FormulaFile, TheFileIsPlainJsonInSlotOrder) {
  const FormulaTexts texts = {"", "kd * dot(N, L)", "R = reflect(-L, N)\nks * pow(max(0, dot(R, V)), n)"};
  EXPECT_EQ(formula_file_text(texts),
            "{\n  \"diffuse\": \"kd * dot(N, L)\",\n  \"specular\": \"R = reflect(-L, N)\\nks * pow(max(0, dot(R, V)), n)\"\n}\n");
  const FormulaFileLoad replaced = load_formula_text(formula_file_text({"kd\xff", "", ""}), "f.json");
  ASSERT_TRUE(replaced.ok());
  EXPECT_EQ((*replaced.texts)[0], "kd\xef\xbf\xbd");
  const FormulaFileLoad unfinished = load_formula_text("{\"specular\": \"ks * pow(\"}", "f.json");
  ASSERT_TRUE(unfinished.ok());
  EXPECT_EQ((*unfinished.texts)[2], "ks * pow(") << "a text that does not compile is kept as typed";
}

TEST(FormulaFile, ErrorsArePositioned) {
  const auto first_error = [](const std::string& text) {
    const FormulaFileLoad r = load_formula_text(text, "mine.json");
    EXPECT_FALSE(r.ok()) << text;
    return r.errors.empty() ? std::string() : r.errors.front().to_string();
  };
  EXPECT_EQ(first_error("{\n  \"difuse\": \"kd\"\n}"), "mine.json:2:3: difuse: unknown slot (did you mean \"diffuse\"?)");
  EXPECT_EQ(first_error("{\"specular\": 3}"), "mine.json:1:14: specular: expected the formula's text as a string (got a number)");
  EXPECT_EQ(first_error("[\"kd\"]"), "mine.json:1:1: expected an object of formulas such as {\"diffuse\": \"kd * dot(N, L)\"} (got an array)");
  const std::string syntax = first_error("{\"diffuse\": \"kd\",\n}");
  EXPECT_EQ(syntax.rfind("mine.json:2:1: ", 0), 0u) << syntax;
  const FormulaFileLoad missing = load_formula_file("/nonexistent/f.json");
  EXPECT_FALSE(missing.ok());
  EXPECT_EQ(missing.errors.front().file, "/nonexistent/f.json");
}

TEST(FormulaFile, ASaveReplacesTheFileWhole) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "phonglab_formula_file_test";
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "mine.formulas.json").string();
  const FormulaTexts a = {"ka * Ia", "", ""};
  const FormulaTexts b = {"", "kd * dot(N, L)", ""};
  ASSERT_EQ(save_formula_file(path, a), "");
  ASSERT_EQ(save_formula_file(path, b), "");
  const FormulaFileLoad back = load_formula_file(path);
  ASSERT_TRUE(back.ok()) << back.error_text();
  EXPECT_EQ(*back.texts, b);
  std::size_t files = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir)) ++files;
  EXPECT_EQ(files, 1u) << "no temporary file is left beside it";
  EXPECT_NE(save_formula_file((dir / "no" / "such" / "f.json").string(), a), "");
  std::filesystem::remove_all(dir);
}

TEST(FormulaFile, TheSessionTakesAFilesTextsAsOneUndoStep) {
  Session session("");
  session.set_formula(FormulaSlot::kDiffuse, "kd * dot(N, L)");
  const std::size_t before = session.undo_count();
  const FormulaFileLoad loaded = load_formula_text("{\"ambient\": \"0.5 * Ia\", \"specular\": \"ks * pow(\"}", "f.json");
  ASSERT_TRUE(loaded.ok());
  session.set_formulas(*loaded.texts);
  EXPECT_EQ(session.undo_count(), before + 1);
  EXPECT_EQ(session.formulas().texts(), *loaded.texts);
  EXPECT_TRUE(session.formulas().slot(FormulaSlot::kSpecular).error.has_value()) << "its error is shown again";
  session.undo();
  EXPECT_EQ(session.formulas().texts()[1], "kd * dot(N, L)");
  EXPECT_EQ(session.formulas().texts()[0], "");
}

}  // namespace
}  // namespace phonglab
