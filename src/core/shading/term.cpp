#include "core/shading/term.h"

namespace phonglab {

namespace {
constexpr std::array<std::string_view, 10> kTermNames = {"full",       "ambient",    "diffuse",
                                                         "specular",   "reflection", "refraction",
                                                         "normal",     "depth",      "rays",
                                                         "indirect"};
}  // namespace

std::optional<Term> term_from_name(std::string_view name) {
  for (std::size_t i = 0; i < kTermNames.size(); ++i) {
    if (kTermNames[i] == name) return static_cast<Term>(i);
  }
  return std::nullopt;
}

std::string_view term_name(Term term) { return kTermNames[static_cast<std::size_t>(term)]; }

TermsWanted terms_wanted(Term term) {
  switch (term) {
    case Term::kAmbient:
    case Term::kIndirect: return {false, false, false};
    case Term::kDiffuse:
    case Term::kSpecular: return {true, false, false};
    case Term::kReflection: return {false, true, false};
    case Term::kRefraction: return {false, false, true};
    default: return {};
  }
}

Color term_value(const Terms& t, Term term) {
  switch (term) {
    case Term::kAmbient:
    case Term::kIndirect: return t.ambient;
    case Term::kDiffuse: return t.diffuse;
    case Term::kSpecular: return t.specular;
    case Term::kReflection: return t.reflection;
    case Term::kRefraction: return t.refraction;
    default: return t.sum();
  }
}

}  // namespace phonglab
