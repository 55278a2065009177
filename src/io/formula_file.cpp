#include "io/formula_file.h"

#include <nlohmann/json.hpp>

#include "io/scene/scene_io.h"
#include "io/scene/scene_load.h"
#include "io/scene/scene_reader.h"

namespace phonglab {

using namespace scene_load;

namespace {

constexpr std::size_t kMaxFormulaFileBytes = std::size_t{1} << 20;  // 1 MiB: three texts of at most 64 KiB

const char* json_kind(const nlohmann::json& v) {
  if (v.is_object()) return "an object";
  if (v.is_array()) return "an array";
  if (v.is_number()) return "a number";
  if (v.is_boolean()) return "true or false";
  if (v.is_null()) return "null";
  return "a string";
}

FormulaFileLoad checked(const std::string& text, const std::string& file_name) {
  Issues issues;
  ParsedText parsed;
  FormulaTexts texts{};
  if (parse_text(text, "a formula file", issues, parsed)) {
    const PosIndex& index = *parsed.index;
    if (!parsed.root.is_object()) {
      issues.add({index.begin(0), "",
                  std::string("expected an object of formulas such as {\"diffuse\": \"kd * dot(N, L)\"} (got ") +
                      json_kind(parsed.root) + ")"});
    } else {
      const std::vector<std::string_view> slots = {"ambient", "diffuse", "specular"};
      for (const std::uint32_t member : index.children(0)) {
        const std::string key = index.key(member);
        const std::optional<FormulaSlot> slot = formula_slot_from_name(key);
        if (!slot) {
          issues.add({index.key_begin(member), key, "unknown slot" + suggestion(key, slots, "the slots are")});
          continue;
        }
        const nlohmann::json& value = parsed.root.at(key);
        if (!value.is_string()) {
          issues.add({index.begin(member), key,
                      std::string("expected the formula's text as a string (got ") + json_kind(value) + ")"});
          continue;
        }
        texts[static_cast<std::size_t>(*slot)] = value.get<std::string>();
      }
    }
  }
  FormulaFileLoad r;
  const bool truncated = issues.full();
  r.errors = to_diagnostics(text, std::move(issues.list()), truncated, file_name);
  if (r.errors.empty()) r.texts = texts;
  return r;
}

FormulaFileLoad failure(const std::string& file, std::string message) {
  FormulaFileLoad r;
  r.errors.push_back(line_diagnostic(file, 0, std::move(message)));
  return r;
}

}  // namespace

std::string formula_file_text(const FormulaTexts& texts) {
  nlohmann::ordered_json out = nlohmann::ordered_json::object();
  for (int s = 0; s < kFormulaSlots; ++s) {
    const std::string& text = texts[static_cast<std::size_t>(s)];
    if (!text.empty()) out[std::string(formula_slot_name(static_cast<FormulaSlot>(s)))] = text;
  }
  // Bytes that are not UTF-8 (none come from the panel's boxes) are written as U+FFFD.
  return out.dump(2, ' ', false, nlohmann::ordered_json::error_handler_t::replace) + "\n";
}

FormulaFileLoad load_formula_text(const std::string& text, const std::string& file_name) {
  try {
    return checked(text, file_name);
  } catch (const std::bad_alloc&) {
    return failure(file_name, "out of memory while reading the formulas");
  } catch (const std::exception& e) {
    return failure(file_name, std::string("internal error while reading the formulas: ") + e.what());
  }
}

FormulaFileLoad load_formula_file(const std::string& path) {
  std::string error;
  const std::optional<std::string> text = read_text_file(path, kMaxFormulaFileBytes, error);
  if (!text) return failure(path, error);
  return load_formula_text(*text, path);
}

std::string save_formula_file(const std::string& path, const FormulaTexts& texts) {
  return write_file_atomically(path, formula_file_text(texts));
}

}  // namespace phonglab
