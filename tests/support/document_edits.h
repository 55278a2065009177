// A document's scene edited in tests that drive SceneDocument alone, as the session edits it: a
// copy changed and handed back (the document has no other writer).
#pragma once

#include <utility>

#include "session/document.h"

namespace phonglab::test {

template <class Change>
void edit_scene(SceneDocument& doc, Change change) {
  Scene scene = doc.scene();
  change(scene);
  doc.restore_edits(std::move(scene));
}

}  // namespace phonglab::test
