// avg_abs_amplitude: an example geotandem attribute plugin, built against an installed geotandem.
//
// The average absolute amplitude is the mean of |amplitude| over a small window around each
// sample: a box filter along the trace and, optionally, across neighbouring traces. It is a classic
// reflection-strength attribute that ignores polarity, so bright spots and strong reflectors stand
// out whatever their sign, and averaging removes the oscillation of the wavelet.
//
// Only the C interface (geotandem/workflow/plugin_abi.h) is used; no framework library is linked.
// The plugin follows the contract of docs/plugins.md:
// - halo: the half window on each axis;
// - boundaries: half-sample symmetric mirroring about the cube's faces (index -1 reads 0, n reads
//   n-1, repeated when the window is wider than the cube), so the attribute is defined for every
//   sample and does not depend on how the cube is cut into boxes;
// - each output sample adds its window in a fixed order (trace, then crossline, then inline), in
//   double, so a box computed alone is bit-identical to the same box of a whole-cube computation;
// - errors are written into the host's buffer, and no C++ exception leaves a callback;
// - no mutable global state: compute may run on several threads at once.

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <new>
#include <vector>

#include "geotandem/workflow/plugin_abi.h"

namespace {

// Parameter positions: the host passes values in spec order.
enum Param : std::uint32_t { half_window = 0, half_traces = 1, param_count = 2 };

const gt_param_spec specs[param_count] = {
    {"half_window", GT_PARAM_INT, "5",
     "half length of the averaging window along the trace, in samples (the window spans 2 half_window + 1 "
     "samples; about half a dominant period is a good start)",
     0.0, 500.0, nullptr},
    {"half_traces", GT_PARAM_INT, "0",
     "half width of the square of traces averaged across, in traces (0: along the trace only)", 0.0, 50.0, nullptr},
};

// Writes a message into the host's buffer (truncated, always NUL-terminated) and returns 1.
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

// The half window along (inline, crossline, sample), from validated parameters.
bool read_half(const gt_params* params, std::int64_t half[3], char* error, std::size_t size) {
  if (!params || params->count != param_count || !params->values) {
    fail(error, size, "expected %u parameter values, got %u", static_cast<unsigned>(param_count),
         params ? static_cast<unsigned>(params->count) : 0U);
    return false;
  }
  half[0] = half[1] = params->values[half_traces].int_value;
  half[2] = params->values[half_window].int_value;
  // The host checked the ranges; a host that did not would make the windows below overflow.
  for (int a = 0; a < 3; ++a)
    if (half[a] < 0 || half[a] > 500) {
      fail(error, size, "half window %lld on axis %d is outside 0 to 500", static_cast<long long>(half[a]), a);
      return false;
    }
  return true;
}

// Half-sample symmetric mirror of index g into [0, n): period 2n, -1 -> 0, n -> n - 1.
std::int64_t mirror(std::int64_t g, std::int64_t n) {
  const std::int64_t period = 2 * n;
  std::int64_t m = g % period;
  if (m < 0) m += period;
  return m < n ? m : period - 1 - m;
}

const char* const axis_names[3] = {"inline", "crossline", "sample"};

// Checks the boxes the host passed: the output inside the cube, the input inside the cube, and
// every mirrored index the window needs inside the input. Fills `index[a]` with, for each position
// of the output's window range [lo - half, hi + half), the mirrored index relative to the input box.
bool map_axes(const gt_cube_info* cube, const gt_box* in, const gt_box* out, const std::int64_t half[3],
              std::vector<std::int64_t> index[3], char* error, std::size_t size) {
  for (int a = 0; a < 3; ++a) {
    const std::int64_t n = cube->shape[a];
    if (n <= 0) {
      fail(error, size, "the cube has %lld samples along the %s axis", static_cast<long long>(n), axis_names[a]);
      return false;
    }
    if (out->lo[a] < 0 || out->hi[a] > n || out->lo[a] > out->hi[a] || in->lo[a] < 0 || in->hi[a] > n ||
        in->lo[a] > in->hi[a]) {
      fail(error, size, "%s axis: output [%lld, %lld) or input [%lld, %lld) is not a box of the cube [0, %lld)",
           axis_names[a], static_cast<long long>(out->lo[a]), static_cast<long long>(out->hi[a]),
           static_cast<long long>(in->lo[a]), static_cast<long long>(in->hi[a]), static_cast<long long>(n));
      return false;
    }
    index[a].clear();
    for (std::int64_t g = out->lo[a] - half[a]; g < out->hi[a] + half[a]; ++g) {
      const std::int64_t m = mirror(g, n);
      if (m < in->lo[a] || m >= in->hi[a]) {
        fail(error, size,
             "%s axis: the window of output [%lld, %lld) needs index %lld, outside the input [%lld, %lld); the "
             "input must be the output grown by the halo (%lld) and clipped to the cube",
             axis_names[a], static_cast<long long>(out->lo[a]), static_cast<long long>(out->hi[a]),
             static_cast<long long>(m), static_cast<long long>(in->lo[a]), static_cast<long long>(in->hi[a]),
             static_cast<long long>(half[a]));
        return false;
      }
      index[a].push_back(m - in->lo[a]);
    }
  }
  return true;
}

int halo(const gt_params* params, const gt_cube_info* cube, std::int64_t out_halo[3], char* error, std::size_t size) {
  (void)cube;
  try {
    std::int64_t half[3];
    if (!read_half(params, half, error, size)) return 1;
    for (int a = 0; a < 3; ++a)
      out_halo[a] = half[a];
    return 0;
  } catch (...) {
    return fail(error, size, "unexpected failure while computing the halo");
  }
}

// Three separable passes, each a plain sum over its window in index order. A sample's value is
// sum_i (sum_j (sum_k |x|)) over mirrored indices, whatever box it was computed in.
int compute_impl(const gt_params* params, const gt_cube_info* cube, const float* input, const gt_box* in, float* output,
                 const gt_box* out, char* error, std::size_t size) {
  std::int64_t half[3];
  if (!read_half(params, half, error, size)) return 1;
  if (!cube || !input || !in || !output || !out) return fail(error, size, "a null pointer was passed to compute");
  std::vector<std::int64_t> index[3];
  if (!map_axes(cube, in, out, half, index, error, size)) return 1;

  std::int64_t in_n[3], out_n[3];
  for (int a = 0; a < 3; ++a) {
    in_n[a] = in->hi[a] - in->lo[a];
    out_n[a] = out->hi[a] - out->lo[a];
  }
  if (out_n[0] == 0 || out_n[1] == 0 || out_n[2] == 0) return 0;
  const std::int64_t wk = 2 * half[2] + 1, wj = 2 * half[1] + 1, wi = 2 * half[0] + 1;
  const auto at = [](std::int64_t i, std::int64_t j, std::int64_t k, std::int64_t nj, std::int64_t nk) {
    return static_cast<std::size_t>((i * nj + j) * nk + k);
  };

  // Pass 1, along the trace: every input trace, at the output's samples.
  std::vector<double> along(static_cast<std::size_t>(in_n[0] * in_n[1] * out_n[2]));
  for (std::int64_t i = 0; i < in_n[0]; ++i)
    for (std::int64_t j = 0; j < in_n[1]; ++j) {
      const float* trace = input + at(i, j, 0, in_n[1], in_n[2]);
      double* row = &along[at(i, j, 0, in_n[1], out_n[2])];
      for (std::int64_t k = 0; k < out_n[2]; ++k) {
        double sum = 0.0;
        for (std::int64_t c = 0; c < wk; ++c)
          sum += std::fabs(static_cast<double>(trace[index[2][static_cast<std::size_t>(k + c)]]));
        row[k] = sum;
      }
    }

  // Pass 2, across crosslines: every input inline, at the output's crosslines.
  std::vector<double> across(static_cast<std::size_t>(in_n[0] * out_n[1] * out_n[2]), 0.0);
  for (std::int64_t i = 0; i < in_n[0]; ++i)
    for (std::int64_t j = 0; j < out_n[1]; ++j) {
      double* row = &across[at(i, j, 0, out_n[1], out_n[2])];
      for (std::int64_t b = 0; b < wj; ++b) {
        const double* src = &along[at(i, index[1][static_cast<std::size_t>(j + b)], 0, in_n[1], out_n[2])];
        for (std::int64_t k = 0; k < out_n[2]; ++k)
          row[k] += src[k];
      }
    }

  // Pass 3, across inlines, then the mean.
  const double count = static_cast<double>(wi * wj * wk);
  std::vector<double> sum(static_cast<std::size_t>(out_n[2]));
  for (std::int64_t i = 0; i < out_n[0]; ++i)
    for (std::int64_t j = 0; j < out_n[1]; ++j) {
      std::fill(sum.begin(), sum.end(), 0.0);
      for (std::int64_t a = 0; a < wi; ++a) {
        const double* src = &across[at(index[0][static_cast<std::size_t>(i + a)], j, 0, out_n[1], out_n[2])];
        for (std::int64_t k = 0; k < out_n[2]; ++k)
          sum[static_cast<std::size_t>(k)] += src[k];
      }
      float* dst = output + at(i, j, 0, out_n[1], out_n[2]);
      for (std::int64_t k = 0; k < out_n[2]; ++k)
        dst[k] = static_cast<float>(sum[static_cast<std::size_t>(k)] / count);
    }
  return 0;
}

int compute(const gt_params* params, const gt_cube_info* cube, const float* input, const gt_box* input_box,
            float* output, const gt_box* output_box, char* error, std::size_t size) {
  // Nothing may escape into the host: it is C on the other side of this call.
  try {
    return compute_impl(params, cube, input, input_box, output, output_box, error, size);
  } catch (const std::bad_alloc&) {
    return fail(error, size, "out of memory for a box of %lld x %lld x %lld samples",
                static_cast<long long>(output_box->hi[0] - output_box->lo[0]),
                static_cast<long long>(output_box->hi[1] - output_box->lo[1]),
                static_cast<long long>(output_box->hi[2] - output_box->lo[2]));
  } catch (const std::exception& e) {
    return fail(error, size, "%s", e.what());
  } catch (...) {
    return fail(error, size, "unexpected failure");
  }
}

const gt_plugin_descriptor descriptor = {
    sizeof(gt_plugin_descriptor),
    GEOTANDEM_PLUGIN_ABI_MAJOR,
    GEOTANDEM_PLUGIN_ABI_MINOR,
    GT_PLUGIN_ATTRIBUTE,
    "avg_abs_amplitude",
    "1.0",
    "average absolute amplitude: mean of |amplitude| in a window along the trace (and optionally across traces)",
    specs,
    param_count,
    {halo, compute},
    {nullptr}, // component step callbacks (interface 1.1): not this plugin's kind
};

} // namespace

GEOTANDEM_PLUGIN_EXPORT const gt_plugin_descriptor* geotandem_plugin_entry(void) {
  return &descriptor;
}
