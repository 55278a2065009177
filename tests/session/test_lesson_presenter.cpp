// The lesson being presented (session/lesson_presenter.h): steps and answers in order, the scene
// adopted only when a place needs it, exploring and the way back, a compare's A first.
#include <gtest/gtest.h>

#include "io/lesson_io.h"
#include "session/lesson_presenter.h"

namespace phonglab {
namespace {

Lesson shading() {
  LessonLoad load = load_lesson_arg("shading");
  EXPECT_TRUE(load.ok()) << load.error_text();
  return std::move(*load.lesson);
}

// The lecture's last step (the exercises follow it): the indirect light against the constant.
int indirect_step(const Lesson& lesson) {
  for (std::size_t i = 0; i < lesson.steps.size(); ++i) {
    if (lesson.steps[i].title == "The light it stands in for") return static_cast<int>(i);
  }
  ADD_FAILURE() << "no step \"The light it stands in for\"";
  return 0;
}

LessonPresenter started() {
  LessonPresenter p;
  p.offer(shading());
  EXPECT_TRUE(p.start().has_value());
  return p;
}

TEST(LessonPresenter, AnOfferedLessonWaitsThenStartsAtItsFirstStepWithItsScene) {
  LessonPresenter p;
  EXPECT_FALSE(p.start().has_value());  // nothing offered
  p.offer(shading());
  EXPECT_EQ(p.lesson(), nullptr);
  ASSERT_NE(p.waiting(), nullptr);
  const std::optional<LessonPresenter::Show> show = p.start();
  ASSERT_TRUE(show.has_value());
  EXPECT_EQ(p.waiting(), nullptr);
  ASSERT_NE(p.lesson(), nullptr);
  EXPECT_EQ(p.place(), (LessonPlace{0, false}));
  EXPECT_EQ(show->adopt_step, 0);
  EXPECT_EQ(show->view.term, Term::kAmbient);
  EXPECT_EQ(p.scene_step(), 0);
  EXPECT_FALSE(show->compare);
}

TEST(LessonPresenter, NextRevealsAnAnswerOnTheSameSceneThenGoesOn) {
  LessonPresenter p = started();
  const auto to_question = p.next();
  ASSERT_TRUE(to_question);
  EXPECT_EQ(p.place(), (LessonPlace{1, false}));
  EXPECT_EQ(to_question->adopt_step, 1);
  const auto answer = p.next();
  ASSERT_TRUE(answer);
  EXPECT_EQ(p.place(), (LessonPlace{1, true}));
  EXPECT_FALSE(answer->adopt_step.has_value()) << "the answer re-shades the step's scene";
  EXPECT_TRUE(answer->view.light_markers);
  const auto step3 = p.next();
  ASSERT_TRUE(step3);
  EXPECT_EQ(p.place(), (LessonPlace{2, false}));
  EXPECT_EQ(step3->adopt_step, 2);
  // Back: to the previous step's question, not its answer.
  ASSERT_TRUE(p.prev());
  EXPECT_EQ(p.place(), (LessonPlace{1, false}));
}

TEST(LessonPresenter, AtTheEndsNothingMovesUnlessSomethingWasExplored) {
  LessonPresenter p = started();
  EXPECT_FALSE(p.prev().has_value());
  p.explored();
  EXPECT_TRUE(p.exploring());
  const auto back = p.prev();  // the step as written again, its scene adopted anew
  ASSERT_TRUE(back);
  EXPECT_EQ(back->adopt_step, 0);
  EXPECT_FALSE(p.exploring());
  const int last = indirect_step(*p.lesson());
  p.show({last, false});
  ASSERT_TRUE(p.awaiting_a());
  EXPECT_TRUE(p.take_a_now());
  ASSERT_TRUE(p.a_taken());
  const auto answer = p.next();
  ASSERT_TRUE(answer);
  EXPECT_EQ(p.place(), (LessonPlace{last, true}));
  EXPECT_FALSE(p.awaiting_a()) << "the last answer compares nothing: it shows the signed gap";
  EXPECT_EQ(answer->view.ambient_shown, AmbientShown::kDifference);
  const int end = static_cast<int>(p.lesson()->steps.size()) - 1;
  p.show({end, false});
  EXPECT_FALSE(p.next().has_value()) << "the last step stays";
}

TEST(LessonPresenter, ShowClampsThePlaceAndRevealsOnlyQuestions) {
  LessonPresenter p = started();
  p.show({100, false});
  EXPECT_EQ(p.place().step, static_cast<int>(p.lesson()->steps.size()) - 1);
  p.show({-3, true});
  EXPECT_EQ(p.place(), (LessonPlace{0, false})) << "step 1 poses no question";
}

// The last step compares the indirect light with the step before (ka·Ia): its scene and view are
// shown first for A, then the step's own view with the compare on.
TEST(LessonPresenter, ACompareShowsItsSourceForAThenTheStep) {
  LessonPresenter p = started();
  const int last = indirect_step(*p.lesson());
  const LessonPresenter::Show source = p.show({last, false});
  EXPECT_EQ(source.adopt_step, last - 1);
  EXPECT_EQ(source.view.ambient, Ambient::kConstant);
  EXPECT_FALSE(source.compare);
  EXPECT_TRUE(p.awaiting_a());
  EXPECT_FALSE(p.a_taken().has_value()) << "A is not asked for yet";
  EXPECT_TRUE(p.take_a_now());
  EXPECT_FALSE(p.take_a_now()) << "asked for once";
  const std::optional<LessonPresenter::Show> step = p.a_taken();
  ASSERT_TRUE(step);
  EXPECT_EQ(step->adopt_step, last);
  EXPECT_EQ(step->view.ambient, Ambient::kIndirect);
  EXPECT_EQ(step->view.compare, CompareView::kWipe);
  EXPECT_TRUE(step->compare);
  EXPECT_FALSE(p.awaiting_a());
  EXPECT_EQ(p.view().ambient, Ambient::kIndirect);
}

TEST(LessonPresenter, AnAThatIsDroppedLeavesTheSourceShown) {
  LessonPresenter p = started();
  const int last = indirect_step(*p.lesson());
  p.show({last, false});
  EXPECT_TRUE(p.take_a_now());
  p.a_dropped();
  EXPECT_FALSE(p.awaiting_a());
  EXPECT_FALSE(p.a_taken().has_value());
  EXPECT_EQ(p.scene_step(), last - 1);
}

// "Move your head" compares with the same step, the head not moved: A of the step's own scene.
TEST(LessonPresenter, AHeadCompareTakesAOfTheSameStepWithTheHeadNotMoved) {
  LessonPresenter p = started();
  p.show({5, false});
  ASSERT_FALSE(p.awaiting_a());
  const LessonPresenter::Show answer_source = *p.next();
  EXPECT_EQ(p.place(), (LessonPlace{5, true}));
  EXPECT_EQ(answer_source.adopt_step, 5);
  EXPECT_FALSE(answer_source.view.head_angle_deg.has_value());
  EXPECT_TRUE(p.take_a_now());
  const std::optional<LessonPresenter::Show> step = p.a_taken();
  ASSERT_TRUE(step);
  EXPECT_FALSE(step->adopt_step.has_value()) << "the same step's scene";
  EXPECT_TRUE(step->view.head_angle_deg.has_value());
  EXPECT_EQ(step->view.compare, CompareView::kDifference);
}

TEST(LessonPresenter, CloseEndsTheLesson) {
  LessonPresenter p = started();
  p.show({12, false});
  p.close();
  EXPECT_EQ(p.lesson(), nullptr);
  EXPECT_FALSE(p.awaiting_a());
  EXPECT_EQ(p.scene_step(), -1);
  EXPECT_FALSE(p.next().has_value());
}


// A term key on a compare step (shading step 6's answer: move your head, |live - A|): the step is
// shown again with that term in its compare's source and in its own view, A taken anew, and the
// step counts as explored; "back" shows it as written. A step without a compare is left alone.
TEST(LessonPresenter, ATermKeyOnACompareStepShowsItAgainWithThatTerm) {
  LessonPresenter p = started();
  EXPECT_FALSE(p.show_term(Term::kDiffuse).has_value()) << "step 1 compares nothing";
  p.show({5, true});
  ASSERT_TRUE(p.awaiting_a());
  ASSERT_TRUE(p.take_a_now());
  ASSERT_TRUE(p.a_taken());
  const std::optional<LessonPresenter::Show> source = p.show_term(Term::kDiffuse);
  ASSERT_TRUE(source);
  EXPECT_EQ(source->view.term, Term::kDiffuse);
  EXPECT_FALSE(source->view.head_angle_deg.has_value()) << "A's view: the head not moved";
  EXPECT_TRUE(p.exploring());
  ASSERT_TRUE(p.take_a_now());
  const std::optional<LessonPresenter::Show> own = p.a_taken();
  ASSERT_TRUE(own);
  EXPECT_TRUE(own->compare);
  EXPECT_EQ(own->view.term, Term::kDiffuse);
  EXPECT_TRUE(own->view.head_angle_deg.has_value());
  EXPECT_EQ(p.place(), (LessonPlace{5, true}));
  const LessonPresenter::Show written = p.show(p.place());
  EXPECT_EQ(written.view.term, Term::kFull) << "the step as written again";
  EXPECT_FALSE(p.exploring());
}

}  // namespace
}  // namespace phonglab
