// geotandem._core: the compiled part of the Python package (python/geotandem wraps it).

#include <pybind11/pybind11.h>

#include "bindings.hpp"
#include "errors.hpp"

#ifndef GEOTANDEM_VERSION
#error "GEOTANDEM_VERSION is set by python/CMakeLists.txt from the project's version"
#endif

PYBIND11_MODULE(_core, m) {
  m.doc() = "geotandem's C++ libraries (store, extraction, workflows); use the geotandem package instead.";
  m.attr("__version__") = GEOTANDEM_VERSION;
  geotandem::python::register_error_translator();
  geotandem::python::bind_store(m);
  geotandem::python::bind_compute(m);
}
