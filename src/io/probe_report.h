// The probe's report: a pixel's equation term by term, light by light, as text or JSON.
#pragma once

#include <string>

#include "core/render/indirect_probe.h"
#include "core/render/render.h"

namespace phonglab {

// JSON (phonglab-cli probe --json, README): pixel, hit, total, terms, lights, and the children;
// with `indirect` (probe --ambient indirect), its "indirect" object too.
std::string probe_to_json(const Scene& scene, const PixelProbe& probe, const IndirectProbe* indirect = nullptr);

// Plain text for people: the lecture's equation with the numbers filled in. `digits` > 0 gives
// every number that many significant digits; 0 keeps phonglab-cli probe's (9 for scalars, 6 for
// vectors and colours).
std::string probe_to_text(const Scene& scene, const PixelProbe& probe, int digits = 0);

// The indirect probe as text: ka·Ia beside the estimate, its standard error and the fitted ka.
std::string indirect_probe_text(const IndirectProbe& indirect, int digits = 0);

// "objects[3]" style name of the scene-file object behind a primitive ("" for none).
std::string object_name(const Scene& scene, ObjectRef ref);

}  // namespace phonglab
