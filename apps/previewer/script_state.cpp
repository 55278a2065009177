// `dump_state`: the previewer's state as key=value lines for the test scripts (docs/previewer.md
// lists the keys).
#include <algorithm>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <sstream>

#include "apps/previewer/viewer_app.h"
#include "interaction/scene_objects.h"
#include "ui/ray_tree_overlay.h"

namespace phonglab {

std::string ScriptDriver::depth_cut_label() const {
  // The depth-cut slider's text, as the Rays panel shows it.
  const int top = std::max(s_.doc.scene().max_depth, 0);
  char text[80];
  std::snprintf(text, sizeof text, ui::depth_cut_format(top).c_str(), std::clamp(s_.rays.cut_depth, 0, top));
  return text;
}

namespace {

std::string vec(const Vec3& v) {
  std::ostringstream s;
  s << v.x << " " << v.y << " " << v.z;
  return s.str();
}

}  // namespace

void ScriptDriver::write_state(const std::string& path) const {
  std::ofstream out(path);
  write_document_state(out);
  write_layout_state(out);
  write_rays_state(out);
  write_probe_state(out);
  lesson_shell_.write_lesson_state(out);
  out << "script_skipped=" << run_.ignored << "\n";
  out << "recovery_offer=" << (files_.recovery().offer ? files_.recovery().offer->source : "") << "\n"
      << "recovery_file=" << s_.session.recovery().written() << "\n";
}

// The document, the view and the renderer's progress.
void ScriptDriver::write_document_state(std::ostream& out) const {
  const Scene& scene = s_.doc.scene();
  const ProgressiveStatus status = s_.renderer.status();
  const bool have_material = s_.selected_material >= 0 && s_.selected_material < static_cast<int>(scene.materials.size());
  int window_w = 0, window_h = 0, fb_w = 0, fb_h = 0;
  s_.platform.window_size(window_w, window_h);
  s_.platform.framebuffer_size(fb_w, fb_h);
  std::string first_error_line = files_.file_state().error_text.substr(0, files_.file_state().error_text.find('\n'));
  const std::vector<std::string> caption_lines = overlays_.captions();
  out << "source=" << s_.doc.source() << "\n"
      << "file=" << s_.doc.file_path() << "\n"
      << "dirty=" << (s_.doc.dirty() ? 1 : 0) << "\n"
      << "modal=" << (files_.guard_visible() ? 1 : 0) << "\n"
      << "conflict=" << (files_.conflict_visible() ? 1 : 0) << "\n"
      << "error=" << first_error_line << "\n"
      << "picked=" << s_.picked_text << "\n"
      << "selected_material=" << (have_material ? scene.materials[static_cast<std::size_t>(s_.selected_material)].name : "") << "\n"
      << "selected_light=" << s_.selected_light << "\n"
      << "hovered_light=" << s_.hovered_light << "\n"
      << "lights=" << scene.lights.size() << "\n"
      << "scene_ambient=" << vec(scene.ambient) << "\n"
      << "camera_position=" << vec(scene.camera.position) << "\n"
      << "camera_look_at=" << vec(scene.camera.look_at) << "\n"
      << "camera_up=" << vec(scene.camera.up) << "\n"
      << "camera_fov=" << std::setprecision(17) << (s_.schedule.snapshot() ? s_.schedule.snapshot()->scene().camera.fov_y_deg : view_camera(s_).fov_y_deg)
      << std::setprecision(6) << "\n"
      << "generation=" << status.generation << "\n"
      << "drawn_generation=" << s_.drawn_generation << "\n"
      << "spp=" << s_.shown.spp << "\n"
      << "divisor=" << s_.shown.divisor << "\n"
      << "quads=" << (s_.shown.quads ? 1 : 0) << "\n"
      << "image=" << s_.shown.width << "x" << s_.shown.height << "\n"
      << "render=" << s_.schedule.width() << "x" << s_.schedule.height() << "\n"
      << "window=" << window_w << "x" << window_h << "\n"
      << "view=" << s_.viewport.x << " " << s_.viewport.y << " " << s_.viewport.width << " " << s_.viewport.height << "\n"
      << "framebuffer=" << fb_w << "x" << fb_h << "\n"
      << "image_rows_from_top=" << (s_.image_view.rows_from_top() ? 1 : 0) << "\n"
      << "frames_drawn=" << s_.stats.frames_drawn << "\n"
      << "nan_count=" << s_.shown.stats.nan_count << "\n"
      << "edit_to_image_ms=" << s_.stats.last_latency_ms << "\n"
      << "edit_first_image=" << s_.stats.last_first_image << "\n"
      << "status=" << files_.file_state().status << "\n"
      << "changed_on_disk=" << (files_.file_state().changed_on_disk ? 1 : 0) << "\n"
      << "sidebar=" << (s_.sidebar_visible ? 1 : 0) << "\n"
      << "sidebar_toggles=" << s_.sidebar_toggles << "\n"
      << "help=" << (s_.help_visible ? 1 : 0) << "\n"
      << "ui_size=" << s_.display.ui_size << "\n"
      << "ui_scale=" << s_.platform.ui_scale() << "\n"
      << "light_markers=" << (s_.display.light_markers ? 1 : 0) << "\n"
      << "stats_details=" << (s_.display.stats_details ? 1 : 0) << "\n"
      << "camera_notice=" << s_.camera_notice << "\n"
      << "camera_distance=" << glm::length(scene.camera.position - scene.camera.look_at) << "\n"
      << "can_save=" << (files_.flow().can_save() ? 1 : 0) << "\n"
      << "figure_status=" << s_.figure_status << "\n"
      << "compare_caption=" << (s_.instruments.compare != 0 ? tools_.compare_caption() : "") << "\n"
      << "captions=" << caption_lines.size() << "\n";
  for (std::size_t i = 0; i < caption_lines.size(); ++i) out << "caption" << i << "=" << caption_lines[i] << "\n";
}

// Where things were drawn last frame, the lights and materials, history and instruments.
void ScriptDriver::write_layout_state(std::ostream& out) const {
  const Scene& scene = s_.doc.scene();
  // The boxes over the image and the named widgets, where they were drawn last frame: x y width height.
  for (const auto& [id, rect] : s_.overlay_rects) {
    out << "overlay_" << id.substr(2) << "=" << rect.min.x << " " << rect.min.y << " " << rect.max.x - rect.min.x << " "
        << rect.max.y - rect.min.y << "\n";
  }
  for (const auto& [item, rect] : s_.item_locations.rects) {
    out << "item_" << item << "=" << rect.min.x << " " << rect.min.y << " " << rect.max.x - rect.min.x << " "
        << rect.max.y - rect.min.y << "\n";
  }
  for (std::size_t i = 0; i < scene.lights.size(); ++i) out << "light" << i << "_position=" << vec(scene.lights[i].position) << "\n";
  // Where each point light's marker was drawn (window coordinates) and whether it is an arrow at
  // the edge (the light out of view).
  for (const ui::LightMarker& m : s_.markers) {
    out << "light" << m.index << "_marker=" << m.pos.x << " " << m.pos.y << "\n"
        << "light" << m.index << "_offscreen=" << (m.offscreen ? 1 : 0) << "\n";
  }
  for (const Material& m : scene.materials) {
    out << "material_" << m.name << "_ka=" << vec(m.ka) << "\n"
        << "material_" << m.name << "_kd=" << vec(m.kd) << "\n"
        << "material_" << m.name << "_n=" << m.n << "\n";
  }
  // The objects in file order: kind, anchor, material; the selection and the last edit's notice.
  out << "file_browser=" << (files_.browser().visible() ? (files_.browser().saving() ? "save" : "open") : "") << "\n"
      << "file_browser_folder=" << files_.browser().folder() << "\n"
      << "file_browser_name=" << files_.browser().name() << "\n"
      << "recent=" << files_.browser().recent().size() << "\n";
  for (std::size_t i = 0; i < files_.browser().recent().size(); ++i) out << "recent" << i << "=" << files_.browser().recent()[i] << "\n";
  out << "objects=" << ui::object_count(scene) << "\n"
      << "selected_object=" << s_.selected_object << "\n"
      << "objects_notice=" << builder_.notice().text << "\n"
      << "materials=" << scene.materials.size() << "\n";
  for (int i = 0; i < ui::object_count(scene); ++i) {
    const int m = ui::object_material(scene, i);
    out << "object" << i << "_kind=" << ui::kind_name(ui::object_at(scene, i).kind) << "\n"
        << "object" << i << "_anchor=" << vec(ui::object_anchor(scene, i)) << "\n"
        << "object" << i << "_material=" << (m >= 0 ? scene.materials[static_cast<std::size_t>(m)].name : "") << "\n";
    const ObjectRef r = ui::object_at(scene, i);
    if (r.kind == ObjectRef::Kind::kSphere) out << "object" << i << "_radius=" << scene.spheres[static_cast<std::size_t>(r.index)].radius << "\n";
    if (const std::optional<ImVec2> at = builder_.object_screen_point(i)) out << "object" << i << "_screen=" << at->x << " " << at->y << "\n";
  }
  std::string enabled;
  for (const Light& light : scene.lights) enabled += light.enabled ? '1' : '0';
  out << "lights_enabled=" << enabled << "\n"
      << "undo=" << s_.session.undo_count() << "\n"
      << "redo=" << s_.session.redo_count() << "\n"
      << "multiples=" << (s_.instruments.small_multiples ? 1 : 0) << "\n"
      << "wipe=" << s_.instruments.wipe << "\n"
      << "compare=" << s_.instruments.compare << "\n"
      << "have_a=" << (tools_.compare().has_image() ? 1 : 0) << "\n"
      << "head=" << (s_.schedule.eye() ? 1 : 0) << "\n";
  if (s_.schedule.eye()) out << "head_eye=" << vec(*s_.schedule.eye()) << "\n";
}

// The Formula panel: each slot's text (newlines as \\n) and error, the view, the check.
static void write_formula_state(std::ostream& out, const FormulaShell& shell, const FormulaBook& book) {
  const auto one_line = [](std::string text) {
    for (std::size_t at = 0; (at = text.find('\n', at)) != std::string::npos; at += 2) text.replace(at, 1, "\\n");
    return text;
  };
  for (int s = 0; s < kFormulaSlots; ++s) {
    const auto slot = static_cast<FormulaSlot>(s);
    const FormulaBook::Slot& f = book.slot(slot);
    out << "formula_" << formula_slot_name(slot) << "=" << one_line(f.text) << "\n"
        << "formula_error_" << formula_slot_name(slot) << "=" << (f.error ? f.error->text() : std::string()) << "\n";
  }
  out << "formula_view=" << ui::formula_view_name(shell.view()) << "\n"
      << "formula_probe=" << one_line(shell.panel().probe) << "\n"
      << "formula_checking=" << (shell.check_settled() ? 0 : 1) << "\n"
      << "formula_file_status=" << shell.formulas_status() << "\n";
  out << "image_check_name=" << shell.image_name() << "\n"
      << "image_check_error=" << shell.image_error() << "\n";
  if (const std::optional<CheckResult>& r = shell.image_check()) {
    out << "image_check_verdict=" << (r->match ? "match" : "differs") << "\n"
        << "image_check_differing=" << r->differing << "\n"
        << "image_check_mistake=" << r->mistake << "\n"
        << "image_check_summary=" << check_summary(*r) << "\n";
  } else {
    out << "image_check_verdict=\n";
  }
  if (const std::optional<CheckResult>& r = shell.last_check(); r && book.any()) {
    out << "formula_verdict=" << (r->match ? "match" : "differs") << "\n"
        << "formula_differing=" << r->differing << "\n"
        << "formula_nan=" << r->nan << "\n"
        << "formula_mistake=" << r->mistake << "\n"
        << "formula_summary=" << check_summary(*r) << "\n";
  } else {
    out << "formula_verdict=\n";
  }
}

void ScriptDriver::write_rays_state(std::ostream& out) const {
  write_formula_state(out, formulas_, s_.session.formulas());
  const Scene& scene = s_.doc.scene();
  // Rays: the overlay as drawn in the last frame, the depth cut and the heat map.
  int tree_blocked = 0, tree_deepest = 0;
  for (const ScreenSegment& segment : s_.tree_segments) {
    tree_blocked += segment.kind == TreeSegmentKind::kShadowBlocked ? 1 : 0;
    if (segment.kind == TreeSegmentKind::kReflection || segment.kind == TreeSegmentKind::kRefraction) {
      tree_deepest = std::max(tree_deepest, segment.depth);
    }
  }
  out << "term=" << term_name(s_.render_settings.term) << "\n"
      << "ambient_view=" << ui::ambient_view_name(s_.render_settings.ambient_view) << "\n"
      << "ray_tree=" << (s_.rays.overlay ? 1 : 0) << "\n"
      << "tree_segments=" << s_.tree_segments.size() << "\n"
      << "tree_blocked=" << tree_blocked << "\n"
      << "tree_deepest=" << tree_deepest << "\n"
      << "depth_cut=" << (s_.rays.depth_cut ? s_.rays.cut_depth : -1) << "\n"
      << "depth_cut_label=" << depth_cut_label() << "\n"
      << "scene_max_depth=" << scene.max_depth << "\n"
      << "render_max_depth=" << (s_.schedule.snapshot() ? s_.schedule.snapshot()->scene().max_depth : -1) << "\n"
      << "heat=" << (tools_.heat_shown() ? 1 : 0) << "\n"
      << "heat_max=" << s_.heat_max << "\n";
}

// The probed pixel: where, what it hit, its blocked shadow rays, and whether it matches the image.
void ScriptDriver::write_probe_state(std::ostream& out) const {
  if (!tools_.probe().tree) return;
  const Color total = tools_.probe().tree->root.total;
  const ImVec2 on_screen = overlays_.probe_point_in_cell(cells(s_).count() - 1);
  out << "probe_cli=" << tools_.probe_cli_command() << "\n";
  out << "probe_pixel=" << tools_.probe().x << " " << tools_.probe().y << "\n"
      << "probe_screen=" << on_screen.x << " " << on_screen.y << "\n"
      << "probe_hit=" << (tools_.probe().tree->root.hit ? 1 : 0) << "\n"
      << "probe_total=" << vec(total) << "\n";
  // Shadow rays of the probed tree that found their light blocked (the overlay's red rays).
  int blocked = 0;
  std::vector<const ProbeNode*> stack{&tools_.probe().tree->root};
  while (!stack.empty()) {
    const ProbeNode* node = stack.back();
    stack.pop_back();
    for (const ProbeLight& light : node->lights) blocked += light.lit_side && !light.visible ? 1 : 0;
    if (node->reflection) stack.push_back(node->reflection.get());
    if (node->refraction) stack.push_back(node->refraction.get());
  }
  const IndirectProbe& indirect = tools_.probe().indirect;
  out << "probe_ambient=" << vec(indirect.ambient) << "\n"
      << "probe_indirect=" << vec(indirect.mean) << "\n"
      << "probe_indirect_se=" << vec(indirect.standard_error) << "\n"
      << "probe_indirect_samples=" << indirect.samples << "\n"
      << "probe_fitted_ka=" << vec(indirect.fitted_ka) << "\n";
  out << "probe_blocked=" << blocked << "\n"
      << "probe_rays=" << tools_.probe().tree->rays.total() << "\n";
  // The shown image's pixel there, when it is the full-resolution 1-spp image of this
  // snapshot: the probe must reproduce it exactly (as float, the texture's precision).
  if (s_.shown.divisor == 1 && !s_.shown.quads && s_.shown.spp == 1 && s_.shown.width == s_.schedule.width() && s_.shown.height == s_.schedule.height()) {
    const glm::vec3 shown = s_.shown.pixels[static_cast<std::size_t>(tools_.probe().y) * static_cast<std::size_t>(s_.shown.width) +
                                          static_cast<std::size_t>(tools_.probe().x)];
    out << "probe_match=" << (glm::vec3(total) == shown ? 1 : 0) << "\n";
  }
}

}  // namespace phonglab
