// Snapshot A of the A/B compare, without a window: asked for, taken once the image it names is
// done (or, for a lesson, its first full-resolution image), dropped when an edit comes first; when
// it and the live image can be compared, the samples a lesson's difference keeps the live image
// at, and the caption that says what the compare view shows. Unit-tested in
// tests/session/test_snapshot_a.cpp.
#pragma once

#include <cstdint>
#include <string>

#include "core/render/progressive.h"
#include "core/teaching/compare.h"

namespace phonglab {

class SnapshotA {
 public:
  // A of the renderer's current `generation`: the finished image of what is on screen now, never
  // a half-converged one (its noise would show in |live - A| as if something had changed). With
  // `first_full`, its first full-resolution image (every pixel's centre sample: a lesson's answer
  // is on screen in seconds, and its difference stays exact at A's samples, target_spp).
  void request(std::uint64_t generation, bool first_full);
  // Each frame: takes A from `shown` once it is the image asked for (`final`: the renderer idles on
  // the generation and its last image is on screen); drops the request when the renderer moved
  // on to another generation first. True when A was taken.
  bool take_when_ready(std::uint64_t renderer_generation, const ProgressiveFrame& shown, bool final);
  void clear();  // another document or lesson step: no A, nothing asked
  // A from a file: a student's own image of the view (docs/checking.md), at the view's size. It
  // is compared with the live image whatever the samples (the student's are the pixel centres).
  void set_file_image(ProgressiveFrame image, std::string name);
  const std::string& file_name() const { return file_name_; }  // "" : A is the renderer's

  bool has_image() const { return !image_.pixels.empty(); }
  const ProgressiveFrame& image() const { return image_; }
  bool requested() const { return requested_; }
  bool dropped() const { return dropped_; }  // the last request was overtaken by an edit
  bool first_full() const { return first_full_; }

  // Whether A and `shown` can be compared in `view`: the same size and level, and for the
  // difference the same samples (only a change shows), except against the indirect light
  // (`constant_ambient` false), which differs everywhere and is shown as it settles.
  bool comparable(const ProgressiveFrame& shown, CompareView view, bool constant_ambient) const;
  // The renderer's target: `wanted`, or A's samples while a presented lesson shows its difference
  // against a first-full A (not for the indirect light: its noise settles only with samples).
  int target_spp(int wanted, bool presenting, CompareView view, bool constant_ambient) const;
  // One line on what the compare view shows, or why it cannot.
  std::string caption(const ProgressiveFrame& shown, CompareView view, bool constant_ambient, int target_spp,
                      double difference_gain) const;

 private:
  ProgressiveFrame image_;  // pixels empty: none
  std::uint64_t generation_ = 0;  // the renderer generation A was asked of
  bool requested_ = false;
  bool dropped_ = false;
  bool first_full_ = false;
  std::string file_name_;  // A came from this file
};

}  // namespace phonglab
