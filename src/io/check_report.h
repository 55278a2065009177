// A check's verdict as JSON (docs/checking.md): the text report's figures under fixed keys, one
// definition for phonglab-cli check --json and the web page.
#pragma once

#include <string>

#include "check/check.h"

namespace phonglab {

// `indent` as nlohmann::json::dump's (-1: one line).
std::string check_to_json(const CheckResult& result, int indent = -1);

}  // namespace phonglab
