// The student's formulas in a session (session/formula_book.h, Session::set_formula): the last
// good formula kept while a text has an error, undo interleaved with the scene's edits, and a
// lesson's exercise steps entered and left (Session::sync_exercise).
#include <gtest/gtest.h>

#include <string>

#include "io/lesson_io.h"
#include "session/session.h"

namespace phonglab {
namespace {

constexpr const char* kWrong = "R = reflect(L, N); ks * pow(max(0, dot(R, V)), n)";
constexpr const char* kRight = "R = reflect(-L, N); ks * pow(max(0, dot(R, V)), n)";

TEST(FormulaBook, AnErrorKeepsTheLastGoodFormulaRendering) {
  FormulaBook book;
  EXPECT_FALSE(book.any());
  EXPECT_TRUE(book.set(FormulaSlot::kSpecular, kWrong));
  const std::uint64_t version = book.version();
  ASSERT_TRUE(book.any());
  EXPECT_FALSE(book.set(FormulaSlot::kSpecular, "R = reflect(L, N) ks"));  // typing on: an error
  const FormulaBook::Slot& slot = book.slot(FormulaSlot::kSpecular);
  ASSERT_TRUE(slot.error.has_value());
  EXPECT_EQ(slot.error->text().rfind("formula:1:19: ", 0), 0U) << slot.error->text();
  ASSERT_NE(slot.formula, nullptr);
  EXPECT_EQ(slot.formula->text(), kWrong);  // still what renders
  EXPECT_EQ(book.version(), version);       // so nothing is re-rendered
  EXPECT_TRUE(book.set(FormulaSlot::kSpecular, "  # blank: the equation's own term\n"));
  EXPECT_FALSE(book.any());
  EXPECT_FALSE(book.slot(FormulaSlot::kSpecular).error.has_value());
}

TEST(SessionFormulas, UndoAndRedoInterleaveWithSceneEdits) {
  Session session("");
  ASSERT_TRUE(session.open("lecture"));
  session.set_formula(FormulaSlot::kSpecular, kWrong);
  Material m = session.scene().materials.at(0);
  const Color kd_before = m.kd;
  m.kd = Color(0.5);
  session.apply({edit::SetMaterial{0, m}});
  session.set_formula(FormulaSlot::kSpecular, kRight, true);  // typed, the box still active
  session.settle(false);                                    // the gesture ends: one step
  EXPECT_EQ(session.undo_count(), 3U);
  ASSERT_TRUE(session.undo());  // the formula's second text
  EXPECT_EQ(session.formulas().slot(FormulaSlot::kSpecular).text, kWrong);
  EXPECT_EQ(session.scene().materials.at(0).kd, Color(0.5));
  ASSERT_TRUE(session.undo());  // the scene's edit
  EXPECT_EQ(session.scene().materials.at(0).kd, kd_before);
  EXPECT_EQ(session.formulas().slot(FormulaSlot::kSpecular).text, kWrong);
  ASSERT_TRUE(session.undo());  // the first formula
  EXPECT_FALSE(session.formulas().any());
  EXPECT_FALSE(session.undo());
  ASSERT_TRUE(session.redo());
  EXPECT_EQ(session.formulas().slot(FormulaSlot::kSpecular).text, kWrong);
  ASSERT_TRUE(session.redo());
  EXPECT_EQ(session.scene().materials.at(0).kd, Color(0.5));
  ASSERT_TRUE(session.redo());
  EXPECT_EQ(session.formulas().slot(FormulaSlot::kSpecular).text, kRight);
  EXPECT_FALSE(session.redo());
}

TEST(SessionFormulas, FormulasStayWithANewSceneAndAreNoUnsavedChange) {
  Session session("");
  ASSERT_TRUE(session.open("lecture"));
  session.set_formula(FormulaSlot::kDiffuse, "kd * dot(N, L)");
  EXPECT_FALSE(session.dirty());  // formulas are not the scene's: saving it does not hold them
  ASSERT_TRUE(session.open("shininess"));
  EXPECT_TRUE(session.formulas().any());
  ASSERT_TRUE(session.undo());
  EXPECT_FALSE(session.formulas().any());
}

TEST(SessionFormulas, AnExerciseStepGivesItsStarterAndLeavingItClearsTheFormulas) {
  Session session("");
  LessonLoad load = load_lesson_arg("shading");
  ASSERT_TRUE(load.ok()) << load.error_text();
  int first_exercise = -1;
  for (std::size_t i = 0; i < load.lesson->steps.size(); ++i) {
    if (load.lesson->steps[i].exercise && first_exercise < 0) first_exercise = static_cast<int>(i);
  }
  ASSERT_GE(first_exercise, 0);
  const LessonExercise exercise = *load.lesson->steps[static_cast<std::size_t>(first_exercise)].exercise;
  EXPECT_EQ(exercise.slot, "diffuse");
  session.lessons().offer(std::move(*load.lesson));
  ASSERT_TRUE(session.lessons().start().has_value());
  EXPECT_FALSE(session.sync_exercise());
  EXPECT_EQ(session.exercise(), nullptr);
  session.lessons().show({first_exercise, false});
  EXPECT_TRUE(session.sync_exercise());
  ASSERT_NE(session.exercise(), nullptr);
  EXPECT_EQ(session.formulas().slot(FormulaSlot::kDiffuse).text, exercise.starter);
  // The student types, asks for hints until none is left.
  session.set_formula(FormulaSlot::kDiffuse, "kd * dot(N, L)");
  for (std::size_t h = 0; h < exercise.hints.size(); ++h) EXPECT_TRUE(session.show_hint());
  EXPECT_FALSE(session.show_hint());
  EXPECT_EQ(session.hints_shown(), static_cast<int>(exercise.hints.size()));
  // Another step: the formulas go; back: the text left there comes back, the hints start again.
  session.lessons().show({0, false});
  session.sync_exercise();
  EXPECT_FALSE(session.formulas().any());
  session.lessons().show({first_exercise, false});
  session.sync_exercise();
  EXPECT_EQ(session.formulas().slot(FormulaSlot::kDiffuse).text, "kd * dot(N, L)");
  EXPECT_EQ(session.hints_shown(), 0);
  session.lessons().close();
  session.sync_exercise();
  EXPECT_FALSE(session.formulas().any());
}

}  // namespace
}  // namespace phonglab
