// app/live/frame_server.cpp and the server side of app/live/tcp.cpp in this process: where a server
// listens (this machine only unless told), what a server address as typed means, clients past
// the cap refused while the others are served, and a thousand connections that leave the
// descriptors, the clients and a kept client's stream as they were. Only loopback addresses are
// connected to; where a server listens is read from its socket.
#include "app/live/frame_server.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <cerrno>
#include <string>
#include <vector>

#include "app/live/tcp.h"
#include "engine/base/error.h"
#include "tests/app/live/live_process.h"

using namespace mostyle;

namespace {

// The address a listening socket is bound to.
std::string bound_host(int fd) {
  sockaddr_storage s{};
  socklen_t length = sizeof s;
  REQUIRE(::getsockname(fd, reinterpret_cast<sockaddr*>(&s), &length) == 0);
  return live::address_host(s);
}

// One turn of the server's poll loop, not waiting.
void serve_once(live::FrameServer& server) {
  std::vector<pollfd> fds;
  server.add_poll_fds(&fds);
  live::poll_until(&fds, live::Clock::now());
  server.handle_poll(fds, 0);
}

// Turns of the poll loop until `done()` holds (test::kLiveTimeout at most).
template <typename Done>
bool serve_until(live::FrameServer& server, Done done) {
  return test::eventually([&] {
    serve_once(server);
    return done();
  });
}

// What has come on a blocking socket so far, without waiting.
std::string received(int fd) {
  std::string out;
  char buffer[1 << 16];
  for (;;) {
    const ssize_t n = ::recv(fd, buffer, sizeof buffer, MSG_DONTWAIT);
    if (n <= 0) return out;
    out.append(buffer, static_cast<size_t>(n));
  }
}

}  // namespace

TEST_CASE("frame server: a server address as typed", "[live]") {
  const live::HostPort port_only = live::parse_serve_address("7001", "--serve");
  CHECK(port_only.host == "127.0.0.1");
  CHECK(port_only.port == 7001);
  CHECK(live::parse_serve_address("0", "--serve").port == 0);
  const live::HostPort any4 = live::parse_serve_address("0.0.0.0:7002", "--serve");
  CHECK(any4.host == "0.0.0.0");
  CHECK(any4.port == 7002);
  CHECK(live::parse_serve_address("[::]:7003", "--serve").host == "::");
  CHECK(live::parse_serve_address("[::1]:0", "--serve").host == "::1");
  CHECK(live::parse_serve_address("192.168.1.20:65535", "--serve").host == "192.168.1.20");
  for (const char* bad : {"", "x", "-1", "65536", ":7001", "localhost:7001", "::1:7001", "[::1]", "[::1]:", "1.2.3:7001",
                          "[1.2.3.4]:7001", "0.0.0.0:70000", "0.0.0.0: 7001", "7001 "}) {
    INFO(bad);
    CHECK_THROWS_AS(live::parse_serve_address(bad, "--serve"), InputError);
    CHECK_THROWS_WITH(live::parse_serve_address(bad, "--serve"), Catch::StartsWith("--serve: expected PORT or ADDRESS:PORT"));
  }
  CHECK(live::serving_text({"127.0.0.1", 7001}) == "127.0.0.1 port 7001 (this machine only)");
  CHECK(live::serving_text({"::1", 7001}) == "[::1] port 7001 (this machine only)");
  CHECK(live::serving_text({"0.0.0.0", 7001}) == "0.0.0.0 port 7001 (every IPv4 interface)");
  CHECK(live::serving_text({"::", 7001}) == "[::] port 7001 (every interface)");
  CHECK(live::serving_text({"192.168.1.20", 7001}) == "192.168.1.20 port 7001");
}

TEST_CASE("frame server: listens on 127.0.0.1 by default, which no other machine reaches; an address on purpose",
          "[live]") {
  int port = 0;
  const int fd = live::listen_on(live::parse_serve_address("0", "--serve"), &port);
  CHECK(bound_host(fd) == "127.0.0.1");
  CHECK(port > 0);
  ::close(fd);

  live::FrameServer server(live::parse_serve_address("0", "--serve"));
  CHECK(server.serving() == "127.0.0.1 port " + std::to_string(server.port()) + " (this machine only)");
  CHECK(test::listening_address(server.port()) == "127.0.0.1");
  // Bound to that address alone: refused by any other, even 127.0.0.2 of the loopback range.
  errno = 0;
  CHECK(test::connect_to(test::other_loopback(), server.port()) < 0);
  CHECK(errno == ECONNREFUSED);
  const int client = test::connect_local(server.port());
  REQUIRE(client >= 0);
  CHECK(serve_until(server, [&] { return server.clients() == 1; }));
  CHECK(server.refused() == 0);
  ::close(client);

  // Opened on purpose: every IPv4 interface.
  live::FrameServer open(live::HostPort{"0.0.0.0", 0});
  CHECK(test::listening_address(open.port()) == "0.0.0.0");
  const int c = test::connect_to(test::other_loopback(), open.port());
  CHECK(c >= 0);
  if (c >= 0) ::close(c);
  // An address that is not numeric, or not this machine's, is said in one sentence.
  CHECK_THROWS_WITH(live::FrameServer(live::HostPort{"localhost", 0}), Catch::StartsWith("cannot serve on localhost"));
  CHECK_THROWS_WITH(live::FrameServer(live::HostPort{"127.0.0.1", server.port()}),
                    "cannot serve on 127.0.0.1 port " + std::to_string(server.port()) + ": Address already in use");
}

TEST_CASE("frame server: past max_clients a client is refused, said at most once a second, the others served",
          "[live]") {
  live::FrameServerOptions options;
  options.max_clients = 2;
  std::vector<std::string> warnings;
  options.warn = [&](const std::string& sentence) { warnings.push_back(sentence); };
  live::FrameServer server(live::HostPort{"127.0.0.1", 0}, options);
  CHECK(live::FrameServerOptions{}.max_clients == live::kDefaultMaxClients);
  CHECK(live::kDefaultMaxClients == 16);
  const int a = test::connect_local(server.port()), b = test::connect_local(server.port());
  REQUIRE(serve_until(server, [&] { return server.clients() == 2; }));
  const int c = test::connect_local(server.port()), d = test::connect_local(server.port());
  REQUIRE(serve_until(server, [&] { return server.refused() == 2; }));
  CHECK(server.clients() == 2);
  REQUIRE(warnings.size() == 1);  // two refused within the second: one sentence
  CHECK(warnings[0] ==
        "refused a client from 127.0.0.1: 2 clients are connected, the most --max-clients allows (1 refused in all)");
  server.send("frame 1\n");
  serve_until(server, [&] { return server.flushed(); });
  CHECK(received(a) == "frame 1\n");
  CHECK(received(b) == "frame 1\n");
  char byte;
  CHECK(::recv(c, &byte, 1, 0) == 0);  // the end of the stream, at once
  CHECK(::recv(d, &byte, 1, 0) == 0);
  for (int fd : {a, b, c, d}) ::close(fd);
}

TEST_CASE("frame server: a thousand connections opened and closed leave its descriptors, its clients and a kept "
          "client's stream as they were",
          "[live]") {
  live::FrameServerOptions options;
  options.warn = [](const std::string&) {};
  live::FrameServer server(live::HostPort{"127.0.0.1", 0}, options);
  const int kept = test::connect_local(server.port());
  REQUIRE(kept >= 0);
  REQUIRE(serve_until(server, [&] { return server.clients() == 1; }));
  const int before = test::open_descriptors();
  std::string sent, got;
  // In batches of 25 held at once (past the cap: some refused), a frame sent after each batch.
  constexpr int kConnections = 1000, kBatch = 25;
  int most = 0;
  for (int round = 0; round < kConnections / kBatch; ++round) {
    std::vector<int> batch;
    for (int k = 0; k < kBatch; ++k) {
      batch.push_back(test::connect_local(server.port()));
      REQUIRE(batch.back() >= 0);
      serve_once(server);
      most = std::max(most, server.clients());
    }
    for (int fd : batch) ::close(fd);
    const std::string line = "frame " + std::to_string(round) + "\n";
    server.send(line);
    sent += line;
    serve_once(server);
    got += received(kept);
  }
  // Every client gone is let go of once a frame finds it gone.
  CHECK(serve_until(server, [&] {
    server.send("tick\n");
    sent += "tick\n";
    got += received(kept);
    return server.clients() == 1 && server.accepted() + server.refused() == kConnections + 1;
  }));
  serve_until(server, [&] { return server.flushed(); });
  got += received(kept);
  CHECK(most <= live::kDefaultMaxClients);
  CHECK(server.refused() > 0);
  CHECK(server.dropped() == 0);
  CHECK(test::open_descriptors() == before);
  CHECK(got == sent);  // the kept client's stream, whole and in order
  ::close(kept);
}
