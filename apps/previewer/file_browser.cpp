#include "apps/previewer/file_browser.h"

#include <filesystem>
#include <fstream>
#include <sstream>
#include <system_error>

#include "interaction/recovery.h"
#include "io/scene/scene_io.h"
#include "ui/panels.h"

namespace phonglab {

namespace {

// What the browser lists: scenes to save to, or scenes and meshes to open.
std::vector<std::string> browser_filter(bool save) {
  return save ? std::vector<std::string>{".json"} : std::vector<std::string>{".json", ".obj"};
}

}  // namespace

std::string FileBrowser::recent_path() {
  const std::string base = ui::state_dir();
  return base.empty() ? std::string() : base + "/recent";
}

void FileBrowser::load_recent() {
  if (recent_loaded_) return;
  recent_loaded_ = true;
  std::ifstream in(recent_path());
  std::ostringstream text;
  text << in.rdbuf();
  recent_ = ui::parse_recent(text.str());
}

void FileBrowser::remember(const std::string& path) {
  load_recent();
  std::error_code ec;
  ui::remember_recent(recent_, std::filesystem::absolute(path, ec).lexically_normal().string());
  const std::string file = recent_path();
  if (file.empty()) return;
  std::filesystem::create_directories(std::filesystem::path(file).parent_path(), ec);
  write_file_atomically(file, ui::recent_text(recent_));  // a list of conveniences: a failure costs nothing
}

void FileBrowser::open(bool save, const std::string& document_path) {
  load_recent();
  save_ = save;
  const std::string folder = listing_.folder.empty() ? ui::start_folder(document_path) : listing_.folder;
  listing_ = ui::list_folder(folder, browser_filter(save));
  // Save as offers the scene file type's own ending (*.phonglab.json, which the desktop opens
  // with the previewer); an existing file keeps its name.
  name_ = save ? (document_path.empty() ? std::string("scene.phonglab.json")
                                        : std::filesystem::path(document_path).filename().string())
               : std::string();
  error_.clear();
  visible_ = open_now_ = true;
}

FileBrowser::Choice FileBrowser::draw() {
  Choice choice;
  if (!visible_) return choice;
  ui::FileBrowserView view;
  view.save = save_;
  view.listing = &listing_;
  view.recent = &recent_;
  view.name_field = &name_;
  view.error = error_;
  ui::FileBrowserActions actions;
  const bool showing = ui::file_browser_dialog(open_now_, view, actions);
  open_now_ = false;
  if (!actions.go_to.empty()) listing_ = ui::list_folder(actions.go_to, browser_filter(save_));
  if (!actions.embedded.empty()) choice = {Choice::Kind::kOpen, actions.embedded};
  std::error_code ec;
  if (!actions.chosen.empty() && std::filesystem::is_directory(actions.chosen, ec)) {
    // A folder typed into the name field: the browser goes there and stays open.
    listing_ = ui::list_folder(actions.chosen, browser_filter(save_));
    name_.clear();
    open_now_ = true;
    return choice;
  }
  // A scene or an OBJ to open alone (a dropped OBJ joins the scene instead), or where to save.
  if (!actions.chosen.empty()) choice = {save_ ? Choice::Kind::kSaveAs : Choice::Kind::kOpen, actions.chosen};
  if (!showing || actions.cancel || !actions.chosen.empty() || !actions.embedded.empty()) visible_ = false;
  return choice;
}

}  // namespace phonglab
