#include "session/file_flow.h"

#include <utility>

namespace phonglab {

FileFlow::Outcome FileFlow::request(Action action) {
  doc_.update_dirty();  // edits made earlier in this frame count
  if (!doc_.dirty()) return Outcome{false, std::nullopt, std::move(action)};
  waiting_ = std::move(action);
  question_ = Question::kUnsavedChanges;
  return {};
}

FileFlow::Outcome FileFlow::save(bool as, const std::string& path) {
  if (question_ != Question::kNone) return {};  // the open question is answered first
  return save_now(as, path);
}

FileFlow::Outcome FileFlow::save_now(bool as, const std::string& path) {
  question_ = Question::kNone;
  if (as) return finish_save(doc_.save_as(path));
  const SceneDocument::SaveResult result = doc_.save();
  if (result == SceneDocument::SaveResult::kChangedOnDisk) {
    question_ = Question::kChangedOnDisk;  // the answer decides; what waits behind the save waits for it
    return {};
  }
  return finish_save(result == SceneDocument::SaveResult::kSaved);
}

FileFlow::Outcome FileFlow::finish_save(bool wrote) {
  Outcome outcome;
  outcome.saved = wrote;
  if (wrote) outcome.run = std::move(waiting_);
  waiting_ = Action{};
  return outcome;
}

FileFlow::Outcome FileFlow::answer(Answer answer, const std::string& path) {
  if (question_ == Question::kUnsavedChanges) {
    switch (answer) {
      case Answer::kSave:
      case Answer::kSaveAs: return save_now(answer == Answer::kSaveAs, path);  // the action waits behind the save
      case Answer::kDiscard: {
        question_ = Question::kNone;
        return Outcome{false, std::nullopt, std::exchange(waiting_, Action{})};
      }
      case Answer::kCancel:
        question_ = Question::kNone;
        waiting_ = Action{};
        return {};
      default: return {};
    }
  }
  if (question_ == Question::kChangedOnDisk) {
    switch (answer) {
      case Answer::kOverwrite:
        question_ = Question::kNone;
        return finish_save(doc_.save(true) == SceneDocument::SaveResult::kSaved);
      case Answer::kReload: {
        question_ = Question::kNone;
        Outcome outcome;
        outcome.reload = true;  // the edits go, the file's version comes
        Action after = std::exchange(waiting_, Action{});
        if (after.kind != Action::Kind::kReload) outcome.run = std::move(after);
        return outcome;
      }
      case Answer::kCancel:
        question_ = Question::kNone;
        waiting_ = Action{};
        return {};
      default: return {};
    }
  }
  return {};
}

bool FileFlow::can_save() const { return !doc_.file_path().empty() && !doc_.opened_mesh(); }

bool FileFlow::file_changed() const { return !doc_.file_path().empty() && doc_.changed_on_disk(); }

FileFlow::OnDisk FileFlow::poll(bool auto_reload) const {
  if (!auto_reload || !file_changed()) return OnDisk::kNothing;
  return doc_.dirty() ? OnDisk::kKeepEdits : OnDisk::kReload;
}

}  // namespace phonglab
