// Plugins that come through the C ABI: descriptor checks, and an attribute volume that calls the
// plugin's halo/compute callbacks box by box.

#include <cstring>
#include <regex>

#include "geotandem/core/error.hpp"
#include "geotandem/workflow/plugin.hpp"

namespace geotandem::workflow {
namespace {

constexpr std::size_t error_buffer_size = 1024;

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
  AbiPlugin(const gt_plugin_descriptor* d, std::string origin)
      : descriptor_(d), origin_(std::move(origin)), name_(d->name), summary_(d->summary ? d->summary : ""),
        version_(d->version ? d->version : "") {
    for (std::uint32_t n = 0; n < d->param_count; ++n)
      params_.push_back(convert(d->params[n]));
  }

  const std::string& name() const override { return name_; }
  PluginKind kind() const override { return PluginKind::attribute; }
  const std::string& summary() const override { return summary_; }
  const std::vector<ParamSpec>& params() const override { return params_; }
  const std::string& origin() const override { return origin_; }
  const std::string& version() const override { return version_; }
  const gt_plugin_descriptor& descriptor() const { return *descriptor_; }

  using Plugin::make_attribute;
  std::shared_ptr<volume::Volume> make_attribute(std::vector<std::shared_ptr<const volume::Volume>> inputs,
                                                 const ParamValues& values) const override {
    if (inputs.size() != 1)
      throw InvalidArgument("attribute '" + name_ + "' takes one input, got " + std::to_string(inputs.size()),
                            {origin_});
    return std::make_shared<AbiAttributeVolume>(shared_from_this(), std::move(inputs.front()), values);
  }

  // Runs a callback and turns a non-zero status into an Error naming the plugin and its file.
  template <typename Call> void call(const char* what, Call&& callback) const {
    char error[error_buffer_size] = {0};
    int status = callback(error, sizeof error);
    if (status != 0) {
      error[sizeof error - 1] = '\0';
      throw DataError("attribute '" + name_ + "' failed in " + what + ": " + (error[0] ? error : "no message"),
                      {origin_}, "the message above is the plugin's own; check its parameters");
    }
  }

private:
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

  const gt_plugin_descriptor* descriptor_;
  std::string origin_, name_, summary_, version_;
  std::vector<ParamSpec> params_;
};

AbiAttributeVolume::AbiAttributeVolume(std::shared_ptr<const AbiPlugin> plugin,
                                       std::shared_ptr<const volume::Volume> input, const ParamValues& values)
    : plugin_(std::move(plugin)), input_(std::move(input)), params_(plugin_->params(), values),
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

void check_descriptor(const gt_plugin_descriptor* d, const std::string& origin) {
  const std::string host =
      std::to_string(GEOTANDEM_PLUGIN_ABI_MAJOR) + "." + std::to_string(GEOTANDEM_PLUGIN_ABI_MINOR);
  if (!d) throw FormatError("the plugin entry point returned no descriptor", {origin});
  if (d->abi_major != GEOTANDEM_PLUGIN_ABI_MAJOR)
    throw FormatError("plugin built for interface version " + std::to_string(d->abi_major) + "." +
                          std::to_string(d->abi_minor) + ", but this geotandem implements version " + host,
                      {origin}, "rebuild the plugin against this geotandem's headers");
  if (d->struct_size < sizeof(gt_plugin_descriptor))
    throw FormatError("plugin descriptor is " + std::to_string(d->struct_size) + " bytes, interface " + host +
                          " needs " + std::to_string(sizeof(gt_plugin_descriptor)),
                      {origin}, "rebuild the plugin against this geotandem's headers");
  static const std::regex identifier("[a-z][a-z0-9_]*");
  if (!d->name || !std::regex_match(d->name, identifier))
    throw FormatError("plugin name must match [a-z][a-z0-9_]*", {origin});
  if (d->kind != GT_PLUGIN_ATTRIBUTE)
    throw FormatError("plugin '" + std::string(d->name) + "' has unknown kind " + std::to_string(d->kind), {origin},
                      "this geotandem knows attribute plugins (kind 1)");
  if (!d->attribute.halo || !d->attribute.compute)
    throw FormatError("attribute plugin '" + std::string(d->name) + "' lacks its halo or compute callback", {origin});
  if (d->param_count > 0 && !d->params)
    throw FormatError("plugin '" + std::string(d->name) + "' declares parameters but gives none", {origin});
  for (std::uint32_t n = 0; n < d->param_count; ++n) {
    const auto& p = d->params[n];
    if (!p.name || !std::regex_match(p.name, identifier))
      throw FormatError("plugin '" + std::string(d->name) + "' has a parameter whose name is not [a-z][a-z0-9_]*",
                        {origin});
    if (p.type < GT_PARAM_INT || p.type > GT_PARAM_CHOICE)
      throw FormatError("parameter '" + std::string(p.name) + "' of plugin '" + d->name + "' has unknown type",
                        {origin});
  }
}

} // namespace

std::shared_ptr<Plugin> plugin_from_descriptor(const gt_plugin_descriptor* descriptor, const std::string& origin) {
  check_descriptor(descriptor, origin);
  auto plugin = std::make_shared<AbiPlugin>(descriptor, origin);
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
