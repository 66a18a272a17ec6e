#pragma once
// Where the tests find the build and source trees. The absolute paths are compiled into
// test_paths.cpp alone, so that no other test file carries one on its command line: a build in
// another checkout of the same commit then reuses the compile cache for all of them (see
// GEOTANDEM_CCACHE in the top CMakeLists.txt).

#include <string>

namespace test_paths {

std::string binary();             // the geotandem executable under test
std::string source();             // the source tree
std::string workflows();          // the recipes in the source tree (workflows/)
std::string scratch();            // the root of the tests' scratch directories
std::string plugins();            // the test plugins built under tests/workflow
std::string lsf_standin();        // tests/schedulers/lsf-standin: bsub, bjobs and bkill stand-ins
std::string hang_simulator();     // tests/schedulers/hang-simulator: scheduler commands that hang
std::string store_crash_writer(); // the helper that store_crash_test kills mid-write

} // namespace test_paths
