// Lessons opened as the previewer opens them (`--lesson`, `lesson_open`, a drop): the shading
// lesson at its first step, a lesson that does not load reported, a lesson file told from a scene
// when it is dropped and opened at its first step, and a lesson file's step explored: its scene is
// nobody's file, so saving asks where and the lesson file never changes.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "interaction/scene_objects.h"
#include "io/lesson_io.h"
#include "session/session.h"
#include "tests/support/test_folder.h"

namespace phonglab {
namespace {

namespace fs = std::filesystem;

struct LessonsOpened : ::testing::Test {
  test::TestFolder temp{"phonglab-lesson-files"};
  const fs::path dir = temp.path();
  std::string write(const std::string& name, const std::string& text) const {
    const std::string path = (dir / name).string();
    std::ofstream(path, std::ios::binary) << text;
    return path;
  }
  static std::string read(const std::string& path) {
    std::stringstream text;
    text << std::ifstream(path, std::ios::binary).rdbuf();
    return text.str();
  }
  // What the shell does with a place the presenter shows: the step's scene becomes the document.
  static void present(Session& session, const LessonPresenter::Show& show) {
    if (!show.adopt_step) return;
    const Lesson& lesson = *session.lessons().lesson();
    session.adopt(lesson.steps[static_cast<std::size_t>(*show.adopt_step)].prepared_scene, "a lesson's step");
  }
};

// `phonglab --lesson shading`: the lesson at its first step, the ambient term alone.
TEST_F(LessonsOpened, TheShadingLessonOpensAtItsFirstStepOnTheAmbientTerm) {
  LessonLoad load = load_lesson_arg("shading");
  ASSERT_TRUE(load.ok()) << load.error_text();
  LessonPresenter presenter;
  presenter.offer(std::move(*load.lesson));
  const std::optional<LessonPresenter::Show> first = presenter.start();
  ASSERT_TRUE(first);
  ASSERT_NE(presenter.lesson(), nullptr);
  EXPECT_EQ(presenter.lesson()->name, "shading");
  EXPECT_EQ(presenter.lesson()->steps.size(), 16U);
  EXPECT_EQ(presenter.place(), (LessonPlace{0, false}));
  EXPECT_EQ(presenter.lesson()->steps[0].title, "Ambient alone");
  EXPECT_EQ(first->view.term, Term::kAmbient);
}

// The reader's side of `lesson_open missing.json`: the error the Lessons panel shows, naming the
// file first. (Keeping the lesson shown is LessonShell::open_lesson's: it offers nothing then.)
TEST_F(LessonsOpened, ALessonThatDoesNotLoadIsReportedWithItsPath) {
  const std::string missing = (dir / "missing.json").string();
  const LessonLoad load = load_lesson_arg(missing);
  EXPECT_FALSE(load.ok());
  EXPECT_EQ(load.error_text().rfind(missing + ": ", 0), 0U) << load.error_text();
  EXPECT_FALSE(is_lesson_file(missing));
}

// A .json dropped on the window: a lesson (a top-level "steps") opens as one, named after its
// file, at its first step and that step's view.
TEST_F(LessonsOpened, ADroppedLessonFileIsToldFromASceneAndOpensAtItsFirstStep) {
  const std::string path = write("my-lesson.json",
                                 R"({"title": "Dropped", "steps": [{"title": "Ambient", "caption": "ka only.", )"
                                 R"("scene": "lecture", "show": {"term": "ambient"}}]})"
                                 "\n");
  const std::string scene = write("scene.json", R"({"objects": [], "materials": {"steps": {"kd": 0.5}}})");
  EXPECT_TRUE(is_lesson_file(path));
  EXPECT_FALSE(is_lesson_file(scene)) << "a scene, even with a material named steps";
  LessonLoad load = load_lesson_arg(path);
  ASSERT_TRUE(load.ok()) << load.error_text();
  EXPECT_EQ(load.lesson->name, "my-lesson");
  Session session("");
  ASSERT_TRUE(session.open("lecture"));
  session.lessons().offer(std::move(*load.lesson));
  const std::optional<LessonPresenter::Show> first = session.lessons().start();
  ASSERT_TRUE(first);
  EXPECT_EQ(session.lessons().place(), (LessonPlace{0, false}));
  EXPECT_EQ(session.lessons().lesson()->steps.size(), 1U);
  EXPECT_EQ(first->adopt_step, 0);
  EXPECT_EQ(first->view.term, Term::kAmbient);
  present(session, *first);
  EXPECT_TRUE(session.document().error_text().empty()) << "no scene error";
}

// A lesson file of one's own, its step explored (a material edited) and Ctrl+S: the step's scene
// has no file (Save asks where), keeps no recovery file, and the lesson file is byte for byte
// what it was.
TEST_F(LessonsOpened, AnExploredStepOfALessonFileIsNobodysFileAndTheLessonFileStaysAsItWas) {
  const std::string path = write("mine.json",
                                 "{\"title\": \"Mine\", \"description\": \"a lesson file of the test's own\",\n"
                                 " \"steps\": [{\"title\": \"The plastic sphere\", \"caption\": \"kd is 0.8, 0.15, 0.1.\", "
                                 "\"scene\": \"lecture\"}]}\n");
  const std::string before = read(path);
  LessonLoad load = load_lesson_arg(path);
  ASSERT_TRUE(load.ok()) << load.error_text();
  EXPECT_EQ(load.lesson->name, "mine");
  Session session((dir / "recovery").string());
  ASSERT_TRUE(session.open("lecture"));
  session.lessons().offer(std::move(*load.lesson));
  const std::optional<LessonPresenter::Show> first = session.lessons().start();
  ASSERT_TRUE(first);
  present(session, *first);
  const int plastic = ui::find_material(session.scene(), "plastic");
  ASSERT_GE(plastic, 0);
  Material edited = session.scene().materials[static_cast<std::size_t>(plastic)];
  edited.kd = Color(0.1, 0.1, 0.9);
  ASSERT_TRUE(session.apply({edit::SetMaterial{plastic, edited}}).unsaved);
  session.lessons().explored();  // a change the lesson did not make (the shell's apply_edits)
  EXPECT_TRUE(session.lessons().exploring());
  EXPECT_TRUE(session.dirty());
  EXPECT_TRUE(session.document().file_path().empty()) << "Ctrl+S asks where to save";
  EXPECT_EQ(session.document().save(), SceneDocument::SaveResult::kFailed);
  EXPECT_FALSE(RecoveryKeeper::source_of(session.document()));
  EXPECT_TRUE(session.recovery().write(session.document()).empty());
  EXPECT_EQ(read(path), before) << "the lesson file is unchanged";
  EXPECT_FALSE(fs::exists(dir / "recovery"));
}

}  // namespace
}  // namespace phonglab
