// Nothing lost: unsaved edits go to a recovery file in the state folder a few seconds after the
// last edit and when SIGINT, SIGTERM or SIGHUP arrives; the next start offers them back; a clean
// save or quit removes the file (docs/previewer.md#recovery).
#include "apps/previewer/viewer_app.h"

#include <pthread.h>
#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <thread>

#include "io/scene/scene_io.h"

namespace phonglab {

namespace {

std::atomic<int> g_signal{0};

}  // namespace

void start_signal_watcher() {
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, SIGINT);
  sigaddset(&set, SIGTERM);
  sigaddset(&set, SIGHUP);
  pthread_sigmask(SIG_BLOCK, &set, nullptr);
  std::thread([set] {
    for (;;) {
      int sig = 0;
      if (sigwait(&set, &sig) != 0) continue;
      if (g_signal.exchange(sig) != 0) _exit(128 + sig);  // asked twice: no more waiting
      Platform::wake();  // from the signal thread: the loop handles it
    }
  }).detach();
}

int pending_signal() { return g_signal.load(); }

bool FileShell::handle_signal() {
  const int sig = pending_signal();
  if (sig == 0) return false;
  s_.doc.update_dirty();
  if (s_.doc.dirty()) {
    const std::string path = s_.session.recovery().write(s_.doc);
    if (!path.empty()) std::cerr << "recovery: " << path << "\n";
  }
  recovery_.keep = true;
  s_.exit_code = 128 + sig;
  s_.quit = true;
  return true;
}

void FileShell::find_recovery() {
  // On the document's scene, or with no SCENE given the newest of any scene.
  recovery_.offer = s_.session.recovery().find(s_.doc, !s_.options.scene_given);
  recovery_.open_modal = recovery_.offer.has_value();
}

void FileShell::handle_recovery_modal() {
  if (!recovery_.offer) return;
  char when[64] = "earlier";
  const std::time_t t = static_cast<std::time_t>(recovery_.offer->saved);
  if (std::tm tm{}; localtime_r(&t, &tm) != nullptr) std::strftime(when, sizeof when, "at %Y-%m-%d %H:%M:%S", &tm);
  const std::string source = recovery_.offer->embedded ? "the embedded scene '" + recovery_.offer->source + "'"
                                                       : recovery_.offer->source;
  const auto choice = ui::recovery_modal(recovery_.open_modal, source, when);
  if (recovery_.open_modal) recovery_.modal_visible = true;
  recovery_.open_modal = false;
  if (choice == ui::RecoveryChoice::kNone) return;
  recovery_.modal_visible = false;
  const ui::RecoveryEntry entry = *recovery_.offer;
  recovery_.offer.reset();
  if (choice == ui::RecoveryChoice::kRestore) {
    restore_recovery(entry);
  } else if (choice == ui::RecoveryChoice::kDiscard) {
    std::error_code ec;
    std::filesystem::remove(entry.scene_path, ec);
    std::filesystem::remove(std::filesystem::path(entry.scene_path).replace_extension(".source"), ec);
  }
}

void FileShell::restore_recovery(const ui::RecoveryEntry& entry) {
  const auto source = RecoveryKeeper::source_of(s_.doc);
  if (!source || source->first != entry.source || source->second != entry.embedded) {
    open_scene(entry.source);
    const auto now_source = RecoveryKeeper::source_of(s_.doc);
    if (!now_source || now_source->first != entry.source) {
      file_state_.error_text = "cannot restore: " + entry.source + " does not open (" + file_state_.error_text +
                               "); the kept edits stay in " + entry.scene_path;
      return;
    }
  }
  const RecoveryKeeper::Restored r = s_.session.recovery().restore(s_.doc, entry);
  if (!r.error.empty()) {
    file_state_.error_text = r.error;
    return;
  }
  file_state_.status = r.status;
  s_.edits.replaced = true;
}

}  // namespace phonglab
