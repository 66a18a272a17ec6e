// The plugin loader against real shared libraries built by this test's CMakeLists.

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "geotandem/core/error.hpp"
#include "geotandem/volume/volume.hpp"
#include "geotandem/workflow/registry.hpp"
#include "scratch.hpp"
#include "test_paths.hpp"

using namespace geotandem;
using namespace geotandem::workflow;
using geotandem::testing::ScratchDir;

namespace {

std::string plugin_file(const std::string& name) {
  return test_paths::plugins() + "/" + name + "/geotandem_" + name + ".so";
}

std::shared_ptr<volume::MemoryVolume> ramp(volume::Index3 shape) {
  volume::Geometry g;
  g.shape = shape;
  std::vector<float> v(g.sample_count());
  for (std::size_t n = 0; n < v.size(); ++n)
    v[n] = static_cast<float>(std::sin(0.37 * double(n)) + 0.001 * double(n));
  return std::make_shared<volume::MemoryVolume>(g, std::move(v));
}

ParamValues defaults(const Plugin& p) {
  ParamValues values;
  for (const auto& spec : p.params())
    values[spec.name] = parse_param(spec, spec.default_value.value());
  return values;
}

} // namespace

TEST(PluginLoader, LoadsDescriptorAndParameters) {
  PluginRegistry registry;
  registry.load_library(plugin_file("boxsum"));
  const Plugin& p = registry.get("boxsum");
  EXPECT_EQ(p.origin(), plugin_file("boxsum"));
  ASSERT_EQ(p.params().size(), 2u);
  EXPECT_EQ(p.params()[0].name, "factor");
  EXPECT_EQ(p.params()[0].type, ParamType::real);
  EXPECT_EQ(p.params()[0].max_value.value(), 100.0);
  EXPECT_EQ(p.params()[1].choices, (std::vector<std::string>{"fast", "exact"}));
}

TEST(PluginLoader, AttributeBoxEqualsWholeCubeComputation) {
  PluginRegistry registry;
  registry.load_library(plugin_file("boxsum"));
  auto input = ramp({9, 7, 11});
  auto values = defaults(registry.get("boxsum"));
  values["factor"] = parse_param(registry.get("boxsum").params()[0], "0.5");
  auto attribute = registry.get("boxsum").make_attribute(input, values);
  auto whole = attribute->read(attribute->geometry().bounds());
  // Independent oracle: the neighbourhood sum computed here directly.
  const auto& all = input->samples();
  auto at = [&](long i, long j, long k) { return all[(std::size_t(i) * 7 + std::size_t(j)) * 11 + std::size_t(k)]; };
  for (long i = 0; i < 9; i += 4)
    for (long j = 0; j < 7; j += 3)
      for (long k = 0; k < 11; k += 5) {
        double sum = 0;
        for (long a = std::max(0l, i - 1); a <= std::min(8l, i + 1); ++a)
          for (long b = std::max(0l, j - 1); b <= std::min(6l, j + 1); ++b)
            for (long c = std::max(0l, k - 1); c <= std::min(10l, k + 1); ++c)
              sum += at(a, b, c);
        EXPECT_NEAR(whole[(std::size_t(i) * 7 + std::size_t(j)) * 11 + std::size_t(k)], 0.5 * sum, 1e-4);
      }
  for (volume::Box box :
       {volume::Box{{0, 0, 0}, {3, 4, 5}}, volume::Box{{4, 2, 3}, {9, 7, 11}}, volume::Box{{2, 1, 6}, {5, 6, 8}}}) {
    auto part = attribute->read(box);
    std::vector<float> cut(box.count());
    volume::copy_region(whole.data(), attribute->geometry().bounds(), cut.data(), box, box);
    EXPECT_EQ(part, cut) << box.to_string();
  }
}

TEST(PluginLoader, RefusesOtherInterfaceVersionNamingBoth) {
  PluginRegistry registry;
  try {
    registry.load_library(plugin_file("oldabi"));
    FAIL() << "a plugin of another major version was accepted";
  } catch (const FormatError& e) {
    std::string what = e.what();
    EXPECT_NE(what.find(plugin_file("oldabi")), std::string::npos) << what;
    EXPECT_NE(what.find("version " + std::to_string(GEOTANDEM_PLUGIN_ABI_MAJOR + 1) + "."), std::string::npos) << what;
    EXPECT_NE(what.find("implements version " + std::to_string(GEOTANDEM_PLUGIN_ABI_MAJOR) + "."), std::string::npos)
        << what;
  }
  EXPECT_EQ(registry.find("oldabi"), nullptr);
}

TEST(PluginLoader, MissingEntryPointIsAClearError) {
  PluginRegistry registry;
  try {
    registry.load_library(plugin_file("noentry"));
    FAIL() << "a library without entry point was accepted";
  } catch (const FormatError& e) {
    std::string what = e.what();
    EXPECT_NE(what.find("geotandem_plugin_entry"), std::string::npos) << what;
    EXPECT_NE(what.find(plugin_file("noentry")), std::string::npos) << what;
  }
}

TEST(PluginLoader, NotALibraryIsAClearError) {
  PluginRegistry registry;
  // A missing file cannot be read (exit 3); a file that is no ELF library is a format error (exit 4).
  EXPECT_THROW(registry.load_library(test_paths::plugins() + "/nonexistent/geotandem_x.so"), IoError);
  ScratchDir dir;
  const std::string text = dir.file("geotandem_text.so");
  std::ofstream(text) << std::string(4096, 'x');
  try {
    registry.load_library(text);
    FAIL() << "a text file loaded as a plugin";
  } catch (const FormatError& e) {
    EXPECT_NE(std::string(e.what()).find(text + ": not an ELF file"), std::string::npos) << e.what();
  }
}

TEST(PluginLoader, PluginFailureCarriesItsMessage) {
  PluginRegistry registry;
  registry.load_library(plugin_file("failing"));
  auto attribute = registry.get("failing").make_attribute(ramp({4, 4, 4}), defaults(registry.get("failing")));
  try {
    attribute->read(volume::Box{{2, 0, 0}, {4, 4, 4}});
    FAIL() << "a failing plugin reported success";
  } catch (const DataError& e) {
    std::string what = e.what();
    EXPECT_NE(what.find("refusing box starting at inline 2"), std::string::npos) << what;
    EXPECT_NE(what.find("failing"), std::string::npos) << what;
  }
}

TEST(PluginLoader, DiscoverySkipsBrokenLibrariesAndExplainsThemOnUse) {
  PluginRegistry registry;
  std::ostringstream log_text;
  Logger log(log_text, LogLevel::warning);
  std::string dir = test_paths::plugins();
  registry.discover(dir + "/boxsum:" + dir + "/oldabi:" + dir + "/does-not-exist", log);
  EXPECT_NE(registry.find("boxsum"), nullptr);
  EXPECT_NE(log_text.str().find("oldabi"), std::string::npos) << log_text.str();
  try {
    registry.get("oldabi");
    FAIL();
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("failed to load"), std::string::npos) << e.what();
  }
}

TEST(PluginLoader, DuplicateNamesAreRefused) {
  PluginRegistry registry;
  registry.load_library(plugin_file("boxsum"));
  EXPECT_THROW(registry.load_library(plugin_file("boxsum")), InvalidArgument);
}

TEST(PluginParams, TypeAndRangeErrorsNameTheParameter) {
  ParamSpec spec{"sigma", ParamType::real, "1", "smoothing in samples", 0.1, 10.0, {}};
  EXPECT_DOUBLE_EQ(parse_param(spec, "2.5").real, 2.5);
  try {
    parse_param(spec, "20");
    FAIL();
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("'sigma' is 20"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("between 0.1 and 10"), std::string::npos) << e.what();
  }
  EXPECT_THROW(parse_param(spec, "two"), InvalidArgument);
  ParamSpec mode{"mode", ParamType::choice, "a", "", {}, {}, {"planarity", "marfurt"}};
  try {
    parse_param(mode, "marfut");
    FAIL();
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("did you mean 'marfurt'"), std::string::npos) << e.what();
  }
}
