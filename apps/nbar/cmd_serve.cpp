// nbar serve: the web app's server (web/server): the JSON API over the library and the
// embedded static files, on 127.0.0.1 unless --host says otherwise. docs/web-api.md.
#include <arpa/inet.h>
#include <ifaddrs.h>
#include <netinet/in.h>
#include <spawn.h>
#include <sys/wait.h>

#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "commands.hpp"
#include "common.hpp"
#include "nbar/web/server.hpp"
#include "validators.hpp"

extern char** environ;

namespace nbar::cli {

namespace {

struct ServeArgs {
  std::string host = "127.0.0.1";
  int port = 8080;
  bool open = false;
  int max_jobs = 2;
  int light_jobs = 0;
  double queue_wait = 10;
  double time_budget = 30;
  int threads = 256;
  int keep_alive = 5;
  double request_timeout = 10;
  int max_connections = 4096;
  int max_connections_per_client = 256;
};

// The browser, by xdg-open with the URL as its one argument: no shell.
void open_browser(const std::string& url) {
  std::string program = "xdg-open";
  char* argv[] = {program.data(), const_cast<char*>(url.c_str()), nullptr};
  pid_t pid = 0;
  if (::posix_spawnp(&pid, "xdg-open", nullptr, nullptr, argv, environ) != 0) {
    std::cerr << "note: cannot start xdg-open; open " << url << " in a browser\n";
    return;
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
}

// The addresses other machines reach this one at (its network interfaces, loopback left out):
// a server on 0.0.0.0 is listening on all of them, and "localhost" means nothing to a student's
// phone. IPv6 ones only when listening on "::"; link-local IPv6 ones need a zone and are left out.
std::vector<std::string> reachable_addresses(bool ipv6) {
  std::vector<std::string> out;
  ifaddrs* list = nullptr;
  if (::getifaddrs(&list) != 0) return out;
  for (const ifaddrs* a = list; a; a = a->ifa_next) {
    if (!a->ifa_addr) continue;
    char text[INET6_ADDRSTRLEN] = {};
    if (a->ifa_addr->sa_family == AF_INET) {
      const auto* in = reinterpret_cast<const sockaddr_in*>(a->ifa_addr);
      if ((ntohl(in->sin_addr.s_addr) >> 24) == 127) continue;
      if (::inet_ntop(AF_INET, &in->sin_addr, text, sizeof text)) out.emplace_back(text);
    } else if (ipv6 && a->ifa_addr->sa_family == AF_INET6) {
      const auto* in6 = reinterpret_cast<const sockaddr_in6*>(a->ifa_addr);
      if (IN6_IS_ADDR_LOOPBACK(&in6->sin6_addr) || IN6_IS_ADDR_LINKLOCAL(&in6->sin6_addr)) continue;
      if (::inet_ntop(AF_INET6, &in6->sin6_addr, text, sizeof text)) out.push_back(std::string("[") + text + "]");
    }
  }
  ::freeifaddrs(list);
  return out;
}

// What to tell the teacher when other machines can reach the server: the addresses to give out.
void print_reachable(const std::string& host, int port) {
  const bool any = host == "0.0.0.0" || host == "::";
  const std::string where = any ? "" : (host.find(':') != std::string::npos ? "[" + host + "]" : host);
  std::cerr << "note: listening on " << host << ": other machines can reach this server";
  if (!any) {
    std::cerr << " at http://" << where << ":" << port << "/\n";
    return;
  }
  const std::vector<std::string> addresses = reachable_addresses(host == "::");
  if (addresses.empty()) {
    std::cerr << " at http://THIS-MACHINE:" << port
              << "/ (this machine's IP address or host name; no network "
                 "address found now)\n";
    return;
  }
  std::cerr << "; give students one of:\n";
  for (const std::string& a : addresses) std::cerr << "  http://" << a << ":" << port << "/\n";
}

int run_serve(const ServeArgs& args) {
  web::ServeOptions options;
  options.host = args.host;
  options.port = args.port;
  options.max_jobs = args.max_jobs;
  options.light_jobs = args.light_jobs;
  options.queue_wait_seconds = args.queue_wait;
  options.threads = args.threads;
  options.keep_alive_seconds = args.keep_alive;
  options.request_read_seconds = args.request_timeout;
  options.max_connections = args.max_connections;
  options.max_connections_per_address = args.max_connections_per_client;
  options.limits.time_budget_seconds = args.time_budget;
  options.limits.max_synthesis_threads = 2;
  web::HttpServer server(options);
  std::string error;
  if (!server.bind(error)) {
    std::cerr << "error: " << error << '\n';
    return kBadUsage;
  }
  const std::string shown_host = args.host == "0.0.0.0" || args.host == "::" ? "localhost" : args.host;
  const std::string url = "http://" +
                          (shown_host.find(':') != std::string::npos ? "[" + shown_host + "]" : shown_host) + ":" +
                          std::to_string(server.bound_port()) + "/";
  std::cerr << "nbar serve: " << url << " (the API is under " << url << "api/; Ctrl-C stops)\n";
  if (args.host != "127.0.0.1" && args.host != "localhost" && args.host != "::1")
    print_reachable(args.host, server.bound_port());
  if (args.open) open_browser(url);
  server.listen();
  return kOk;
}

}  // namespace

Command add_serve_command(CommandLine& app) {
  auto args = std::make_shared<ServeArgs>();
  Subcommand* sub = app.add_subcommand("serve", "Serve the web app and its JSON API (docs/web-api.md) on this machine");
  sub->add_option("--port", args->port, "TCP port (default 8080; 0 for any free port)")
      ->check(nbar::cli::in_range(0, 65535));
  sub->add_option("--host", args->host,
                  "address to listen on (default 127.0.0.1, this machine only; 0.0.0.0 for a classroom)");
  sub->add_flag("--open", args->open, "open the page in a browser");
  sub->add_option("--max-jobs", args->max_jobs,
                  "heavy computations at once (synthesis, stresses, reports, animations, large sweeps; default 2)")
      ->check(nbar::cli::in_range(1, 256));
  sub->add_option("--light-jobs", args->light_jobs,
                  "light computations at once (checks, small solves, drawings; default one per core, at least 2)")
      ->check(nbar::cli::in_range(1, 256));
  sub->add_option("--queue-wait", args->queue_wait,
                  "seconds a computation may wait for its turn before it is answered 503 (default 10)")
      ->check(nbar::cli::in_range(0.0, 600.0));
  sub->add_option("--time-budget", args->time_budget,
                  "seconds one request may compute before it is stopped (default 30)")
      ->check(nbar::cli::in_range(0.01, 86400.0));
  sub->add_option("--threads", args->threads,
                  "requests served at once (default 256; a connection holds a thread only while its request is "
                  "served)")
      ->check(nbar::cli::in_range(2, 1024));
  sub->add_option("--keep-alive", args->keep_alive,
                  "seconds an idle connection is kept open (default 5; 0: closed after every answer)")
      ->check(nbar::cli::in_range(0, 3600));
  sub->add_option("--request-timeout", args->request_timeout,
                  "seconds a request may take to arrive whole, header and body, from its first byte (default 10; "
                  "then 408)")
      ->check(nbar::cli::in_range(0.1, 3600.0));
  sub->add_option("--max-connections", args->max_connections,
                  "open connections in all (default 4096, at most the descriptors the process may open; past it "
                  "the longest idle one is closed)")
      ->check(nbar::cli::in_range(16, 1 << 20));
  sub->add_option("--max-connections-per-client", args->max_connections_per_client,
                  "open connections from one client address (default 256; more are refused 503)")
      ->check(nbar::cli::in_range(1, 1 << 20));
  return {sub, [args] { return run_serve(*args); }};
}

}  // namespace nbar::cli
