// Building a scene: the objects of the scene file's "objects" array and the materials they use,
// added, duplicated, deleted, moved and edited as plain data (no ImGui, no files). An object is
// named by its index I in that array, as the file and the previewer's scripts count them; the
// Scene keeps the typed vectors plus, for each primitive, that index (sphere_object, ...), and
// every edit here keeps those indices a permutation of 0..count-1.
//
// Every edit returns an empty string or what was wrong, in words a user reads ("objects[3] is a
// plane: it has no radius"), and leaves the scene untouched when it fails. Mesh geometry is
// loaded by the caller (src/io): here a mesh's transform or file is only recorded.
#pragma once

#include <string>
#include <vector>

#include "core/scene/scene.h"

namespace phonglab::ui {

// The objects in file order. A scene built in code may leave the file indices out:
// complete_object_indices numbers the rest after the indexed ones, in vector order, as the
// writer orders them (every edit below does it first).
void complete_object_indices(Scene& scene);
int object_count(const Scene& scene);
ObjectRef object_at(const Scene& scene, int object);  // kind kNone when out of range
int file_object_of(const Scene& scene, const ObjectRef& ref);  // the inverse: -1 for none
std::string_view kind_name(ObjectRef::Kind kind);      // "sphere", "plane", "triangle", "mesh"
// The kind a name gives; kNone for anything else.
ObjectRef::Kind kind_from_name(std::string_view name);
// The object's material index (a mesh: its override's, or -1 when its MTL's are used).
int object_material(const Scene& scene, int object);
// A point that stands for the object: a sphere's centre, a plane's point, a triangle's centroid,
// a mesh's translation.
Vec3 object_anchor(const Scene& scene, int object);
// The object's optional name ("" for none); "objects[2] \"ball\": sphere, plastic" for lists and messages.
std::string object_name_of(const Scene& scene, int object);
std::string object_label(const Scene& scene, int object);

// Where a new object goes: in front of the camera, at its look-at point, sized to a tenth of
// the distance to it.
struct Placement {
  Vec3 at{0};       // look-at point
  Vec3 right{1, 0, 0}, up{0, 1, 0}, towards_eye{0, 0, 1};  // the camera's frame
  double size = 1;  // a tenth of the eye's distance to the look-at point
};
Placement placement_in_front_of(const Camera& camera);

// Appends an object of `kind` (sphere, plane or triangle) at `where` with `material`; returns
// its index. A mesh comes through append_mesh_object.
int add_primitive(Scene& scene, ObjectRef::Kind kind, const Placement& where, int material);
// Appends a mesh object (its geometry may still be missing: the caller loads it).
int append_mesh_object(Scene& scene, Mesh mesh);
std::string delete_object(Scene& scene, int object);
// Appends a copy of the object; `copy` receives its index.
std::string duplicate_object(Scene& scene, int object, int& copy);
// Moves the object by `delta`: a sphere's centre, a plane's point, a triangle's corners, a
// mesh's translation (its geometry must then be placed again).
std::string move_object(Scene& scene, int object, const Vec3& delta);
// `set object I FIELD V..` of the scripts and the Objects panel's fields: center, radius
// (spheres), point, normal (planes), v0, v1, v2 (triangles), translate, rotate_deg, scale
// (meshes), material NAME and name TEXT (any; an empty name removes it). `values` are the
// numbers (three, or one for radius; a scale may be one number for all three axes); `text` the
// material's name or the object's new name.
std::string set_object_field(Scene& scene, int object, const std::string& field, const std::vector<double>& values,
                             const std::string& text = {});
// Whether an edit of this field changes a mesh's placement (its geometry must be loaded again).
bool moves_mesh_geometry(const std::string& field);

// Materials.
int find_material(const Scene& scene, const std::string& name);  // -1: none
// A name not yet used: `base`, else base 2, base 3, ...
std::string unused_material_name(const Scene& scene, const std::string& base);
// Appends a material named `name` (grey plastic); fails when the name is taken or empty.
std::string new_material(Scene& scene, const std::string& name, int& index);
std::string duplicate_material(Scene& scene, int material, int& copy);
std::string rename_material(Scene& scene, int material, const std::string& name);
// Whether the object uses the material (a mesh through its override or its MTL's triangles),
// and how many objects do.
bool uses_material(const Scene& scene, int object, int material);
int material_users(const Scene& scene, int material);
// Deletes a material no object uses; one in use is refused, saying which object uses it.
std::string delete_material(Scene& scene, int material);

}  // namespace phonglab::ui
