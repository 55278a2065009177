#include "session/snapshot_a.h"

#include <algorithm>
#include <cstdio>

namespace phonglab {

void SnapshotA::request(std::uint64_t generation, bool first_full) {
  requested_ = true;
  first_full_ = first_full;
  generation_ = generation;
  dropped_ = false;
}

bool SnapshotA::take_when_ready(std::uint64_t renderer_generation, const ProgressiveFrame& shown, bool final) {
  if (!requested_) return false;
  if (renderer_generation != generation_) {
    requested_ = false;
    dropped_ = true;
    return false;
  }
  const bool ready = first_full_ ? shown.generation == generation_ && shown.divisor == 1 && !shown.quads : final;
  if (!ready || shown.pixels.empty()) return false;
  image_ = shown;
  requested_ = false;
  file_name_.clear();
  return true;
}

void SnapshotA::clear() {
  image_ = ProgressiveFrame{};
  requested_ = dropped_ = false;
  file_name_.clear();
}

void SnapshotA::set_file_image(ProgressiveFrame image, std::string name) {
  image_ = std::move(image);
  file_name_ = std::move(name);
  requested_ = dropped_ = first_full_ = false;
}

bool SnapshotA::comparable(const ProgressiveFrame& shown, CompareView view, bool constant_ambient) const {
  if (image_.pixels.empty() || image_.width != shown.width || image_.height != shown.height ||
      image_.divisor != shown.divisor || image_.pixels.size() != shown.pixels.size()) {
    return false;
  }
  if (!file_name_.empty()) return true;
  return view != CompareView::kDifference || image_.spp == shown.spp || !constant_ambient;
}

int SnapshotA::target_spp(int wanted, bool presenting, CompareView view, bool constant_ambient) const {
  const bool lesson_difference =
      presenting && first_full_ && view == CompareView::kDifference && has_image() && constant_ambient;
  const int target = std::max(wanted, 1);
  return lesson_difference ? std::min(target, static_cast<int>(std::max(image_.spp, 1u))) : target;
}

std::string SnapshotA::caption(const ProgressiveFrame& shown, CompareView view, bool constant_ambient, int target_spp,
                               double difference_gain) const {
  char text[160];
  if (requested_ && first_full_) {
    std::snprintf(text, sizeof text, "A is taken at its first full-resolution image");
  } else if (requested_) {
    std::snprintf(text, sizeof text, "A is taken when the image is done (%u of %d spp)", shown.spp, target_spp);
  } else if (image_.pixels.empty()) {
    std::snprintf(text, sizeof text, "%s", dropped_ ? "A was not taken: the view changed before the image was done"
                                                    : "no A yet: Snapshot A keeps the finished image");
  } else if (!file_name_.empty() && (image_.width != shown.width || image_.height != shown.height)) {
    std::snprintf(text, sizeof text, "A is your image %dx%d, the view is now %dx%d: open it at the view's size",
                  image_.width, image_.height, shown.width, shown.height);
  } else if (!file_name_.empty()) {
    std::snprintf(text, sizeof text, "%s A, your image %.60s, against the live image",
                  view == CompareView::kWipe ? "wipe:" : "|live - A|:", file_name_.c_str());
  } else if (image_.width != shown.width || image_.height != shown.height) {
    std::snprintf(text, sizeof text, "A is %dx%d, the view is now %dx%d: take A again to compare", image_.width,
                  image_.height, shown.width, shown.height);
  } else if (!comparable(shown, view, constant_ambient)) {
    std::snprintf(text, sizeof text, "|live - A| shows when live has A's %u spp (now %u)", image_.spp, shown.spp);
  } else if (view == CompareView::kWipe) {
    std::snprintf(text, sizeof text, "wipe: A (%u spp) left of the line, live right", image_.spp);
  } else {
    std::snprintf(text, sizeof text, "|live - A| \xC3\x97 %.0f (%u spp each)", difference_gain, image_.spp);
  }
  return text;
}

}  // namespace phonglab
