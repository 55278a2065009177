// The Lessons panel: open a lesson, its steps to jump to, next and previous, presenter mode,
// and the way back from exploring to the step as written.
#include "ui/panels.h"

#include <cstdio>

#include "io/embedded_scenes.h"
#include "ui/widgets.h"

namespace phonglab::ui {

void lessons_panel(const LessonPanelView& view, std::string& path_field, LessonActions& actions) {
  for (const EmbeddedLesson& l : embedded_lessons()) {
    const std::string name(l.name);
    if (ImGui::Button(name.c_str())) actions.open = name;
    locate("lesson.open." + name);
    ImGui::SameLine();
  }
  ImGui::NewLine();
  ImGui::SetNextItemWidth(-ImGui::GetFontSize() * 4);
  input_text("##lesson_path", path_field);
  locate("lesson.path");
  ImGui::SameLine();
  if (ImGui::Button("Open##lesson") && !path_field.empty()) actions.open = path_field;
  locate("lesson.open");
  if (!view.error.empty()) ImGui::TextColored(ImVec4(1, 0.45f, 0.35f, 1), "%s", view.error.c_str());
  if (view.lesson == nullptr) {
    ImGui::TextDisabled("a lesson walks through the lecture step by step");
    return;
  }
  const Lesson& lesson = *view.lesson;
  ImGui::TextWrapped("%s", lesson.title.c_str());
  if (ImGui::Button("< Prev")) actions.prev = true;
  locate("lesson.prev");
  ImGui::SameLine();
  const LessonStep& step = lesson.steps[static_cast<std::size_t>(view.place.step)];
  const bool posed = step.has_question() && !view.place.revealed;
  if (ImGui::Button(posed ? "Answer >" : "Next >")) actions.next = true;
  locate("lesson.next");
  ImGui::SameLine();
  if (ImGui::Button(view.presenting ? "Leave presenter (F11)" : "Present (F11)")) actions.present = true;
  locate("lesson.present");
  if (view.exploring) {
    ImGui::TextColored(ImVec4(1, 0.8f, 0.3f, 1), "exploring: edits here change no file");
    if (ImGui::Button("Back to the step as written")) actions.back = true;
    locate("lesson.back");
  }
  if (ImGui::BeginListBox("##steps", ImVec2(-1, ImGui::GetTextLineHeightWithSpacing() * 8))) {
    for (int i = 0; i < static_cast<int>(lesson.steps.size()); ++i) {
      char label[256];
      std::snprintf(label, sizeof label, "%2d  %s", i + 1, lesson.steps[static_cast<std::size_t>(i)].title.c_str());
      if (ImGui::Selectable(label, i == view.place.step)) actions.go_to = i;
      locate("lesson.step." + std::to_string(i + 1));
    }
    ImGui::EndListBox();
  }
  if (ImGui::Button("Close lesson")) actions.close = true;
  locate("lesson.close");
}

}  // namespace phonglab::ui
