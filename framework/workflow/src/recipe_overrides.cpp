// --set overrides, applied to the recipe's YAML tree before validation.

#include "recipe_overrides.hpp"

#include <cstdlib>
#include <optional>
#include <vector>

#include "geotandem/core/error.hpp"
#include "yaml_reader.hpp"

namespace geotandem::workflow::detail {

namespace {
// The element `part` of `node`: in a list of steps, the step with that 1-based index or that
// name ('as', else 'step'; an error when there is none); in a mapping, the value of that key (none
// when there is none).
std::optional<YAML::Node> element(const YAML::Node& node, const std::string& part, const std::string& text) {
  if (node.IsSequence()) {
    YAML::Node found;
    bool matched = false; // a default YAML::Node is a valid null node, so track the match apart
    char* end = nullptr;
    long index = std::strtol(part.c_str(), &end, 10);
    if (*end == '\0' && index >= 1 && static_cast<std::size_t>(index) <= node.size()) {
      found.reset(node[static_cast<std::size_t>(index - 1)]);
      matched = true;
    } else {
      for (std::size_t i = 0; i < node.size() && !matched; ++i) {
        YAML::Node item = node[i];
        if (item.IsMap() && ((item["as"] && item["as"].Scalar() == part) ||
                             (!item["as"] && item["step"] && item["step"].Scalar() == part))) {
          found.reset(item);
          matched = true;
        }
      }
    }
    if (!matched)
      throw InvalidArgument("--set " + text + ": no step '" + part + "'", {},
                            "address steps by their 1-based index or by name");
    return found;
  }
  const YAML::Node value = node[part]; // read only: a missing key is not added
  if (!value) return std::nullopt;
  return value;
}
} // namespace

GraftedOverride apply_override(YAML::Node root, const std::string& text) {
  auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0)
    throw InvalidArgument("--set '" + text + "' is not key=value", {}, "for example --set execution.workers=4");
  std::string path = text.substr(0, eq), value = text.substr(eq + 1);
  // An empty value is refused rather than read as YAML's null: `--set KEY=` is almost always a
  // value lost to the shell (an unset variable, a missing argument), and null is no parameter's value.
  if (value.find_first_not_of(" \t") == std::string::npos)
    throw InvalidArgument("--set " + text + ": the value after '=' is empty", {},
                          "give a value: --set " + path + "=VALUE (quote text that is meant to be empty: --set '" +
                              path + "=\"\"')");
  std::vector<std::string> parts;
  for (std::size_t start = 0;;) {
    auto dot = path.find('.', start);
    parts.push_back(path.substr(start, dot == std::string::npos ? std::string::npos : dot - start));
    if (dot == std::string::npos) break;
    start = dot + 1;
  }
  YAML::Node node;
  node.reset(root);
  for (std::size_t n = 0; n + 1 < parts.size(); ++n) {
    const std::optional<YAML::Node> next = element(node, parts[n], text);
    if (next) {
      node.reset(*next);
    } else {
      node[parts[n]] = YAML::Node(YAML::NodeType::Map);
      node.reset(node[parts[n]]);
    }
    if (node.IsScalar()) {
      std::string prefix = parts[0];
      for (std::size_t k = 1; k <= n; ++k)
        prefix += "." + parts[k];
      throw InvalidArgument("--set " + text + ": '" + parts[n] + "' holds a value ('" + node.Scalar() + "'), not keys",
                            {}, "set '" + prefix + "' itself");
    }
  }
  // A malformed value is the --set's fault, named as such (not "base.yaml:1:1").
  try {
    GraftedOverride grafted;
    grafted.value = load_single_document(value, "--set " + text);
    if (node.IsSequence()) {
      // A whole step: the element is replaced in the list (a key would turn the list into a map).
      YAML::Node target = *element(node, parts.back(), text);
      target = grafted.value;
      return grafted;
    }
    node[parts.back()] = grafted.value;
    for (const auto& entry : node)
      if (entry.second.is(grafted.value)) grafted.key.reset(entry.first);
    return grafted;
  } catch (const YAML::Exception& e) {
    throw InvalidArgument("--set " + text + ": the value is not valid YAML: " + e.msg, {},
                          "quote the value, e.g. --set 'key=\"text\"'");
  }
}

} // namespace geotandem::workflow::detail
