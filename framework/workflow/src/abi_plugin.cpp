// Plugins that come through the C ABI: descriptor checks (read up to the descriptor's own size),
// an attribute volume that calls the plugin's halo/compute callbacks box by box, and component
// steps that hand the plugin the components' measures and store the selection it returns.

#include <algorithm>
#include <cstddef>
#include <cstring>
#include <regex>
#include <type_traits>
#include <unordered_set>

#include "geotandem/core/error.hpp"
#include "geotandem/store/store.hpp"
#include "geotandem/workflow/plugin.hpp"

namespace geotandem::workflow {
namespace {

constexpr std::size_t error_buffer_size = 1024;
// The descriptor of interface 1.0 ends after `attribute`; every later minor version appends.
constexpr std::size_t descriptor_size_1_0 = offsetof(gt_plugin_descriptor, component);
constexpr std::size_t descriptor_size_1_1 = offsetof(gt_plugin_descriptor, component) + sizeof(gt_component_ops);
static_assert(descriptor_size_1_1 <= sizeof(gt_plugin_descriptor));

// The integer a plugin stored in a C enum field. A C plugin may store any value there, and loading
// an out-of-range value as the C++ enum type is undefined: read the bytes instead.
template <class Enum> long long raw_value(const Enum& field) {
  std::underlying_type_t<Enum> value;
  std::memcpy(&value, &field, sizeof value);
  return static_cast<long long>(value);
}

// The plugin's descriptor as this host reads it: the fields its struct_size covers, the rest zero.
gt_plugin_descriptor read_descriptor(const gt_plugin_descriptor* d) {
  gt_plugin_descriptor copy;
  std::memset(&copy, 0, sizeof copy);
  std::memcpy(&copy, d, std::min<std::size_t>(d->struct_size, sizeof copy));
  return copy;
}

// The parameter values in the C layout, owning the strings they point to.
class CParams {
public:
  CParams(const std::vector<ParamSpec>& specs, const ParamValues& values) {
    for (const auto& spec : specs) {
      auto it = values.find(spec.name);
      if (it == values.end()) throw InvalidArgument("parameter '" + spec.name + "' has no value");
      names_.push_back(spec.name);
      texts_.push_back(it->second.text);
    }
    for (std::size_t n = 0; n < specs.size(); ++n) {
      const ParamValue& v = values.at(specs[n].name);
      gt_param_value c{};
      c.name = names_[n].c_str();
      c.int_value = v.integer;
      c.float_value = v.real;
      c.bool_value = v.boolean ? 1 : 0;
      c.text_value = texts_[n].c_str();
      values_.push_back(c);
    }
    params_.values = values_.data();
    params_.count = static_cast<std::uint32_t>(values_.size());
  }
  CParams(const CParams&) = delete;
  CParams& operator=(const CParams&) = delete;
  const gt_params* get() const { return &params_; }

private:
  std::vector<std::string> names_;
  std::vector<std::string> texts_;
  std::vector<gt_param_value> values_;
  gt_params params_{};
};

gt_cube_info cube_info(const volume::Geometry& g) {
  gt_cube_info info{};
  for (int a = 0; a < 3; ++a)
    info.shape[a] = g.shape[a];
  info.dz = g.dz;
  info.z_unit_is_ms = g.z_unit == volume::SampleUnit::milliseconds ? 1 : 0;
  info.bin_i = g.affine.step_i();
  info.bin_j = g.affine.step_j();
  return info;
}

gt_box to_c(const volume::Box& box) {
  gt_box b{};
  for (int a = 0; a < 3; ++a) {
    b.lo[a] = box.lo[a];
    b.hi[a] = box.hi[a];
  }
  return b;
}

class AbiPlugin;

class AbiAttributeVolume final : public volume::Volume {
public:
  AbiAttributeVolume(std::shared_ptr<const AbiPlugin> plugin, std::shared_ptr<const volume::Volume> input,
                     const ParamValues& values);
  const volume::Geometry& geometry() const override { return input_->geometry(); }
  std::string format() const override;
  std::string source() const override;

protected:
  void read_box(const volume::Box& box, std::span<float> out) const override;

private:
  std::shared_ptr<const AbiPlugin> plugin_;
  std::shared_ptr<const volume::Volume> input_;
  CParams params_;
  gt_cube_info cube_{};
  volume::Index3 halo_{0, 0, 0};
};

class AbiPlugin final : public Plugin, public std::enable_shared_from_this<AbiPlugin> {
public:
  AbiPlugin(const gt_plugin_descriptor& d, std::string origin)
      : descriptor_(d), origin_(std::move(origin)), name_(d.name), summary_(d.summary ? d.summary : ""),
        version_(d.version ? d.version : "") {
    for (std::uint32_t n = 0; n < d.param_count; ++n)
      params_.push_back(convert(d.params[n]));
    own_params_ = params_;
    if (kind() == StepKind::component &&
        std::none_of(params_.begin(), params_.end(), [](const ParamSpec& p) { return p.name == "selection"; })) {
      // The host writes the selection: its name is a parameter of every component step.
      ParamSpec selection;
      selection.name = "selection";
      selection.type = ParamType::text;
      selection.default_value = name_;
      selection.help = "name of the selection this step writes";
      params_.push_back(selection);
    }
  }

  const std::string& name() const override { return name_; }
  StepKind kind() const override {
    return descriptor_.kind == GT_PLUGIN_COMPONENT_STEP ? StepKind::component : StepKind::attribute;
  }
  const std::string& summary() const override { return summary_; }
  const std::vector<ParamSpec>& params() const override { return params_; }
  // The parameters the plugin itself declared (the C values it is given, in its order).
  const std::vector<ParamSpec>& own_params() const { return own_params_; }
  const std::string& origin() const override { return origin_; }
  const std::string& version() const override { return version_; }
  const gt_plugin_descriptor& descriptor() const { return descriptor_; }

  using Plugin::make_attribute;
  std::shared_ptr<volume::Volume> make_attribute(std::vector<std::shared_ptr<const volume::Volume>> inputs,
                                                 const ParamValues& values) const override {
    if (kind() != StepKind::attribute) return Plugin::make_attribute(std::move(inputs), values);
    if (inputs.size() != 1)
      throw InvalidArgument("attribute '" + name_ + "' takes one input, got " + std::to_string(inputs.size()),
                            {origin_});
    return std::make_shared<AbiAttributeVolume>(shared_from_this(), std::move(inputs.front()), values);
  }

  ComponentOutcome select(store::ComponentStore& store, const ParamValues& values, const std::string& from,
                          StepContext& context) const override;

  // Runs a callback and turns a non-zero status, or an exception that escaped the plugin, into an
  // Error naming the plugin and its file.
  template <typename Call> void call(const char* what, Call&& callback) const {
    char error[error_buffer_size] = {0};
    int status = 0;
    try {
      status = callback(error, sizeof error);
    } catch (const std::exception& e) {
      throw DataError("plugin '" + name_ + "' threw an exception in " + what + ": " + e.what(), {origin_},
                      "a plugin must catch its exceptions and return non-zero with a message (docs/plugins.md)");
    } catch (...) {
      throw DataError("plugin '" + name_ + "' threw an exception in " + what, {origin_},
                      "a plugin must catch its exceptions and return non-zero with a message (docs/plugins.md)");
    }
    if (status != 0) {
      error[sizeof error - 1] = '\0';
      throw DataError(std::string(to_string(kind())) + " '" + name_ + "' failed in " + what + ": " +
                          (error[0] ? error : "no message"),
                      {origin_}, "the message above is the plugin's own; check its parameters");
    }
  }

private:
  // gt_param_spec is the C form of the one parameter model (geotandem/core/params.hpp): each field
  // maps to the ParamSpec field of the same name. The C form's bounds are closed and it has no odd
  // flag or unit (the help carries the unit); values go back to C in CParams above.
  ParamSpec convert(const gt_param_spec& c) {
    ParamSpec s;
    s.name = c.name;
    switch (c.type) {
    case GT_PARAM_INT: s.type = ParamType::integer; break;
    case GT_PARAM_FLOAT: s.type = ParamType::real; break;
    case GT_PARAM_BOOL: s.type = ParamType::boolean; break;
    case GT_PARAM_STRING: s.type = ParamType::text; break;
    case GT_PARAM_CHOICE: s.type = ParamType::choice; break;
    }
    if (c.default_value) s.default_value = c.default_value;
    s.help = c.help ? c.help : "";
    if ((c.type == GT_PARAM_INT || c.type == GT_PARAM_FLOAT) && c.min_value <= c.max_value) {
      s.min_value = c.min_value;
      s.max_value = c.max_value;
    }
    if (c.type == GT_PARAM_CHOICE && c.choices) {
      std::string all = c.choices;
      std::size_t start = 0;
      for (std::size_t bar; (bar = all.find('|', start)) != std::string::npos; start = bar + 1)
        s.choices.push_back(all.substr(start, bar - start));
      s.choices.push_back(all.substr(start));
    }
    return s;
  }

  gt_plugin_descriptor descriptor_;
  std::string origin_, name_, summary_, version_;
  std::vector<ParamSpec> params_, own_params_;
};

gt_component to_c(std::uint64_t key, const mesh::ComponentStats& s) {
  gt_component c{};
  c.key = key;
  c.vertex_count = s.vertex_count;
  c.triangle_count = s.triangle_count;
  c.closed = s.closed ? 1 : 0;
  c.cut_by_border = s.cut_by_border ? 1 : 0;
  c.volume = s.volume;
  c.area = s.area;
  for (int a = 0; a < 3; ++a) {
    c.centroid[a] = s.centroid[a];
    c.box_min[a] = s.box_min[a];
    c.box_max[a] = s.box_max[a];
    c.obb_half_extents[a] = s.obb_half_extents[a];
  }
  c.azimuth = s.azimuth;
  c.dip = s.dip;
  c.elongation = s.elongation;
  return c;
}

ComponentOutcome AbiPlugin::select(store::ComponentStore& store, const ParamValues& values, const std::string& from,
                                   StepContext& context) const {
  store::Query q;
  if (!from.empty()) q.selection = from;
  auto rows = store.query(q);
  std::vector<gt_component> components;
  components.reserve(rows.size());
  for (const auto& r : rows)
    components.push_back(to_c(r.key, r.stats));
  CParams params(own_params_, values);
  std::vector<std::uint64_t> selected(rows.size());
  std::uint64_t count = 0;
  int ranked = 0;
  call("select", [&](char* error, std::size_t size) {
    return descriptor_.component.select(params.get(), components.data(), components.size(), selected.data(), &count,
                                        &ranked, error, size);
  });
  context.cancel.throw_if_cancelled();
  if (count > rows.size())
    throw DataError("component step '" + name_ + "' returned " + std::to_string(count) + " keys from " +
                        std::to_string(rows.size()) + " components",
                    {origin_}, "a selection holds at most the components given");
  selected.resize(count);
  std::unordered_set<std::uint64_t> given, seen;
  for (const auto& r : rows)
    given.insert(r.key);
  for (std::uint64_t key : selected)
    if (!given.count(key) || !seen.insert(key).second)
      throw DataError("component step '" + name_ + "' returned key " + std::to_string(key) +
                          (given.count(key) ? " twice" : ", which is not among the components it was given"),
                      {origin_}, "return each kept key once, from the components given");
  const std::string& selection = values.at("selection").text;
  nlohmann::json record = {{"step", name_},         {"plugin", origin_}, {"version", version_},  {"from", from},
                           {"before", rows.size()}, {"after", count},    {"ranked", ranked != 0}};
  for (const auto& spec : own_params_)
    record["params"][spec.name] = values.at(spec.name).text;
  store.save_selection(selection, selected, record.dump(), true);
  return {rows.size(), count, selection, std::string(ranked ? "ranked" : "filtered") + " by " + origin_, {}};
}

AbiAttributeVolume::AbiAttributeVolume(std::shared_ptr<const AbiPlugin> plugin,
                                       std::shared_ptr<const volume::Volume> input, const ParamValues& values)
    : plugin_(std::move(plugin)), input_(std::move(input)), params_(plugin_->own_params(), values),
      cube_(cube_info(input_->geometry())) {
  std::int64_t halo[3] = {0, 0, 0};
  plugin_->call("halo", [&](char* error, std::size_t size) {
    return plugin_->descriptor().attribute.halo(params_.get(), &cube_, halo, error, size);
  });
  for (int a = 0; a < 3; ++a) {
    if (halo[a] < 0)
      throw DataError("attribute '" + plugin_->name() + "' declared a negative halo", {plugin_->origin()});
    halo_[a] = halo[a];
  }
}

std::string AbiAttributeVolume::format() const {
  return "attribute " + plugin_->name();
}
std::string AbiAttributeVolume::source() const {
  return plugin_->name() + "(" + input_->source() + ")";
}

void AbiAttributeVolume::read_box(const volume::Box& box, std::span<float> out) const {
  volume::Box in_box = box.grown(halo_).intersection(geometry().bounds());
  std::vector<float> in = input_->read(in_box);
  gt_box c_in = to_c(in_box), c_out = to_c(box);
  plugin_->call("compute", [&](char* error, std::size_t size) {
    return plugin_->descriptor().attribute.compute(params_.get(), &cube_, in.data(), &c_in, out.data(), &c_out, error,
                                                   size);
  });
}

gt_plugin_descriptor check_descriptor(const gt_plugin_descriptor* given, const std::string& origin) {
  const std::string host =
      std::to_string(GEOTANDEM_PLUGIN_ABI_MAJOR) + "." + std::to_string(GEOTANDEM_PLUGIN_ABI_MINOR);
  if (!given) throw FormatError("the plugin entry point returned no descriptor", {origin});
  if (given->abi_major != GEOTANDEM_PLUGIN_ABI_MAJOR)
    throw FormatError("plugin built for interface version " + std::to_string(given->abi_major) + "." +
                          std::to_string(given->abi_minor) + ", but this geotandem implements version " + host,
                      {origin}, "rebuild the plugin against this geotandem's headers");
  if (given->struct_size < descriptor_size_1_0)
    throw FormatError("plugin descriptor is " + std::to_string(given->struct_size) + " bytes, smaller than the " +
                          std::to_string(descriptor_size_1_0) + " of interface version 1.0",
                      {origin}, "set struct_size to sizeof(gt_plugin_descriptor) and rebuild the plugin");
  // Fields beyond the plugin's struct_size are read as zero (an older minor version).
  const gt_plugin_descriptor d = read_descriptor(given);
  static const std::regex identifier("[a-z][a-z0-9_]*");
  if (!d.name || !std::regex_match(d.name, identifier))
    throw FormatError("plugin name must match [a-z][a-z0-9_]*", {origin});
  const long long kind = raw_value(d.kind);
  if (kind == GT_PLUGIN_ATTRIBUTE) {
    if (!d.attribute.halo || !d.attribute.compute)
      throw FormatError("attribute plugin '" + std::string(d.name) + "' lacks its halo or compute callback", {origin});
  } else if (kind == GT_PLUGIN_COMPONENT_STEP) {
    if (d.struct_size < descriptor_size_1_1)
      throw FormatError("component step plugin '" + std::string(d.name) + "' has a descriptor of " +
                            std::to_string(d.struct_size) + " bytes, too small to hold its callbacks (interface 1.1)",
                        {origin}, "build it against interface version 1.1 or later");
    if (!d.component.select)
      throw FormatError("component step plugin '" + std::string(d.name) + "' lacks its select callback", {origin});
  } else {
    throw FormatError("plugin '" + std::string(d.name) + "' has unknown kind " + std::to_string(kind), {origin},
                      "this geotandem knows attribute plugins (kind 1) and component step plugins (kind 2)");
  }
  if (d.param_count > 0 && !d.params)
    throw FormatError("plugin '" + std::string(d.name) + "' declares parameters but gives none", {origin});
  for (std::uint32_t n = 0; n < d.param_count; ++n) {
    const auto& p = d.params[n];
    if (!p.name || !std::regex_match(p.name, identifier))
      throw FormatError("plugin '" + std::string(d.name) + "' has a parameter whose name is not [a-z][a-z0-9_]*",
                        {origin});
    if (raw_value(p.type) < GT_PARAM_INT || raw_value(p.type) > GT_PARAM_CHOICE)
      throw FormatError("parameter '" + std::string(p.name) + "' of plugin '" + d.name + "' has unknown type",
                        {origin});
  }
  return d;
}

} // namespace

std::shared_ptr<Plugin> plugin_from_descriptor(const gt_plugin_descriptor* descriptor, const std::string& origin) {
  auto plugin = std::make_shared<AbiPlugin>(check_descriptor(descriptor, origin), origin);
  // Defaults must parse under their own specs, or every recipe would fail later and obscurely.
  for (const auto& spec : plugin->params())
    if (spec.default_value) {
      try {
        parse_param(spec, *spec.default_value);
      } catch (const Error& e) {
        throw FormatError("plugin '" + plugin->name() + "' has a bad default: " + e.message(), {origin});
      }
    }
  return plugin;
}

} // namespace geotandem::workflow
