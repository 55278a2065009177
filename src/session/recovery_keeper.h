// Nothing lost: a document's unsaved edits kept in a recovery file of the state folder
// (interaction/recovery.h names the files), written a few seconds after the last edit of a
// burst, at once when a signal arrives, restored at the next start, removed once saved or
// discarded. The file side only: the offer's dialog and the signals are the shell's.
#pragma once

#include <optional>
#include <string>
#include <utility>

#include "interaction/recovery.h"
#include "session/document.h"

namespace phonglab {

class RecoveryKeeper {
 public:
  static constexpr double kAutosaveDelay = 2.0;  // seconds after the last edit: a drag's many edits are one write

  // `folder`: where recovery files go (empty: nowhere, nothing is kept).
  explicit RecoveryKeeper(std::string folder) : folder_(std::move(folder)) {}
  // The state folder's recovery/ ($XDG_STATE_HOME/phonglab/recovery, or under ~/.local/state).
  static std::string default_folder();

  // What a document's recovery file is named after: (the embedded scene's name, true) or (the
  // file's absolute path, false); nothing for a lesson's step (nobody's file).
  static std::optional<std::pair<std::string, bool>> source_of(const SceneDocument& doc);

  // The scene was edited at `now` (seconds, any clock the caller keeps).
  void edited(double now) { last_edit_ = now; }
  // Once a UI frame: a document with no unsaved edits keeps no file; otherwise the file is
  // written when the last edit is kAutosaveDelay old, once per burst of edits.
  void autosave(const SceneDocument& doc, double now);
  // Writes the document's recovery file now (unchanged text is not written again); its path,
  // or "" when there is none to write or the write failed (error() says why).
  std::string write(const SceneDocument& doc);
  // The file this session wrote or restored, removed.
  void remove();
  // A recovery to offer at start: the newest of `doc`'s source, or with `any_source` the newest
  // of any scene.
  std::optional<ui::RecoveryEntry> find(const SceneDocument& doc, bool any_source) const;
  // Restores `entry` into `doc`, which must already hold its source (the scene or file it was
  // edited from): the kept scene replaces the document's, carrying the file's identity of the
  // edits' time (SceneDocument::edits_made_over: Save asks when another program changed the file
  // since), and the recovery file becomes this document's (rewritten on the next edits, removed
  // once saved). The diagnostics when the kept scene does not load (the document is unchanged).
  struct Restored {
    std::string error;           // empty on success
    bool changed_on_disk = false;  // the file changed since the edits were made
    std::string status;            // what the restore did, as the Scene file panel says it
  };
  Restored restore(SceneDocument& doc, const ui::RecoveryEntry& entry);

  const std::string& written() const { return written_; }
  const std::string& error() const { return error_; }
  const std::string& folder() const { return folder_; }

 private:
  std::string folder_;
  std::string written_;       // this document's recovery file, once written or restored ("" none)
  std::string written_text_;  // what it holds (unchanged edits are not written again)
  double last_edit_ = 0;      // when the scene was last edited
  double written_for_ = -1;   // the last_edit_ the file holds
  std::string error_;         // why the last write failed

  void adopt(const ui::RecoveryEntry& entry);
};

}  // namespace phonglab
