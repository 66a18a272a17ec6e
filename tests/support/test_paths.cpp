#include "test_paths.hpp"

namespace test_paths {

std::string binary() {
  return GEOTANDEM_TEST_BINARY;
}
std::string source() {
  return GEOTANDEM_TEST_SOURCE_DIR;
}
std::string workflows() {
  return source() + "/workflows";
}
std::string scratch() {
  return GEOTANDEM_TEST_SCRATCH;
}
std::string plugins() {
  return GEOTANDEM_TEST_PLUGIN_DIR;
}
std::string lsf_standin() {
  return source() + "/tests/schedulers/lsf-standin";
}
std::string hang_simulator() {
  return source() + "/tests/schedulers/hang-simulator";
}
std::string store_crash_writer() {
  return GEOTANDEM_TEST_STORE_CRASH_WRITER;
}

} // namespace test_paths
