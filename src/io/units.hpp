// Numbers with units in configuration files. Every value is stored in SI; a config may give a
// plain number (read as SI) or a string "value unit", e.g. "150 kPa", "2 mm", "0.01 m/s".
#pragma once

#include <string>
#include <string_view>

namespace grainlab {

enum class Quantity {
  dimensionless,
  length,
  area,
  time,
  pressure,
  density,
  velocity,
  acceleration,
  angular_velocity,
  mass,
  force
};

const char* si_unit(Quantity q);

// Parses "value unit" for quantity q into SI. Throws std::invalid_argument with a message that
// lists the accepted units.
double parse_quantity(std::string_view text, Quantity q);

}  // namespace grainlab
