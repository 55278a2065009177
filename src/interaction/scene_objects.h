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

#include <optional>
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

// A place in front of the camera, at its look-at point, sized to a tenth of the distance to it
// (the previewer places new objects with place_new_object below).
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

// The floor the objects stand on: of the scene's planes whose normal (either side) is within 30
// degrees of the camera's up, the highest one below every finite object's anchor (below the
// look-at point when there are none), objects[`except`] left out (the one being placed or
// dragged). `normal` is the plane's unit normal on that side.
struct Floor {
  Vec3 point{0};
  Vec3 normal{0, 1, 0};
  int object = -1;  // the plane's index in the file
};
std::optional<Floor> find_floor(const Scene& scene, const Camera& camera, int except = -1);
// How far `p` is above the floor (negative: under it).
double height_above(const Floor& floor, const Vec3& p);
// The object's lowest point's height above the floor (a sphere's centre's height less its radius,
// a triangle's lowest corner, a mesh's lowest vertex); -infinity for a plane.
double lowest_above(const Scene& scene, int object, const Floor& floor);
// How far above the floor an object's lowest point rests: 0 for a sphere or a triangle (they
// touch it at a point or an edge), and for a mesh a hair, kMeshClearance of its largest side: a
// mesh's own flat bottom (a room's floor) must not lie in the floor's plane, where two coplanar
// surfaces would take turns at the nearest hit and speckle.
inline constexpr double kMeshClearance = 1e-3;
double floor_clearance(const Scene& scene, int object);
// The size of the scene's objects: the median sphere diameter; with no spheres, the largest side
// of the finite objects' bounds / 4; with none, a fifth of the eye's distance to the look-at
// point. Two significant digits (0.6, 1.4), objects[`except`] left out.
double typical_size(const Scene& scene, const Camera& camera, int except = -1);

// Gives the object just appended (objects[`object`], a sphere, a triangle or a loaded mesh) the
// scene's typical size and its place beside the others (docs/previewer.md, "Building a scene"):
// resting on the floor when there is one (a sphere's centre a radius above it, a triangle standing
// on its base edge facing the eye, a mesh's lowest vertex floor_clearance above it), at the free spot nearest to the
// point of the floor under the camera's look-at point, the right before the left at equal
// distance, searched on a grid along the floor in the view's right direction and towards the eye,
// spaced by half the new object's radius. Free: its bounds apart from every other finite
// object's; in view: its bounds inside a view of `aspect` (width / height; 0: the scene's image)
// through `camera`; seen: its middle not inside the screen rectangle of a nearer object's bounds.
// Free, in view, seen and not further from the eye than the look-at point first; then free, in
// view and seen anywhere; then free and in view; then free. Without a floor, the same in the view plane
// through the look-at point. A plane is left where it is. A mesh's scale and translation are set
// (its geometry must then be loaded again); the others' numbers are set directly.
std::string place_new_object(Scene& scene, const Camera& camera, double aspect, int object);

// Dragging an object over the floor (docs/previewer.md, "Selecting and moving"). `grab` is the
// point under the pointer when the object was grabbed, with its anchor at `anchor_start`; the
// pointer's ray now starts at `origin` along `dir`. Along the floor: where the ray meets the plane
// through `grab` parallel to the floor (the object's height kept); `vertical`: along the floor's
// normal through `grab`, to the point nearest to the ray. The result is the new anchor, lifted so
// that the object's lowest point stays at or above the floor (or as low as it started, when it
// started under it); nothing when the ray does not meet that plane or line in front of the eye.
std::optional<Vec3> drag_over_floor(const Scene& scene, int object, const Floor& floor, const Vec3& anchor_start,
                                    const Vec3& grab, const Vec3& origin, const Vec3& dir, bool vertical);
// The anchor `anchor` lifted as drag_over_floor lifts it (for the X, Y, Z drags).
Vec3 keep_above_floor(const Scene& scene, int object, const Floor& floor, const Vec3& anchor_start, const Vec3& anchor);
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
// An MTL material whose coefficients an edit changed (`before` -> `after`, material by material)
// becomes the scene file's own: saved in its "materials" under the MTL material's name, which
// the mesh takes it by again when the file is read. Without it the edit would be shown, but
// neither unsaved nor ever written. Undo gives the MTL's back.
void own_edited_mtl_materials(const Scene& before, Scene& after);
// The mesh file whose MTL material `material` stands for (an MTL material, or one edited and
// owned by the scene file); empty for the scene file's other materials.
std::string mtl_origin(const Scene& scene, int material);
// Whether the object uses the material (a mesh through its override or its MTL's triangles),
// and how many objects do.
bool uses_material(const Scene& scene, int object, int material);
int material_users(const Scene& scene, int material);
// Deletes a material no object uses; one in use is refused, saying which object uses it.
std::string delete_material(Scene& scene, int material);

}  // namespace phonglab::ui
