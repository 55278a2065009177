#include "io/check_report.h"

#include <cmath>

#include <nlohmann/json.hpp>

namespace phonglab {

std::string check_to_json(const CheckResult& r, int indent) {
  const auto number = [](double v) -> nlohmann::json {
    if (std::isfinite(v)) return v;
    return nullptr;  // JSON has no NaN
  };
  const auto colour = [&](const Color& c) { return nlohmann::json::array({number(c.x), number(c.y), number(c.z)}); };
  nlohmann::json mistakes = nlohmann::json::array();
  for (const Mistake m : r.mistakes) mistakes.push_back(std::string(mistake_info(m).name));
  const nlohmann::json j = {{"verdict", r.match ? "match" : "differs"},
                            {"pixels", r.pixels},
                            {"differing", r.differing},
                            {"max_difference", number(r.max_difference)},
                            {"worst_pixel", {r.worst_x, r.worst_y}},
                            {"yours", colour(r.worst_yours)},
                            {"reference", colour(r.worst_reference)},
                            {"units", r.codes8 ? "8-bit codes" : "linear"},
                            {"nan", r.nan},
                            {"mistake", r.mistake.empty() ? nlohmann::json(nullptr) : nlohmann::json(r.mistake)},
                            {"mistakes", mistakes},
                            {"explained", r.mistake.empty() ? 0.0 : r.explained},
                            {"summary", check_summary(r)}};
  return j.dump(indent);
}

}  // namespace phonglab
