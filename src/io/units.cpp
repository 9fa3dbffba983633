#include "io/units.hpp"

#include <charconv>
#include <cmath>
#include <stdexcept>
#include <utility>
#include <vector>

namespace grainlab {
namespace {

using UnitTable = std::vector<std::pair<std::string_view, double>>;

const UnitTable& units_of(Quantity q) {
  static const UnitTable none{{"", 1.0}, {"%", 0.01}};
  static const UnitTable length{{"m", 1.0}, {"cm", 1e-2}, {"mm", 1e-3}, {"um", 1e-6}, {"µm", 1e-6}};
  static const UnitTable area{{"m2", 1.0},    {"m^2", 1.0},  {"cm2", 1e-4},
                              {"cm^2", 1e-4}, {"mm2", 1e-6}, {"mm^2", 1e-6}};
  static const UnitTable time{{"s", 1.0},   {"ms", 1e-3},  {"us", 1e-6}, {"µs", 1e-6},
                              {"ns", 1e-9}, {"min", 60.0}, {"h", 3600.0}};
  static const UnitTable pressure{{"Pa", 1.0}, {"kPa", 1e3}, {"MPa", 1e6}, {"GPa", 1e9}};
  static const UnitTable density{{"kg/m3", 1.0}, {"kg/m^3", 1.0}, {"g/cm3", 1e3}, {"g/cm^3", 1e3}};
  static const UnitTable velocity{
      {"m/s", 1.0}, {"mm/s", 1e-3}, {"cm/s", 1e-2}, {"mm/min", 1e-3 / 60.0}, {"m/min", 1.0 / 60.0}};
  static const UnitTable acceleration{{"m/s2", 1.0}, {"m/s^2", 1.0}, {"g", 9.80665}};
  static const UnitTable angular{{"rad/s", 1.0}, {"rpm", 2.0 * 3.14159265358979323846 / 60.0}};
  static const UnitTable mass{{"kg", 1.0}, {"g", 1e-3}, {"mg", 1e-6}};
  static const UnitTable force{{"N", 1.0}, {"mN", 1e-3}, {"kN", 1e3}};
  switch (q) {
    case Quantity::dimensionless:
      return none;
    case Quantity::length:
      return length;
    case Quantity::area:
      return area;
    case Quantity::time:
      return time;
    case Quantity::pressure:
      return pressure;
    case Quantity::density:
      return density;
    case Quantity::velocity:
      return velocity;
    case Quantity::acceleration:
      return acceleration;
    case Quantity::angular_velocity:
      return angular;
    case Quantity::mass:
      return mass;
    case Quantity::force:
      return force;
  }
  return none;
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

}  // namespace

const char* si_unit(Quantity q) {
  switch (q) {
    case Quantity::dimensionless:
      return "-";
    case Quantity::length:
      return "m";
    case Quantity::area:
      return "m^2";
    case Quantity::time:
      return "s";
    case Quantity::pressure:
      return "Pa";
    case Quantity::density:
      return "kg/m^3";
    case Quantity::velocity:
      return "m/s";
    case Quantity::acceleration:
      return "m/s^2";
    case Quantity::angular_velocity:
      return "rad/s";
    case Quantity::mass:
      return "kg";
    case Quantity::force:
      return "N";
  }
  return "?";
}

double parse_quantity(std::string_view text, Quantity q) {
  const std::string_view s = trim(text);
  double value = 0.0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
  if (ec != std::errc{} || end == s.data())
    throw std::invalid_argument("expected a number with a unit, e.g. \"2 mm\", got \"" +
                                std::string(text) + "\"");
  // "inf", "nan" and overflowing values parse as numbers; as quantities they are errors, like
  // the TOML inf and nan (TableReader::to_number).
  auto finite = [&](double v) {
    if (!std::isfinite(v))
      throw std::invalid_argument("expected a finite number, got \"" + std::string(text) + "\"");
    return v;
  };
  const std::string_view unit = trim(std::string_view(end, s.data() + s.size() - end));
  if (unit.empty()) return finite(value);  // a bare number is SI
  std::string accepted;
  for (const auto& [name, factor] : units_of(q)) {
    if (name == unit) return finite(value * factor);
    if (!name.empty()) accepted += (accepted.empty() ? "" : ", ") + std::string(name);
  }
  throw std::invalid_argument("unknown unit \"" + std::string(unit) + "\" for a " +
                              std::string(si_unit(q)) + " quantity (accepted: " + accepted + ")");
}

}  // namespace grainlab
