// What the previewer draws over the image, apart from each other and from the panels: the stats
// box, the captions (the term shown, the depth cut, the compare), the "move your head" plot, the
// small multiples' labels and the probed pixel's ring, the wipe line, the light markers and the
// arrows to lights out of view, the probed pixel's ray tree, the selected object. It reads the
// shell's shared state (ShellState, shell_state.h) and the components it works with, given by
// reference.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <imgui.h>

#include "ui/overlay.h"

namespace phonglab {

struct ShellState;
class FileShell;
class Instruments;
class LessonShell;
class SceneBuilder;

class Overlays {
 public:
  Overlays(ShellState& shell, SceneBuilder& builder, FileShell& files, LessonShell& lesson_shell, Instruments& tools)
      : s_(shell), builder_(builder), files_(files), lesson_shell_(lesson_shell), tools_(tools) {}
  Overlays(const Overlays&) = delete;
  Overlays& operator=(const Overlays&) = delete;

  void draw_overlays();                          // boxes, captions, markers and labels over the image, apart
  std::vector<std::string> captions() const;     // what the top-centre captions say, top first
  ImVec2 probe_point_in_cell(int cell) const;    // the probed pixel's centre as cell `cell` shows it
  bool light_markers_shown() const;
  std::optional<float> wipe_line_x() const;      // where the wipe's split line is drawn, when it is

 private:
  void draw_stats();                             // the stats box's contents
  void draw_head_plot();                         // the "move your head" plot's contents
  void draw_cell_labels_and_probe_ring();        // small multiples' labels, the probed pixel's ring
  void draw_wipe_line();
  void draw_light_markers(const std::vector<ui::ScreenRect>& taken);  // markers and labels, clear of `taken`
  void draw_ray_tree_lines();                    // the probed tree over the full image's cell
  void draw_selected_object();                   // its outline or handle where the view shows it

  ShellState& s_;  // the shell's shared state (shell_state.h)
  SceneBuilder& builder_;
  FileShell& files_;
  LessonShell& lesson_shell_;
  Instruments& tools_;
};

}  // namespace phonglab
