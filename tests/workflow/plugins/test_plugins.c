/* Plugins built by the tests as real shared libraries. Which one is compiled is chosen by a
 * preprocessor symbol (see CMakeLists.txt): each variant exercises one path of the loader. */
#include <stdio.h>
#include <string.h>

#include "geotandem/workflow/plugin_abi.h"

#define GT_STR2(x) #x
#define GT_STR(x) GT_STR2(x)

static int halo_box(const gt_params* params, const gt_cube_info* cube, int64_t halo[3], char* error, size_t size) {
  (void)params; (void)cube; (void)error; (void)size;
  halo[0] = halo[1] = halo[2] = 1;
  return 0;
}

/* out = factor * (sum of the 3x3x3 neighbourhood inside the cube). */
static int compute_box(const gt_params* params, const gt_cube_info* cube, const float* in, const gt_box* ib, float* out,
                       const gt_box* ob, char* error, size_t size) {
  double factor = params->values[0].float_value;
  int64_t ni = ib->hi[0] - ib->lo[0], nj = ib->hi[1] - ib->lo[1], nk = ib->hi[2] - ib->lo[2];
#ifdef GT_TEST_FAILING
  /* Refuses the second half of the cube only, so that a run sweeping inline by inline has finished
   * and committed the components of the first half when it fails. */
  if (2 * ob->lo[0] >= cube->shape[0]) {
    snprintf(error, size, "refusing box starting at inline %lld", (long long)ob->lo[0]);
    return 1;
  }
#endif
  (void)cube; (void)error; (void)size;
  size_t n = 0;
  for (int64_t i = ob->lo[0]; i < ob->hi[0]; ++i)
    for (int64_t j = ob->lo[1]; j < ob->hi[1]; ++j)
      for (int64_t k = ob->lo[2]; k < ob->hi[2]; ++k) {
        double sum = 0;
        for (int64_t a = i - 1; a <= i + 1; ++a)
          for (int64_t b = j - 1; b <= j + 1; ++b)
            for (int64_t c = k - 1; c <= k + 1; ++c) {
              if (a < ib->lo[0] || a >= ib->hi[0] || b < ib->lo[1] || b >= ib->hi[1] || c < ib->lo[2] || c >= ib->hi[2])
                continue;
              sum += in[((a - ib->lo[0]) * nj + (b - ib->lo[1])) * nk + (c - ib->lo[2])];
            }
        out[n++] = (float)(factor * sum);
      }
  (void)ni;
  return 0;
}

static const gt_param_spec specs[] = {
    {"factor", GT_PARAM_FLOAT, "2", "multiplies the neighbourhood sum", 0.0, 100.0, NULL},
    {"mode", GT_PARAM_CHOICE, "fast", "an unused choice", 0.0, -1.0, "fast|exact"},
};

static gt_plugin_descriptor descriptor = {
    sizeof(gt_plugin_descriptor),
#ifdef GT_TEST_WRONG_VERSION
    GEOTANDEM_PLUGIN_ABI_MAJOR + 1,
#else
    GEOTANDEM_PLUGIN_ABI_MAJOR,
#endif
    GEOTANDEM_PLUGIN_ABI_MINOR,
    GT_PLUGIN_ATTRIBUTE,
    GT_STR(GT_TEST_NAME),
    "0.1",
    "test attribute: scaled 3x3x3 neighbourhood sum",
    specs,
    2,
    {halo_box, compute_box},
};

#ifndef GT_TEST_NO_ENTRY
GEOTANDEM_PLUGIN_EXPORT const gt_plugin_descriptor* geotandem_plugin_entry(void) { return &descriptor; }
#else
GEOTANDEM_PLUGIN_EXPORT const gt_plugin_descriptor* some_other_function(void) { return &descriptor; }
#endif
