// The manager's listening endpoint from a user's --bind (bind_address.hpp).
#include "geotandem/runtime/bind_address.hpp"

#include <arpa/inet.h>
#include <ifaddrs.h>
#include <netinet/in.h>

#include <map>

#include "geotandem/core/error.hpp"

namespace geotandem::runtime {

namespace {

bool is_ipv4(const std::string& text) {
  in_addr a{};
  return inet_pton(AF_INET, text.c_str(), &a) == 1;
}

// Every interface's first IPv4 address, by name.
std::map<std::string, std::string> interfaces() {
  std::map<std::string, std::string> out;
  ifaddrs* list = nullptr;
  if (getifaddrs(&list) != 0) return out;
  for (ifaddrs* i = list; i; i = i->ifa_next) {
    if (!i->ifa_addr || i->ifa_addr->sa_family != AF_INET || out.count(i->ifa_name)) continue;
    char text[INET_ADDRSTRLEN] = {};
    inet_ntop(AF_INET, &reinterpret_cast<const sockaddr_in*>(i->ifa_addr)->sin_addr, text, sizeof text);
    out[i->ifa_name] = text;
  }
  freeifaddrs(list);
  return out;
}

// A port as the user gave it: "*" (any free one) or 1 to 65535. ZeroMQ itself reads a larger number
// modulo 65536 (99999 listened on 34463), and 0 as any port: both are refused here instead.
void check_port(const std::string& spec, const std::string& port) {
  if (port == "*") return;
  if (port.empty() || port.find_first_not_of("0123456789") != std::string::npos)
    throw InvalidArgument("bind '" + spec + "': the port '" + port + "' is not a number", {},
                          "give an interface (eth0), an address (10.0.0.5) or an address and port (10.0.0.5:5555)");
  if (port.size() > 5 || std::stoul(port) < 1 || std::stoul(port) > 65535)
    throw InvalidArgument("bind '" + spec + "': the port " + port + " is out of range (ports run from 1 to 65535)", {},
                          "give a port from 1 to 65535, or leave the port out for a free one");
}

} // namespace

std::string manager_bind_endpoint(const std::string& spec) {
  if (spec.empty() || spec == "loopback") return "tcp://127.0.0.1:*";
  if (spec.rfind("tcp://", 0) == 0) {
    const auto colon = spec.rfind(':');
    if (colon < 6)
      throw InvalidArgument("bind '" + spec + "' has no port", {},
                            "give tcp://ADDRESS:PORT, or tcp://ADDRESS:* for a free port");
    check_port(spec, spec.substr(colon + 1));
    return spec;
  }
  std::string host = spec, port = "*";
  if (const auto colon = spec.rfind(':'); colon != std::string::npos) {
    host = spec.substr(0, colon);
    port = spec.substr(colon + 1);
    check_port(spec, port);
  }
  if (host == "0.0.0.0" || host == "*")
    throw InvalidArgument("bind '" + spec + "': a wildcard address cannot be handed to the workers", {},
                          "give the interface or address the compute nodes reach this machine by, e.g. --bind ib0");
  if (is_ipv4(host)) return "tcp://" + host + ":" + port;
  const auto all = interfaces();
  if (auto it = all.find(host); it != all.end()) return "tcp://" + it->second + ":" + port;
  std::string names;
  for (const auto& [name, address] : all)
    names += (names.empty() ? "" : ", ") + name + " (" + address + ")";
  throw InvalidArgument("bind '" + spec + "' is neither an IPv4 address nor an interface of this machine", {},
                        "this machine's interfaces: " + (names.empty() ? std::string("none found") : names));
}

} // namespace geotandem::runtime
