// The previewer's panels down the right, in the order a lecture uses them: what is shown,
// materials, objects, lights, the probe, the instruments, rays, camera, file, render settings. Each
// draws ImGui widgets over the shell's state and turns what they change into session edits or
// settings (src/ui holds the widgets themselves). It reaches the shell's shared state (ShellState,
// shell_state.h) and the components it works with, given by reference.
#pragma once

namespace phonglab {

struct ShellState;
class FileShell;
class FormulaShell;
class Instruments;
class LessonShell;
class SceneBuilder;

class Sidebar {
 public:
  Sidebar(ShellState& shell, SceneBuilder& builder, FileShell& files, FormulaShell& formulas, LessonShell& lesson_shell, Instruments& tools)
      : s_(shell), builder_(builder), files_(files), formulas_(formulas), lesson_shell_(lesson_shell), tools_(tools) {}
  Sidebar(const Sidebar&) = delete;
  Sidebar& operator=(const Sidebar&) = delete;

  void draw_sidebar();  // the panels; edits set the shell's flags

 private:
  void sidebar_show();
  void sidebar_materials();
  void sidebar_ambient_fit();  // the selected material's best constant ambient for this view
  void sidebar_objects();
  void sidebar_lights();
  void sidebar_probe();
  void sidebar_instruments();
  void sidebar_rays();
  void sidebar_camera();
  void sidebar_file();
  void sidebar_render();

  ShellState& s_;  // the shell's shared state (shell_state.h)
  SceneBuilder& builder_;
  FileShell& files_;
  FormulaShell& formulas_;
  LessonShell& lesson_shell_;
  Instruments& tools_;
  // The probe panel's tallest height for the pixel probed now: the panel keeps it while the same
  // pixel stays probed, so the widgets below never jump under the pointer when its text shortens
  // (a depth cut, fewer digits); a new pixel starts again.
  float probe_height_ = 0;
  int probe_key_[3] = {-1, -1, 0};  // x, y and whether a tree is shown
};

}  // namespace phonglab
