#pragma once
// What the loader checks on a plugin-path entry before dlopen() sees it. dlopen() of a FIFO blocks
// until a writer comes (forever), of a device reads whatever the device gives, and of a truncated
// library maps segments past the end of the file, so that the first touch of those pages kills the
// process with SIGBUS. None of that can be undone once dlopen() runs, so the file is checked first.

#include <string>

namespace geotandem::workflow::detail {

// Throws FormatError naming `path` and why when it is not a plausibly complete shared library of
// this machine: a FIFO, socket, device or directory (found by stat before anything opens it), a
// file this user cannot read (IoError), or an ELF header that is not a shared object of this
// machine's class, byte order and architecture, or whose program headers, section headers or
// loadable segments reach beyond the end of the file (a truncated copy).
// The file may still change between this check and dlopen(): whoever can write the plugin
// directory can run code in every geotandem process anyway, so this guards against accidents
// (an interrupted copy, a stray FIFO), not against an attacker.
void check_plugin_library(const std::string& path);

} // namespace geotandem::workflow::detail
