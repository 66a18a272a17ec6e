#include "errors.hpp"

#include <pybind11/pybind11.h>

#include "geotandem/core/error.hpp"

namespace py = pybind11;

namespace geotandem::python {
namespace {

// The Python class of a C++ error (geotandem/errors.py defines them).
const char* class_name(const Error& e) {
  if (dynamic_cast<const InvalidArgument*>(&e)) return e.context().line ? "RecipeError" : "InvalidArgumentError";
  if (dynamic_cast<const IoError*>(&e)) return "IoError";
  if (dynamic_cast<const FormatError*>(&e)) return "FormatError";
  if (dynamic_cast<const DataError*>(&e)) return "DataError";
  return "Error";
}

void raise(const Error& e) {
  py::object errors = py::module_::import("geotandem.errors");
  py::object cls = errors.attr(class_name(e));
  const ErrorContext& c = e.context();
  auto optional = [](const std::optional<long>& v) { return v ? py::object(py::int_(*v)) : py::object(py::none()); };
  auto text = [](const std::string& s) { return s.empty() ? py::object(py::none()) : py::object(py::str(s)); };
  py::object instance = cls(py::str(e.what()), py::arg("message") = e.message(), py::arg("file") = text(c.file),
                            py::arg("line") = optional(c.line), py::arg("column") = optional(c.column),
                            py::arg("hint") = text(e.hint()), py::arg("exit_code") = e.exit_code());
  PyErr_SetObject(cls.ptr(), instance.ptr());
}

} // namespace

void register_error_translator() {
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const Cancelled&) {
      PyErr_SetNone(PyExc_KeyboardInterrupt);
    } catch (const Error& e) {
      try {
        raise(e);
      } catch (py::error_already_set& failed) {
        failed.restore(); // geotandem.errors could not be imported: say so instead
      }
    }
  });
}

} // namespace geotandem::python
