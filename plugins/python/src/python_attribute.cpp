#include "python_attribute.hpp"

#include <cmath>
#include <cstring>
#include <stdexcept>
#include <vector>

#include <pybind11/numpy.h>

#include "geotandem/core/error.hpp"

namespace py = pybind11;

namespace geotandem::python_step {
namespace {

// The index `index` reads on an axis of `size` samples: half-sample symmetric reflection about the
// faces, repeated with period 2 size (-1 -> 0, size -> size - 1), as the built-in attributes read.
std::int64_t mirrored(std::int64_t index, std::int64_t size) {
  const std::int64_t period = 2 * size;
  std::int64_t r = index % period;
  if (r < 0) r += period;
  return r < size ? r : period - 1 - r;
}

// `box` grown by `halo`, in C order, mirrored where it leaves the cube. One read of the part inside.
std::vector<float> read_grown(const volume::Volume& input, const volume::Box& box, const volume::Index3& halo) {
  const volume::Box grown = box.grown(halo);
  const volume::Index3& shape = input.geometry().shape;
  const volume::Box inside = grown.intersection(input.geometry().bounds());
  const std::vector<float> read = input.read(inside);
  std::vector<std::int64_t> source[3]; // per axis: the index inside `inside` each grown index reads
  for (int a = 0; a < 3; ++a)
    for (std::int64_t i = grown.lo[a]; i < grown.hi[a]; ++i) {
      const std::int64_t m = mirrored(i, shape[a]);
      // The reflection of a grown box stays in the grown box's part inside the cube.
      if (m < inside.lo[a] || m >= inside.hi[a]) throw std::logic_error("python step: mirrored index outside its read");
      source[a].push_back(m - inside.lo[a]);
    }
  std::vector<float> out(grown.count());
  const auto nj = static_cast<std::size_t>(inside.size(1)), nk = static_cast<std::size_t>(inside.size(2));
  const std::size_t gk = source[2].size();
  // Along the trace only the ends are mirrored: the run between them is one copy.
  const std::size_t first = static_cast<std::size_t>(std::max<std::int64_t>(0, -grown.lo[2]));
  const std::size_t run = static_cast<std::size_t>(inside.size(2));
  float* o = out.data();
  for (std::int64_t si : source[0])
    for (std::int64_t sj : source[1]) {
      const float* row = read.data() + (static_cast<std::size_t>(si) * nj + static_cast<std::size_t>(sj)) * nk;
      for (std::size_t k = 0; k < first; ++k)
        o[k] = row[source[2][k]];
      std::memcpy(o + first, row + source[2][first], run * sizeof(float));
      for (std::size_t k = first + run; k < gk; ++k)
        o[k] = row[source[2][k]];
      o += gk;
    }
  return out;
}

std::string shape_text(const std::vector<py::ssize_t>& shape) {
  std::string text = "(";
  for (std::size_t n = 0; n < shape.size(); ++n)
    text += (n ? ", " : "") + std::to_string(shape[n]);
  return text + (shape.size() == 1 ? ",)" : ")");
}

std::string shape_text(const volume::Index3& shape) {
  return shape_text(std::vector<py::ssize_t>{shape[0], shape[1], shape[2]});
}

} // namespace

PythonAttribute::PythonAttribute(attributes::VolumePtr input, std::string function, const volume::Index3& halo,
                                 std::shared_ptr<const PyRef> callable)
    : Attribute("python",
                "function=" + function + ", halo=[" + std::to_string(halo[0]) + ", " + std::to_string(halo[1]) + ", " +
                    std::to_string(halo[2]) + "]",
                {std::move(input)}, halo),
      function_(std::move(function)), callable_(std::move(callable)) {}

void PythonAttribute::compute(const volume::Box& box, std::span<float> out) const {
  const volume::Box grown = box.grown(halo());
  auto samples = std::make_unique<std::vector<float>>(read_grown(*inputs().front(), box, halo()));
  const std::string what = "python step (function " + function_ + ")";
  const ErrorContext where{
      {}, {}, {}, "block " + box.to_string() + " (inline, crossline, sample; the halo not included)", {}};
  const volume::Index3 full = grown.shape(), inner = box.shape();

  py::gil_scoped_acquire gil;
  // The array owns the samples through a capsule: no copy, and nothing dangles if the function
  // keeps a reference to its argument.
  py::capsule owner(samples.get(), [](void* p) { delete static_cast<std::vector<float>*>(p); });
  float* data = samples.release()->data();
  py::array_t<float> block({full[0], full[1], full[2]}, data, owner);

  py::object result;
  try {
    result = callable_->get()(block);
  } catch (py::error_already_set& e) {
    throw DataError(what + " raised " + py::str(py::type::handle_of(e.value()).attr("__name__")).cast<std::string>() +
                        ":\n" + traceback_text(e),
                    where, "the traceback above is Python's; the run stopped, components already stored are kept");
  }
  if (!py::isinstance<py::array>(result))
    throw DataError(what + " returned a " + py::str(py::type::handle_of(result).attr("__name__")).cast<std::string>() +
                        ", not a numpy array",
                    where, "return a float32 numpy array of shape " + shape_text(full) + " or " + shape_text(inner));
  const py::array array = py::reinterpret_borrow<py::array>(result);
  if (!py::isinstance<py::array_t<float>>(array))
    throw DataError(what + " returned an array of dtype " + py::str(array.dtype()).cast<std::string>() +
                        "; it must return float32",
                    where, "cast the result: return result.astype(numpy.float32)");
  std::vector<py::ssize_t> shape(array.shape(), array.shape() + array.ndim());
  const bool whole = shape == std::vector<py::ssize_t>{full[0], full[1], full[2]};
  const bool cropped = shape == std::vector<py::ssize_t>{inner[0], inner[1], inner[2]};
  if (!whole && !cropped)
    throw DataError(
        what + " returned an array of shape " + shape_text(shape) + ", given one of shape " + shape_text(full), where,
        "return the shape it was given, " + shape_text(full) + ", or that shape less the halo " + shape_text(halo()) +
            " on each side, " + shape_text(inner));
  // Strides as numpy has them (a transposed or sliced result is read as it is, not copied first).
  const auto values = array.unchecked<float, 3>();
  const volume::Index3 skip = whole ? halo() : volume::Index3{0, 0, 0};
  float* o = out.data();
  for (std::int64_t i = 0; i < inner[0]; ++i)
    for (std::int64_t j = 0; j < inner[1]; ++j)
      for (std::int64_t k = 0; k < inner[2]; ++k) {
        const float v = values(i + skip[0], j + skip[1], k + skip[2]);
        if (!std::isfinite(v))
          throw DataError(what + " returned " + (std::isnan(v) ? "NaN" : "an infinite value") + " at sample (" +
                              std::to_string(box.lo[0] + i) + ", " + std::to_string(box.lo[1] + j) + ", " +
                              std::to_string(box.lo[2] + k) + ")",
                          where, "an attribute must be finite everywhere: guard divisions and logarithms");
        *o++ = v;
      }
}

} // namespace geotandem::python_step
