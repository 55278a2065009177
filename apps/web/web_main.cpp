// The web page's binding (embind): the page's JavaScript (apps/web/phonglab.html) calls WebView
// (web_view.h), which drives the same session and renderer as the desktop previewer.
#include <emscripten/bind.h>

#include <string>

#include "apps/web/web_view.h"
#include "core/packet/packet.h"
#include "io/embedded_scenes.h"

namespace phonglab {
namespace {

// One line per embedded scene or lesson: its name, a tab, what it teaches.
std::string scene_names() {
  std::string out;
  for (const EmbeddedScene& s : embedded_scenes()) out += std::string(s.name) + "\t" + std::string(s.description) + "\n";
  return out;
}
// The instance of the packet kernels the page runs ("SIMD128"), or "" (the scalar renderer).
std::string simd_target() { return packet_simd_target(); }
std::string lesson_names() {
  std::string out;
  for (const EmbeddedLesson& l : embedded_lessons()) out += std::string(l.name) + "\n";
  return out;
}

// A method of one of the binding's parts, bound as the page's `view` object's own: the page's
// JavaScript keeps one object (its names are the page's test interface), the C++ is split by
// concern (web_view.h).
template <auto Part, auto Method>
struct Via;
template <class C, C& (WebView::*Part)(), class R, class... A, R (C::*Method)(A...)>
struct Via<Part, Method> {
  static R call(WebView& view, A... args) { return ((view.*Part)().*Method)(args...); }
};
template <class C, C& (WebView::*Part)(), class R, class... A, R (C::*Method)(A...) const>
struct Via<Part, Method> {
  static R call(WebView& view, A... args) { return ((view.*Part)().*Method)(args...); }
};

}  // namespace
}  // namespace phonglab

EMSCRIPTEN_BINDINGS(phonglab) {
  using phonglab::WebView;
  using phonglab::WebScene;
  using phonglab::WebInstruments;
  using phonglab::WebFormulas;
  using phonglab::WebLesson;
  using phonglab::Via;
  emscripten::function("sceneNames", &phonglab::scene_names);
  emscripten::function("simdTarget", &phonglab::simd_target);
  emscripten::function("lessonNames", &phonglab::lesson_names);
  emscripten::class_<WebView>("WebView")
      .constructor<>()
      .function("open", &Via<&WebView::scene, &WebScene::open>::call)
      .function("sceneJson", &Via<&WebView::scene, &WebScene::scene_json>::call)
      .function("meshFilesJson", &Via<&WebView::scene, &WebScene::mesh_files_json>::call)
      .function("source", &Via<&WebView::scene, &WebScene::source>::call)
      .function("sceneLabel", &Via<&WebView::scene, &WebScene::scene_label>::call)
      .function("viewTerm", &Via<&WebView::instruments, &WebInstruments::view_term>::call)
      .function("width", &WebView::width)
      .function("height", &WebView::height)
      .function("setSize", &WebView::set_size)
      .function("setTarget", &WebView::set_target)
      .function("target", &WebView::target)
      .function("setTerm", &Via<&WebView::instruments, &WebInstruments::set_term>::call)
      .function("setHeadAngle", &Via<&WebView::instruments, &WebInstruments::set_head_angle>::call)
      .function("setInteracting", &WebView::set_interacting)
      .function("setThreads", &WebView::set_threads)
      .function("threads", &WebView::threads)
      .function("live", &WebView::live)
      .function("reshaded", &WebView::reshaded)
      .function("step", &WebView::step)
      .function("imageWidth", &WebView::image_width)
      .function("imageHeight", &WebView::image_height)
      .function("spp", &WebView::spp)
      .function("divisor", &WebView::divisor)
      .function("quads", &WebView::quads)
      .function("generation", &WebView::generation)
      .function("shownGeneration", &WebView::shown_generation)
      .function("pixels", &WebView::pixels)
      .function("orbit", &Via<&WebView::scene, &WebScene::orbit>::call)
      .function("resetCamera", &Via<&WebView::scene, &WebScene::reset_camera>::call)
      .function("dolly", &Via<&WebView::scene, &WebScene::dolly>::call)
      .function("pan", &Via<&WebView::scene, &WebScene::pan>::call)
      .function("lightMarkers", &Via<&WebView::scene, &WebScene::light_markers>::call)
      .function("lightDepth", &Via<&WebView::scene, &WebScene::light_depth>::call)
      .function("dragLight", &Via<&WebView::scene, &WebScene::drag_light>::call)
      .function("setSmallMultiples", &Via<&WebView::instruments, &WebInstruments::set_small_multiples>::call)
      .function("takeA", &Via<&WebView::instruments, &WebInstruments::take_a>::call)
      .function("setCompare", &Via<&WebView::instruments, &WebInstruments::set_compare>::call)
      .function("hasA", &Via<&WebView::instruments, &WebInstruments::has_a>::call)
      .function("setHeatMap", &Via<&WebView::instruments, &WebInstruments::set_heat_map>::call)
      .function("heatMax", &WebView::heat_max)
      .function("images", &WebView::images)
      .function("compareCaption", &Via<&WebView::instruments, &WebInstruments::compare_caption>::call)
      .function("setDepthCut", &Via<&WebView::instruments, &WebInstruments::set_depth_cut>::call)
      .function("maxDepth", &Via<&WebView::instruments, &WebInstruments::max_depth>::call)
      .function("depthCut", &Via<&WebView::instruments, &WebInstruments::depth_cut>::call)
      .function("rayTree", &Via<&WebView::instruments, &WebInstruments::ray_tree>::call)
      .function("probedPixel", &Via<&WebView::instruments, &WebInstruments::probed_pixel>::call)
      .function("setRayTree", &Via<&WebView::instruments, &WebInstruments::set_ray_tree>::call)
      .function("materialAt", &Via<&WebView::instruments, &WebInstruments::material_at>::call)
      .function("probe", &Via<&WebView::instruments, &WebInstruments::probe>::call)
      .function("materialCount", &Via<&WebView::scene, &WebScene::material_count>::call)
      .function("materialName", &Via<&WebView::scene, &WebScene::material_name>::call)
      .function("coefficient", &Via<&WebView::scene, &WebScene::coefficient>::call)
      .function("setCoefficient", &Via<&WebView::scene, &WebScene::set_coefficient>::call)
      .function("lightCount", &Via<&WebView::scene, &WebScene::light_count>::call)
      .function("lightIntensity", &Via<&WebView::scene, &WebScene::light_intensity>::call)
      .function("setLightIntensity", &Via<&WebView::scene, &WebScene::set_light_intensity>::call)
      .function("setFormula", &Via<&WebView::formulas, &WebFormulas::set_formula>::call)
      .function("formulasFileText", &Via<&WebView::formulas, &WebFormulas::formulas_file_text>::call)
      .function("openFormulas", &Via<&WebView::formulas, &WebFormulas::open_formulas>::call)
      .function("formulaText", &Via<&WebView::formulas, &WebFormulas::formula_text>::call)
      .function("formulaError", &Via<&WebView::formulas, &WebFormulas::formula_error>::call)
      .function("setFormulaView", &Via<&WebView::formulas, &WebFormulas::set_formula_view>::call)
      .function("checkFormulas", &Via<&WebView::formulas, &WebFormulas::check_formulas_json>::call)
      .function("checkImage", &Via<&WebView::formulas, &WebFormulas::check_image_json>::call)
      .function("closeImage", &Via<&WebView::formulas, &WebFormulas::close_image>::call)
      .function("setCheckView", &Via<&WebView::formulas, &WebFormulas::set_check_view>::call)
      .function("undo", &Via<&WebView::scene, &WebScene::undo>::call)
      .function("redo", &Via<&WebView::scene, &WebScene::redo>::call)
      .function("openLesson", &Via<&WebView::lesson, &WebLesson::open_lesson>::call)
      .function("lessonNext", &Via<&WebView::lesson, &WebLesson::lesson_next>::call)
      .function("lessonPrev", &Via<&WebView::lesson, &WebLesson::lesson_prev>::call)
      .function("lessonShow", &Via<&WebView::lesson, &WebLesson::lesson_show>::call)
      .function("closeLesson", &Via<&WebView::lesson, &WebLesson::close_lesson>::call)
      .function("lessonState", &Via<&WebView::lesson, &WebLesson::lesson_state>::call)
      .function("lessonHint", &Via<&WebView::lesson, &WebLesson::lesson_hint>::call)
      .function("viewProbe", &Via<&WebView::lesson, &WebLesson::view_probe>::call)
      .function("bench", &WebView::bench);
}
