#pragma once
// An attribute computed by a Python function, box by box (docs/plugins.md, "Attributes written in
// Python").
//
// For a box B the function receives B grown by the declared halo as a C-contiguous float32 array
// of shape (inlines, crosslines, samples), with the built-in attributes' border rule: where the
// grown box leaves the cube, the input is mirrored about the cube's faces (half-sample symmetric,
// attribute.hpp), so the array always has the full halo. The array owns its samples (no copy of
// them is made for Python, and the function may keep it). It returns a float32 array of either the
// grown shape (the halo is cropped here) or B's shape; anything else, a NaN or an infinite value,
// or an exception is a DataError naming the function and B, with Python's traceback.
//
// Large boxes are computed in tiles (Attribute::kTile), each one call. Calls hold the GIL; the
// mirrored read and the copy of the result run without it.

#include <memory>
#include <string>

#include "geotandem/attributes/attribute.hpp"
#include "interpreter.hpp"

namespace geotandem::python_step {

class PythonAttribute final : public attributes::Attribute {
public:
  // `function` is the recipe's text (module:function), for messages; `callable` the imported
  // function.
  PythonAttribute(attributes::VolumePtr input, std::string function, const volume::Index3& halo,
                  std::shared_ptr<const PyRef> callable);

protected:
  void compute(const volume::Box& box, std::span<float> out) const override;

private:
  std::string function_;
  std::shared_ptr<const PyRef> callable_;
};

} // namespace geotandem::python_step
