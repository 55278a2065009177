// A lesson's exercise step as the previewer presents it: the shading lesson's step 14 puts its diffuse starter in the Formula panel (an
// unfinished text: its error shown, the equation's own term rendering), the student's diffuse term
// matches the reference on the step's scene and a hint is shown; another step clears the formulas,
// and back at the exercise the student's text is given back. The shell's part is LessonShell::
// present: the step's scene adopted, then Session::sync_exercise.
#include <gtest/gtest.h>

#include "check/check.h"
#include "io/lesson_io.h"
#include "session/session.h"

namespace phonglab {
namespace {

constexpr int kDiffuseExercise = 13;  // `lesson_goto 14`

struct ShadingExercise : ::testing::Test {
  Session session{""};
  void SetUp() override {
    ASSERT_TRUE(session.open("lecture"));
    LessonLoad load = load_lesson_arg("shading");
    ASSERT_TRUE(load.ok()) << load.error_text();
    session.lessons().offer(std::move(*load.lesson));
    ASSERT_TRUE(session.lessons().start());
    session.sync_exercise();
  }
  // LessonShell::show_place and present: the step's scene, then its exercise.
  void go_to(int step) {
    const LessonPresenter::Show show = session.lessons().show({step, false});
    if (show.adopt_step) {
      session.adopt(session.lessons().lesson()->steps[static_cast<std::size_t>(*show.adopt_step)].prepared_scene,
                    "a lesson's step");
    }
    session.sync_exercise();
  }
  const FormulaBook::Slot& diffuse() const { return session.formulas().slot(FormulaSlot::kDiffuse); }
};

TEST_F(ShadingExercise, TheDiffuseExercisePutsItsStarterInThePanelWithItsError) {
  go_to(kDiffuseExercise);
  ASSERT_NE(session.exercise(), nullptr);
  EXPECT_EQ(session.exercise()->slot, "diffuse");
  EXPECT_EQ(diffuse().text, "kd * ");
  ASSERT_TRUE(diffuse().error.has_value());
  EXPECT_EQ(diffuse().error->text(), "formula:1:6: expected an expression (got the end of the formula)");
  EXPECT_FALSE(session.formulas().any()) << "the equation's own term renders meanwhile";
}

TEST_F(ShadingExercise, TheStudentsDiffuseTermMatchesOnTheStepsSceneAndAHintIsShown) {
  go_to(kDiffuseExercise);
  EXPECT_TRUE(session.set_formula(FormulaSlot::kDiffuse, "kd * dot(N, L)"));
  Scene scene = session.scene();  // the step's scene, as the view renders it (reduced for the check)
  scene.width = 160;
  scene.height = 90;
  const CheckResult r = check_formulas(scene, session.formulas().rules());
  EXPECT_TRUE(r.match) << check_report_text(r);
  EXPECT_EQ(session.hints_shown(), 0);
  EXPECT_TRUE(session.show_hint());
  EXPECT_EQ(session.hints_shown(), 1);
}

TEST_F(ShadingExercise, AnotherStepClearsTheFormulasAndBackAtTheExerciseTheTextIsGivenBack) {
  go_to(kDiffuseExercise);
  session.set_formula(FormulaSlot::kDiffuse, "kd * dot(N, L)");
  go_to(0);
  EXPECT_EQ(session.exercise(), nullptr);
  EXPECT_EQ(diffuse().text, "");
  EXPECT_FALSE(session.formulas().any()) << "the step shows the equation's terms: no verdict";
  go_to(kDiffuseExercise);
  EXPECT_EQ(diffuse().text, "kd * dot(N, L)");
}

}  // namespace
}  // namespace phonglab
