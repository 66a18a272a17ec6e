// shape_filter: an example geotandem component step plugin, built against an installed geotandem.
//
// After the extraction, geobodies are often told apart by their shape: channels are long and lie
// flat, fault-bounded blocks dip, bright spots are round. This step keeps the bodies whose dip and
// horizontal elongation fall in the given ranges and ranks them, largest volume first (or keeps
// them in the order given with rank_by: none). The host hands it the measures of the components
// of the previous selection (C types only), and writes the keys it returns as a named selection
// in the store (parameter `selection`, added by the host; default: shape_filter).
//
// Only the C interface (geotandem/workflow/plugin_abi.h) is used; no framework library is linked.
// The plugin follows the contract of docs/plugins.md: parameters arrive validated in spec order,
// every kept key is one of those given, errors go into the host's buffer, and no C++ exception
// leaves the callback.

#include <algorithm>
#include <cstdarg>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <exception>
#include <vector>

#include "geotandem/workflow/plugin_abi.h"

namespace {

// Parameter positions: the host passes values in spec order.
enum Param : std::uint32_t { dip_min = 0, dip_max, elongation_min, elongation_max, rank_by, param_count };

const gt_param_spec specs[param_count] = {
    {"dip_min", GT_PARAM_FLOAT, "0", "smallest dip of the body's main axis kept, in degrees below the horizontal", 0.0,
     90.0, nullptr},
    {"dip_max", GT_PARAM_FLOAT, "90", "largest dip kept, in degrees", 0.0, 90.0, nullptr},
    {"elongation_min", GT_PARAM_FLOAT, "0",
     "smallest horizontal elongation kept: 1 - (second extent / first extent), 0 round to 1 a line", 0.0, 1.0, nullptr},
    {"elongation_max", GT_PARAM_FLOAT, "1", "largest horizontal elongation kept", 0.0, 1.0, nullptr},
    {"rank_by", GT_PARAM_CHOICE, "volume",
     "order of the selection: volume (largest first; area for bodies cut by the border), elongation (most "
     "elongated first) or none (the order given)",
     0.0, -1.0, "volume|elongation|none"},
};

int fail(char* error, std::size_t size, const char* format, ...) __attribute__((format(printf, 3, 4)));
int fail(char* error, std::size_t size, const char* format, ...) {
  if (error && size > 0) {
    va_list args;
    va_start(args, format);
    std::vsnprintf(error, size, format, args);
    va_end(args);
  }
  return 1;
}

// A body cut by the cube's border has no enclosed volume: rank it by its area instead.
double size_of(const gt_component& c) {
  return c.closed ? c.volume : c.area;
}

int select_bodies(const gt_params* params, const gt_component* components, std::uint64_t count, std::uint64_t* selected,
                  std::uint64_t* selected_count, int* ranked, char* error, std::size_t error_size) {
  try {
    if (!params || params->count != param_count)
      return fail(error, error_size, "expected %u parameter values", static_cast<unsigned>(param_count));
    const double dip_lo = params->values[dip_min].float_value, dip_hi = params->values[dip_max].float_value;
    const double el_lo = params->values[elongation_min].float_value;
    const double el_hi = params->values[elongation_max].float_value;
    if (dip_lo > dip_hi) return fail(error, error_size, "dip_min %g is above dip_max %g", dip_lo, dip_hi);
    if (el_lo > el_hi) return fail(error, error_size, "elongation_min %g is above elongation_max %g", el_lo, el_hi);
    const char* order = params->values[rank_by].text_value;

    std::vector<const gt_component*> kept;
    for (std::uint64_t n = 0; n < count; ++n) {
      const gt_component& c = components[n];
      if (c.dip >= dip_lo && c.dip <= dip_hi && c.elongation >= el_lo && c.elongation <= el_hi) kept.push_back(&c);
    }
    *ranked = 0;
    if (std::strcmp(order, "volume") == 0) {
      std::stable_sort(kept.begin(), kept.end(),
                       [](const gt_component* a, const gt_component* b) { return size_of(*a) > size_of(*b); });
      *ranked = 1;
    } else if (std::strcmp(order, "elongation") == 0) {
      std::stable_sort(kept.begin(), kept.end(),
                       [](const gt_component* a, const gt_component* b) { return a->elongation > b->elongation; });
      *ranked = 1;
    }
    for (std::size_t n = 0; n < kept.size(); ++n)
      selected[n] = kept[n]->key;
    *selected_count = kept.size();
    return 0;
  } catch (const std::exception& e) { // never let an exception cross the C boundary
    return fail(error, error_size, "%s", e.what());
  } catch (...) {
    return fail(error, error_size, "unknown error");
  }
}

gt_plugin_descriptor make_descriptor() {
  gt_plugin_descriptor d{};
  d.struct_size = sizeof(gt_plugin_descriptor);
  d.abi_major = GEOTANDEM_PLUGIN_ABI_MAJOR;
  d.abi_minor = GEOTANDEM_PLUGIN_ABI_MINOR;
  d.kind = GT_PLUGIN_COMPONENT_STEP;
  d.name = "shape_filter";
  d.version = "1.0";
  d.summary = "keeps the bodies whose dip and horizontal elongation are in ranges, largest first";
  d.params = specs;
  d.param_count = param_count;
  d.component.select = select_bodies;
  return d;
}

const gt_plugin_descriptor descriptor = make_descriptor();

} // namespace

GEOTANDEM_PLUGIN_EXPORT const gt_plugin_descriptor* geotandem_plugin_entry(void) {
  return &descriptor;
}
