#pragma once
// A parameter declaration in one call, for the built-in steps' tables (builtin_steps.cpp,
// extract_step.cpp): name, type, default (empty: required), help, optional closed range, choices.

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "geotandem/workflow/plugin.hpp"

namespace geotandem::workflow::detail {

inline ParamSpec param_spec(std::string name, ParamType type, std::optional<std::string> def, std::string help,
                            std::optional<double> lo = {}, std::optional<double> hi = {},
                            std::vector<std::string> choices = {}) {
  ParamSpec s;
  s.name = std::move(name);
  s.type = type;
  s.default_value = std::move(def);
  s.help = std::move(help);
  s.min_value = lo;
  s.max_value = hi;
  s.choices = std::move(choices);
  return s;
}

} // namespace geotandem::workflow::detail
