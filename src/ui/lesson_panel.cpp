// The Lessons panel: open a lesson, its steps to jump to, next and previous, presenter mode,
// and the way back from exploring to the step as written.
#include "ui/panels.h"

#include <algorithm>
#include <cstdio>
#include <string_view>
#include <vector>

#include "io/embedded_scenes.h"
#include "ui/widgets.h"

namespace phonglab::ui {

namespace {

// Every diagnostic of a lesson that does not load, one a line as the loader writes them
// (file:line:col: json.path: (step N) message, with its suggestion), each wrapped to the
// panel; many of them scroll in a box of their own.
void lesson_errors(const std::string& text) {
  std::vector<std::string_view> lines;
  for (std::size_t at = 0; at <= text.size();) {
    const std::size_t end = std::min(text.find('\n', at), text.size());
    if (end > at) lines.emplace_back(text.data() + at, end - at);
    at = end + 1;
  }
  const ImVec4 red(1, 0.45f, 0.35f, 1);
  if (lines.size() > 1) ImGui::TextColored(red, "the lesson does not load: %zu problems", lines.size());
  constexpr std::size_t kShownWithoutScrolling = 6;
  const bool scroll = lines.size() > kShownWithoutScrolling;
  if (scroll) ImGui::BeginChild("##lesson_errors", ImVec2(-1, ImGui::GetTextLineHeightWithSpacing() * 10), true);
  ImGui::PushStyleColor(ImGuiCol_Text, red);
  for (const std::string_view line : lines) {
    if (lines.size() > 1) ImGui::Bullet();
    ImGui::TextWrapped("%.*s", static_cast<int>(line.size()), line.data());
  }
  ImGui::PopStyleColor();
  if (scroll) ImGui::EndChild();
}

}  // namespace

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
  if (!view.error.empty()) lesson_errors(view.error);
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
  // Always drawn (disabled when there is nothing to go back to): the step list below never moves.
  ImGui::BeginDisabled(!view.exploring);
  if (ImGui::Button("Back to the step as written")) actions.back = true;
  locate("lesson.back");
  ImGui::EndDisabled();
  ImGui::SameLine();
  if (view.exploring) ImGui::TextColored(ImVec4(1, 0.8f, 0.3f, 1), "exploring: no file changes");
  else ImGui::TextDisabled("as written");
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
