// What a pixel shows (Term) and where its ambient term comes from (Ambient): the names of the
// images every renderer draws, the scalar and the packet tracer alike, and the rules that read a
// term off a hit's five terms.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string_view>

#include "core/scene/scene.h"
#include "core/shading/shading.h"

namespace phonglab {

// What a pixel shows: the full equation, one of its five terms at the primary hit, or a
// debug view.
enum class Term : std::uint8_t {
  kFull,
  kAmbient,
  kDiffuse,
  kSpecular,
  kReflection,
  kRefraction,
  kNormal,  // facing shading normal N mapped to 0.5 + 0.5 N
  kDepth,   // primary hit distance t (world units; 0 on a miss)
  kRays,    // rays cast for the sample, all kinds (a heat map input)
  kIndirect,  // the indirect term at the primary hit (the ambient term's place, ambient indirect)
};

// Where the ambient term of every hit comes from: the lecture's constant ka·Ia, or the indirect
// light it stands in for (docs/model.md: the indirect term's estimate, the scene's bounces).
enum class Ambient : std::uint8_t { kConstant, kIndirect };

// The five terms in the equation's order, as Term values and as the members of Terms that hold them.
inline constexpr std::array<Term, 5> kFiveTerms = {Term::kAmbient, Term::kDiffuse, Term::kSpecular, Term::kReflection,
                                                   Term::kRefraction};
inline constexpr std::array<Color Terms::*, 5> kFiveTermMembers = {&Terms::ambient, &Terms::diffuse, &Terms::specular,
                                                                   &Terms::reflection, &Terms::refraction};

// Whether `term` is the equation's image or one of its five terms (not a debug view).
inline bool is_equation_term(Term term) { return term <= Term::kRefraction || term == Term::kIndirect; }
// The ambient term's source a render of `term` uses: the indirect term's image is the ambient
// term under indirect light.
inline Ambient ambient_for(Term term, Ambient ambient) { return term == Term::kIndirect ? Ambient::kIndirect : ambient; }

// What a primary ray that meets nothing gives for `term`: the background in the full image, 0
// in a term or debug image.
inline Color miss_value(const Scene& scene, Term term) { return term == Term::kFull ? scene.background : Color(0); }

// The value a shaded primary hit gives for `term`: one of its five terms, else their sum.
Color term_value(const Terms& terms, Term term);
// What shading a primary hit must compute for `term`: a term image needs only its own term.
TermsWanted terms_wanted(Term term);

// Parses "full", "ambient", ... ; nullopt for an unknown name.
std::optional<Term> term_from_name(std::string_view name);
std::string_view term_name(Term term);

}  // namespace phonglab
