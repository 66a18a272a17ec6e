// Where the manager listens (--bind): loopback by default, an interface's address, an address with
// or without a port; a wildcard, a bad port and an unknown interface are refused with the reason.
#include <gtest/gtest.h>

#include "geotandem/core/error.hpp"
#include "geotandem/runtime/bind_address.hpp"

namespace geotandem::runtime {
namespace {

TEST(BindAddress, LoopbackByDefault) {
  EXPECT_EQ(manager_bind_endpoint(""), "tcp://127.0.0.1:*");
  EXPECT_EQ(manager_bind_endpoint("loopback"), "tcp://127.0.0.1:*");
}

TEST(BindAddress, AnInterfaceGivesItsAddress) {
  EXPECT_EQ(manager_bind_endpoint("lo"), "tcp://127.0.0.1:*"); // every Linux machine has lo
  EXPECT_EQ(manager_bind_endpoint("lo:5555"), "tcp://127.0.0.1:5555");
}

TEST(BindAddress, AnAddressWithOrWithoutAPort) {
  EXPECT_EQ(manager_bind_endpoint("10.0.0.5"), "tcp://10.0.0.5:*");
  EXPECT_EQ(manager_bind_endpoint("10.0.0.5:5555"), "tcp://10.0.0.5:5555");
  EXPECT_EQ(manager_bind_endpoint("tcp://10.0.0.5:7"), "tcp://10.0.0.5:7");
}

std::string refusal(const std::string& spec) {
  try {
    (void)manager_bind_endpoint(spec);
  } catch (const InvalidArgument& e) {
    return e.what();
  }
  return "accepted";
}

TEST(BindAddress, WildcardsBadPortsAndUnknownInterfacesAreRefused) {
  EXPECT_NE(refusal("0.0.0.0").find("wildcard"), std::string::npos) << refusal("0.0.0.0");
  EXPECT_NE(refusal("*:5555").find("wildcard"), std::string::npos);
  EXPECT_NE(refusal("10.0.0.5:http").find("is not a number"), std::string::npos);
  // ZeroMQ reads a port past 65535 modulo 65536 (99999 listened on 34463): refused, saying why.
  for (const std::string spec : {"127.0.0.1:99999", "lo:65536", "10.0.0.5:0", "tcp://127.0.0.1:99999",
                                 "127.0.0.1:123456789012345678901234567890"}) {
    const std::string text = refusal(spec);
    EXPECT_NE(text.find("is out of range (ports run from 1 to 65535)"), std::string::npos) << spec << ": " << text;
  }
  EXPECT_EQ(manager_bind_endpoint("127.0.0.1:65535"), "tcp://127.0.0.1:65535");
  EXPECT_EQ(manager_bind_endpoint("127.0.0.1:1"), "tcp://127.0.0.1:1");
  const std::string unknown = refusal("nosuch9");
  EXPECT_NE(unknown.find("neither an IPv4 address nor an interface"), std::string::npos) << unknown;
  EXPECT_NE(unknown.find("lo (127.0.0.1)"), std::string::npos) << "the hint lists the interfaces: " << unknown;
}

} // namespace
} // namespace geotandem::runtime
