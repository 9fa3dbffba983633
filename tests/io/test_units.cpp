// Numbers with units in configs (docs/scene-schema.md).
#include <gtest/gtest.h>

#include "io/units.hpp"

using namespace grainlab;

TEST(Units, ConvertsToSI) {
  EXPECT_DOUBLE_EQ(parse_quantity("150 kPa", Quantity::pressure), 150e3);
  EXPECT_DOUBLE_EQ(parse_quantity("46.2 GPa", Quantity::pressure), 46.2e9);
  EXPECT_DOUBLE_EQ(parse_quantity("2 mm", Quantity::length), 2e-3);
  EXPECT_DOUBLE_EQ(parse_quantity("0.01 m/s", Quantity::velocity), 0.01);
  EXPECT_DOUBLE_EQ(parse_quantity("6 mm/min", Quantity::velocity), 1e-4);
  EXPECT_DOUBLE_EQ(parse_quantity("2500 kg/m3", Quantity::density), 2500.0);
  EXPECT_DOUBLE_EQ(parse_quantity("15 %", Quantity::dimensionless), 0.15);
  EXPECT_DOUBLE_EQ(parse_quantity("400 mm^2", Quantity::area), 4e-4);
  EXPECT_DOUBLE_EQ(parse_quantity("2.5 cm2", Quantity::area), 2.5e-4);
  EXPECT_DOUBLE_EQ(parse_quantity("1e-3", Quantity::length), 1e-3);  // bare number: SI
}

TEST(Units, RejectsWrongDimensionAndGarbage) {
  EXPECT_THROW(parse_quantity("2 kPa", Quantity::length), std::invalid_argument);
  EXPECT_THROW(parse_quantity("two mm", Quantity::length), std::invalid_argument);
  try {
    parse_quantity("3 furlongs", Quantity::length);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("mm"), std::string::npos) << "lists accepted units";
  }
}

TEST(Units, RejectsNonFiniteQuantities) {
  // Strings skip TOML's own checks: "inf s" once made a run of -9223372036854775808 steps.
  for (const char* text : {"inf s", "nan", "-inf ms", "1e308 GPa", "infinity"}) {
    SCOPED_TRACE(text);
    try {
      parse_quantity(text, text[0] == '1' ? Quantity::pressure : Quantity::time);
      FAIL() << "accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("finite"), std::string::npos) << e.what();
    }
  }
  EXPECT_DOUBLE_EQ(parse_quantity("1e300 s", Quantity::time), 1e300);  // large but finite
}
