#pragma once
// Small command-line helpers shared by the benchmarks: positional arguments read with a check, so
// that `--help` prints the usage and a value that is not a number is refused with it (exit 2)
// instead of running on 0 or ending in std::terminate, and a main whose errors are printed (exit 1).

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace geotandem::bench {

// "a,b,c" -> {"a", "b", "c"}.
inline std::vector<std::string> split(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ','))
    out.push_back(item);
  return out;
}

// `text` as a whole number of at least `min`, into `out`; false when it is not one.
inline bool to_integer(const std::string& text, std::int64_t min, std::int64_t& out) {
  char* end = nullptr;
  errno = 0;
  const long long v = std::strtoll(text.c_str(), &end, 10);
  if (text.empty() || *end != '\0' || errno != 0 || v < min) return false;
  out = v;
  return true;
}

// The positional arguments argv[1..]. `usage` is the line after "usage: " ("bench_x [n=256] ...").
class Args {
public:
  Args(int argc, char** argv, std::string usage) : usage_(std::move(usage)) {
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      if (a == "-h" || a == "--help") {
        std::printf("usage: %s\n", usage_.c_str());
        std::exit(0);
      }
      values_.push_back(a);
    }
  }

  std::size_t size() const { return values_.size(); }
  bool has(std::size_t i) const { return i >= 1 && i <= values_.size(); }
  std::string text(std::size_t i, const std::string& fallback) const { return has(i) ? values_[i - 1] : fallback; }
  // A whole number of at least `min`.
  std::int64_t integer(std::size_t i, std::int64_t fallback, std::int64_t min) const {
    if (!has(i)) return fallback;
    std::int64_t v = 0;
    if (!to_integer(values_[i - 1], min, v)) fail(i, "is not a whole number of at least " + std::to_string(min));
    return v;
  }
  // A number of at least `min`.
  double real(std::size_t i, double fallback, double min) const {
    return has(i) ? to_real(i, values_[i - 1], min) : fallback;
  }
  // A comma-separated list of numbers of at least `min`.
  std::vector<double> reals(std::size_t i, const std::string& fallback, double min) const {
    std::vector<double> out;
    for (const std::string& item : split(text(i, fallback)))
      out.push_back(to_real(i, item, min));
    if (out.empty()) fail(i, "is an empty list");
    return out;
  }
  // A comma-separated list of whole numbers of at least `min`.
  std::vector<std::int64_t> integers(std::size_t i, const std::string& fallback, std::int64_t min) const {
    std::vector<std::int64_t> out;
    for (const std::string& item : split(text(i, fallback)))
      if (std::int64_t v = 0; to_integer(item, min, v))
        out.push_back(v);
      else
        fail(i, "is not a list of whole numbers of at least " + std::to_string(min));
    if (out.empty()) fail(i, "is an empty list");
    return out;
  }
  // One word of `allowed`.
  std::string word(std::size_t i, const std::string& fallback, const std::vector<std::string>& allowed) const {
    const std::string w = text(i, fallback);
    check_word(i, w, allowed);
    return w;
  }
  // A comma-separated list of words, each one of `allowed`.
  std::vector<std::string> words(std::size_t i, const std::string& fallback,
                                 const std::vector<std::string>& allowed) const {
    std::vector<std::string> out = split(text(i, fallback));
    for (const std::string& w : out)
      check_word(i, w, allowed);
    if (out.empty()) fail(i, "is an empty list");
    return out;
  }
  [[noreturn]] void fail(std::size_t i, const std::string& why) const {
    const std::string name = usage_.substr(0, usage_.find(' ')); // the usage starts with it
    const std::string what = has(i) ? " ('" + values_[i - 1] + "')" : "";
    std::fprintf(stderr, "%s: argument %zu%s %s\nusage: %s\n", name.c_str(), i, what.c_str(), why.c_str(),
                 usage_.c_str());
    std::exit(2);
  }

private:
  double to_real(std::size_t i, const std::string& s, double min) const {
    char* end = nullptr;
    const double v = std::strtod(s.c_str(), &end);
    if (s.empty() || *end != '\0' || !(v >= min)) fail(i, "is not a number of at least " + shortest(min));
    return v;
  }

  void check_word(std::size_t i, const std::string& w, const std::vector<std::string>& allowed) const {
    if (std::find(allowed.begin(), allowed.end(), w) != allowed.end()) return;
    std::string choices;
    for (const std::string& a : allowed)
      choices += (choices.empty() ? "" : ", ") + a;
    fail(i, "names '" + w + "': the choices are " + choices);
  }

  static std::string shortest(double v) {
    std::ostringstream out;
    out << v;
    return out.str();
  }

  std::string usage_;
  std::vector<std::string> values_;
};

// Runs a benchmark's body: an error it throws is printed, with exit status 1, instead of ending in
// std::terminate.
template <class Body> int guarded_main(const char* name, Body body) {
  try {
    return body();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", name, e.what());
    return 1;
  }
}

} // namespace geotandem::bench
