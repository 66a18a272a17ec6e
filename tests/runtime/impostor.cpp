// runtime_impostor MANAGER_PID SECONDS: a stranger on the machine, for impostor_test.cpp. It does
// what any local user can: reads the command lines of the manager's workers in /proc (their launch
// token and the manager's endpoint), connects under each token (and under the next tokens, which
// a replacement would get) racing the real worker, says HELLO, and answers every task with a
// forged DONE ("surface empty"). Started as root, it first becomes the user nobody, so that it
// reads nothing the run's user keeps to themself. It prints what it saw and what it got:
//   "saw worker PID token T endpoint E", "got SETUP as T" (it joined the run), "forged DONE as T".
#include <grp.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>
#include <zmq.hpp>

#include "geotandem/runtime/protocol.hpp"

namespace {

using namespace geotandem::runtime;
using Clock = std::chrono::steady_clock;

// The parent of `pid` from /proc/PID/stat; -1 when it is gone.
long parent_of(const std::string& pid) {
  std::ifstream in("/proc/" + pid + "/stat");
  std::string text((std::istreambuf_iterator<char>(in)), {});
  const auto close = text.rfind(')');
  if (close == std::string::npos) return -1;
  std::istringstream rest(text.substr(close + 2));
  char state = 0;
  long ppid = -1;
  rest >> state >> ppid;
  return state == 'Z' ? -1 : ppid;
}

std::vector<std::string> cmdline_of(const std::string& pid) {
  std::ifstream in("/proc/" + pid + "/cmdline");
  std::vector<std::string> args;
  std::string arg;
  while (std::getline(in, arg, '\0'))
    args.push_back(arg);
  return args;
}

struct Peer {
  std::string token;
  bool answers = true; // false: says HELLO, then nothing (a worker that went silent)
  zmq::socket_t socket;
};

void send(Peer& p, const Message& m) {
  const std::vector<std::byte> bytes = encode(m);
  (void)p.socket.send(zmq::buffer(bytes.data(), bytes.size()), zmq::send_flags::dontwait);
}

std::unique_ptr<Peer> connect_as(zmq::context_t& context, const std::string& token, const std::string& endpoint,
                                 bool answers) {
  auto p = std::make_unique<Peer>(Peer{token, answers, zmq::socket_t(context, zmq::socket_type::dealer)});
  p->socket.set(zmq::sockopt::linger, 0);
  p->socket.set(zmq::sockopt::routing_id, token);
  p->socket.connect(endpoint);
  Message hello;
  hello.kind = MessageKind::hello;
  hello.text = token;
  hello.number = static_cast<std::uint64_t>(getpid());
  send(*p, hello);
  return p;
}

// What a forger answers to each message: ASK after SETUP and WAIT, DONE with an empty surface to
// every task.
void answer(Peer& p, const Message& m) {
  std::printf("got %s as %s\n", to_string(m.kind), p.token.c_str());
  Message r;
  switch (m.kind) {
  case MessageKind::setup:
  case MessageKind::wait: r.kind = MessageKind::ask; break;
  case MessageKind::extract:
  case MessageKind::merge:
  case MessageKind::finished:
    r.kind = MessageKind::done;
    r.lease = m.lease;
    r.box[1] = 1; // "my surface is empty": its leaves would be recorded finished
    std::printf("forged DONE as %s\n", p.token.c_str());
    break;
  default: return;
  }
  if (p.answers) send(p, r);
}

} // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: runtime_impostor MANAGER_PID SECONDS\n");
    return 2;
  }
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  const std::string manager = argv[1];
  const auto until = Clock::now() + std::chrono::duration<double>(std::atof(argv[2]));
  if (::geteuid() == 0 && (::setgroups(0, nullptr) != 0 || ::setgid(65534) != 0 || ::setuid(65534) != 0)) {
    std::perror("cannot become nobody");
    return 1;
  }
  std::printf("running as uid %d\n", static_cast<int>(::geteuid()));
  zmq::context_t context(1);
  std::vector<std::unique_ptr<Peer>> peers;
  std::set<std::string> seen, tokens;
  auto beat = Clock::now();
  while (Clock::now() < until && parent_of(manager) >= 0) {
    for (const auto& entry : std::filesystem::directory_iterator("/proc")) {
      const std::string pid = entry.path().filename().string();
      if (pid.find_first_not_of("0123456789") != std::string::npos || seen.count(pid)) continue;
      if (std::to_string(parent_of(pid)) != manager) continue;
      const std::vector<std::string> args = cmdline_of(pid); // the manager's own until the exec
      std::string token, endpoint;
      for (std::size_t i = 0; i + 1 < args.size(); ++i) {
        if (args[i] == "--token") token = args[i + 1];
        if (args[i] == "--connect") endpoint = args[i + 1];
      }
      if (token.empty() || endpoint.empty()) continue;
      seen.insert(pid);
      std::printf("saw worker %s token %s endpoint %s\n", pid.c_str(), token.c_str(), endpoint.c_str());
      if (tokens.insert(token).second) peers.push_back(connect_as(context, token, endpoint, true));
      // The tokens of the replacements to come: the same prefix, the next numbers. Taken first and
      // left silent, each would be found dead and replaced, until the replacements run out.
      const auto dash = token.rfind('-');
      if (dash == std::string::npos) continue;
      const long n = std::strtol(token.c_str() + dash + 1, nullptr, 10);
      for (long k = n + 1; k <= n + 3; ++k) {
        const std::string next = token.substr(0, dash + 1) + std::to_string(k);
        if (tokens.insert(next).second) peers.push_back(connect_as(context, next, endpoint, false));
      }
    }
    std::vector<zmq::pollitem_t> items;
    for (auto& p : peers)
      items.push_back({p->socket.handle(), 0, ZMQ_POLLIN, 0});
    if (items.empty()) {
      std::this_thread::sleep_for(std::chrono::microseconds(300));
      continue;
    }
    zmq::poll(items.data(), items.size(), std::chrono::milliseconds(2));
    for (std::size_t i = 0; i < items.size(); ++i) {
      if (!(items[i].revents & ZMQ_POLLIN)) continue;
      zmq::message_t frame;
      while (peers[i]->socket.recv(frame, zmq::recv_flags::dontwait)) {
        try {
          answer(*peers[i], decode(std::span(static_cast<const std::byte*>(frame.data()), frame.size())));
        } catch (const std::exception& e) {
          std::printf("undecodable message as %s: %s\n", peers[i]->token.c_str(), e.what());
        }
      }
    }
    if (Clock::now() - beat > std::chrono::milliseconds(300)) { // a live worker, as far as heartbeats go
      Message h;
      h.kind = MessageKind::heartbeat;
      for (auto& p : peers)
        if (p->answers) send(*p, h);
      beat = Clock::now();
    }
  }
  std::printf("impostor done: %zu tokens tried\n", tokens.size());
  // Out without tearing the sockets down: with their peer gone mid-handshake, libzmq 4.3.4 aborted
  // here once (an assertion in its teardown), which is no part of what this stranger tests.
  std::fflush(stdout);
  std::_Exit(0);
}
