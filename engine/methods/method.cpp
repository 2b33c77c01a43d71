#include <rrlab/methods/method.hpp>

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace rrlab {

int Diagnostics::add(std::string name) {
  names.push_back(std::move(name));
  values.conservativeResize(static_cast<Eigen::Index>(names.size()));
  values[values.size() - 1] = 0.0;
  return static_cast<int>(names.size()) - 1;
}

int find_param(const std::vector<ParamSpec>& specs, std::string_view name) {
  for (size_t i = 0; i < specs.size(); ++i)
    if (specs[i].name == name) return static_cast<int>(i);
  return -1;
}

int choice_index(const ParamSpec& spec, std::string_view label) {
  for (size_t i = 0; i < spec.choices.size(); ++i)
    if (spec.choices[i] == label) return static_cast<int>(i);
  return -1;
}

std::string param_problem(const ParamSpec& spec, double value) {
  std::ostringstream msg;
  if (!std::isfinite(value)) return "must be a finite number";
  if (!spec.choices.empty()) {
    if (value != std::floor(value) || value < 0 || value >= double(spec.choices.size())) {
      msg << "must be one of";
      for (size_t i = 0; i < spec.choices.size(); ++i)
        msg << (i ? ", " : " ") << '"' << spec.choices[i] << "\" (" << i << ')';
      return msg.str();
    }
    return {};
  }
  if (value < spec.min || value > spec.max) {
    msg << "must be in [" << spec.min << ", " << spec.max << "]" << (spec.unit.empty() ? "" : " ") << spec.unit;
    return msg.str();
  }
  return {};
}

Method::Method(std::vector<ParamSpec> specs) : specs_(std::move(specs)), values_(specs_.size()) {
  for (size_t i = 0; i < specs_.size(); ++i) values_[static_cast<Eigen::Index>(i)] = specs_[i].def;
}

void Method::set_param(std::string_view name, double value) {
  const int index = find_param(specs_, name);
  if (index < 0) throw ParamError(std::string(name), "unknown parameter '" + std::string(name) + "'");
  const std::string problem = param_problem(specs_[index], value);
  if (!problem.empty()) throw ParamError(std::string(name), std::string(name) + ": " + problem);
  values_[index] = value;
  on_param_changed(ParamSlot{index});
}

ParamSlot Method::slot(std::string_view name) const {
  const int index = find_param(specs_, name);
  if (index < 0) throw std::logic_error("the method reads a parameter '" + std::string(name) + "' it does not declare");
  return ParamSlot{index};
}

int Method::label(ParamSlot choice, std::string_view label) const {
  const int value = choice_index(specs_.at(size_t(choice.index)), label);
  if (value < 0)
    throw std::logic_error("parameter '" + specs_.at(size_t(choice.index)).name + "' has no label '" + std::string(label) + "'");
  return value;
}

double Method::param(std::string_view name) const {
  const int index = find_param(specs_, name);
  if (index < 0) throw ParamError(std::string(name), "unknown parameter '" + std::string(name) + "'");
  return values_[index];
}

int Method::declare_diagnostic(std::string name) {
  diag_names_.push_back(std::move(name));
  return static_cast<int>(diag_names_.size()) - 1;
}

}  // namespace rrlab
