#pragma once
// SIGINT and SIGTERM for a command-line process: the first signal cancels the token (long
// operations stop at their next safe point and the command exits 130); if the process is still
// running `grace_seconds` later (a wait that does not poll the token), a watchdog thread ends it
// with _exit(128 + signal). A second signal ends it at once. Every store write is crash-safe, so
// ending the process at any moment leaves a valid store (see docs/store-format.md).
// SIGBUS (a mapped file, e.g. a SEG-Y cube, truncated by another process) ends the process with a
// clear message and exit status 4 instead of a core dump.

#include "geotandem/core/cancel.hpp"

namespace geotandem {

// Installs the handlers and starts the watchdog. Call once, from main, before the work starts.
void install_interrupt_handling(const CancelToken& cancel, double grace_seconds = 0.8);

} // namespace geotandem
