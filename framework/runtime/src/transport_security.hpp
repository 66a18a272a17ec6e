#pragma once
// CurveZMQ for the manager/worker sockets, on every address, loopback included.
//
// The manager makes fresh keys for every run: its own pair and one pair for its workers. They are
// written to STORE.keys/ (the directory 0700, owned by the user and never a symbolic link; each
// file 0600: readable by the user alone), the worker's file path is exported as
// GEOTANDEM_CURVE_KEY_FILE so that workers started from this process (locally or as scheduler
// jobs, which inherit the environment) find it, and a ZAP handler admits only the workers' public
// key; every refusal is logged with the peer's address.
// Why on loopback too: any user of the machine can connect to a loopback port, and a worker's
// launch token (its routing id) and the port are in its command line, which every user can read
// in /proc. Without authentication a stranger could join as a worker, answer a task with a forged
// result and take the real worker's place (issue 52). The workers' secret key is the one thing a
// stranger cannot read; the token only names a worker among the run's own.
#include <memory>
#include <string>

#include <zmq.hpp>

#include "geotandem/core/log.hpp"

namespace geotandem::runtime::detail {

// The variable that carries the worker's key file to the workers.
inline constexpr const char* curve_key_variable = "GEOTANDEM_CURVE_KEY_FILE";

class ServerSecurity; // the ZAP handler's thread and the key files; ends the handler when destroyed

// True for tcp://127.x.x.x:..., tcp://localhost:..., tcp://[::1]:... and non-TCP transports.
bool is_loopback_endpoint(const std::string& endpoint);

// Call before `router.bind(bind)`: makes the keys in `key_dir`, starts the ZAP handler in
// `context` and makes `router` a CURVE server; returns the object that keeps them (keep it until
// the socket is closed). `bind` only chooses how loudly this is logged. Throws IoError when the
// keys cannot be written, or when `key_dir` is a symbolic link, not a directory, another user's,
// or open to others (its mode is not 0700).
std::shared_ptr<ServerSecurity> secure_manager_socket(zmq::context_t& context, zmq::socket_t& router,
                                                      const std::string& bind, const std::string& key_dir, Logger& log);

// Throws IoError (naming the file) when GEOTANDEM_CURVE_KEY_FILE is set but cannot be read or
// holds no valid keys. The worker calls it before its I/O thread starts. Without the variable a
// worker connects without CURVE, and the manager refuses it and logs the refusal.
void check_worker_keys();

// Call before `dealer.connect(...)`: makes `dealer` a CURVE client with the keys in
// GEOTANDEM_CURVE_KEY_FILE (the client checks the server's key too: nobody else can pose as the
// manager). Without the variable, or without valid keys (check_worker_keys said why), it changes
// nothing.
void secure_worker_socket(zmq::socket_t& dealer) noexcept;

} // namespace geotandem::runtime::detail
