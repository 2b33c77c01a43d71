#include <rrlab/scenario/physical_bounds.hpp>

#include <cmath>
#include <cstdio>

#include <rrlab/scenario/scenario.hpp>

namespace rrlab {

std::string format_number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

double check_quantity(double value, const Quantity& q, const std::string& path, double radians_per_unit) {
  const bool degrees = q.angular && radians_per_unit != 1.0;
  const double bound = q.angular ? q.bound / radians_per_unit : q.bound;
  if (std::isfinite(value) && std::abs(value) <= bound) return value;
  std::string unit = q.unit;
  if (degrees) unit = unit == "rad" ? "deg" : "deg/s";
  throw ScenarioError(path, "must be finite with magnitude at most " + format_number(bound) + " " + unit +
                                ", got " + format_number(value) + " " + unit);
}

}  // namespace rrlab
