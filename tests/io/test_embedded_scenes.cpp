// Every embedded scene loads, renders without NaN, and shows what it is meant to teach.
#include <gtest/gtest.h>

#include "io/embedded_scenes.h"
#include "core/render/render.h"
#include "io/scene/scene_io.h"
#include "tests/support/test_support.h"

using namespace phonglab;

namespace {

// An embedded scene, loaded with the mesh files compiled in beside it, and prepared.
PreparedScene load(std::string_view name) {
  const EmbeddedScene* e = find_embedded_scene(name);
  EXPECT_NE(e, nullptr) << name;
  return load_prepared(name);
}

Accumulator render(const PreparedScene& s, Term term, int spp, PassStats* total = nullptr) {
  Accumulator acc;
  acc.reset(96, 54);
  RenderOptions opt;
  opt.term = term;
  for (int i = 0; i < spp; ++i) {
    const PassStats st = render_pass(s, opt, acc);
    if (total) {
      total->rays += st.rays;
      total->nan_count += st.nan_count;
    }
  }
  return acc;
}

double sum_of(const Accumulator& a) {
  double t = 0;
  for (const Color& c : a.sum) t += c.x + c.y + c.z;
  return t;
}

}  // namespace

TEST(EmbeddedScenes, ThereAreTheFiveOfTheLectureAndLectureIsFirst) {
  ASSERT_GE(embedded_scenes().size(), 5u);
  EXPECT_EQ(embedded_scenes().front().name, "lecture");
  for (const char* name : {"lecture", "shininess", "lights", "mirrors", "glass"}) {
    const EmbeddedScene* e = find_embedded_scene(name);
    ASSERT_NE(e, nullptr) << name;
    EXPECT_FALSE(e->description.empty());
  }
}

TEST(EmbeddedScenes, EveryOneRendersWithoutNaN) {
  for (const EmbeddedScene& e : embedded_scenes()) {
    const PreparedScene s = load(e.name);
    PassStats stats;
    const Accumulator a = render(s, Term::kFull, 4, &stats);
    EXPECT_EQ(stats.nan_count, 0u) << e.name;
    EXPECT_GT(sum_of(a), 0) << e.name;
    EXPECT_EQ(stats.rays.primary, 4u * 96 * 54) << e.name;
  }
}

TEST(EmbeddedScenes, MirrorsSceneRecursesDeeply) {
  const PreparedScene s = load("mirrors");
  PassStats stats;
  render(s, Term::kFull, 1, &stats);
  // Facing mirrors: many primary rays spawn several generations of reflections.
  EXPECT_GT(stats.rays.reflection, 2 * stats.rays.primary / 3);
}

TEST(EmbeddedScenes, GlassSceneRefracts) {
  const PreparedScene s = load("glass");
  EXPECT_GT(sum_of(render(s, Term::kRefraction, 1)), 0);
}

TEST(EmbeddedScenes, LecturesSceneHasEveryTerm) {
  const PreparedScene s = load("lecture");
  for (Term t : {Term::kAmbient, Term::kDiffuse, Term::kSpecular, Term::kReflection, Term::kRefraction}) {
    EXPECT_GT(sum_of(render(s, t, 1)), 0) << term_name(t);
  }
}
