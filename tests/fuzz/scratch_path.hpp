#pragma once
// A fuzz target's scratch file in /tmp, named after the process (parallel runs do not share it) and
// removed when the process ends normally: the mutation driver returns from main and libFuzzer
// calls exit(), both of which run this destructor. (Before, every run left its files behind.)
#include <unistd.h>

#include <cstdio>
#include <string>

class ScratchPath {
public:
  explicit ScratchPath(const std::string& suffix)
      : path_("/tmp/geotandem-fuzz-" + std::to_string(::getpid()) + suffix) {}
  ~ScratchPath() { std::remove(path_.c_str()); }
  ScratchPath(const ScratchPath&) = delete;
  ScratchPath& operator=(const ScratchPath&) = delete;

  const std::string& str() const { return path_; }

private:
  std::string path_;
};
