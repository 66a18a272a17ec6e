#pragma once
// The parts of geotandem._core, each bound in its own file and added by module.cpp.

#include <pybind11/pybind11.h>

namespace geotandem::python {

void bind_store(pybind11::module_& m);   // store_binding.cpp: Store
void bind_compute(pybind11::module_& m); // compute_binding.cpp: extract, run_workflow, synth, parameters

} // namespace geotandem::python
