// libFuzzer target: any bytes as a lesson file. A rejected lesson must come with diagnostics; an
// accepted one has each of its first steps rendered as the handout renders it (tiny, 1 spp),
// which must stay finite.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "io/handout.h"
#include "io/lesson_io.h"

using namespace phonglab;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const LessonLoad load = load_lesson_text(text, "fuzz.json", "/nonexistent");
  if (!load.ok()) {
    if (load.errors.empty()) std::abort();  // rejected without saying why
    return 0;
  }
  const Lesson& lesson = *load.lesson;
  if (lesson.steps.empty()) std::abort();
  HandoutOptions options;
  options.width = 6;
  options.height = 4;
  options.spp = 1;
  options.threads = 1;
  const int steps = std::min(static_cast<int>(lesson.steps.size()), 3);
  for (int i = 0; i < steps; ++i) {
    for (const bool revealed : {false, true}) {
      const Image image = render_step_view(lesson, {i, revealed}, options);
      for (const glm::vec3& p : image.pixels) {
        if (!std::isfinite(p.x + p.y + p.z)) std::abort();
      }
    }
  }
  return 0;
}
