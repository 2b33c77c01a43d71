// One set of physical bounds for every way a number enters a run: scenario
// files, REST bodies, live edits and sweep specs all check against these, so a
// value refused live is refused in a file too. Generous for any real arm, and
// small enough that the engine's arithmetic on them stays finite.
#pragma once

#include <string>

namespace rrlab {

// A bounded physical quantity: |value| ≤ bound (SI units), with the unit
// named in messages. Angular quantities are reported in the file's angle unit.
struct Quantity {
  double bound;
  const char* unit;   // SI unit, as printed
  bool angular;       // rad-based: printed in degrees when the file uses them
};

struct PhysicalBounds {
  static constexpr Quantity length{1.0e4, "m", false};           // coordinates, lengths, sizes, radii
  static constexpr Quantity angle{1.0e3, "rad", true};           // joint angles, limits, rpy (≈159 turns)
  static constexpr Quantity linear_speed{1.0e2, "m/s", false};   // obstacle and prismatic joint speeds
  static constexpr Quantity angular_speed{1.0e3, "rad/s", true}; // revolute joint speed limits
  static constexpr Quantity acceleration{1.0e6, "m/s² or rad/s²", false};
  static constexpr Quantity time{1.0e7, "s", false};             // segment durations
  static constexpr Quantity turns{1.0e4, "turns", false};        // circle/ellipse turns
  static constexpr Quantity joystick_speed{10.0, "m/s", false};  // live joystick, linear
  static constexpr Quantity joystick_rate{10.0, "rad/s", false}; // live joystick, angular
};

// Throws ScenarioError(path, "must be finite with magnitude at most B UNIT,
// got V UNIT") unless |value| ≤ bound. `value` is in the file's units;
// `radians_per_unit` is 1 for radians and π/180 for degrees.
double check_quantity(double value, const Quantity& q, const std::string& path,
                      double radians_per_unit = 1.0);

// A number as people read it: %g with up to 6 significant digits.
std::string format_number(double value);

}  // namespace rrlab
