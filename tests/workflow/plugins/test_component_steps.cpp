// Component step plugins built by the tests as real shared libraries; the variant is chosen by a
// preprocessor symbol (see CMakeLists.txt), each exercising one path of the host:
//   (none)              keeps components with at least min_triangles triangles, ranked by key,
//                       largest first (an order no built-in step produces)
//   GT_TEST_THROWS      throws a C++ exception out of select (a broken plugin)
//   GT_TEST_FOREIGN_KEY returns a key it was not given
//   GT_TEST_WRONG_MAJOR declares the next major interface version
//   GT_TEST_NO_ENTRY    exports no entry point
#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "geotandem/workflow/plugin_abi.h"

#define GT_STR2(x) #x
#define GT_STR(x) GT_STR2(x)

namespace {

const gt_param_spec specs[] = {
    {"min_triangles", GT_PARAM_INT, "0", "fewest triangles kept", 0.0, 1e9, nullptr},
};

int select_keys(const gt_params* params, const gt_component* components, std::uint64_t count, std::uint64_t* selected,
                std::uint64_t* selected_count, int* ranked, char* error, std::size_t size) {
  (void)error;
  (void)size;
#ifdef GT_TEST_THROWS
  throw std::runtime_error("select exploded on purpose");
#endif
  std::vector<std::uint64_t> keys;
  for (std::uint64_t n = 0; n < count; ++n)
    if (components[n].triangle_count >= static_cast<std::uint64_t>(params->values[0].int_value))
      keys.push_back(components[n].key);
  std::sort(keys.rbegin(), keys.rend());
#ifdef GT_TEST_FOREIGN_KEY
  if (!keys.empty()) keys.front() = 0xdeadbeefull;
#endif
  std::copy(keys.begin(), keys.end(), selected);
  *selected_count = keys.size();
  *ranked = 1;
  return 0;
}

gt_plugin_descriptor make_descriptor() {
  gt_plugin_descriptor d{};
  d.struct_size = sizeof(gt_plugin_descriptor);
#ifdef GT_TEST_WRONG_MAJOR
  d.abi_major = GEOTANDEM_PLUGIN_ABI_MAJOR + 1;
#else
  d.abi_major = GEOTANDEM_PLUGIN_ABI_MAJOR;
#endif
  d.abi_minor = GEOTANDEM_PLUGIN_ABI_MINOR;
  d.kind = GT_PLUGIN_COMPONENT_STEP;
  d.name = GT_STR(GT_TEST_NAME);
  d.version = "0.2";
  d.summary = "test component step: keys with enough triangles, largest key first";
  d.params = specs;
  d.param_count = 1;
  d.component.select = select_keys;
  return d;
}

const gt_plugin_descriptor descriptor = make_descriptor();

} // namespace

#ifndef GT_TEST_NO_ENTRY
GEOTANDEM_PLUGIN_EXPORT const gt_plugin_descriptor* geotandem_plugin_entry(void) {
  return &descriptor;
}
#else
GEOTANDEM_PLUGIN_EXPORT const gt_plugin_descriptor* another_entry(void) {
  return &descriptor;
}
#endif
