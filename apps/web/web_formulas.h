// The student's formulas and images on the page (docs/formulas.md): the session's formulas with
// their undo, their file, which image is traced (yours or the reference), and the checks of yours
// against the reference, of the formulas and of an image from the student's own ray tracer.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "apps/web/page_state.h"

namespace phonglab {

class WebFormulas {
 public:
  WebFormulas(PageState& state, PageImage& image) : s_(state), image_(image) {}
  WebFormulas(const WebFormulas&) = delete;
  WebFormulas& operator=(const WebFormulas&) = delete;

  // Slot 0 ambient, 1 diffuse, 2 specular. Returns the text's positioned error ("" when it
  // compiles; with an error the last good formula keeps rendering).
  std::string set_formula(int slot, const std::string& text);
  std::string formula_text(int slot) const;
  std::string formula_error(int slot) const;
  // The formulas' own file: the session's texts as the file's text, and a file's text opened as
  // one undo step ("", or its first error, positioned: nothing changes).
  std::string formulas_file_text() const;
  std::string open_formulas(const std::string& text, const std::string& name);
  // What the image shows: 0 yours (with the formulas), 1 the reference (the equation's terms).
  void set_formula_view(int view);
  // The formulas checked against the reference at a reduced size (at most 320 wide, the view's
  // aspect; a second or less on one core): the verdict as JSON (check's --json keys and a
  // `summary` in words), or "" with no formula.
  std::string check_formulas_json();
  // A student's own image of the view (a file in the page's memory file system, from the
  // chooser): refused unless it has the image's size (both sizes named); checked against the
  // reference at the view's camera and size, A of the compare. The verdict as JSON (keys of
  // check --json, `summary`, or `error`).
  std::string check_image_json(const std::string& path);
  void close_image();
  // What the image shows with a student's image checked: 0 the live render, 1 the student's
  // image, 2 the check's difference (orange brighter, blue darker, magenta NaN).
  void set_check_view(int view);
  // The pixels that view shows in the image's place, or none (the live render).
  std::optional<std::vector<glm::vec3>> check_view_pixels() const;

 private:
  PageState& s_;
  PageImage& image_;
};

}  // namespace phonglab
