// Errors in user input (configuration files, data files, options): the message names the file,
// the key or line, and what was expected. The program exits with code 2 and writes nothing.
#pragma once

#include <stdexcept>
#include <string>

namespace grainlab {

class ConfigError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace grainlab
