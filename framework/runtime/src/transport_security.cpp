// CurveZMQ keys, the ZAP handler and the socket options (transport_security.hpp).
#include "transport_security.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <thread>
#include <vector>

#include "geotandem/core/error.hpp"
#include "zmq_poll.hpp"

namespace geotandem::runtime::detail {

namespace {

namespace fs = std::filesystem;

struct KeyPair {
  std::string public_key, secret_key; // Z85, 40 characters each
};

KeyPair new_key_pair() {
  char pub[41] = {}, sec[41] = {};
  if (zmq_curve_keypair(pub, sec) != 0)
    throw IoError(std::string("cannot make CURVE keys: ") + zmq_strerror(zmq_errno()), {},
                  "this libzmq lacks CURVE (libsodium); install Debian's libzmq5");
  return {pub, sec};
}

// The key directory, made 0700 or checked: never a symbolic link (it is opened with O_NOFOLLOW, so
// a link planted where it goes, e.g. in a shared /tmp, is refused rather than followed), owned by
// this user and closed to everyone else. Returns a descriptor of it; the key files are made
// relative to it, so that nothing is written anywhere else even if the path changes meanwhile.
int open_key_dir(const fs::path& dir) {
  const std::string hint = "remove it (or name another output): the manager makes it, mode 0700, for each run's keys";
  if (::mkdir(dir.c_str(), 0700) != 0 && errno != EEXIST)
    throw IoError("cannot make the key directory: " + std::string(std::strerror(errno)), {.file = dir.string()},
                  "the manager needs a writable output directory");
  const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
  if (fd < 0) {
    const int error = errno;
    struct stat link {};
    if (error == ELOOP || (::lstat(dir.c_str(), &link) == 0 && S_ISLNK(link.st_mode)))
      throw IoError("the key directory is a symbolic link: the run's keys are never written through one",
                    {.file = dir.string()}, hint);
    throw IoError("cannot open the key directory: " + std::string(std::strerror(error)), {.file = dir.string()},
                  error == ENOTDIR ? hint : "the manager needs a writable output directory");
  }
  struct stat st {};
  std::string wrong;
  if (::fstat(fd, &st) != 0)
    wrong = std::strerror(errno);
  else if (st.st_uid != ::geteuid())
    wrong = "it belongs to user id " + std::to_string(st.st_uid) + ", not to this user";
  else if ((st.st_mode & 077) != 0)
    wrong = "its mode is " + std::to_string((st.st_mode >> 6) & 7) + std::to_string((st.st_mode >> 3) & 7) +
            std::to_string(st.st_mode & 7) + " (others may read or change it), not 700";
  if (!wrong.empty()) {
    ::close(fd);
    throw IoError("the key directory cannot be trusted: " + wrong, {.file = dir.string()}, hint);
  }
  return fd;
}

// Made afresh with mode 0600 (never readable by others, even for a moment), inside the checked
// directory: an old file is removed first and a link in its place is neither followed nor kept.
void write_private(int dir, const fs::path& path, const std::string& text) {
  const std::string name = path.filename().string();
  if (::unlinkat(dir, name.c_str(), 0) != 0 && errno != ENOENT) {
    const int error = errno;
    throw IoError("cannot replace the key file: " + std::string(std::strerror(error)), {.file = path.string()},
                  "the manager needs a writable output directory");
  }
  const int fd = ::openat(dir, name.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0600);
  if (fd < 0 || ::fchmod(fd, 0600) != 0 || ::write(fd, text.data(), text.size()) != static_cast<ssize_t>(text.size())) {
    const int error = errno;
    if (fd >= 0) ::close(fd);
    throw IoError("cannot write the key file: " + std::string(std::strerror(error)), {.file = path.string()},
                  "the manager needs a writable output directory");
  }
  ::close(fd);
}

std::string z85_of(const zmq::message_t& key) {
  if (key.size() != 32) return {};
  char text[41] = {};
  zmq_z85_encode(text, static_cast<const std::uint8_t*>(key.data()), 32);
  return text;
}

} // namespace

class ServerSecurity {
public:
  ServerSecurity(zmq::context_t& context, zmq::socket_t& router, std::set<std::string> allowed, std::string key_file,
                 Logger& log)
      : socket_(context, zmq::socket_type::rep), monitor_(context, zmq::socket_type::pair), router_(router.handle()),
        allowed_(std::move(allowed)), key_file_(std::move(key_file)), log_(log) {
    socket_.set(zmq::sockopt::linger, 0);
    socket_.bind("inproc://zeromq.zap.01"); // before the router binds: no handshake goes unchecked
    // A peer without CURVE fails before ZAP is asked: the socket's monitor reports it.
    const std::string monitor =
        "inproc://geotandem-curve-monitor-" + std::to_string(reinterpret_cast<std::uintptr_t>(this));
    if (zmq_socket_monitor(router_, monitor.c_str(),
                           ZMQ_EVENT_HANDSHAKE_FAILED_PROTOCOL | ZMQ_EVENT_HANDSHAKE_FAILED_NO_DETAIL) == 0) {
      monitor_.set(zmq::sockopt::linger, 0);
      monitor_.connect(monitor);
      monitoring_ = true;
    }
    thread_ = std::thread([this] { serve(); });
  }
  ~ServerSecurity() {
    stop_ = true;
    thread_.join();
    if (monitoring_) zmq_socket_monitor(router_, nullptr, 0);
    const char* current = std::getenv(curve_key_variable);
    if (current && key_file_ == current) ::unsetenv(curve_key_variable);
  }
  ServerSecurity(const ServerSecurity&) = delete;
  ServerSecurity& operator=(const ServerSecurity&) = delete;

private:
  // ZAP (RFC 27): version, request id, domain, address, identity, mechanism, credentials...
  void serve() {
    while (!stop_) {
      zmq::pollitem_t items[] = {{socket_.handle(), 0, ZMQ_POLLIN, 0}, {monitor_.handle(), 0, ZMQ_POLLIN, 0}};
      poll_items(items, monitoring_ ? 2 : 1, std::chrono::milliseconds(100));
      if (monitoring_ && (items[1].revents & ZMQ_POLLIN)) handshake_failed();
      if (!(items[0].revents & ZMQ_POLLIN)) continue;
      std::vector<zmq::message_t> frames;
      do {
        zmq::message_t frame;
        if (!socket_.recv(frame, zmq::recv_flags::none)) break;
        const bool more = frame.more();
        frames.push_back(std::move(frame));
        if (!more) break;
      } while (true);
      if (frames.size() < 2) continue;
      const std::string address = frames.size() > 3 ? frames[3].to_string() : "?";
      const std::string mechanism = frames.size() > 5 ? frames[5].to_string() : "";
      const std::string key = mechanism == "CURVE" && frames.size() > 6 ? z85_of(frames[6]) : "";
      const bool ok = !key.empty() && allowed_.count(key) > 0;
      if (!ok && ++refused_ <= 20)
        log_.warning("refused a worker connection from " + address + ": " +
                     (key.empty() ? "it did not use CURVE" : "its CURVE key " + key + " is not this run's") +
                     " (each run makes new keys; a worker needs the key file the manager wrote)");
      socket_.send(zmq::str_buffer("1.0"), zmq::send_flags::sndmore);
      socket_.send(frames[1], zmq::send_flags::sndmore);
      socket_.send(zmq::buffer(std::string(ok ? "200" : "400")), zmq::send_flags::sndmore);
      socket_.send(zmq::buffer(std::string(ok ? "OK" : "unknown key")), zmq::send_flags::sndmore);
      socket_.send(zmq::buffer(std::string(ok ? "worker" : "")), zmq::send_flags::sndmore);
      socket_.send(zmq::str_buffer(""), zmq::send_flags::none);
    }
  }

  // A monitor event: 6 bytes (event, value), then the endpoint.
  void handshake_failed() {
    zmq::message_t event, address;
    if (!monitor_.recv(event, zmq::recv_flags::dontwait)) return;
    if (event.more()) (void)monitor_.recv(address, zmq::recv_flags::none);
    if (++refused_ <= 20)
      log_.warning("refused a worker connection on " + address.to_string() +
                   ": its handshake failed (it did not use CURVE with this run's server key)");
  }

  zmq::socket_t socket_, monitor_;
  void* router_;
  bool monitoring_ = false;
  std::set<std::string> allowed_;
  std::string key_file_;
  Logger& log_;
  std::atomic<bool> stop_{false};
  int refused_ = 0;
  std::thread thread_;
};

bool is_loopback_endpoint(const std::string& endpoint) {
  if (endpoint.rfind("tcp://", 0) != 0) return true; // inproc, ipc: this machine only
  const std::string host = endpoint.substr(6, endpoint.rfind(':') - 6);
  return host.rfind("127.", 0) == 0 || host == "localhost" || host == "[::1]" || host == "::1";
}

std::shared_ptr<ServerSecurity> secure_manager_socket(zmq::context_t& context, zmq::socket_t& router,
                                                      const std::string& bind, const std::string& key_dir,
                                                      Logger& log) {
  const KeyPair server = new_key_pair(), worker = new_key_pair();
  const fs::path dir = fs::absolute(fs::path(key_dir));
  const int dir_fd = open_key_dir(dir);
  const fs::path worker_file = dir / "worker.key";
  try {
    write_private(dir_fd, dir / "manager.key", "public " + server.public_key + "\nsecret " + server.secret_key + "\n");
    write_private(dir_fd, worker_file,
                  "server " + server.public_key + "\npublic " + worker.public_key + "\nsecret " + worker.secret_key +
                      "\n");
  } catch (...) {
    ::close(dir_fd);
    throw;
  }
  ::close(dir_fd);
  auto security = std::make_shared<ServerSecurity>(context, router, std::set<std::string>{worker.public_key},
                                                   worker_file.string(), log);
  router.set(zmq::sockopt::zap_domain, "geotandem");
  router.set(zmq::sockopt::curve_server, 1);
  router.set(zmq::sockopt::curve_secretkey, server.secret_key);
  ::setenv(curve_key_variable, worker_file.c_str(), 1); // inherited by the workers
  if (is_loopback_endpoint(bind))
    log.debug("listening on " + bind + ": CurveZMQ is on, with this run's keys in " + dir.string());
  else
    log.info("listening on " + bind + " (not loopback): CurveZMQ is on, with this run's keys in " + dir.string());
  return security;
}

namespace {
// The worker's keys from GEOTANDEM_CURVE_KEY_FILE: empty when it is not set. Such a worker
// connects without CURVE and is refused by the manager, which logs it: every run is authenticated.
std::map<std::string, std::string> worker_keys() {
  const char* file = std::getenv(curve_key_variable);
  if (!file || !*file) return {};
  std::ifstream in(file);
  std::map<std::string, std::string> keys;
  std::string name, value;
  while (in >> name >> value)
    keys[name] = value;
  for (const char* k : {"server", "public", "secret"})
    if (keys[k].size() != 40)
      throw IoError(std::string("the CURVE key file has no valid '") + k + "' key" +
                        (!fs::exists(file) ? " (it does not exist here)" : ""),
                    {.file = file},
                    "the manager writes it for each run next to its store; is that directory shared with this node?");
  return keys;
}
} // namespace

void check_worker_keys() {
  (void)worker_keys();
}

void secure_worker_socket(zmq::socket_t& dealer) noexcept {
  try {
    auto keys = worker_keys();
    if (keys.empty()) return;
    dealer.set(zmq::sockopt::curve_serverkey, keys["server"]);
    dealer.set(zmq::sockopt::curve_publickey, keys["public"]);
    dealer.set(zmq::sockopt::curve_secretkey, keys["secret"]);
  } catch (const std::exception&) {
    // check_worker_keys() reported it before the I/O thread started; without keys the manager
    // refuses this worker, which then stops when the manager stays silent.
  }
}

} // namespace geotandem::runtime::detail
