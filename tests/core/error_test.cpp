#include <gtest/gtest.h>

#include <string>
#include <utility>

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

// Each kind keeps its exit code, context and hint; the note ends the message; a cancel stays one.
TEST(Error, ANoteKeepsTheKindContextAndHint) {
  const auto noted = [](const Error& e) -> std::pair<int, std::string> {
    try {
      throw_with_note(e, "; in step 'x'");
    } catch (const Cancelled& c) {
      return {-c.exit_code(), c.what()};
    } catch (const Error& thrown) {
      return {thrown.exit_code(), thrown.what()};
    }
  };
  const ErrorContext where{"out/a.ply", {}, {}, {}, "w2"};
  EXPECT_EQ(noted(InvalidArgument("bad", where, "fix it")),
            std::make_pair(2, std::string("out/a.ply, worker w2: bad; in step 'x' (fix it)")));
  EXPECT_EQ(noted(IoError("gone", where)).first, 3);
  EXPECT_EQ(noted(FormatError("odd")), std::make_pair(4, std::string("odd; in step 'x'")));
  EXPECT_EQ(noted(DataError("nan")).first, 5);
  EXPECT_EQ(noted(Error("plain")), std::make_pair(1, std::string("plain; in step 'x'")));
  EXPECT_EQ(noted(Cancelled()), std::make_pair(-130, std::string(Cancelled().what())));
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
