// The web page's binding (embind): the page (apps/web/phonglab.html) drives the same session and
// renderer as the desktop previewer. The document, its edits and undo are the session's
// (src/session); the image is the core's render_pass, coarse to fine (1/8, 1/4, 1/2, then full
// resolution, then more samples), one pass per call of step(), on the page's one thread.
#include <emscripten/bind.h>
#include <emscripten/val.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "core/accel/prepared_scene.h"
#include "core/render/render.h"
#include "core/scene/display8.h"
#include "interaction/camera_control.h"
#include "io/embedded_scenes.h"
#include "io/probe_report.h"
#include "io/scene/scene_io.h"
#include "session/session.h"

namespace phonglab {
namespace {

constexpr int kDivisors[] = {8, 4, 2, 1};

// The page's view of one session: the document, the progressive image, what the hand does.
class WebView {
 public:
  WebView() : session_("") {}

  // An embedded scene's name or a file in the page's memory file system (an upload): "" or the
  // positioned errors, the last good scene kept.
  std::string open(const std::string& scene_arg) {
    if (!session_.open(scene_arg)) return session_.document().error_text();
    restart();
    return "";
  }
  std::string scene_json() const { return scene_to_json(session_.scene()); }
  std::string source() const { return session_.document().source(); }

  void set_size(int width, int height) {
    width_ = std::max(width, 1);
    height_ = std::max(height, 1);
    restart();
  }
  void set_target(int spp) { target_ = std::max(spp, 1); }
  void set_term(int term) {
    term_ = static_cast<Term>(std::clamp(term, 0, 5));
    restart();
  }
  // While the hand is on, the image stays at 1/4 resolution: each new view shows at once.
  void set_interacting(bool on) {
    interacting_ = on;
    if (!on) session_.settle(false);
  }

  // One pass: true when it made a new image (false: the target is reached).
  bool step() {
    if (!prepared_) prepared_ = std::make_shared<const PreparedScene>(session_.scene());
    const int finest = interacting_ ? 1 : 3;
    if (level_ > finest) return false;
    const int divisor = kDivisors[level_];
    if (level_ == 3 && accum_.samples >= static_cast<std::uint32_t>(target_)) return false;
    const int w = std::max(1, width_ / divisor), h = std::max(1, height_ / divisor);
    if (accum_.width != w || accum_.height != h || accum_.samples == 0) accum_.reset(w, h);
    RenderOptions options;
    options.term = term_;
    options.threads = 1;
    render_pass(*prepared_, options, accum_);
    encode();
    if (level_ < finest) {
      ++level_;
      accum_.samples = 0;
    }
    return true;
  }
  int image_width() const { return accum_.width; }
  int image_height() const { return accum_.height; }
  int spp() const { return static_cast<int>(shown_spp_); }
  int divisor() const { return shown_divisor_; }
  // Restarts so far, and the one the image on show belongs to (equal: the image is of the
  // document and settings as they are now).
  int generation() const { return generation_; }
  int shown_generation() const { return shown_generation_; }
  emscripten::val pixels() const { return emscripten::val(emscripten::typed_memory_view(rgba_.size(), rgba_.data())); }

  // Navigation, as on the desktop: a drag of the view orbits about look_at, the wheel dollies.
  void orbit(double dx_px, double dy_px) {
    Camera camera = session_.scene().camera;
    ui::orbit(camera, -dx_px * 0.01, dy_px * 0.01);
    apply({edit::SetCamera{camera}, false});
  }
  void dolly(double steps) {
    Camera camera = session_.scene().camera;
    ui::dolly(camera, std::pow(0.9, steps));
    apply({edit::SetCamera{camera}, false});
  }

  // The material under a point of the image (u, v in [0, 1) from the top-left), -1: none.
  int material_at(double u, double v) const {
    const PixelProbe probe = probe_at(u, v);
    return probe.root.hit ? probe.root.material : -1;
  }
  // The equation's numbers at that point, as `phonglab-cli probe` prints them.
  std::string probe(double u, double v) const { return probe_to_text(session_.scene(), probe_at(u, v), 4); }

  int material_count() const { return static_cast<int>(session_.scene().materials.size()); }
  std::string material_name(int m) const {
    return m >= 0 && m < material_count() ? session_.scene().materials[static_cast<std::size_t>(m)].name : "";
  }
  // A coefficient as the page's slider shows it: the largest channel of a colour, or the number.
  double coefficient(int m, const std::string& name) const {
    if (m < 0 || m >= material_count()) return 0;
    const Material& mat = session_.scene().materials[static_cast<std::size_t>(m)];
    if (const Color* c = colour(mat, name)) return std::max({c->x, c->y, c->z});
    if (name == "n") return mat.n;
    if (name == "ior") return mat.ior;
    return 0;
  }
  // Sets it: a colour keeps its hue (black becomes grey). `held`: part of a slider drag (one undo
  // step when it ends).
  void set_coefficient(int m, const std::string& name, double value, bool held) {
    if (m < 0 || m >= material_count()) return;
    Material mat = session_.scene().materials[static_cast<std::size_t>(m)];
    if (Color* c = colour(mat, name)) {
      const double top = std::max({c->x, c->y, c->z});
      *c = top > 0 ? *c * (value / top) : Color(value);
    } else if (name == "n") {
      mat.n = value;
    } else if (name == "ior") {
      mat.ior = value;
    } else {
      return;
    }
    apply({edit::SetMaterial{m, mat}, held});
  }
  bool undo() { return session_.undo() && (restart(), true); }
  bool redo() { return session_.redo() && (restart(), true); }

 private:
  static Color* colour(Material& m, const std::string& name) {
    return name == "ka" ? &m.ka : name == "kd" ? &m.kd : name == "ks" ? &m.ks : name == "kr" ? &m.kr
                                                                                   : name == "kt" ? &m.kt : nullptr;
  }
  static const Color* colour(const Material& m, const std::string& name) { return colour(const_cast<Material&>(m), name); }

  void apply(const Edit& e) {
    if (session_.apply(e).changed) restart();
  }
  void restart() {
    ++generation_;
    prepared_.reset();
    level_ = interacting_ ? 1 : 0;
    accum_.samples = 0;
  }
  PixelProbe probe_at(double u, double v) const {
    const PreparedScene prepared(session_.scene());
    const int x = std::clamp(static_cast<int>(u * width_), 0, width_ - 1);
    const int y = std::clamp(static_cast<int>(v * height_), 0, height_ - 1);
    return probe_pixel(prepared, width_, height_, x, y);
  }
  // The accumulator's means as 8-bit sRGB, RGBA (what `phonglab-cli render -o x.png` writes).
  void encode() {
    const Display8Encoder& srgb = Display8Encoder::srgb();
    rgba_.resize(4 * accum_.sum.size());
    std::size_t i = 0;
    for (int y = 0; y < accum_.height; ++y) {
      for (int x = 0; x < accum_.width; ++x, i += 4) {
        const glm::vec3 c(accum_.mean(x, y));  // mean_image's float, as the PNG writer encodes it
        rgba_[i] = srgb(c.x), rgba_[i + 1] = srgb(c.y), rgba_[i + 2] = srgb(c.z), rgba_[i + 3] = 255;
      }
    }
    shown_spp_ = accum_.samples;
    shown_divisor_ = kDivisors[level_];
    shown_generation_ = generation_;
  }

  Session session_;
  std::shared_ptr<const PreparedScene> prepared_;
  Accumulator accum_;
  std::vector<unsigned char> rgba_;
  int width_ = 640, height_ = 360, target_ = 16, level_ = 0;
  std::uint32_t shown_spp_ = 0;
  int shown_divisor_ = 8;
  int generation_ = 0, shown_generation_ = -1;
  Term term_ = Term::kFull;
  bool interacting_ = false;
};

std::string scene_names() {
  std::string out;
  for (const EmbeddedScene& s : embedded_scenes()) out += std::string(s.name) + "\t" + std::string(s.description) + "\n";
  return out;
}

}  // namespace
}  // namespace phonglab

EMSCRIPTEN_BINDINGS(phonglab) {
  using phonglab::WebView;
  emscripten::function("sceneNames", &phonglab::scene_names);
  emscripten::class_<WebView>("WebView")
      .constructor<>()
      .function("open", &WebView::open)
      .function("sceneJson", &WebView::scene_json)
      .function("source", &WebView::source)
      .function("setSize", &WebView::set_size)
      .function("setTarget", &WebView::set_target)
      .function("setTerm", &WebView::set_term)
      .function("setInteracting", &WebView::set_interacting)
      .function("step", &WebView::step)
      .function("imageWidth", &WebView::image_width)
      .function("imageHeight", &WebView::image_height)
      .function("spp", &WebView::spp)
      .function("divisor", &WebView::divisor)
      .function("generation", &WebView::generation)
      .function("shownGeneration", &WebView::shown_generation)
      .function("pixels", &WebView::pixels)
      .function("orbit", &WebView::orbit)
      .function("dolly", &WebView::dolly)
      .function("materialAt", &WebView::material_at)
      .function("probe", &WebView::probe)
      .function("materialCount", &WebView::material_count)
      .function("materialName", &WebView::material_name)
      .function("coefficient", &WebView::coefficient)
      .function("setCoefficient", &WebView::set_coefficient)
      .function("undo", &WebView::undo)
      .function("redo", &WebView::redo);
}
