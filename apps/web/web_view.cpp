#include "apps/web/web_view.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "check/check.h"
#include "io/check_report.h"
#include "io/formula_file.h"
#include "io/image_read.h"

#include "core/scene/display8.h"
#include "core/teaching/compare.h"
#include "core/teaching/heat_map.h"
#include "core/teaching/ray_tree_view.h"
#include "interaction/camera_control.h"
#include "interaction/numbers.h"
#include "io/probe_report.h"
#include "io/scene/scene_io.h"

namespace phonglab {
namespace {

constexpr int kColumns = 3, kRows = 2;  // the small multiples: the five terms, then the full image

Color* colour(Material& m, const std::string& name) {
  if (name == "ka") return &m.ka;
  if (name == "kd") return &m.kd;
  if (name == "ks") return &m.ks;
  if (name == "kr") return &m.kr;
  if (name == "kt") return &m.kt;
  return nullptr;
}
double largest(const Color& c) { return std::max({c.x, c.y, c.z}); }
// A colour to `value` at its largest channel, keeping its hue (black becomes grey), each channel
// to float precision as the desktop's panels keep it: a saved file reads 0.008, not
// 0.008000000000000002.
Color scaled(const Color& c, double value) { return ui::tidy_color(largest(c) > 0 ? c * (value / largest(c)) : Color(value)); }

}  // namespace

std::string WebView::open(const std::string& scene_arg) {
  if (!session_.open(scene_arg)) return session_.document().error_text();
  step_scene_.clear();
  tree_pixel_.reset();
  probe_pixel_.reset();
  a_.clear();
  close_lesson();
  restart();
  return "";
}

std::string WebView::scene_json() const { return scene_to_json(session_.scene()); }

std::string WebView::scene_label() const {
  const SceneDocument& document = session_.document();
  if (!document.embedded_name().empty()) return document.embedded_name();
  if (!document.file_path().empty()) return std::filesystem::path(document.file_path()).filename().string();
  return step_scene_.empty() ? document.source() : step_scene_;
}

int WebView::view_term() const {
  if (view_.small_multiples) return -2;
  if (view_.term == Term::kRays) return -3;
  const int term = static_cast<int>(view_.term);
  return term <= static_cast<int>(Term::kRefraction) ? term : -1;
}

void WebView::set_target(int spp) {
  const int before = target_;
  target_ = std::max(spp, 1);
  if (target_ < before && shown_spp_ > static_cast<std::uint32_t>(target_)) restart();
}

void WebView::set_size(int width, int height) {
  width_ = std::max(width, 1);
  height_ = std::max(height, 1);
  restart();
}

void WebView::set_term(int term) {
  view_.term = static_cast<Term>(std::clamp(term, 0, 5));
  view_.small_multiples = false;
  edited_by_hand();
  restart();
}

void WebView::set_heat_map(bool on) {
  view_.term = on ? Term::kRays : Term::kFull;
  view_.small_multiples = false;
  edited_by_hand();
  restart();
}

void WebView::set_head_angle(double degrees) {
  view_.head_angle_deg = degrees != 0 ? std::optional<double>(degrees) : std::nullopt;
  edited_by_hand();
  restart();
}

void WebView::set_interacting(bool on) {
  interacting_ = on;
  // The hand stopped: the gesture is one undo step; the scheduler replaces a live image by the
  // exact re-shade, or goes on to finer levels from the live one.
  if (!on) session_.settle(false);
}

bool WebView::step() {
  // A view changed without a restart (a lesson closed) may change the ladder: it starts again.
  if (!prepared_ || passes_.ladder().levels() != progressive_levels(trace_width(), trace_height(), settings())) {
    begin_generation();
  }
  passes_.update(settings(), interacting_);
  if (!passes_.wants_pass()) return false;
  const auto start = std::chrono::steady_clock::now();
  passes_.step();
  shown_divisor_ = passes_.level().divisor;
  shown_quads_ = passes_.level().quads;
  encode();
  const bool a_taken = a_.requested() && !a_.first_full() &&
                       a_.take_when_ready(static_cast<std::uint64_t>(generation_), shown_, finished());
  if (a_taken) encode();  // shown against the new A
  // The level's time is what the student waits for: the pass and its image encoded.
  passes_.shown(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
  update_lesson();
  return true;
}

int WebView::trace_width() const { return view_.small_multiples ? std::max(1, width_ / kColumns) : width_; }
int WebView::trace_height() const { return view_.small_multiples ? std::max(1, height_ / kRows) : height_; }

// The page's generation, as the desktop's render thread has it (core/render/pass_scheduler.h): the
// image of one cell of the small multiples' grid, the view's term and "move your head"'s eye.
ProgressiveSettings WebView::settings() const {
  ProgressiveSettings s;
  s.term = pass_term();
  s.ambient = view_.ambient;
  s.term_images = view_.small_multiples || ambient_pair();
  s.shading_eye = eye_;
  s.threads = threads_;
  // A difference against a first-full A compares like with like: the live image stays at A's sample.
  s.target_spp = target_spp();
  s.tree_budget_bytes = std::size_t{256} << 20;
  s.refine_while_interacting = false;  // no restart cancels a pass here: one image per edit while the hand is on
  return s;
}

void WebView::begin_generation() {
  // With formulas, the equation traced with its hooks (src/check/rules.h): no trees to re-shade.
  const FormulaBook& formulas = session_.formulas();
  prepared_ = formulas.any() && formula_view_ == 0
                  ? std::make_shared<const PreparedScene>(view_scene(session_.scene(), view_), PreparedScene::AccelFactory{},
                                                          make_rules_experiment(formulas.rules()))
                  : std::make_shared<const PreparedScene>(view_scene(session_.scene(), view_));
  eye_ = view_shading_eye(*prepared_, view_, width_, height_);
  // The trees are of the traced image's size: one cell of the grid in the small multiples, so a
  // switch between the grid and one image traces anew.
  passes_.begin(prepared_, trace_width(), trace_height(), settings(), interacting_);
}

emscripten::val WebView::pixels() const {
  return emscripten::val(emscripten::typed_memory_view(rgba_.size(), rgba_.data()));
}

void WebView::orbit(double dx_px, double dy_px) {
  Camera camera = session_.scene().camera;
  ui::orbit_in(session_.scene(), camera, -dx_px * 0.01, dy_px * 0.01);  // never under the floor
  apply({edit::SetCamera{camera}, false});
}

void WebView::reset_camera() { apply({edit::SetCamera{session_.document().loaded_camera()}, false}); }

void WebView::dolly(double steps) {
  Camera camera = session_.scene().camera;
  if (prepared_) ui::dolly_in(*prepared_, camera, std::pow(0.9, steps));  // never inside an object
  else ui::dolly(camera, std::pow(0.9, steps));
  apply({edit::SetCamera{camera}, false});
}

void WebView::pan(double dx_px, double dy_px) {
  Camera camera = session_.scene().camera;
  ui::pan(camera, dx_px, dy_px, height_);
  apply({edit::SetCamera{camera}, false});
}

std::string WebView::light_markers() const {
  // Each light's point on the canvas, or null (a directional light, or behind the eye).
  nlohmann::json out = nlohmann::json::array();
  if (!view_.light_markers) return out.dump();  // a lesson step that does not show where the lights are
  const Scene& scene = session_.scene();
  for (const Light& light : scene.lights) {
    const auto at = light.type == LightType::kPoint ? ui::project(scene.camera, light.position, width_, height_)
                                                    : std::nullopt;
    out.push_back(at ? nlohmann::json::array({at->x, at->y}) : nlohmann::json(nullptr));
  }
  return out.dump();
}

double WebView::light_depth(int l) const {
  if (l < 0 || l >= light_count()) return 0;
  const Scene& scene = session_.scene();
  return ui::view_depth(scene.camera, scene.lights[static_cast<std::size_t>(l)].position);
}

void WebView::drag_light(int l, double x_px, double y_px, double depth) {
  if (l < 0 || l >= light_count() || !(depth > 0)) return;
  const Scene& scene = session_.scene();
  const Vec3 p = ui::unproject(scene.camera, {x_px, y_px}, depth, width_, height_);
  Light light = scene.lights[static_cast<std::size_t>(l)];
  // Kept to float precision, as the desktop keeps a dragged light: a saved file reads 1.8074448.
  light.position = Vec3(ui::tidy_float(p.x), ui::tidy_float(p.y), ui::tidy_float(p.z));
  apply({edit::SetLight{l, light}, true});
}

void WebView::set_small_multiples(bool on) {
  view_.small_multiples = on;
  edited_by_hand();
  restart();
}

bool WebView::finished() const {
  return shown_generation_ == generation_ && shown_divisor_ == 1 && !shown_quads_ && !passes_.live_shown() &&
         shown_spp_ >= static_cast<std::uint32_t>(target_spp()) && !view_.small_multiples;
}

int WebView::target_spp() const {
  return a_.target_spp(target_, session_.lessons().lesson() != nullptr, view_.compare, constant_ambient());
}

void WebView::take_a() {
  a_.request(static_cast<std::uint64_t>(generation_), false);
  if (a_.take_when_ready(static_cast<std::uint64_t>(generation_), shown_, finished())) encode();
}

std::string WebView::compare_caption() const {
  return a_.caption(shown_, view_.compare, constant_ambient(), target_spp(), view_.difference_gain);
}

void WebView::set_compare(int mode, double wipe) {
  view_.compare = static_cast<CompareView>(std::clamp(mode, 0, 2));
  view_.wipe = std::clamp(wipe, 0.0, 1.0);
  if (shown_generation_ == generation_) encode();  // the same live image, shown against A
}

void WebView::set_depth_cut(int cut) {
  view_.depth_cut = cut > 0 ? std::optional<int>(cut) : std::nullopt;
  edited_by_hand();
  restart();
}

std::string WebView::probed_pixel() const {
  if (!probe_pixel_ || view_.small_multiples) return "null";
  return nlohmann::json::array({(*probe_pixel_)[0], (*probe_pixel_)[1]}).dump();
}

std::string WebView::ray_tree() const {
  if (!tree_shown_ || !tree_pixel_ || view_.small_multiples) return "[]";
  const std::shared_ptr<const PreparedScene> prepared =
      prepared_ ? prepared_ : std::make_shared<const PreparedScene>(view_scene(session_.scene(), view_));
  const Scene& shown = prepared->scene();
  const PixelProbe probe = probe_pixel(*prepared, width_, height_, (*tree_pixel_)[0], (*tree_pixel_)[1], eye_);
  const CameraFrame frame = make_camera_frame(shown.camera, width_, height_);
  const bool blinn = shown.specular_model == SpecularModel::kBlinn;
  nlohmann::json out = nlohmann::json::array();
  for (const ScreenSegment& s : project_ray_tree(frame, ray_tree_segments(shown, probe.root), ray_tree_near(shown, probe.root))) {
    static constexpr const char* kKinds[] = {"primary", "seen", "blocked", "reflection", "refraction"};
    const std::string kind = is_arrow(s.kind) ? arrow_letter(s.kind, blinn) : kKinds[static_cast<int>(s.kind)];
    const std::array<std::uint8_t, 3> c = segment_srgb8(s.kind, s.depth, s.blocked);  // the one palette
    char colour[8];
    std::snprintf(colour, sizeof colour, "#%02x%02x%02x", c[0], c[1], c[2]);
    out.push_back({{"kind", kind}, {"depth", s.depth}, {"light", s.light}, {"escapes", s.escapes},
                   {"blocked", s.blocked}, {"colour", colour},
                   {"from", {s.from.x, s.from.y}}, {"to", {s.to.x, s.to.y}}, {"end", s.to_visible}});
  }
  return out.dump();
}

int WebView::material_at(double u, double v) const {
  const PixelProbe probe = probe_at(u, v);
  return probe.root.hit ? probe.root.material : -1;
}

std::string WebView::probe(double u, double v) {
  const PixelProbe probe = probe_at(u, v);
  tree_pixel_ = std::array<int, 2>{probe.x, probe.y};
  probe_pixel_ = tree_pixel_;
  // With formulas: yours against the reference at the hit, with your statements' values.
  const std::string formulas = formula_probe_text(session_.scene(), probe.root, session_.formulas().rules());
  return probe_to_text(session_.scene(), probe, 4) + (formulas.empty() ? "" : "\n" + formulas);
}

std::string WebView::material_name(int m) const {
  return m >= 0 && m < material_count() ? session_.scene().materials[static_cast<std::size_t>(m)].name : "";
}

double WebView::coefficient(int m, const std::string& name) const {
  if (m < 0 || m >= material_count()) return 0;
  Material mat = session_.scene().materials[static_cast<std::size_t>(m)];
  if (const Color* c = colour(mat, name)) return largest(*c);
  if (name == "n") return mat.n;
  if (name == "ior") return mat.ior;
  return 0;
}

void WebView::set_coefficient(int m, const std::string& name, double value, bool held) {
  if (m < 0 || m >= material_count()) return;
  Material mat = session_.scene().materials[static_cast<std::size_t>(m)];
  if (Color* c = colour(mat, name)) {
    *c = scaled(*c, value);
  } else if (name == "n") {
    mat.n = value;
  } else if (name == "ior") {
    mat.ior = value;
  } else {
    return;
  }
  apply({edit::SetMaterial{m, mat}, held});
}

double WebView::light_intensity(int l) const {
  return l >= 0 && l < light_count() ? largest(session_.scene().lights[static_cast<std::size_t>(l)].intensity) : 0;
}

void WebView::set_light_intensity(int l, double value, bool held) {
  if (l < 0 || l >= light_count()) return;
  Light light = session_.scene().lights[static_cast<std::size_t>(l)];
  light.intensity = scaled(light.intensity, value);
  apply({edit::SetLight{l, light}, held});
}

std::string WebView::set_formula(int slot, const std::string& text) {
  if (slot < 0 || slot >= kFormulaSlots) return "no such slot";
  if (session_.set_formula(static_cast<FormulaSlot>(slot), text)) restart();
  return formula_error(slot);
}

std::string WebView::formulas_file_text() const { return formula_file_text(session_.formulas().texts()); }

std::string WebView::open_formulas(const std::string& text, const std::string& name) {
  const FormulaFileLoad loaded = load_formula_text(text, name);
  if (!loaded.ok()) return loaded.errors.empty() ? name + ": cannot read" : loaded.errors.front().to_string();
  if (session_.set_formulas(*loaded.texts)) restart();
  return "";
}

std::string WebView::formula_text(int slot) const {
  if (slot < 0 || slot >= kFormulaSlots) return "";
  return session_.formulas().slot(static_cast<FormulaSlot>(slot)).text;
}

std::string WebView::formula_error(int slot) const {
  if (slot < 0 || slot >= kFormulaSlots) return "";
  const std::optional<FormulaError>& error = session_.formulas().slot(static_cast<FormulaSlot>(slot)).error;
  return error ? error->text() : std::string();
}

void WebView::set_formula_view(int view) {
  const int v = view == 1 ? 1 : 0;
  if (v == formula_view_) return;
  formula_view_ = v;
  if (session_.formulas().any()) restart();
}

std::string WebView::check_formulas_json() {
  if (!session_.formulas().any()) return "";
  Scene scene = view_scene(session_.scene(), view_);
  constexpr int kCheckWidth = 320;
  const double scale = std::min(1.0, static_cast<double>(kCheckWidth) / std::max(1, width_));
  scene.width = std::max(1, static_cast<int>(width_ * scale));
  scene.height = std::max(1, static_cast<int>(height_ * scale));
  CheckOptions options;
  options.threads = threads_;
  return check_to_json(check_formulas(scene, session_.formulas().rules(), options));
}

std::string WebView::check_image_json(const std::string& path) {
  std::string error;
  const std::optional<ReadImage> read = read_image_file(path, &error);
  if (read && (read->width != width_ || read->height != height_)) {
    error = path + " is " + std::to_string(read->width) + "x" + std::to_string(read->height) + ", the view renders " +
            std::to_string(width_) + "x" + std::to_string(height_) + ": render yours at the view's size";
  }
  if (!error.empty()) return nlohmann::json{{"error", error}}.dump();
  Scene scene = view_scene(session_.scene(), view_);
  CheckOptions options;
  options.threads = threads_;
  image_check_ = check_image(scene, student_image(*read), options);
  ProgressiveFrame a;
  a.width = image_check_->width;
  a.height = image_check_->height;
  a.spp = 1;
  for (const Color& c : image_check_->yours) a.pixels.emplace_back(c);
  a_.set_file_image(std::move(a), path);
  check_view_ = 2;
  if (shown_generation_ == generation_) encode();
  return check_to_json(*image_check_);
}

void WebView::close_image() {
  image_check_.reset();
  check_view_ = 0;
  if (!a_.file_name().empty()) a_.clear();
  if (shown_generation_ == generation_) encode();
}

void WebView::set_check_view(int view) {
  check_view_ = std::clamp(view, 0, 2);
  if (shown_generation_ == generation_) encode();
}

std::optional<std::vector<glm::vec3>> WebView::check_view_pixels() const {
  if (!image_check_ || check_view_ == 0 || image_check_->width != shown_width_ || image_check_->height != shown_height_) {
    return std::nullopt;
  }
  const std::vector<Color> source = check_view_ == 1 ? image_check_->yours : check_difference_image(*image_check_);
  std::vector<glm::vec3> out;
  out.reserve(source.size());
  for (const Color& c : source) out.emplace_back(c);
  return out;
}

bool WebView::undo() {
  if (!session_.undo()) return false;
  edited_by_hand();
  restart();
  return true;
}

bool WebView::redo() {
  if (!session_.redo()) return false;
  edited_by_hand();
  restart();
  return true;
}

void WebView::apply(const Edit& e) {
  if (!session_.apply(e).changed) return;
  edited_by_hand();
  restart();
}

void WebView::restart() {
  ++generation_;
  prepared_.reset();  // the next step begins the generation (the scheduler's ladder: the hand's budget)
}

PixelProbe WebView::probe_at(double u, double v) const {
  const PreparedScene prepared(view_scene(session_.scene(), view_));
  const int x = std::clamp(static_cast<int>(u * width_), 0, width_ - 1);
  const int y = std::clamp(static_cast<int>(v * height_), 0, height_ - 1);
  return probe_pixel(prepared, width_, height_, x, y, eye_);
}

// The image as the desktop shows it: the accumulator's means, or the small multiples' grid (the
// five terms in the equation's order, then the full image).
std::vector<glm::vec3> WebView::live_pixels() const {
  const Accumulator& accum = passes_.accum();
  const int w = accum.width, h = accum.height;
  if (!view_.small_multiples) {
    std::vector<glm::vec3> out(static_cast<std::size_t>(w) * static_cast<std::size_t>(h));
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) out[static_cast<std::size_t>(y * w + x)] = glm::vec3(accum.mean(x, y));
    return out;
  }
  const int gw = w * kColumns;
  std::vector<glm::vec3> out(static_cast<std::size_t>(gw) * static_cast<std::size_t>(h * kRows));
  const double inv = 1.0 / static_cast<double>(std::max(accum.samples, 1u));
  for (int cell = 0; cell < kColumns * kRows; ++cell) {
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        const std::size_t i = static_cast<std::size_t>(y * w + x);
        const Color c = cell < 5 ? accum.terms[i].*kFiveTermMembers[static_cast<std::size_t>(cell)] * inv
                                 : accum.mean(x, y);
        out[static_cast<std::size_t>((cell / kColumns * h + y) * gw + cell % kColumns * w + x)] = glm::vec3(c);
      }
    }
  }
  return out;
}

std::string WebView::bench(int frames) const {
  const PreparedScene prepared(session_.scene());
  RenderOptions options;
  options.threads = threads_;
  std::string times;
  std::uint64_t rays = 0;
  for (int f = 0; f < frames; ++f) {
    Accumulator accum;
    accum.reset(width_, height_);
    const auto start = std::chrono::steady_clock::now();
    const PassStats pass = render_pass(prepared, options, accum);
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    times += (times.empty() ? "" : ", ") + std::to_string(ms);
    rays = pass.rays.total();
  }
  return "{\"ms\": [" + times + "], \"rays\": " + std::to_string(rays) + "}";
}

// 8-bit sRGB of the image (what `phonglab-cli render -o x.png` writes), against A in a compare.
void WebView::encode() {
  const Accumulator& accum = passes_.accum();
  shown_width_ = accum.width * (view_.small_multiples ? kColumns : 1);
  shown_height_ = accum.height * (view_.small_multiples ? kRows : 1);
  shown_spp_ = accum.samples;
  shown_generation_ = generation_;
  shown_.generation = static_cast<std::uint64_t>(generation_);
  shown_.width = shown_width_, shown_.height = shown_height_, shown_.divisor = shown_divisor_, shown_.spp = shown_spp_;
  shown_.pixels = live_pixels();
  std::vector<glm::vec3> live = shown_.pixels;
  heat_max_ = view_.term == Term::kRays ? phonglab::heat_max(live) : 0;
  if (view_.term == Term::kRays) live = heat_map_pixels(live, heat_max_);
  if (ambient_pair() && accum.has_terms()) {
    std::vector<glm::vec3> ambient(live.size());
    const double inv = 1.0 / static_cast<double>(std::max(accum.samples, 1u));
    for (std::size_t i = 0; i < ambient.size(); ++i) ambient[i] = glm::vec3(accum.terms[i].ambient * inv);
    live = ambient_shown_pixels(view_.ambient_shown, live, ambient, shown_width_, view_.wipe);
  }
  if (view_.compare != CompareView::kNone && a_.comparable(shown_, view_.compare, constant_ambient())) {
    live = compare_pixels(live, a_.image().pixels, shown_width_, view_.compare, view_.wipe, view_.difference_gain);
  }
  if (std::optional<std::vector<glm::vec3>> checked = check_view_pixels()) live = std::move(*checked);
  const Display8Encoder& srgb = Display8Encoder::srgb();
  rgba_.resize(4 * live.size());
  for (std::size_t i = 0; i < live.size(); ++i) {
    rgba_[4 * i] = srgb(live[i].x), rgba_[4 * i + 1] = srgb(live[i].y), rgba_[4 * i + 2] = srgb(live[i].z);
    rgba_[4 * i + 3] = 255;
  }
  ++images_;
}

}  // namespace phonglab
