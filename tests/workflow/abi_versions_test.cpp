// The interface's minor-version promise: a plugin built against the frozen 1.0 header (a smaller
// descriptor) loads and computes; descriptors too small for what they claim are refused.

#include <gtest/gtest.h>

#include <dlfcn.h>

#include <cmath>
#include <cstddef>
#include <cstring>
#include <type_traits>

#include "geotandem/core/error.hpp"
#include "geotandem/volume/volume.hpp"
#include "geotandem/workflow/registry.hpp"
#include "test_paths.hpp"

using namespace geotandem;
using namespace geotandem::workflow;

namespace {

std::string plugin_file(const std::string& name) {
  return test_paths::plugins() + "/" + name + "/geotandem_" + name + ".so";
}

std::shared_ptr<volume::MemoryVolume> wave(volume::Index3 shape) {
  volume::Geometry g;
  g.shape = shape;
  std::vector<float> v(g.sample_count());
  for (std::size_t n = 0; n < v.size(); ++n)
    v[n] = static_cast<float>(std::cos(0.21 * double(n)) - 0.002 * double(n));
  return std::make_shared<volume::MemoryVolume>(g, std::move(v));
}

ParamValues defaults(const Plugin& p) {
  return default_values(p.params());
}

int dummy_select(const gt_params*, const gt_component*, uint64_t, uint64_t*, uint64_t*, int*, char*, size_t) {
  return 0;
}
int dummy_halo(const gt_params*, const gt_cube_info*, int64_t h[3], char*, size_t) {
  h[0] = h[1] = h[2] = 0;
  return 0;
}
int dummy_compute(const gt_params*, const gt_cube_info*, const float*, const gt_box*, float*, const gt_box*, char*,
                  size_t) {
  return 0;
}

std::string load_error(const gt_plugin_descriptor& d) {
  try {
    plugin_from_descriptor(&d, "test-descriptor");
  } catch (const FormatError& e) {
    return e.what();
  }
  return {};
}

} // namespace

TEST(AbiVersions, PluginBuiltAgainstTheFrozen10HeaderLoadsAndComputesLikeTheCurrentOne) {
  // The library really carries the smaller 1.0 descriptor (read without the host's loader).
  void* handle = ::dlopen(plugin_file("boxsum10").c_str(), RTLD_NOW | RTLD_LOCAL);
  ASSERT_NE(handle, nullptr) << ::dlerror();
  auto entry = reinterpret_cast<gt_plugin_entry_fn>(::dlsym(handle, GEOTANDEM_PLUGIN_ENTRY_NAME));
  ASSERT_NE(entry, nullptr);
  EXPECT_EQ(entry()->abi_minor, 0u);
  EXPECT_EQ(entry()->struct_size, offsetof(gt_plugin_descriptor, component));
  EXPECT_LT(entry()->struct_size, sizeof(gt_plugin_descriptor));

  PluginRegistry registry;
  registry.load_library(plugin_file("boxsum10")); // same source as boxsum, 1.0 header
  registry.load_library(plugin_file("boxsum"));
  const Plugin& old_plugin = registry.get("boxsum10");
  EXPECT_EQ(old_plugin.kind(), StepKind::attribute);
  ASSERT_EQ(old_plugin.params().size(), 2u);
  EXPECT_EQ(old_plugin.params()[0].name, "factor");
  auto input = wave({10, 9, 12});
  auto a = old_plugin.make_attribute(input, defaults(old_plugin));
  auto b = registry.get("boxsum").make_attribute(input, defaults(registry.get("boxsum")));
  for (volume::Box box : {volume::Box{{0, 0, 0}, {10, 9, 12}}, volume::Box{{3, 2, 5}, {7, 9, 12}}}) {
    auto x = a->read(box), y = b->read(box);
    ASSERT_EQ(x.size(), box.count());
    EXPECT_EQ(x, y) << box.to_string();
    // Not trivially zero: the sum of a 3x3x3 neighbourhood of the wave, times 2.
    EXPECT_GT(std::abs(x[box.count() / 2]), 1e-3);
  }
}

TEST(AbiVersions, SmallerDescriptorsAreReadUpToTheirSize) {
  static const gt_param_spec none[1] = {{"k", GT_PARAM_INT, "1", "", 0, 10, nullptr}};
  gt_plugin_descriptor d{};
  d.abi_major = GEOTANDEM_PLUGIN_ABI_MAJOR;
  d.abi_minor = 0;
  d.kind = GT_PLUGIN_ATTRIBUTE;
  d.name = "sized";
  d.version = "1";
  d.params = none;
  d.param_count = 1;
  d.attribute = {dummy_halo, dummy_compute};
  // An attribute with a 1.0 descriptor: accepted, whatever lies beyond its size.
  d.struct_size = static_cast<uint32_t>(offsetof(gt_plugin_descriptor, component));
  d.component.select = nullptr;
  EXPECT_EQ(load_error(d), "");
  // A descriptor smaller than 1.0's: refused, naming both sizes.
  d.struct_size = 16;
  std::string tiny = load_error(d);
  EXPECT_NE(tiny.find("16 bytes"), std::string::npos) << tiny;
  EXPECT_NE(tiny.find("interface version 1.0"), std::string::npos) << tiny;
  // A component step needs the 1.1 fields: with a 1.0 size its callback is not read at all.
  d.kind = GT_PLUGIN_COMPONENT_STEP;
  d.component.select = dummy_select;
  d.struct_size = static_cast<uint32_t>(offsetof(gt_plugin_descriptor, component));
  std::string small = load_error(d);
  EXPECT_NE(small.find("too small"), std::string::npos) << small;
  EXPECT_NE(small.find("1.1"), std::string::npos) << small;
  d.struct_size = sizeof(gt_plugin_descriptor);
  EXPECT_EQ(load_error(d), "");
  // An unknown kind is named.
  const std::underlying_type_t<gt_plugin_kind> seven = 7; // what a C plugin may store; no such enumerator
  std::memcpy(&d.kind, &seven, sizeof seven);
  EXPECT_NE(load_error(d).find("unknown kind 7"), std::string::npos);
}
