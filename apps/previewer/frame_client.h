// The one seam between the shell's main loop and a client that drives it from inside (the test
// scripts' ScriptDriver): the loop calls these at fixed points of every frame and knows nothing
// else of the client. Without a client (no --script), none of them runs.
#pragma once

#include <string>

namespace phonglab {

class FrameClient {
 public:
  virtual ~FrameClient() = default;
  // Before the frame's ImGui frame: the client injects this frame's input and acts.
  virtual void before_frame(double now) = 0;
  // After the frame is drawn, before the swap: a path to save the window to, or "".
  virtual std::string screenshot_wanted() = 0;
  // That screenshot could not be written (the shell has said why and quits).
  virtual void screenshot_failed() = 0;
  // The client has more to do: the loop does not sleep idle.
  virtual bool busy() const = 0;
  // The client's hand is on the view (its input under way): the frame counts as interacting.
  virtual bool hand_on() const = 0;
  // What the program exits with when the window closes: 0, or the client's failure status.
  virtual int exit_status() const = 0;
};

}  // namespace phonglab
