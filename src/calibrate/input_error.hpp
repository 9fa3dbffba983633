// The error type of the calibrate part: something is wrong with the user's data or options.
// The command-line program turns it into exit code 2; the message already names the file and,
// where there is one, the line ("throws.csv line 7: ...").
#pragma once

#include <stdexcept>
#include <string>

namespace grainlab::calibrate {

class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace grainlab::calibrate
