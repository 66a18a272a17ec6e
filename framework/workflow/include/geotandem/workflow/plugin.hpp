#pragma once
// Plugins as the host sees them: a name, a kind, described parameters, and a factory. Built-in
// plugins and shared libraries loaded through the C ABI (plugin_abi.h) look the same from here.

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "geotandem/volume/volume.hpp"
#include "geotandem/workflow/plugin_abi.h"

namespace geotandem::workflow {

enum class ParamType { integer, real, boolean, text, choice };
const char* to_string(ParamType type);

struct ParamSpec {
  std::string name;
  ParamType type = ParamType::real;
  std::optional<std::string> default_value; // empty: required
  std::string help;
  std::optional<double> min_value; // inclusive, for integer and real
  std::optional<double> max_value;
  std::vector<std::string> choices; // for choice
};

// A parameter value after validation against its spec.
struct ParamValue {
  ParamType type = ParamType::real;
  std::int64_t integer = 0;
  double real = 0.0;
  bool boolean = false;
  std::string text;
};
using ParamValues = std::map<std::string, ParamValue>;

// Parses `text` for `spec` (a recipe value or a default), checks type and range; throws
// InvalidArgument with a message naming the parameter, the value and what is allowed.
ParamValue parse_param(const ParamSpec& spec, const std::string& text);

enum class PluginKind { attribute };

class Plugin {
public:
  virtual ~Plugin() = default;
  virtual const std::string& name() const = 0;
  virtual PluginKind kind() const = 0;
  virtual const std::string& summary() const = 0;
  virtual const std::vector<ParamSpec>& params() const = 0;
  // Where it comes from: "built-in" or the shared library's path; and its own version.
  virtual const std::string& origin() const = 0;
  virtual const std::string& version() const = 0;

  // How many input volumes the attribute combines (1 for most; 2 for a product).
  virtual int input_count() const { return 1; }

  // For attribute plugins: the attribute of `inputs` (input_count() of them, same shape) as a lazy
  // volume with their geometry. `values` holds every parameter (defaults filled in). Throws
  // InvalidArgument for a wrong number of inputs or parameters the plugin refuses.
  virtual std::shared_ptr<volume::Volume> make_attribute(std::vector<std::shared_ptr<const volume::Volume>> inputs,
                                                         const ParamValues& values) const = 0;
  std::shared_ptr<volume::Volume> make_attribute(std::shared_ptr<const volume::Volume> input,
                                                 const ParamValues& values) const {
    return make_attribute(std::vector<std::shared_ptr<const volume::Volume>>{std::move(input)}, values);
  }
};

// Wraps a descriptor returned by a plugin's entry point (or a built-in's static descriptor).
// `origin` names the file for messages. Validates the descriptor (size, version, kind, names,
// parameter specs) and throws FormatError naming `origin` when it is wrong.
std::shared_ptr<Plugin> plugin_from_descriptor(const gt_plugin_descriptor* descriptor, const std::string& origin);

} // namespace geotandem::workflow
