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

}  // namespace
}  // namespace phonglab

EMSCRIPTEN_BINDINGS(phonglab) {
  using phonglab::WebView;
  emscripten::function("sceneNames", &phonglab::scene_names);
  emscripten::function("simdTarget", &phonglab::simd_target);
  emscripten::function("lessonNames", &phonglab::lesson_names);
  emscripten::class_<WebView>("WebView")
      .constructor<>()
      .function("open", &WebView::open)
      .function("sceneJson", &WebView::scene_json)
      .function("source", &WebView::source)
      .function("sceneLabel", &WebView::scene_label)
      .function("viewTerm", &WebView::view_term)
      .function("width", &WebView::width)
      .function("height", &WebView::height)
      .function("setSize", &WebView::set_size)
      .function("setTarget", &WebView::set_target)
      .function("target", &WebView::target)
      .function("setTerm", &WebView::set_term)
      .function("setHeadAngle", &WebView::set_head_angle)
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
      .function("orbit", &WebView::orbit)
      .function("resetCamera", &WebView::reset_camera)
      .function("dolly", &WebView::dolly)
      .function("pan", &WebView::pan)
      .function("lightMarkers", &WebView::light_markers)
      .function("lightDepth", &WebView::light_depth)
      .function("dragLight", &WebView::drag_light)
      .function("setSmallMultiples", &WebView::set_small_multiples)
      .function("takeA", &WebView::take_a)
      .function("setCompare", &WebView::set_compare)
      .function("hasA", &WebView::has_a)
      .function("setHeatMap", &WebView::set_heat_map)
      .function("heatMax", &WebView::heat_max)
      .function("images", &WebView::images)
      .function("compareCaption", &WebView::compare_caption)
      .function("setDepthCut", &WebView::set_depth_cut)
      .function("maxDepth", &WebView::max_depth)
      .function("depthCut", &WebView::depth_cut)
      .function("rayTree", &WebView::ray_tree)
      .function("probedPixel", &WebView::probed_pixel)
      .function("setRayTree", &WebView::set_ray_tree)
      .function("materialAt", &WebView::material_at)
      .function("probe", &WebView::probe)
      .function("materialCount", &WebView::material_count)
      .function("materialName", &WebView::material_name)
      .function("coefficient", &WebView::coefficient)
      .function("setCoefficient", &WebView::set_coefficient)
      .function("lightCount", &WebView::light_count)
      .function("lightIntensity", &WebView::light_intensity)
      .function("setLightIntensity", &WebView::set_light_intensity)
      .function("setFormula", &WebView::set_formula)
      .function("formulasFileText", &WebView::formulas_file_text)
      .function("openFormulas", &WebView::open_formulas)
      .function("formulaText", &WebView::formula_text)
      .function("formulaError", &WebView::formula_error)
      .function("setFormulaView", &WebView::set_formula_view)
      .function("checkFormulas", &WebView::check_formulas_json)
      .function("checkImage", &WebView::check_image_json)
      .function("closeImage", &WebView::close_image)
      .function("setCheckView", &WebView::set_check_view)
      .function("undo", &WebView::undo)
      .function("redo", &WebView::redo)
      .function("openLesson", &WebView::open_lesson)
      .function("lessonNext", &WebView::lesson_next)
      .function("lessonPrev", &WebView::lesson_prev)
      .function("lessonShow", &WebView::lesson_show)
      .function("closeLesson", &WebView::close_lesson)
      .function("lessonState", &WebView::lesson_state)
      .function("lessonHint", &WebView::lesson_hint)
      .function("viewProbe", &WebView::view_probe)
      .function("bench", &WebView::bench);
}
