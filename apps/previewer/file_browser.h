// The Open and Save-as file browser (Ctrl+O, Ctrl+Shift+S, the Scene file panel's buttons) and
// the recent files it lists, kept in the state folder ($XDG_STATE_HOME/phonglab/recent). It owns
// its state and says what was chosen; the previewer opens or saves through its guards.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "interaction/file_browser.h"

namespace phonglab {

class FileBrowser {
 public:
  // Opens the dialog: to save (JSON scenes listed, the name field holding the document's file
  // name) or to open (scenes and meshes), in the last folder shown or the document's.
  void open(bool save, const std::string& document_path);
  // What the user chose in a frame.
  struct Choice {
    enum class Kind : std::uint8_t { kNone, kOpen, kSaveAs };
    Kind kind = Kind::kNone;
    std::string path;  // a file, or an embedded scene's name (kOpen)
  };
  // Draws the dialog while it is open (ImGui); its choice this frame.
  Choice draw();
  // A file opened or saved: first in the recent list, which is written back.
  void remember(const std::string& path);

  bool visible() const { return visible_; }
  bool saving() const { return save_; }
  const std::string& folder() const { return listing_.folder; }
  const std::string& name() const { return name_; }
  // The recent files as far as they were read (on opening the browser or remembering a file).
  const std::vector<std::string>& recent() const { return recent_; }

 private:
  static std::string recent_path();
  void load_recent();  // the list the last session left, once

  bool visible_ = false;
  bool open_now_ = false;  // open the popup this frame
  bool save_ = false;      // Save as, else Open
  ui::FolderListing listing_;
  std::string name_;       // the name field
  std::string error_;
  std::vector<std::string> recent_;
  bool recent_loaded_ = false;
};

}  // namespace phonglab
