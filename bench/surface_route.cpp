// bench_surface_route: the two routes a partial surface can take from the worker that SENDs it to
// the worker that MERGEs it, measured with the runtime's own messages (protocol.hpp) over TCP on
// this machine, each party its own process:
//   direct: sender DEALER -> receiver ROUTER, chunks under the receiver's credits;
//   relay:  sender DEALER -> manager ROUTER, which keeps the whole surface (checked against its
//           size and XXH64) and then feeds it to the receiver's DEALER under its credits; this is
//           what the runtime does (surface_relay.cpp).
// Prints per surface size: wall time per surface, throughput, and the CPU seconds each process
// spent (the manager's is what the relay costs the run).
//   bench_surface_route [MiB=1,4,16] [surfaces=16]
// Not a test: figures only.
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <optional>
#include <random>
#include <string>
#include <vector>
#include <zmq.hpp>

#include "bench_args.hpp"
#include "geotandem/runtime/protocol.hpp"
#include "geotandem/runtime/surface_chunks.hpp"

using namespace geotandem::runtime;
using Clock = std::chrono::steady_clock;

namespace {

void send(zmq::socket_t& s, const Message& m, const std::string* to = nullptr) {
  const std::vector<std::byte> bytes = encode(m);
  if (to) s.send(zmq::buffer(*to), zmq::send_flags::sndmore);
  s.send(zmq::buffer(bytes), zmq::send_flags::none);
}

// The next message (and, on a ROUTER, who sent it).
Message receive(zmq::socket_t& s, std::string* from = nullptr) {
  zmq::message_t part;
  if (from) {
    (void)s.recv(part);
    *from = part.to_string();
  }
  (void)s.recv(part);
  return decode(std::span(static_cast<const std::byte*>(part.data()), part.size()));
}

std::vector<std::byte> make_surface(std::size_t bytes, unsigned seed) {
  std::vector<std::byte> out(bytes);
  std::mt19937_64 random(seed);
  for (std::size_t i = 0; i + 8 <= bytes; i += 8) {
    const std::uint64_t v = random();
    std::memcpy(out.data() + i, &v, 8);
  }
  return out;
}

// Sends `record` as a SEND does: chunks at most kChunkWindow ahead of the credits, then its size
// and checksum.
void send_surface(zmq::socket_t& s, const std::vector<std::byte>& record, const std::string* to, MessageKind chunk_kind,
                  MessageKind credit_kind, std::string* credit_from = nullptr) {
  std::size_t ahead = 0;
  std::uint64_t offset = 0;
  for (std::span<const std::byte> piece : cut_into_chunks(record)) {
    while (ahead >= kChunkWindow) {
      const Message c = receive(s, credit_from);
      if (c.kind == credit_kind) ahead -= std::min<std::size_t>(ahead, c.number);
    }
    Message m;
    m.kind = chunk_kind;
    m.number = offset;
    m.bytes.assign(piece.begin(), piece.end());
    send(s, m, to);
    offset += piece.size();
    ++ahead;
  }
  if (chunk_kind == MessageKind::surface_chunk) {
    Message end;
    end.kind = MessageKind::surface;
    end.number = record.size();
    end.box[0] = static_cast<std::int64_t>(surface_checksum(record));
    send(s, end, to);
  }
}

// Receives one surface of `total` bytes (chunks, each answered with a credit) and checks it.
std::vector<std::byte> receive_surface(zmq::socket_t& s, std::uint64_t total, std::uint64_t checksum,
                                       MessageKind chunk_kind, MessageKind credit_kind, bool router) {
  SurfaceAssembler in(kDefaultMaxSurface, total);
  std::string from;
  while (!in.complete() && !in.broken()) {
    const Message c = receive(s, router ? &from : nullptr);
    if (c.kind != chunk_kind) continue;
    if (const std::optional<std::string> why = in.add(c.number, c.bytes)) std::fprintf(stderr, "%s\n", why->c_str());
    Message credit;
    credit.kind = credit_kind;
    credit.number = 1;
    send(s, credit, router ? &from : nullptr);
  }
  if (const std::optional<std::string> why = in.finish(total, checksum)) {
    std::fprintf(stderr, "damaged surface: %s\n", why->c_str());
    std::exit(1);
  }
  return in.take();
}

struct Plan {
  std::size_t bytes = 0;
  int surfaces = 0;
};

// Each party is a child process (forked before any ZeroMQ context exists); the endpoints are
// fixed ports on the loopback, passed in order.
int sender(const Plan& plan, const std::string& endpoint) {
  zmq::context_t context(1);
  zmq::socket_t s(context, zmq::socket_type::dealer);
  s.set(zmq::sockopt::routing_id, "sender");
  s.connect(endpoint);
  for (int i = 0; i < plan.surfaces; ++i) {
    const std::vector<std::byte> record = make_surface(plan.bytes, static_cast<unsigned>(i));
    send_surface(s, record, nullptr, MessageKind::surface_chunk, MessageKind::surface_credit);
  }
  while (receive(s).kind != MessageKind::finished) {
  } // the receiver's (or the relay's) last word: everything arrived
  return 0;
}

// Direct route: the receiver binds; surfaces come straight from the sender.
int direct_receiver(const Plan& plan, const std::string& endpoint) {
  zmq::context_t context(1);
  zmq::socket_t s(context, zmq::socket_type::router);
  s.bind(endpoint);
  std::string from;
  for (int i = 0; i < plan.surfaces; ++i) {
    SurfaceAssembler in;
    for (;;) {
      const Message m = receive(s, &from);
      if (m.kind == MessageKind::surface_chunk) {
        if (in.add(m.number, m.bytes)) return 1;
        Message credit;
        credit.kind = MessageKind::surface_credit;
        credit.number = 1;
        send(s, credit, &from);
      } else if (m.kind == MessageKind::surface) {
        if (in.finish(m.number, static_cast<std::uint64_t>(m.box[0]))) return 1;
        break;
      }
    }
  }
  Message over;
  over.kind = MessageKind::finished;
  send(s, over, &from);
  return 0;
}

// Relay route: the manager binds; it keeps each surface whole (checked), then feeds it to the
// receiver under the receiver's credits, while the sender goes on with its next surface.
int relay(const std::string& endpoint) {
  zmq::context_t context(1);
  zmq::socket_t s(context, zmq::socket_type::router);
  s.bind(endpoint);
  const std::string to = "receiver", sender_id = "sender";
  struct Record {
    std::vector<std::byte> bytes;
    std::uint64_t checksum = 0;
  };
  std::vector<Record> ready; // arrived whole, not yet fed
  std::optional<SurfaceAssembler> in;
  std::optional<Record> out;
  std::uint64_t offset = 0;
  std::size_t ahead = 0;
  bool receiver_here = false; // a ROUTER drops what it sends to a peer not yet connected
  for (;;) {
    std::string from;
    const Message m = receive(s, &from);
    if (from == sender_id) {
      if (!in) in.emplace();
      if (m.kind == MessageKind::surface_chunk) {
        if (in->add(m.number, m.bytes)) return 1;
        Message credit;
        credit.kind = MessageKind::surface_credit;
        credit.number = 1;
        send(s, credit, &from);
      } else if (m.kind == MessageKind::surface) {
        if (in->finish(m.number, static_cast<std::uint64_t>(m.box[0]))) return 1;
        ready.push_back({in->take(), static_cast<std::uint64_t>(m.box[0])});
        in.reset();
      }
    } else if (m.kind == MessageKind::hello) {
      receiver_here = true;
    } else if (m.kind == MessageKind::merge_credit) {
      ahead -= std::min<std::size_t>(ahead, m.number);
    } else if (m.kind == MessageKind::done) {
      break;
    }
    if (receiver_here && !out && !ready.empty()) {
      out = std::move(ready.front());
      ready.erase(ready.begin());
      offset = 0;
      ahead = 0;
      Message merge;
      merge.kind = MessageKind::merge;
      merge.number = out->bytes.size();
      merge.box[0] = static_cast<std::int64_t>(out->checksum);
      send(s, merge, &to);
    }
    while (out && ahead < kChunkWindow && offset < out->bytes.size()) {
      const std::size_t n = std::min<std::size_t>(kChunkBytes, out->bytes.size() - offset);
      Message c;
      c.kind = MessageKind::merge_chunk;
      c.number = offset;
      c.bytes.assign(out->bytes.begin() + static_cast<std::ptrdiff_t>(offset),
                     out->bytes.begin() + static_cast<std::ptrdiff_t>(offset + n));
      send(s, c, &to);
      offset += n;
      ++ahead;
    }
    if (out && offset == out->bytes.size()) out.reset(); // the next one may start at once
  }
  Message over;
  over.kind = MessageKind::finished;
  send(s, over, &sender_id);
  return 0;
}

int relay_receiver(const Plan& plan, const std::string& endpoint) {
  zmq::context_t context(1);
  zmq::socket_t s(context, zmq::socket_type::dealer);
  s.set(zmq::sockopt::routing_id, "receiver");
  s.connect(endpoint);
  Message hello;
  hello.kind = MessageKind::hello;
  send(s, hello);
  for (int i = 0; i < plan.surfaces; ++i) {
    Message m = receive(s);
    while (m.kind != MessageKind::merge)
      m = receive(s);
    (void)receive_surface(s, m.number, static_cast<std::uint64_t>(m.box[0]), MessageKind::merge_chunk,
                          MessageKind::merge_credit, false);
  }
  Message done;
  done.kind = MessageKind::done;
  send(s, done);
  return 0;
}

struct Child {
  pid_t pid = -1;
  double cpu = 0;
};

template <typename F> Child spawn(F&& role) {
  std::fflush(nullptr);
  const pid_t pid = fork();
  if (pid == 0) {
    int code = 1;
    try {
      code = role();
    } catch (const std::exception& e) {
      std::fprintf(stderr, "bench_surface_route: %s\n", e.what());
    }
    std::_Exit(code);
  }
  return {pid, 0};
}

bool reap(Child& c) {
  int status = 0;
  rusage u{};
  wait4(c.pid, &status, 0, &u);
  c.cpu = static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
          static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec) / 1e6;
  return WIFEXITED(status) && WEXITSTATUS(status) == 0;
}

std::string endpoint_for(int salt) {
  return "tcp://127.0.0.1:" + std::to_string(20000 + (getpid() * 7 + salt) % 20000);
}

} // namespace

int bench_main(int argc, char** argv) {
  const geotandem::bench::Args args(argc, argv, "bench_surface_route [MiB list=1,4,16] [surfaces=16]");
  const std::vector<double> sizes = args.reals(1, "1,4,16", 1.0 / 1024);
  const auto surfaces = static_cast<int>(args.integer(2, 16, 1));
  std::printf("partial surfaces from one worker process to another, %d per size, chunks of %zu KiB, window %zu\n",
              surfaces, kChunkBytes >> 10, kChunkWindow);
  int salt = 0;
  for (const double mib : sizes) {
    const Plan plan{static_cast<std::size_t>(mib * 1024 * 1024), surfaces};
    for (const bool via_manager : {false, true}) {
      const std::string endpoint = endpoint_for(++salt);
      const auto start = Clock::now();
      std::vector<Child> children;
      if (via_manager) {
        children.push_back(spawn([&] { return relay(endpoint); }));
        children.push_back(spawn([&] { return relay_receiver(plan, endpoint); }));
      } else {
        children.push_back(spawn([&] { return direct_receiver(plan, endpoint); }));
      }
      children.push_back(spawn([&] { return sender(plan, endpoint); }));
      bool ok = true;
      for (Child& c : children)
        ok = reap(c) && ok;
      const double wall = std::chrono::duration<double>(Clock::now() - start).count();
      const double total_mib = static_cast<double>(plan.bytes) * surfaces / (1024.0 * 1024.0);
      if (!ok) {
        std::printf("%6g MiB %-7s: FAILED\n", mib, via_manager ? "relay" : "direct");
        return 1;
      }
      if (via_manager)
        std::printf(
            "%6g MiB relay : %7.2f ms per surface, %7.0f MiB/s; CPU s: sender %.3f, manager %.3f, receiver %.3f "
            "(manager %.2f ms per MiB)\n",
            mib, 1000.0 * wall / surfaces, total_mib / wall, children[2].cpu, children[0].cpu, children[1].cpu,
            1000.0 * children[0].cpu / total_mib);
      else
        std::printf("%6g MiB direct: %7.2f ms per surface, %7.0f MiB/s; CPU s: sender %.3f, receiver %.3f\n", mib,
                    1000.0 * wall / surfaces, total_mib / wall, children[1].cpu, children[0].cpu);
    }
  }
  return 0;
}

int main(int argc, char** argv) {
  return geotandem::bench::guarded_main("bench_surface_route", [&] { return bench_main(argc, argv); });
}
