// Building the scene in the previewer: objects and materials added, duplicated, deleted, moved
// and edited (the rules in src/interaction/scene_objects.h), meshes placed by the loader, files
// dropped on the window. Every change is one undo step and marks the scene unsaved; a refused one
// changes nothing and says why in the Objects panel.
#include <filesystem>
#include <iostream>
#include <optional>

#include "apps/previewer/script_words.h"
#include "apps/previewer/scene_builder.h"

#include "session/dropped_file.h"

#include "apps/previewer/viewer_app.h"
#include "core/accel/accel.h"
#include "interaction/camera_control.h"
#include "interaction/material_presets.h"
#include "interaction/numbers.h"
#include "interaction/scene_objects.h"
#include "io/lesson_io.h"
#include "io/scene/scene_io.h"

namespace phonglab {

std::string SceneBuilder::place_meshes(Scene& scene) const {
  if (scene.meshes.empty()) return {};
  const bool embedded = s_.doc.file_path().empty();
  const std::string dir = embedded ? "" : std::filesystem::path(s_.doc.file_path()).parent_path().string();
  LoadResult loaded = reload_meshes(scene, dir, embedded);
  if (!loaded.ok()) {
    // "the edited scene:91:30: objects[7].file: bunny.obj:2: ...": the position is in text no
    // one wrote; what matters is the mesh file's own.
    std::string text = loaded.error_text();
    const std::size_t file = text.find("].file: ");
    if (text.rfind("the edited scene:", 0) == 0 && file != std::string::npos) text = text.substr(file + 8);
    return "cannot load the mesh: " + text;
  }
  scene = std::move(*loaded.scene);
  return {};
}

std::string SceneBuilder::refuse(std::string why) {
  notice_ = ui::EditNotice{why, true};
  return why;
}

std::string SceneBuilder::edit_scene(const std::function<std::string(Scene&)>& edit, bool meshes_move) {
  Scene scene = s_.doc.scene();
  ui::complete_object_indices(scene);
  std::string error = edit(scene);
  if (error.empty() && meshes_move) error = place_meshes(scene);
  if (!error.empty()) return refuse(error);  // the scene stays as it was
  notice_ = ui::EditNotice{};
  // An object dragged is one undo step when the drag ends.
  apply_edit(s_, {edit::SetScene{std::move(scene)}, s_.drag.mode != DragMode::kNone || ImGui::IsAnyItemActive()});
  return {};
}

void SceneBuilder::undo() {
  if (s_.session.undo()) restored();
}

void SceneBuilder::redo() {
  if (s_.session.redo()) restored();
}

void SceneBuilder::restored() {
  const Scene& scene = s_.session.scene();
  s_.selected_light = std::min(s_.selected_light, static_cast<int>(scene.lights.size()) - 1);
  if (s_.selected_object >= ui::object_count(scene)) s_.selected_object = -1;
  notice_ = ui::EditNotice{};
  s_.edits.scene = true;
}

void SceneBuilder::select_object(int object) {
  const Scene& scene = s_.doc.scene();
  s_.selected_object = object >= 0 && object < ui::object_count(scene) ? object : -1;
  const int material = s_.selected_object >= 0 ? ui::object_material(scene, s_.selected_object) : -1;
  if (material >= 0) s_.selected_material = material;
}

std::string SceneBuilder::add_object(ObjectRef::Kind kind, const std::string& obj_path) {
  int added = -1;
  std::string error;
  if (kind == ObjectRef::Kind::kMesh) {
    if (obj_path.empty()) return refuse("a mesh object needs an OBJ file");
    if (!is_obj_path(obj_path)) return refuse("'" + obj_path + "' is not an OBJ file (.obj)");
    const std::string file = std::filesystem::absolute(obj_path).lexically_normal().string();
    // Loaded where its file puts it, then scaled to the scene and set down beside the others
    // (ui::place_new_object), and loaded again there.
    error = edit_scene([&](Scene& s) {
      Mesh mesh;
      mesh.file = file;
      added = ui::append_mesh_object(s, std::move(mesh));
      std::string failed = place_meshes(s);
      if (!failed.empty()) return failed;
      return ui::place_new_object(s, view_camera(s_), view_aspect(s_), added);
    }, true);
  } else {
    error = edit_scene([&](Scene& s) {
      // A material of its own, the selected one's copy (so it looks the same until edited): an
      // edit of the new object's material must not change the others'.
      int material = s_.selected_material;
      std::string failed;
      if (s.materials.empty()) {
        failed = ui::new_material(s, "default", material);
      } else {
        const int source = std::clamp(material, 0, static_cast<int>(s.materials.size()) - 1);
        failed = ui::duplicate_material(s, source, material);
      }
      if (!failed.empty()) return failed;
      added = ui::add_primitive(s, kind, ui::placement_in_front_of(view_camera(s_)), material);
      if (added < 0) return std::string("only a sphere, a plane, a triangle or a mesh can be added");
      return ui::place_new_object(s, view_camera(s_), view_aspect(s_), added);
    }, false);
  }
  if (error.empty()) {
    select_object(added);
    notice_.text = "added " + ui::object_label(s_.doc.scene(), added);
  }
  return error;
}

std::string SceneBuilder::delete_object(int object) {
  const int count = ui::object_count(s_.doc.scene());
  const std::string error = edit_scene([&](Scene& s) { return ui::delete_object(s, object); }, false);
  if (!error.empty()) return error;
  s_.selected_object = -1;
  notice_.text = count == 1 ? "deleted the last object: the scene is empty (Ctrl+Z brings it back)"
                                    : "deleted objects[" + std::to_string(object) + "]";
  return {};
}

std::string SceneBuilder::duplicate(int object) {
  int copy = -1;
  // The copy stands where the original does, selected (its handle shows it): drag it away, as
  // after Blender's Shift+D.
  const std::string error = edit_scene([&](Scene& s) { return ui::duplicate_object(s, object, copy); }, false);
  if (error.empty()) {
    select_object(copy);
    notice_.text = "duplicated objects[" + std::to_string(object) + "] as " +
                           ui::object_label(s_.doc.scene(), copy) + ", in the same place: drag it away";
  }
  return error;
}

std::string SceneBuilder::set_object(int object, const std::string& field, const std::vector<double>& values,
                               const std::string& text) {
  const bool mesh = ui::object_at(s_.doc.scene(), object).kind == ObjectRef::Kind::kMesh;
  const bool moves = mesh && (ui::moves_mesh_geometry(field) || field == "material");
  return edit_scene([&](Scene& s) { return ui::set_object_field(s, object, field, values, text); }, moves);
}

std::string SceneBuilder::apply_material_preset(const std::string& name, const std::string& preset_name) {
  const ui::MaterialPreset* preset = ui::find_preset(preset_name);
  if (preset == nullptr) return refuse("no preset named '" + preset_name + "'");
  int index = ui::find_material(s_.doc.scene(), name);
  Color scale(1);
  const std::string error = edit_scene([&](Scene& s) {
    if (index < 0) {  // a new material of that name, starting from the preset
      std::string failed = ui::new_material(s, name, index);
      if (!failed.empty()) return failed;
    }
    scale = ui::apply_preset(s.materials[static_cast<std::size_t>(index)], *preset, s.specular_model, s.ambient);
    return std::string();
  }, false);
  if (error.empty()) {
    s_.selected_material = index;
    // What the preset's ambient note means for this scene: in the Materials panel, not on stderr.
    notice_ = ui::EditNotice{ui::preset_applied_text(*preset, scale, s_.doc.scene().ambient), false, true};
  }
  return error;
}

std::string SceneBuilder::add_material(const std::string& name) {
  int index = -1;
  const std::string error = edit_scene([&](Scene& s) { return ui::new_material(s, name, index); }, false);
  if (error.empty()) s_.selected_material = index;
  return error;
}

std::string SceneBuilder::drop_file(const std::string& path) {
  const DroppedFile dropped = classify_drop(path);
  switch (dropped.kind) {
    case DroppedFile::Kind::kMesh: return add_object(ObjectRef::Kind::kMesh, path);
    case DroppedFile::Kind::kLesson: lesson_shell_.open_lesson(path); return {};  // unsaved edits guarded as for Open
    case DroppedFile::Kind::kScene:
      files_.request(FileShell::PendingAction{FileShell::PendingAction::Kind::kOpen, path});  // through the unsaved-changes guard
      return {};
    case DroppedFile::Kind::kImage: {
      // A student's own render of the view: checked against the reference (docs/checking.md).
      const std::string why = formulas_.open_image(path);
      files_.file_state().error_text = why;  // a refusal where one looks; a check clears the last
      return why;
    }
    case DroppedFile::Kind::kRefused: break;
  }
  // Said where one looks (the overlay's error line and the Scene file panel), not only in the
  // Objects panel, which may be folded.
  const std::string why = refuse(dropped.refusal);
  files_.file_state().error_text = why;
  return why;
}

std::optional<ImVec2> SceneBuilder::object_screen_point(int object) const {
  const Scene& scene = s_.doc.scene();
  if (object < 0 || object >= ui::object_count(scene)) return std::nullopt;
  const int w = std::max(1, static_cast<int>(std::lround(s_.viewport.width)));
  const int h = std::max(1, static_cast<int>(std::lround(s_.viewport.height)));
  const auto p = ui::project(view_camera(s_), ui::object_anchor(scene, object), w, h);
  if (!p) return std::nullopt;
  return ImVec2(s_.viewport.x + static_cast<float>(p->x), s_.viewport.y + static_cast<float>(p->y));
}

}  // namespace phonglab

namespace phonglab {

namespace {

bool parse_numbers(const std::vector<std::string>& w, std::size_t first, std::vector<double>& out) {
  for (std::size_t i = first; i < w.size(); ++i) {
    double v = 0;
    if (!script::parse_double(w[i], v)) return false;
    out.push_back(v);
  }
  return true;
}

}  // namespace

// The scene-building commands of the test scripts (docs/previewer.md, "Test scripts"): nullopt
// when `w` is none of them, else "" or what is wrong with the command. An edit the scene's rules
// refuse (a radius of -1, a material in use) is not a broken script: the program says why, as
// the panel does, in dump_state's objects_notice and on stderr, and the script goes on.
std::optional<std::string> SceneBuilder::script_scene_command(const std::vector<std::string>& w) {
  notice_.refused = false;  // what this command refuses, not an earlier one
  const std::optional<std::string> usage = script_scene_edit(w);
  if (usage && usage->empty() && notice_.refused) {
    std::cerr << "phonglab: " << w[0] << ": " << notice_.text << "\n";
  }
  return usage;
}

std::optional<std::string> SceneBuilder::script_scene_edit(const std::vector<std::string>& w) {
  const std::string& name = w[0];
  int index = -1;
  const auto object_word = [&](std::size_t i) { return w.size() > i && script::parse_int(w[i], index); };
  if (name == "add_object") {
    const ObjectRef::Kind kind = w.size() >= 2 ? ui::kind_from_name(w[1]) : ObjectRef::Kind::kNone;
    const bool mesh = kind == ObjectRef::Kind::kMesh;
    if (kind == ObjectRef::Kind::kNone || w.size() != (mesh ? 3u : 2u)) {
      return "usage: add_object sphere|plane|triangle|mesh [OBJ_PATH]";
    }
    add_object(kind, mesh ? w[2] : std::string());
    return "";
  }
  if (name == "select_object") {
    if (w.size() != 2 || !object_word(1)) return "usage: select_object I";
    if (index < -1 || index >= ui::object_count(s_.doc.scene())) {
      refuse("no objects[" + w[1] + "]");
      return "";
    }
    select_object(index);
    return "";
  }
  if (name == "delete_object") {
    if (w.size() != 2 || !object_word(1)) return "usage: delete_object I";
    delete_object(index);
    return "";
  }
  if (name == "duplicate_object") {
    if (w.size() != 2 || !object_word(1)) return "usage: duplicate_object I";
    duplicate(index);
    return "";
  }
  if (name == "set" && w.size() >= 4 && w[1] == "object") {
    if (!object_word(2)) return "usage: set object I FIELD V..";
    std::vector<double> values;
    const bool text = w[3] == "material" || w[3] == "name";
    if (text && w.size() != 5) return "usage: set object I material|name TEXT";
    if (!text && !parse_numbers(w, 4, values)) return "set object: the values must be numbers";
    set_object(index, w[3], values, text ? w[4] : std::string());
    return "";
  }
  if (name == "new_material") {
    if (w.size() != 2) return "usage: new_material NAME";
    add_material(w[1]);
    return "";
  }
  if (name == "material_preset") {
    if (w.size() != 3) return "usage: material_preset NAME PRESET";
    apply_material_preset(w[1], w[2]);
    return "";
  }
  if (name == "drop") {
    if (w.size() != 2) return "usage: drop PATH";
    drop_file(w[1]);
    return "";  // a refused drop is the program's message, not a broken script
  }
  return std::nullopt;
}

}  // namespace phonglab
