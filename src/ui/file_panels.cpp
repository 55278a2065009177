// The scene file and screenshot panels, and the dialogs that guard unsaved edits.
#include "ui/panels.h"

#include <algorithm>
#include <array>
#include <cfloat>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "io/embedded_scenes.h"
#include "ui/overlay.h"
#include "ui/widgets.h"

namespace phonglab::ui {

namespace {

// Opens the modal `title` when `open_now`, centred in the window; whether it is showing (then
// end it with end_choice).
bool begin_centred_modal(const char* title, bool open_now) {
  if (open_now) ImGui::OpenPopup(title);
  const ImGuiViewport* viewport = ImGui::GetMainViewport();
  ImGui::SetNextWindowPos(viewport->GetCenter(), ImGuiCond_Appearing, ImVec2(0.5f, 0.5f));
  return ImGui::BeginPopupModal(title, nullptr, ImGuiWindowFlags_AlwaysAutoResize);
}

// The last row of a dialog: Cancel (or Esc; located as "<dialog>.cancel"), and the dialog closed
// once answered. Call inside BeginPopupModal; ends the popup.
GuardChoice end_choice(GuardChoice choice, const char* dialog) {
  if (ImGui::Button("Cancel") || ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape))) choice = GuardChoice::kCancel;
  locate(std::string(dialog) + ".cancel");
  if (choice != GuardChoice::kNone) ImGui::CloseCurrentPopup();
  ImGui::EndPopup();
  return choice;
}

}  // namespace

void scene_file_panel(SceneFileState& state, SceneFileActions& actions) {
  ImGui::TextWrapped("%s%s", state.source.c_str(), state.dirty ? "  (modified)" : "");
  if (ImGui::Button("Open... (Ctrl+O)")) actions.browse_open = true;
  locate("file.browse_open");
  ImGui::SameLine();
  if (ImGui::Button("Save as... (Ctrl+Shift+S)")) actions.browse_save = true;
  locate("file.browse_save");
  input_text("path", state.path_field);
  if (ImGui::Button("Open")) actions.open = true;
  ImGui::SameLine();
  // Save writes the document's own JSON file: not an embedded scene's, not over an OBJ.
  const bool can_save = !state.file_path.empty() && !state.opened_mesh;
  ImGui::BeginDisabled(!can_save);
  if (ImGui::Button("Save")) actions.save = true;
  ImGui::EndDisabled();
  if (!can_save && ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) {
    ImGui::SetTooltip(state.opened_mesh ? "Opened from an OBJ file: Save as writes a scene .json that uses it."
                                        : "An embedded scene has no file: Save as writes one.");
  }
  ImGui::SameLine();
  if (ImGui::Button("Save as")) actions.save_as = true;
  ImGui::SameLine();
  ImGui::BeginDisabled(state.file_path.empty());
  if (ImGui::Button("Reload")) actions.reload = true;
  ImGui::EndDisabled();
  if (ImGui::BeginCombo("embedded", "open an embedded scene")) {
    for (const EmbeddedScene& scene : embedded_scenes()) {
      ImGui::PushID(scene.name.data(), scene.name.data() + scene.name.size());
      const std::string name(scene.name);
      if (ImGui::Selectable(name.c_str())) actions.open_embedded = name;
      if (ImGui::IsItemHovered()) {
        const std::string description(scene.description);
        ImGui::SetTooltip("%s", description.c_str());
      }
      ImGui::PopID();
    }
    ImGui::EndCombo();
  }
  ImGui::BeginDisabled(state.file_path.empty());
  ImGui::Checkbox("reload when the file changes", &state.auto_reload);
  ImGui::EndDisabled();
  if (state.changed_on_disk) {
    ImGui::PushStyleColor(ImGuiCol_Text, kWarningColor);
    ImGui::TextWrapped("The file changed on disk. Reload to see it (your edits will be lost).");
    ImGui::PopStyleColor();
  }
  if (!state.error_text.empty()) {
    ImGui::PushStyleColor(ImGuiCol_Text, kErrorColor);
    ImGui::TextWrapped("%s", state.error_text.c_str());
    ImGui::PopStyleColor();
    ImGui::TextDisabled("The previous scene stays open.");
  }
  if (!state.status.empty()) ImGui::TextDisabled("%s", state.status.c_str());
}

void screenshot_panel(ScreenshotState& state, ScreenshotActions& actions) {
  input_text("##png", state.png_path);
  ImGui::SameLine();
  if (ImGui::Button("Save PNG")) actions.save_png = true;
  input_text("##pfm", state.pfm_path);
  ImGui::SameLine();
  if (ImGui::Button("Save PFM")) actions.save_pfm = true;
  ImGui::TextDisabled("PNG: what is shown. PFM: the linear image.");
  if (!state.status.empty()) ImGui::TextWrapped("%s", state.status.c_str());
}

GuardChoice unsaved_changes_modal(bool open_now, const GuardView& view, std::string& save_as_path) {
  constexpr const char* kTitle = "Unsaved changes";
  GuardChoice choice = GuardChoice::kNone;
  if (begin_centred_modal(kTitle, open_now)) {
    ImGui::Text("The scene has unsaved changes.");
    ImGui::Text("Save them before you %s?", view.action.c_str());
    if (view.changed_on_disk) {
      ImGui::PushStyleColor(ImGuiCol_Text, kWarningColor);
      ImGui::Text("The file also changed on disk since it was opened: Save would overwrite that change.");
      ImGui::PopStyleColor();
    }
    ImGui::Spacing();
    ImGui::BeginDisabled(!view.can_save);
    if (ImGui::Button("Save")) choice = GuardChoice::kSave;
    ImGui::EndDisabled();
    locate("guard.save");
    ImGui::SameLine();
    if (ImGui::Button("Save as")) choice = GuardChoice::kSaveAs;
    locate("guard.save_as");
    ImGui::SameLine();
    ImGui::SetNextItemWidth(ImGui::GetFontSize() * 16);
    input_text("##save_as", save_as_path);
    if (ImGui::Button("Discard")) choice = GuardChoice::kDiscard;
    locate("guard.discard");
    ImGui::SameLine();
    choice = end_choice(choice, "guard");
  }
  return choice;
}

RecoveryChoice recovery_modal(bool open_now, const std::string& source, const std::string& saved) {
  constexpr const char* kTitle = "Unsaved edits were kept";
  RecoveryChoice choice = RecoveryChoice::kNone;
  if (begin_centred_modal(kTitle, open_now)) {
    ImGui::Text("phonglab ended before these edits of %s were saved.", source.c_str());
    ImGui::Text("They were kept %s.", saved.c_str());
    ImGui::Spacing();
    if (ImGui::Button("Restore")) choice = RecoveryChoice::kRestore;
    locate("recovery.restore");
    ImGui::SameLine();
    if (ImGui::Button("Discard")) choice = RecoveryChoice::kDiscard;
    locate("recovery.discard");
    ImGui::SameLine();
    if (ImGui::Button("Not now") || ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape))) choice = RecoveryChoice::kLater;
    locate("recovery.later");
    if (choice != RecoveryChoice::kNone) ImGui::CloseCurrentPopup();
    ImGui::EndPopup();
  }
  return choice;
}

GuardChoice changed_on_disk_modal(bool open_now, const std::string& file) {
  constexpr const char* kTitle = "The file changed on disk";
  GuardChoice choice = GuardChoice::kNone;
  if (begin_centred_modal(kTitle, open_now)) {
    ImGui::Text("%s changed on disk since it was opened or saved here.", file.c_str());
    ImGui::Text("Saving now would overwrite that change with your version.");
    ImGui::Spacing();
    if (ImGui::Button("Overwrite")) choice = GuardChoice::kOverwrite;
    locate("conflict.overwrite");
    ImGui::SameLine();
    if (ImGui::Button("Reload from disk (lose my edits)")) choice = GuardChoice::kReload;
    locate("conflict.reload");
    ImGui::SameLine();
    choice = end_choice(choice, "conflict");
  }
  return choice;
}

bool file_browser_dialog(bool open_now, const FileBrowserView& view, FileBrowserActions& actions) {
  const char* title = view.save ? "Save scene as##browser" : "Open a scene or a mesh##browser";
  const ImGuiViewport* viewport = ImGui::GetMainViewport();
  ImGui::SetNextWindowSize(ImVec2(viewport->Size.x * 0.6f, viewport->Size.y * 0.7f), ImGuiCond_Appearing);
  if (open_now) ImGui::OpenPopup(title);
  ImGui::SetNextWindowPos(viewport->GetCenter(), ImGuiCond_Appearing, ImVec2(0.5f, 0.5f));
  ImGui::SetNextWindowBgAlpha(1.0f);  // opaque: the image behind it must not show through the list
  if (!ImGui::BeginPopupModal(title, nullptr)) return false;
  const FolderListing& listing = *view.listing;
  ImGui::TextWrapped("%s", listing.folder.c_str());
  ImGui::TextDisabled(view.save ? "Scene files (.json)" : "Scene files (.json) and meshes (.obj)");
  const float footer = ImGui::GetFrameHeightWithSpacing() * 3 + ImGui::GetTextLineHeightWithSpacing() * 2;
  const float side = ImGui::GetContentRegionAvail().x * 0.35f;
  if (ImGui::BeginChild("##entries", ImVec2(-side, -footer), true)) {
    if (!listing.error.empty()) ImGui::TextColored(kErrorColor, "%s", listing.error.c_str());
    for (const FileEntry& e : listing.entries) {
      const std::string label = e.folder ? "[" + e.name + "]" : e.name;
      const bool selected = !e.folder && *view.name_field == e.name;
      if (ImGui::Selectable(label.c_str(), selected, ImGuiSelectableFlags_AllowDoubleClick)) {
        if (e.folder) {
          actions.go_to = entry_path(listing, e);  // one click goes in: fewer steps than a double click
        } else {
          *view.name_field = e.name;
          if (ImGui::IsMouseDoubleClicked(0)) actions.chosen = entry_path(listing, e);
        }
      }
      locate("browser.entry." + e.name);
    }
  }
  ImGui::EndChild();
  ImGui::SameLine();
  if (ImGui::BeginChild("##places", ImVec2(0, -footer), true)) {
    ImGui::TextDisabled("Recent");
    for (const std::string& path : *view.recent) {
      // The name first (a long folder would hide it), the folder after it and in full on hover.
      const std::filesystem::path p(path);
      const std::string label = p.filename().string() + "   " + p.parent_path().string();
      if (ImGui::Selectable(label.c_str())) actions.chosen = path;
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", path.c_str());
    }
    if (view.recent->empty()) ImGui::TextDisabled("  (none yet)");
    if (!view.save) {
      ImGui::Separator();
      ImGui::TextDisabled("Embedded scenes");
      for (const EmbeddedScene& scene : embedded_scenes()) {
        const std::string name(scene.name);
        if (ImGui::Selectable(name.c_str())) actions.embedded = name;
      }
    }
  }
  ImGui::EndChild();
  if (ImGui::IsWindowAppearing()) ImGui::SetKeyboardFocusHere();
  const bool entered =
      input_text("file", *view.name_field, ImGuiInputTextFlags_EnterReturnsTrue | ImGuiInputTextFlags_AutoSelectAll);
  locate("browser.name");
  // A name is taken in the listed folder; a path as it is (relative to the working folder).
  const auto typed_path = [&] {
    const std::string& name = *view.name_field;
    if (name.empty() || name[0] == '/') return name;
    return listing.folder + "/" + name;
  };
  if (ImGui::Button(view.save ? "Save" : "Open") || entered) {
    if (!view.name_field->empty()) actions.chosen = typed_path();
  }
  locate("browser.accept");
  ImGui::SameLine();
  if (ImGui::Button("Cancel") || ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape))) actions.cancel = true;
  locate("browser.cancel");
  if (!view.error.empty()) ImGui::TextColored(kErrorColor, "%s", view.error.c_str());
  if (actions.cancel || !actions.chosen.empty() || !actions.embedded.empty()) ImGui::CloseCurrentPopup();
  ImGui::EndPopup();
  return true;
}

}  // namespace phonglab::ui
