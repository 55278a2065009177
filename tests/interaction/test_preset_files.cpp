// A material preset applied and the scene saved (`material_preset matte gold`, then Save as): the classic table's gold scaled to the lecture's Ia = 1 (ka by 0.2, as
// SceneBuilder::apply_material_preset applies it through the session) is written without float
// noise: no run of nine or more digits anywhere in the saved file.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>

#include "interaction/material_presets.h"
#include "interaction/scene_objects.h"
#include "session/session.h"

namespace phonglab {
namespace {

namespace fs = std::filesystem;

TEST(MaterialPresetFiles, APresetScaledToTheScenesIaIsSavedWithoutFloatNoise) {
  const fs::path dir = fs::temp_directory_path() / ("phonglab-preset-files-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  Session session("");
  ASSERT_TRUE(session.open("lecture"));
  const ui::MaterialPreset* gold = ui::find_preset("gold");
  ASSERT_NE(gold, nullptr);
  const int matte = ui::find_material(session.scene(), "matte");
  ASSERT_GE(matte, 0);
  Scene edited = session.scene();
  const Color scale = ui::apply_preset(edited.materials[static_cast<std::size_t>(matte)], *gold, edited.specular_model,
                                       edited.ambient);
  EXPECT_EQ(scale, Color(0.2)) << "the table assumes Ia = 0.2, the lecture's is 1";
  ASSERT_TRUE(session.apply({edit::SetScene{edited}}).unsaved);
  const std::string path = (dir / "preset.json").string();
  ASSERT_TRUE(session.document().save_as(path)) << session.document().error_text();
  std::stringstream text;
  text << std::ifstream(path).rdbuf();
  ASSERT_FALSE(text.str().empty());
  std::smatch noise;
  const std::string saved = text.str();
  EXPECT_FALSE(std::regex_search(saved, noise, std::regex("[0-9]{9,}"))) << noise.str(0) << " in\n" << saved;
  EXPECT_NE(saved.find("\"matte\""), std::string::npos);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace phonglab
