#include "interpreter.hpp"

#include <mutex>
#include <regex>

#include "geotandem/core/error.hpp"

namespace py = pybind11;

namespace geotandem::python_step {
namespace {

// Whether a ModuleNotFoundError is about `module` itself or one of its parent packages ("a.b" for
// "a.b.c"), not about a module that `module` imports (numpy, scipy, ...).
bool missing_module_is(const pybind11::error_already_set& e, const std::string& module) {
  if (!pybind11::hasattr(e.value(), "name")) return true;
  const pybind11::object name = e.value().attr("name");
  if (name.is_none()) return true;
  const auto missing = name.cast<std::string>();
  return module == missing || module.rfind(missing + ".", 0) == 0;
}

} // namespace

void ensure_interpreter() {
  static std::once_flag once;
  // A throw leaves the flag unset: the next step tries again and says the same.
  std::call_once(once, [] {
    if (Py_IsInitialized()) return; // geotandem inside python3: its interpreter, its GIL
    PyConfig config;
    PyConfig_InitPythonConfig(&config); // PYTHONPATH, PYTHONHOME and the site packages as python3 has them
    config.install_signal_handlers = 0; // Ctrl-C stays geotandem's (core/interrupt.hpp)
    config.parse_argv = 0;
    // Unbuffered, as `python3 -u`: the interpreter is never finalised (interpreter.hpp), so a user's
    // print() in a worker's log would otherwise be lost in a buffer at exit.
    config.buffered_stdio = 0;
    // The interpreter finds its standard library from the program's location. Left to itself an
    // embedded one searches PATH for "python3", which may be another installation's (pyenv):
    // name the interpreter geotandem was built against.
    PyStatus status = PyConfig_SetBytesString(&config, &config.program_name, GEOTANDEM_PYTHON_EXECUTABLE);
    if (!PyStatus_Exception(status)) status = Py_InitializeFromConfig(&config);
    PyConfig_Clear(&config);
    if (PyStatus_Exception(status))
      throw InvalidArgument(std::string("cannot start the Python interpreter: ") +
                                (status.err_msg ? status.err_msg : "no reason given"),
                            {GEOTANDEM_PYTHON_EXECUTABLE},
                            "install python3 (Debian: python3, python3-numpy) on every machine of the run");
    // Initialising took the GIL: give it back, every call takes it (PyGILState) for its duration.
    PyEval_SaveThread();
  });
}

PyRef::~PyRef() {
  // At the exit of a python3 process the interpreter goes first and owns what is left.
  if (!object_ || !Py_IsInitialized() || _Py_IsFinalizing()) return;
  PyGILState_STATE state = PyGILState_Ensure();
  Py_DECREF(object_);
  PyGILState_Release(state);
}

std::string traceback_text(py::error_already_set& error) {
  try {
    py::object lines =
        py::module_::import("traceback").attr("format_exception")(error.type(), error.value(), error.trace());
    std::string text = py::str("").attr("join")(lines).cast<std::string>();
    while (!text.empty() && text.back() == '\n')
      text.pop_back();
    return text;
  } catch (const py::error_already_set&) {
    return error.what();
  }
}

PyRef import_function(const std::string& function, const std::string& directory) {
  static const std::regex form(R"(([A-Za-z_]\w*(\.[A-Za-z_]\w*)*):([A-Za-z_]\w*(\.[A-Za-z_]\w*)*))");
  std::smatch parts;
  if (!std::regex_match(function, parts, form))
    throw InvalidArgument("parameter 'function' is '" + function + "', not module:function", {},
                          "name a module and a function in it, e.g. function: mypkg.attrs:sweetness");
  const std::string module = parts[1], name = parts[3];
  const std::string where = directory.empty() ? std::string("PYTHONPATH") : directory + " or PYTHONPATH";
  ensure_interpreter();
  py::gil_scoped_acquire gil;
  py::object target;
  try {
    if (!directory.empty()) {
      py::list path = py::module_::import("sys").attr("path");
      py::str entry(directory);
      if (!path.contains(entry)) path.insert(0, entry); // ahead of PYTHONPATH, as a script's own directory is
    }
    target = py::module_::import(module.c_str());
  } catch (py::error_already_set& e) {
    // The module itself not found says so in one line; anything else (an error raised by its code, or
    // a module that it imports missing) gets its traceback.
    if (e.matches(PyExc_ModuleNotFoundError) && missing_module_is(e, module))
      throw InvalidArgument("parameter 'function' is '" + function + "': cannot import module '" + module +
                                "': " + py::str(e.value()).cast<std::string>(),
                            {}, "put the module in " + where + ", or set the step's 'path' to its directory");
    throw InvalidArgument("parameter 'function' is '" + function + "': importing module '" + module + "' failed:\n" +
                              traceback_text(e),
                          {}, "fix the module (the traceback above is Python's)");
  }
  std::size_t start = 0;
  for (;;) {
    const std::size_t dot = name.find('.', start);
    const std::string attribute = name.substr(start, dot == std::string::npos ? std::string::npos : dot - start);
    if (!py::hasattr(target, attribute.c_str()))
      throw InvalidArgument("parameter 'function' is '" + function + "': module '" + module + "' has no '" +
                                name.substr(0, dot) + "'",
                            {}, "check the function's name (module:function)");
    target = target.attr(attribute.c_str());
    if (dot == std::string::npos) break;
    start = dot + 1;
  }
  if (!PyCallable_Check(target.ptr()))
    throw InvalidArgument("parameter 'function' is '" + function + "', which is not callable (" +
                              py::str(py::type::handle_of(target).attr("__name__")).cast<std::string>() + ")",
                          {}, "name a function that takes the block as a numpy array");
  return PyRef(std::move(target));
}

} // namespace geotandem::python_step
