// docs/architecture.md names files and functions for a newcomer to open: each must exist. A file
// (a `path` in backticks) must be in the source tree; a function (`name()` or `Class::name()`)
// must be defined or declared there: a qualified one anywhere as Class::name(, an unqualified one
// in a file its paragraph names (anywhere when it names none).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <regex>
#include <set>
#include <sstream>

#include "test_paths.hpp"

namespace {

namespace fs = std::filesystem;

std::string read(const fs::path& path) {
  std::ifstream in(path);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Every C++ source of the project, by path relative to the source root.
std::map<std::string, std::string> sources(const fs::path& root) {
  std::map<std::string, std::string> out;
  for (const char* dir : {"framework", "apps", "plugins", "schedulers", "python/src"})
    for (const auto& entry : fs::recursive_directory_iterator(root / dir)) {
      const auto ext = entry.path().extension();
      if (entry.is_regular_file() && (ext == ".cpp" || ext == ".hpp" || ext == ".h"))
        out[fs::relative(entry.path(), root).string()] = read(entry.path());
    }
  return out;
}

// The paragraphs (and list items) of a Markdown text: the scope in which a function's file is named.
std::vector<std::string> paragraphs(const std::string& text) {
  std::vector<std::string> out(1);
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    const bool item = line.rfind("- ", 0) == 0 || std::regex_search(line, std::regex("^[0-9]+\\. "));
    if (line.empty() || item || line.rfind("|", 0) == 0) out.emplace_back();
    out.back() += line + "\n";
  }
  return out;
}

TEST(ArchitectureDoc, EveryNamedFileAndFunctionExists) {
  const fs::path root = test_paths::source();
  const std::string doc = read(root / "docs/architecture.md");
  ASSERT_FALSE(doc.empty());
  const auto code = sources(root);
  std::set<std::string> file_names;
  for (const auto& [path, text] : code)
    file_names.insert(fs::path(path).filename().string());

  const std::regex token("`([^`]+)`");
  std::size_t files = 0, functions = 0;
  for (const std::string& paragraph : paragraphs(doc)) {
    std::vector<std::string> named_files, named_functions;
    for (std::sregex_iterator it(paragraph.begin(), paragraph.end(), token), end; it != end; ++it) {
      const std::string t = (*it)[1];
      if (t.find_first_of(" <*") != std::string::npos) continue; // a pattern, not a name
      if (t.size() > 2 && t.substr(t.size() - 2) == "()") {
        named_functions.push_back(t.substr(0, t.size() - 2));
      } else if (t.find('/') != std::string::npos) {
        ++files;
        EXPECT_TRUE(fs::exists(root / t)) << "docs/architecture.md names " << t << ", which does not exist";
        if (code.count(t)) named_files.push_back(t);
      } else if (std::regex_match(t, std::regex("[A-Za-z0-9_]+\\.(cpp|hpp|h)"))) {
        ++files;
        EXPECT_TRUE(file_names.count(t)) << "docs/architecture.md names " << t << ", which no source file is";
      }
    }
    for (const std::string& f : named_functions) {
      ++functions;
      bool found = false;
      if (f.find("::") != std::string::npos) {
        for (const auto& [path, text] : code)
          found = found || text.find(f + "(") != std::string::npos;
      } else {
        const std::regex call("(^|[^A-Za-z0-9_])" + f + "\\(");
        if (named_files.empty())
          for (const auto& [path, text] : code)
            found = found || std::regex_search(text, call);
        for (const auto& path : named_files)
          found = found || std::regex_search(code.at(path), call);
      }
      EXPECT_TRUE(found) << "docs/architecture.md names " << f << "() beside "
                         << (named_files.empty() ? std::string("no file") : named_files.front())
                         << ", where it is not defined:\n"
                         << paragraph;
    }
  }
  EXPECT_GT(files, 30u) << "the page names the files it points to";
  EXPECT_GT(functions, 30u) << "and the functions";
}

} // namespace
