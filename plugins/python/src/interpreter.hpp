#pragma once
// The Python interpreter as the `python` step uses it.
//
// One interpreter per process, made on first use and never finalised: numpy cannot be initialised
// twice in a process, and objects held by volumes may outlive any owner we could give the
// interpreter. When the process already runs one (geotandem inside python3), it is used as it is.
// The GIL is held only around calls into Python: everything else runs without it, so several
// threads may read attributes at once (numpy releases the GIL inside many of its operations).

#include <string>

#include <pybind11/pybind11.h>

namespace geotandem::python_step {

// Makes sure this process has a Python interpreter, initialising one without Python's signal
// handlers (geotandem's own handle Ctrl-C) when it has none. Throws InvalidArgument when the
// interpreter cannot start. Call without the GIL held.
void ensure_interpreter();

// A reference to a Python object that may be dropped on any thread, with or without the GIL, and
// at process exit (when the interpreter is finalising the reference is left to it).
class PyRef {
public:
  PyRef() = default;
  explicit PyRef(pybind11::object object) : object_(object.release().ptr()) {}
  PyRef(PyRef&& other) noexcept : object_(other.object_) { other.object_ = nullptr; }
  PyRef(const PyRef&) = delete;
  PyRef& operator=(const PyRef&) = delete;
  ~PyRef();
  // Borrowed; use with the GIL held.
  pybind11::handle get() const { return object_; }

private:
  PyObject* object_ = nullptr;
};

// What `function` names: "module.path:function" (dotted attribute paths after the colon are
// followed, "mod:Class.method"). `directory`, when not empty, is put at the front of sys.path first
// (once). Throws InvalidArgument naming the parameter 'function' with Python's reason (the
// traceback for an error raised while importing). Takes the GIL itself.
PyRef import_function(const std::string& function, const std::string& directory);

// The current Python exception as Python prints it: "Traceback (most recent call last): ...".
// Use with the GIL held, inside the catch of an error_already_set.
std::string traceback_text(pybind11::error_already_set& error);

} // namespace geotandem::python_step
