#include <gtest/gtest.h>

#include "geotandem/core/cancel.hpp"
#include "geotandem/core/error.hpp"
#include "geotandem/core/log.hpp"

using namespace geotandem;

TEST(Error, MessageNamesFileLineColumnAndHint) {
  InvalidArgument e("unknown key 'isovalue'", {"recipe.yaml", 12, 5, {}, {}}, "did you mean 'iso'?");
  EXPECT_EQ(std::string(e.what()), "recipe.yaml:12:5: unknown key 'isovalue' (did you mean 'iso'?)");
  EXPECT_EQ(e.exit_code(), 2);
  EXPECT_EQ(e.message(), "unknown key 'isovalue'");
}

TEST(Error, BlockAndWorkerContext) {
  IoError e("read failed", {"cube.nc", {}, {}, "block 3", "w7"});
  EXPECT_EQ(std::string(e.what()), "cube.nc, block 3, worker w7: read failed");
}

TEST(Error, MessageWithoutContextIsBare) {
  FormatError e("bad");
  EXPECT_EQ(std::string(e.what()), "bad");
}

TEST(CancelToken, CopiesShareTheFlag) {
  CancelToken token;
  CancelToken copy = token;
  EXPECT_NO_THROW(copy.throw_if_cancelled());
  token.cancel();
  EXPECT_TRUE(copy.cancelled());
  EXPECT_THROW(copy.throw_if_cancelled(), Cancelled);
}

TEST(Logger, FiltersByLevel) {
  std::ostringstream out;
  Logger log(out, LogLevel::warning);
  log.info("hidden");
  log.warning("shown");
  EXPECT_EQ(out.str(), "geotandem: warning: shown\n");
  EXPECT_THROW(parse_log_level("loud"), InvalidArgument);
}
