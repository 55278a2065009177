// The page's document and its edits: opening a scene, the materials' and lights' coefficients,
// undo and redo, navigation, the lights' markers and their drag. Every edit is the session's (one
// undo step a gesture) and restarts the image.
#pragma once

#include <string>

#include "apps/web/page_state.h"

namespace phonglab {

class WebLesson;

class WebScene {
 public:
  WebScene(PageState& state, PageImage& image, WebLesson& lesson) : s_(state), image_(image), lesson_(lesson) {}
  WebScene(const WebScene&) = delete;
  WebScene& operator=(const WebScene&) = delete;

  // The document: an embedded scene's name or a file in the page's memory file system (an
  // upload): "" or the positioned errors, the last good scene kept.
  std::string open(const std::string& scene_arg);
  std::string scene_json() const;
  // The files the scene needs beside it when downloaded (an embedded scene's OBJ and MTL files,
  // io's embedded_mesh_files): JSON [{"path": "cornell/...", "text": ...}], [] for none.
  std::string mesh_files_json() const;
  std::string source() const { return s_.session.document().source(); }
  // What the scene list shows for the document: an embedded scene's name, a file's name, or the
  // scene a lesson's step showed (also after the lesson is left).
  std::string scene_label() const;

  int material_count() const { return static_cast<int>(s_.session.scene().materials.size()); }
  std::string material_name(int m) const;
  double coefficient(int m, const std::string& name) const;  // a colour's largest channel, or n, ior
  void set_coefficient(int m, const std::string& name, double value, bool held);
  int light_count() const { return static_cast<int>(s_.session.scene().lights.size()); }
  double light_intensity(int l) const;  // the largest channel
  void set_light_intensity(int l, double value, bool held);
  bool undo();
  bool redo();

  // Navigation, as on the desktop: a drag orbits about look_at, the wheel dollies, a shift-drag
  // (or the middle button) pans.
  void orbit(double dx_px, double dy_px);  // never under the scene's floor (ui::orbit_in)
  void reset_camera();                      // the camera the document was read with (the key R)
  void dolly(double steps);
  void pan(double dx_px, double dy_px);
  // The point lights' markers: JSON [[x, y] or null (behind the camera or not a point light), ...]
  // in the image's pixels. A marker dragged moves its light in the view plane at the depth it
  // had when grabbed (light_depth), one undo step for the drag (held until the hand is off).
  std::string light_markers() const;
  double light_depth(int l) const;
  void drag_light(int l, double x_px, double y_px, double depth);

 private:
  void apply(const Edit& e);  // to the session; a change is made by hand (the lesson explored) and restarts

  PageState& s_;
  PageImage& image_;
  WebLesson& lesson_;
};

}  // namespace phonglab
