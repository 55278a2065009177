// The Objects panel and the materials' library buttons: building a scene (issue 16). They edit
// nothing themselves: each press or field comes back as a request the app carries out through
// src/interaction/scene_objects.h, so a refusal keeps the scene and is shown as `notice`.
#include <algorithm>
#include <cfloat>
#include <array>
#include <string>

#include "interaction/material_presets.h"
#include "interaction/scene_objects.h"
#include "ui/panels.h"
#include "ui/widgets.h"

namespace phonglab::ui {

namespace {

using Kind = ObjectRef::Kind;

// A button that scripts can find by `name`; whether it was pressed.
bool button(const char* label, const std::string& name) {
  const bool pressed = ImGui::Button(label);
  locate(name);
  return pressed;
}

// One three-number field of the selected object: edited values come back as a request.
void vec3_field(const char* label, const char* name, Vec3 v, const char* field, ObjectActions& actions) {
  if (drag_vec3(label, v, 0.01f, "%.3f")) {
    actions.field = field;
    actions.values = {v.x, v.y, v.z};
  }
  locate(name);
}

void selected_fields(const Scene& scene, int selected, ObjectActions& actions) {
  const ObjectRef r = object_at(scene, selected);
  const auto i = static_cast<std::size_t>(r.index);
  ImGui::PushID(selected);
  // Its name, kept in the file (Enter renames; empty: objects[i] and its kind).
  std::string name = object_name_of(scene, selected);
  if (input_text("name", name, ImGuiInputTextFlags_EnterReturnsTrue)) {
    actions.field = "name";
    actions.text = name;
  }
  locate("objects.name");
  switch (r.kind) {
    case Kind::kSphere: {
      vec3_field("centre", "objects.center", scene.spheres[i].center, "center", actions);
      double radius = scene.spheres[i].radius;
      if (slider_double("radius", radius, 0.001, 100.0, "%.3f", true)) {
        actions.field = "radius";
        actions.values = {radius};
      }
      locate("objects.radius");
      break;
    }
    case Kind::kPlane:
      vec3_field("point", "objects.point", scene.planes[i].point, "point", actions);
      vec3_field("normal", "objects.normal", scene.planes[i].normal, "normal", actions);
      break;
    case Kind::kTriangle:
      vec3_field("v0", "objects.v0", scene.triangles[i].v0, "v0", actions);
      vec3_field("v1", "objects.v1", scene.triangles[i].v1, "v1", actions);
      vec3_field("v2", "objects.v2", scene.triangles[i].v2, "v2", actions);
      break;
    case Kind::kMesh: {
      const MeshTransform& t = scene.meshes[i].transform;
      ImGui::TextDisabled("%s", scene.meshes[i].file.c_str());
      vec3_field("translate", "objects.translate", t.translate, "translate", actions);
      vec3_field("rotate (deg)", "objects.rotate_deg", t.rotate_deg, "rotate_deg", actions);
      vec3_field("scale", "objects.scale", t.scale, "scale", actions);
      break;
    }
    default:
      break;
  }
  // Any material for any object (a mesh: one for all its faces, replacing its MTL's).
  const int current = object_material(scene, selected);
  const char* shown = current >= 0 ? scene.materials[static_cast<std::size_t>(current)].name.c_str()
                                   : "(the MTL file's)";
  if (ImGui::BeginCombo("material", shown)) {
    for (const Material& m : scene.materials) {
      if (ImGui::Selectable(m.name.c_str(), m.name == shown)) {
        actions.field = "material";
        actions.text = m.name;
      }
    }
    ImGui::EndCombo();
  }
  locate("objects.material");
  ImGui::PopID();
}

}  // namespace

void objects_panel(const Scene& scene, int& selected, std::string& mesh_path, const EditNotice& notice,
                   ObjectActions& actions) {
  const int count = object_count(scene);
  if (selected >= count) selected = -1;
  const auto rows = static_cast<float>(std::clamp(count, 1, 6));
  if (ImGui::BeginListBox("##objects", ImVec2(-FLT_MIN, ImGui::GetTextLineHeightWithSpacing() * (rows + 0.4f)))) {
    for (int i = 0; i < count; ++i) {
      ImGui::PushID(i);
      if (ImGui::Selectable(object_label(scene, i).c_str(), selected == i)) selected = i;
      ImGui::PopID();
    }
    if (count == 0) ImGui::TextDisabled("No objects: add one below.");
    ImGui::EndListBox();
  }
  // Added in front of the camera, at its look-at point, and selected.
  for (const Kind kind : {Kind::kSphere, Kind::kPlane, Kind::kTriangle}) {
    const std::string label = "+ " + std::string(kind_name(kind));
    if (button(label.c_str(), "objects.add_" + std::string(kind_name(kind)))) actions.add = kind;
    ImGui::SameLine();
  }
  ImGui::BeginDisabled(selected < 0);
  if (button("Duplicate", "objects.duplicate")) actions.duplicate = selected;
  ImGui::SameLine();
  if (button("Delete", "objects.delete")) actions.remove = selected;
  ImGui::EndDisabled();
  input_text("##obj", mesh_path);
  locate("objects.mesh_path");
  ImGui::SameLine();
  if (button("+ mesh (OBJ)", "objects.add_mesh")) actions.add = Kind::kMesh;
  if (!notice.text.empty()) ImGui::TextColored(notice.refused ? kErrorColor : kWarningColor, "%s", notice.text.c_str());
  if (selected >= 0) {
    ImGui::TextDisabled("Drag its handle in the view, or its surface with Alt held: over the floor (hold V: up and down; X, Y or Z: one axis), or type its numbers:");
    selected_fields(scene, selected, actions);
  } else {
    ImGui::TextDisabled("Click an object in the view or the list to select it.");
  }
}

void material_library(const Scene& scene, int selected, std::string& name_field, MaterialActions& actions) {
  const bool has = selected >= 0 && selected < static_cast<int>(scene.materials.size());
  if (button("New", "materials.new")) actions.add = true;
  ImGui::SameLine();
  ImGui::BeginDisabled(!has);
  if (button("Duplicate", "materials.duplicate")) actions.duplicate = true;
  ImGui::SameLine();
  if (button("Delete", "materials.delete")) actions.remove = true;
  ImGui::EndDisabled();
  // The new name on a row of its own, as wide as the panel leaves it: never past the edge.
  ImGui::BeginDisabled(!has);
  if (button("Rename to", "materials.rename")) actions.rename = name_field;
  ImGui::EndDisabled();
  ImGui::SameLine();
  ImGui::SetNextItemWidth(-FLT_MIN);
  input_text("##material_name", name_field);
  locate("materials.name");
  // The preset library, by group: one press, one undo step.
  ImGui::BeginDisabled(!has);
  if (ImGui::BeginCombo("preset", "apply a preset...")) {
    std::string_view group;
    for (const MaterialPreset& p : material_presets()) {
      if (p.group != group) {
        group = p.group;
        ImGui::TextDisabled("%.*s", static_cast<int>(group.size()), group.data());
      }
      const std::string label = std::string(p.name);
      if (ImGui::Selectable(label.c_str())) actions.preset = label;
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", with_font_subscripts(preset_note(p)).c_str());
    }
    ImGui::EndCombo();
  }
  locate("materials.preset");
  ImGui::EndDisabled();
  // The classic table's ka was made for a dim ambient: say how the scene's is taken into account.
  ImGui::TextDisabled("%s", ("A preset's ka is scaled to this scene's " + i_a() + " (the classic table assumes 0.2).").c_str());
}

}  // namespace phonglab::ui
