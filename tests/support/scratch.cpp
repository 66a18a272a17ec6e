#include "scratch.hpp"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include "test_paths.hpp"
#include <cstdio>
#include <fstream>
#include <sstream>

namespace geotandem::testing {
namespace {

std::string slurp(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

} // namespace

ScratchDir::ScratchDir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::string name = info ? std::string(info->test_suite_name()) + "." + info->name() : "scratch";
  for (char& c : name)
    if (c == '/' || c == ' ') c = '_';
  path_ = std::filesystem::path(test_paths::scratch()) / name;
  std::filesystem::remove_all(path_);
  std::filesystem::create_directories(path_);
}

ScratchDir::~ScratchDir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  if (info && info->result() && info->result()->Failed()) return;
  std::error_code ec;
  std::filesystem::remove_all(path_, ec);
}

CommandResult run_geotandem(const std::string& args) {
  static int counter = 0;
  auto base = std::filesystem::path(test_paths::scratch()) /
              ("cmd-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
  std::filesystem::create_directories(base.parent_path());
  std::string command = std::string("\"") + test_paths::binary() + "\" " + args + " >" + base.string() + ".out 2>" +
                        base.string() + ".err </dev/null";
  int status = std::system(command.c_str());
  CommandResult result;
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  result.out = slurp(base.string() + ".out");
  result.err = slurp(base.string() + ".err");
  std::filesystem::remove(base.string() + ".out");
  std::filesystem::remove(base.string() + ".err");
  return result;
}

} // namespace geotandem::testing
