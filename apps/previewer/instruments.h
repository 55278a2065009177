// The teaching instruments' state and rules in the previewer: the probed pixel (its ray tree,
// report and the indirect light's numbers), snapshot A and what the compare views show, the heat
// map, "move your head" (its eye and pivot), the ambient views and the best constant ambient, and
// the image that goes on screen from all of them. It reaches the shell's shared state (ShellState,
// shell_state.h) and the components it works with, given by reference.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include <imgui.h>

#include "core/render/indirect_probe.h"
#include "core/render/progressive.h"
#include "core/render/render.h"
#include "session/snapshot_a.h"
#include "ui/panels.h"

namespace phonglab {

struct ShellState;
class FormulaShell;

class Instruments {
 public:
  // The probed pixel and what the Probe panel shows of it.
  struct ProbeState {
    std::optional<PixelProbe> tree;  // the probed pixel's ray tree, in the shell's snapshot
    int x = 0;                       // the probed render pixel
    int y = 0;
    std::string report;                  // probe_to_text of tree
    bool every_digit = false;            // the probe panel shows every digit (else four significant)
    std::vector<std::string> occluders;  // object_name of each primary-hit light's occluder
    IndirectProbe indirect;              // ka·Ia beside the indirect term's estimate at the pixel
    bool with_indirect = false;          // `indirect` was taken (an ambient view is on)
  };
  Instruments(ShellState& shell, FormulaShell& formulas)
      : s_(shell), formulas_(formulas) {}
  Instruments(const Instruments&) = delete;
  Instruments& operator=(const Instruments&) = delete;

  ProbeState& probe() { return probed_; }
  const ProbeState& probe() const { return probed_; }
  SnapshotA& compare() { return a_; }  // snapshot A (src/session/snapshot_a.h)
  const SnapshotA& compare() const { return a_; }
  std::optional<AmbientFit>& ambient_fit() { return ambient_fit_; }  // the last "best constant ambient for this view"
  std::string& ambient_fit_material() { return ambient_fit_material_; }  // the material it was asked for

  void probe_at(ImVec2 mouse);                   // probes the rendered pixel under a click
  void refresh_probe();                          // probes the same pixel again in the newest snapshot
  void snapshot_a(bool first_full = false);      // asks for A: the image shown, once it is done (or at full resolution)
  int target_spp() const;                        // the renderer's target: a lesson's difference stays at A's samples
  void take_a_when_final();                      // takes the asked-for A when the image is done
  bool a_comparable() const;                     // A and the live image can be compared as the view asks
  void save_figure(const std::string& path);     // the slide figure of the current snapshot
  std::optional<Vec3> head_eye() const;          // "move your head": the shading eye, nullopt when off
  Vec3 head_pivot() const;                       // the point the head turns about: the probed hit or look-at
  std::vector<glm::vec3> display_pixels() const; // the shown image, its heat map, its wipe / difference against A
  bool ambient_view_pixels_shown(ui::AmbientView view) const;  // that view, and a frame that has it
  bool heat_shown() const;                       // the rays view is on screen as a heat map
  bool shows_indirect() const;                   // an ambient view other than ka·Ia is chosen
  void set_heat_map(bool on);                    // switches the rays view on (remembering the term) or back
  std::string compare_caption() const;
  // The probed pixel as `phonglab-cli probe` takes it (the scene's name, the view's size and field
  // of view), or why it cannot be had; "" with no probe or no name to give.
  std::string probe_cli_command() const;           // what the compare view shows, or why it cannot
  // The render pixel under a window point, and the viewport cell (small multiples) it lies in.
  std::optional<std::array<int, 2>> render_pixel_at(ImVec2 mouse) const;

 private:
  std::optional<std::vector<glm::vec3>> ambient_view_pixels() const;  // the ambient views beside / difference
  CompareView compare_view() const;  // the panel's compare choice

  ShellState& s_;  // the shell's shared state (shell_state.h)
  FormulaShell& formulas_;
  ProbeState probed_;
  SnapshotA a_;
  std::optional<AmbientFit> ambient_fit_;
  std::string ambient_fit_material_;
  Term term_before_heat_ = Term::kFull;  // what the heat map switch goes back to
};

}  // namespace phonglab
