// Under the address sanitizer: the embedded Python interpreter's memory is not leaked memory.
//
// The python step starts one interpreter per process and never finalises it (numpy cannot be
// initialised twice in a process: plugins/python/src/interpreter.hpp), so at exit everything the
// interpreter, numpy and the modules they loaded allocated is still held, much of it in
// uninstrumented libraries whose stacks LeakSanitizer cannot follow to a root. These suppressions
// name those libraries only: an allocation made by geotandem's own code (the blocks handed to
// Python are allocated in plugins/python) is still reported. LeakSanitizer reads the hook from
// the executable, not from a shared library, so it lives here.

#if defined(__SANITIZE_ADDRESS__)
extern "C" const char* __lsan_default_suppressions() {
  return "leak:libpython3\n"    // the interpreter
         "leak:.cpython-3\n"    // extension modules (numpy's among them), any 3.x
         "leak:libcrypto.so\n"; // loaded by hashlib when numpy.random is imported
}
#endif
