// One command of a test script being run, as the script driver's units share it
// (script_driver.cpp, script_driver_drag.cpp): its words, a failure said, a wait begun.
#pragma once

#include <string>
#include <vector>

#include "apps/previewer/script_driver.h"
#include "apps/previewer/script_words.h"

namespace phonglab {

constexpr double kDefaultWaitSeconds = 30;  // generous: sanitizer builds render slowly

struct ScriptDriver::ScriptStep {
  ScriptDriver& driver;
  const ScriptCommand& command;
  const std::vector<std::string>& w;
  double now;
  bool fail(const std::string& message) {
    driver.fail_script(command, message);
    return false;
  }
  // Waits for `kind`, with the timeout in word `timeout_word` when there is one.
  bool wait_for(ScriptWait kind, std::size_t timeout_word) {
    double timeout = kDefaultWaitSeconds;
    if (w.size() > timeout_word && !script::parse_double(w[timeout_word], timeout)) return fail("bad timeout");
    driver.run_.wait = kind;
    driver.run_.deadline = now + timeout;
    return true;
  }
};

}  // namespace phonglab
