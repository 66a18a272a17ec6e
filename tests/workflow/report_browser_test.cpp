// A real run's report opened in headless Chromium (Debian's chromium, software WebGL): the 3-D
// view draws the bodies (pixels other than the background on its canvas) and a click on a body
// names one of the kept ones. Skipped when no chromium is installed (scripts/setup.sh installs it).

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>

#include "e2e_support.hpp"
#include "geotandem/store/store.hpp"

namespace geotandem {
namespace {

using testing::run_workflow;
using testing::ScratchDir;
using testing::workflow_recipe;

std::string chromium() {
  const char* env = std::getenv("GEOTANDEM_CHROMIUM");
  if (env && *env) return env;
  for (const char* path : {"/usr/bin/chromium", "/usr/bin/chromium-browser"})
    if (std::filesystem::exists(path)) return path;
  return {};
}

// Runs after the page has loaded: counts the canvas pixels that differ from the background,
// then clicks a grid of points until the info line names a body, and writes both into the DOM.
const char* probe = R"(<script>
window.addEventListener('load', function () { setTimeout(function () {
  var c = document.getElementById('gt-view'), r = c.getBoundingClientRect();
  var copy = document.createElement('canvas'); copy.width = c.width; copy.height = c.height;
  var ctx = copy.getContext('2d'); ctx.drawImage(c, 0, 0);
  var px = ctx.getImageData(0, 0, c.width, c.height).data, drawn = 0;
  for (var n = 0; n < px.length; n += 4)
    if (Math.abs(px[n] - 250) + Math.abs(px[n + 1] - 250) + Math.abs(px[n + 2] - 250) > 30) drawn++;
  var clicked = 'none';
  for (var y = 0.1; y < 0.95 && clicked === 'none'; y += 0.04)
    for (var x = 0.1; x < 0.95 && clicked === 'none'; x += 0.04) {
      var cx = r.left + x * r.width, cy = r.top + y * r.height;
      c.dispatchEvent(new PointerEvent('pointerdown', {clientX: cx, clientY: cy, bubbles: true}));
      c.dispatchEvent(new MouseEvent('click', {clientX: cx, clientY: cy, bubbles: true}));
      var m = /body (\d+)/.exec(document.getElementById('gt-info').textContent);
      if (m) clicked = m[1];
    }
  var out = document.createElement('pre'); out.id = 'probe';
  out.textContent = 'PROBE drawn=' + drawn + ' meshes=' + c.getAttribute('data-drawn') + ' clicked=' + clicked;
  document.body.appendChild(out);
}, 300); });
</script></body>)";

TEST(ReportBrowser, ThreeDViewDrawsAndAClickNamesAKeptBody) {
  const std::string browser = chromium();
  if (browser.empty()) GTEST_SKIP() << "no chromium installed (scripts/setup.sh installs it)";
  ScratchDir dir;
  const auto out = dir.path() / "run";
  auto run = run_workflow(workflow_recipe("quickstart.yaml"), out, {"input.synthetic.shape=[96, 96, 80]"});
  ASSERT_EQ(run.command.exit_code, 0) << run.command.err;
  const auto store = store::ComponentStore::open(out / "store");
  const auto kept = store.load_selection("sorted").keys;
  const std::set<std::uint64_t> kept_keys(kept.begin(), kept.end());

  std::ifstream in(out / "report.html");
  std::string html((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto end = html.rfind("</body>");
  ASSERT_NE(end, std::string::npos);
  html.replace(end, 7, probe);
  const auto page = out / "probe.html";
  std::ofstream(page) << html;

  const std::string command = "timeout 180 '" + browser +
                              "' --headless --no-sandbox --use-gl=swiftshader --enable-unsafe-swiftshader "
                              "--window-size=1200,2600 --virtual-time-budget=10000 --dump-dom 'file://" +
                              page.string() + "' 2>/dev/null";
  std::string dom;
  if (FILE* pipe = popen(command.c_str(), "r")) {
    char buffer[65536];
    for (std::size_t got; (got = fread(buffer, 1, sizeof buffer, pipe)) > 0;)
      dom.append(buffer, got);
    pclose(pipe);
  }
  std::smatch m;
  ASSERT_TRUE(std::regex_search(dom, m, std::regex("PROBE drawn=(\\d+) meshes=(\\d+) clicked=(\\w+)")))
      << "the probe did not run; the browser printed " << dom.size() << " bytes";
  EXPECT_GT(std::stoul(m[1].str()), 640u * 480u / 50) << "the canvas is (nearly) blank: the 3-D view is not drawn";
  EXPECT_EQ(std::stoul(m[2].str()), kept.size()) << "one mesh per kept body";
  ASSERT_NE(m[3].str(), "none") << "no click hit a body";
  EXPECT_TRUE(kept_keys.count(std::stoull(m[3].str()))) << "clicked body " << m[3].str() << " is not a kept one";
}

} // namespace
} // namespace geotandem
