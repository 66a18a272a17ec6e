#pragma once
// Where the manager listens (`execution.bind`, `--bind`): loopback unless told an interface or an
// address, so that the endpoint handed to the workers is one they can reach. CurveZMQ is on
// whatever the address, loopback included (see the README's scheduler section).
#include <string>

namespace geotandem::runtime {

// "" or "loopback": tcp://127.0.0.1:* (a free port). An interface name ("eth0", "ib0"): its first
// IPv4 address. An IPv4 address, optionally with ":PORT". A full "tcp://HOST:PORT" as given.
// Throws InvalidArgument for a wildcard (0.0.0.0, *: workers cannot connect to it), a port that is
// not a number or not in 1-65535 ("*" is any free one), an unknown interface (naming the ones this
// machine has) or anything else.
std::string manager_bind_endpoint(const std::string& spec);

} // namespace geotandem::runtime
