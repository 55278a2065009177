// Building the scene in the previewer: objects and materials added, duplicated, deleted and edited
// (each one undo step, through the session), meshes placed through the loader, dropped files, the
// selection of an object and its material, and the scripts' scene commands. The rules are
// src/interaction/scene_objects' (unit-tested); this class holds the panels' fields and the last
// edit's notice, and reaches the shell's shared state (ShellState, shell_state.h) and the
// components it works with, given by reference.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <imgui.h>

#include "core/scene/scene.h"
#include "ui/panels.h"

namespace phonglab {

struct ShellState;
class FileShell;
class FormulaShell;
class LessonShell;

class SceneBuilder {
 public:
  SceneBuilder(ShellState& shell, FileShell& files, FormulaShell& formulas, LessonShell& lesson_shell)
      : s_(shell), files_(files), formulas_(formulas), lesson_shell_(lesson_shell) {}
  SceneBuilder(const SceneBuilder&) = delete;
  SceneBuilder& operator=(const SceneBuilder&) = delete;

  ui::EditNotice& notice() { return notice_; }  // the last object or material edit's result or refusal
  const ui::EditNotice& notice() const { return notice_; }
  std::string& mesh_path_field() { return mesh_path_field_; }          // the Objects panel's OBJ path
  std::string& material_name_field() { return material_name_field_; }  // the Materials panel's "Rename to"

  // Each returns "" or why nothing changed.
  std::string edit_scene(const std::function<std::string(Scene&)>& edit, bool meshes_move);  // one undo step
  std::string place_meshes(Scene& scene) const;  // meshes loaded again where their transforms say
  std::string add_object(ObjectRef::Kind kind, const std::string& obj_path);  // last, in front, selected
  std::string delete_object(int object);
  std::string duplicate(int object);             // the copy beside the original, selected
  std::string set_object(int object, const std::string& field, const std::vector<double>& values,
                         const std::string& text);
  std::string apply_material_preset(const std::string& name, const std::string& preset);  // a new material if none is so named
  std::string add_material(const std::string& name);
  std::string drop_file(const std::string& path);  // a .json opens (guarded), an .obj becomes a mesh object
  void select_object(int object);                // -1: none; selects its material too
  void undo();                                   // Ctrl+Z: the scene before the last edit
  void redo();                                   // Ctrl+Shift+Z
  std::optional<ImVec2> object_screen_point(int object) const;  // its anchor on screen
  std::optional<std::string> script_scene_command(const std::vector<std::string>& words);
  std::optional<std::string> script_scene_edit(const std::vector<std::string>& words);
  std::string refuse(std::string why);           // the notice says why nothing changed; returns it

 private:
  void restored();  // after an undo or redo step: the selection kept in the scene, a restart

  ShellState& s_;  // the shell's shared state (shell_state.h)
  FileShell& files_;
  FormulaShell& formulas_;
  LessonShell& lesson_shell_;
  ui::EditNotice notice_;
  std::string mesh_path_field_;
  std::string material_name_field_;
};

}  // namespace phonglab
