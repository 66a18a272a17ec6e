#include "flying_edges/child_and_ply.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

extern char** environ;

namespace geotandem::bench {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

Timing run_child(const std::vector<std::string>& argv, const fs::path& out, const fs::path& err) {
  std::vector<char*> args;
  for (const std::string& a : argv)
    args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&actions, 2, err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  const auto start = Clock::now();
  pid_t pid = 0;
  const int spawned = posix_spawn(&pid, args[0], &actions, nullptr, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawned != 0) throw std::runtime_error("cannot start " + argv[0] + ": " + std::strerror(spawned));
  int status = 0;
  rusage usage{};
  if (wait4(pid, &status, 0, &usage) != pid) throw std::runtime_error("wait4 failed for " + argv[0]);
  Timing t;
  t.wall = std::chrono::duration<double>(Clock::now() - start).count();
  auto tv = [](const timeval& v) { return static_cast<double>(v.tv_sec) + 1e-6 * static_cast<double>(v.tv_usec); };
  t.cpu = tv(usage.ru_utime) + tv(usage.ru_stime);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    std::ifstream in(err);
    std::stringstream text;
    text << in.rdbuf();
    std::string s = text.str();
    if (s.size() > 2000) s = s.substr(s.size() - 2000);
    std::string command;
    for (const std::string& a : argv)
      command += (command.empty() ? "" : " ") + a;
    throw std::runtime_error(command + " failed (status " + std::to_string(status) + "):\n" + s);
  }
  return t;
}

std::string read_text(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

Surface read_ply(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot open " + path.string());
  auto size_of = [&](const std::string& type) -> std::size_t {
    if (type == "char" || type == "uchar" || type == "int8" || type == "uint8") return 1;
    if (type == "short" || type == "ushort" || type == "int16" || type == "uint16") return 2;
    if (type == "int" || type == "uint" || type == "float" || type == "int32" || type == "uint32" || type == "float32")
      return 4;
    if (type == "double" || type == "float64") return 8;
    throw std::runtime_error(path.string() + ": PLY property type '" + type + "' not handled");
  };
  struct Property {
    std::string name, type, count_type; // count_type set for a list
  };
  std::vector<Property> vertex_props, face_props;
  std::size_t vertices = 0, faces = 0;
  std::string line, element;
  std::getline(in, line);
  if (line != "ply") throw std::runtime_error(path.string() + " is not a PLY file");
  while (std::getline(in, line) && line != "end_header") {
    std::istringstream words(line);
    std::string key;
    words >> key;
    if (key == "format") {
      std::string f;
      words >> f;
      if (f != "binary_little_endian") throw std::runtime_error(path.string() + ": PLY format " + f + " not handled");
    } else if (key == "element") {
      std::size_t n = 0;
      words >> element >> n;
      (element == "vertex" ? vertices : faces) = n;
    } else if (key == "property") {
      Property p;
      words >> p.type;
      if (p.type == "list") words >> p.count_type >> p.type;
      words >> p.name;
      (element == "vertex" ? vertex_props : face_props).push_back(p);
    }
  }
  Surface s;
  s.xyz.resize(3 * vertices);
  std::vector<char> record;
  for (std::size_t v = 0; v < vertices; ++v)
    for (const Property& p : vertex_props) {
      const std::size_t n = size_of(p.type);
      record.resize(n);
      in.read(record.data(), static_cast<std::streamsize>(n));
      const int axis = p.name == "x" ? 0 : p.name == "y" ? 1 : p.name == "z" ? 2 : -1;
      if (axis < 0) continue;
      double value = 0.0;
      if (n == 8) {
        std::memcpy(&value, record.data(), 8);
      } else if (p.type == "float" || p.type == "float32") {
        float f = 0.0f;
        std::memcpy(&f, record.data(), 4);
        value = f;
      } else {
        throw std::runtime_error(path.string() + ": vertex coordinate of type " + p.type + " not handled");
      }
      s.xyz[3 * v + static_cast<std::size_t>(axis)] = static_cast<float>(value);
    }
  s.corners.reserve(3 * faces);
  for (std::size_t f = 0; f < faces; ++f)
    for (const Property& p : face_props) {
      if (p.count_type.empty()) {
        in.ignore(static_cast<std::streamsize>(size_of(p.type)));
        continue;
      }
      std::uint32_t count = 0;
      in.read(reinterpret_cast<char*>(&count), static_cast<std::streamsize>(size_of(p.count_type)));
      if (count != 3 || size_of(p.type) != 4)
        throw std::runtime_error(path.string() + ": a face that is not a triangle of 32-bit indices");
      std::uint32_t c[3];
      in.read(reinterpret_cast<char*>(c), sizeof c);
      for (std::uint32_t x : c) {
        if (x >= vertices) throw std::runtime_error(path.string() + ": a face index out of range");
        s.corners.push_back(x);
      }
    }
  if (!in) throw std::runtime_error(path.string() + " ends early");
  return s;
}

} // namespace geotandem::bench
