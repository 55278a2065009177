// The file dialogs' decisions, for any client (the previewer's modals and its scripts, tests): an
// action that would lose unsaved edits waits for the unsaved-changes question; a Save that meets
// a change another program made on disk waits for the changed-on-disk question; what waited
// behind a save runs once the save wrote. The flow saves through the document itself; opening,
// reloading, quitting and starting a lesson are the client's, handed back as the action to run.
// No GLFW, ImGui or GL.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "session/document.h"

namespace phonglab {

class FileFlow {
 public:
  // Something that would lose unsaved edits.
  struct Action {
    enum class Kind : std::uint8_t { kNone, kQuit, kOpen, kReload, kLesson };
    Kind kind = Kind::kNone;
    std::string arg;  // kOpen: what to open; kLesson: the lesson's name
    bool operator==(const Action&) const = default;
  };
  // The question waiting for an answer.
  enum class Question : std::uint8_t { kNone, kUnsavedChanges, kChangedOnDisk };
  // The answers: the unsaved-changes question takes Save, Save as, Discard and Cancel; the
  // changed-on-disk one Overwrite, Reload and Cancel.
  enum class Answer : std::uint8_t { kSave, kSaveAs, kDiscard, kCancel, kOverwrite, kReload };
  // What a call leaves to the client, in order: reload the file (the edits go), report the save,
  // then run the action.
  struct Outcome {
    bool reload = false;        // the changed-on-disk question's Reload: the file's version comes
    std::optional<bool> saved;  // a save was tried: whether it wrote (the document's error_text() says why not)
    Action run;                 // to run now; kNone: nothing
  };
  // What a file changed on disk (seen by a poll) asks for.
  enum class OnDisk : std::uint8_t { kNothing, kReload, kKeepEdits };

  explicit FileFlow(SceneDocument& doc) : doc_(doc) {}

  // Runs `action` at once (returned) when nothing unsaved would be lost; otherwise it waits
  // for the unsaved-changes question. Edits made before the call count.
  Outcome request(Action action);
  // Save (to the document's file) or Save as `path`; what waited behind it runs once it wrote.
  // A Save that meets a change made on disk writes nothing and asks. While a question is open it
  // does nothing (Ctrl+S under the dialog): the question is answered first.
  Outcome save(bool as, const std::string& path);
  // The open question's answer; `path` is where Save as writes. An answer that does not belong
  // to the question (or no question) changes nothing.
  Outcome answer(Answer answer, const std::string& path);

  Question question() const { return question_; }
  // What waits for the unsaved-changes question (or behind a save: the changed-on-disk one).
  const Action& waiting() const { return waiting_; }
  // Whether Save can write the document's file (it has one, and it is not an OBJ opened alone).
  bool can_save() const;
  // Whether the document's file changed on disk since it was read or written here.
  bool file_changed() const;
  // A poll of the file: a change on disk reloads a clean document (keeping the view), and is
  // only flagged over unsaved edits, which are never thrown away silently.
  OnDisk poll(bool auto_reload) const;

 private:
  Outcome save_now(bool as, const std::string& path);  // save(), what waits behind it kept
  Outcome finish_save(bool wrote);

  SceneDocument& doc_;
  Question question_ = Question::kNone;
  Action waiting_;
};

}  // namespace phonglab
