// Ctrl-C / SIGTERM during a long run: the handler only raises a flag; the run loop sees it,
// writes a checkpoint and stops cleanly (grainlab run --resume DIR continues).
#pragma once

#include <stdexcept>

namespace grainlab {

void install_interrupt_handler();
bool interrupt_requested();

// Thrown by a run loop after it has saved what can be resumed.
class Interrupted : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace grainlab
