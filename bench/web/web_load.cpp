// Load test of `nbar serve`: many clients at once on 127.0.0.1, bounded in time. It starts the
// server itself (or uses one already listening on a local port), then every client loops:
// pick a request from the mix, send it, check the answer, pause ("think"), until the time is up.
//
//   web_load --nbar build/apps/nbar/nbar                       # 200 clients for 60 s
//   web_load --nbar build/apps/nbar/nbar --clients 20 --seconds 5
//   web_load --port 8080 --clients 50                          # a server (or nginx) already running
//
// The mix, by weight: check (four-bar), solve (four-bar, 361 steps), dynamics (steel four-bar,
// 361 steps), stress (steel four-bar, 73 steps, 200 sections), five-point synthesis, and two
// requests over the limits that must be answered with a clean 413 JSON error: a body over
// 1 MiB and a sweep of 200 000 steps. Prints, per kind, the answers and their latency
// (p50/p90/p99/max), the throughput, and the server's resident memory (VmRSS, VmHWM from
// /proc/PID/status) at the start and the end. Exit 0 only when there was no error (the
// intended rejections are counted apart) and the server still answers at the end.
#include <httplib.h>
#include <nlohmann/json.hpp>

#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <map>
#include <mutex>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

extern char** environ;

namespace {

using Clock = std::chrono::steady_clock;
using Json = nlohmann::json;
constexpr const char* kHost = "127.0.0.1";  // never anything else

struct Settings {
  std::string nbar;  // start `nbar serve` from this program
  std::vector<std::string> server_args;
  int port = 0;  // or use a server already on this port
  int clients = 200;
  double seconds = 60;
  double think_ms = 1000;  // mean pause between a client's requests (uniform in [0, 2 x mean])
  bool keep_alive = true;
};

[[noreturn]] void usage(const std::string& problem) {
  std::cerr << "web_load: " << problem << "\n"
            << "usage: web_load (--nbar PATH [--server-arg ARG]... | --port N) [--clients N] [--seconds S]\n"
            << "                [--think-ms MS] [--no-keep-alive]\n";
  std::exit(2);
}

Settings parse_arguments(int argc, char** argv) {
  Settings s;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const auto value = [&]() -> std::string {
      if (i + 1 >= argc) usage(a + " needs a value");
      return argv[++i];
    };
    if (a == "--nbar")
      s.nbar = value();
    else if (a == "--server-arg")
      s.server_args.push_back(value());
    else if (a == "--port")
      s.port = std::stoi(value());
    else if (a == "--clients")
      s.clients = std::stoi(value());
    else if (a == "--seconds")
      s.seconds = std::stod(value());
    else if (a == "--think-ms")
      s.think_ms = std::stod(value());
    else if (a == "--no-keep-alive")
      s.keep_alive = false;
    else
      usage("unknown argument " + a);
  }
  if (s.nbar.empty() == (s.port == 0)) usage("give --nbar or --port");
  if (s.clients < 1 || s.clients > 2000 || !(s.seconds > 0 && s.seconds <= 3600) || !(s.think_ms >= 0))
    usage("--clients 1..2000, --seconds up to 3600, --think-ms >= 0");
  return s;
}

// ----------------------------------------------------------------------------- the server

struct Server {
  pid_t pid = -1;
  int port = 0;
  std::thread drain;  // reads the server's standard error so that it never blocks on it
};

// `nbar serve --port 0 ...`, its port read from the line it prints first.
Server start_server(const Settings& s) {
  int pipe_fds[2];
  if (::pipe(pipe_fds) != 0) usage("cannot make a pipe");
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, pipe_fds[1], 2);
  posix_spawn_file_actions_addclose(&actions, pipe_fds[0]);
  std::vector<std::string> args = {s.nbar, "serve", "--host", kHost, "--port", "0"};
  args.insert(args.end(), s.server_args.begin(), s.server_args.end());
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  Server server;
  if (::posix_spawn(&server.pid, s.nbar.c_str(), &actions, nullptr, argv.data(), environ) != 0)
    usage("cannot start " + s.nbar);
  posix_spawn_file_actions_destroy(&actions);
  ::close(pipe_fds[1]);
  FILE* err = ::fdopen(pipe_fds[0], "r");
  char line[1024];
  while (server.port == 0 && std::fgets(line, sizeof line, err)) {
    std::cerr << "server: " << line;
    const std::string text = line;
    const std::string marker = std::string("http://") + kHost + ":";
    if (const auto at = text.find(marker); at != std::string::npos)
      server.port = std::atoi(text.c_str() + at + marker.size());
  }
  if (server.port == 0) usage("the server did not start");
  server.drain = std::thread([err] {
    char rest[1024];
    while (std::fgets(rest, sizeof rest, err)) std::cerr << "server: " << rest;
    std::fclose(err);
  });
  return server;
}

// VmRSS and VmHWM of a process, in KiB (0 when unknown).
std::pair<long, long> memory_kib(pid_t pid) {
  std::ifstream status("/proc/" + std::to_string(pid) + "/status");
  long rss = 0, hwm = 0;
  for (std::string line; std::getline(status, line);) {
    if (line.rfind("VmRSS:", 0) == 0) rss = std::atol(line.c_str() + 6);
    if (line.rfind("VmHWM:", 0) == 0) hwm = std::atol(line.c_str() + 6);
  }
  return {rss, hwm};
}

// ----------------------------------------------------------------------------- the mix

struct Kind {
  std::string name;
  std::string path;
  std::string body;
  int weight;
  int expected_status;          // 200, or 413 for the requests over a limit
  std::string expected_marker;  // a text every right answer holds
};

std::string fetch_example(httplib::Client& client, const std::string& name) {
  const auto r = client.Get(("/api/examples/" + name).c_str());
  if (!r || r->status != 200) usage("cannot fetch example " + name + " from the server");
  return r->body;
}

std::vector<Kind> request_mix(httplib::Client& client) {
  const std::string fourbar = fetch_example(client, "fourbar-crank-rocker");
  const std::string steel = fetch_example(client, "fourbar-steel-bars");
  const std::string task = fetch_example(client, "five-point-crank-rocker");
  std::vector<Kind> mix;
  mix.push_back({"check", "/api/check", Json{{"model", fourbar}}.dump(), 25, 200, "\"grashof\""});
  mix.push_back(
      {"solve", "/api/solve", Json{{"model", fourbar}, {"steps", 361}}.dump(), 35, 200, "\"complete\": true"});
  mix.push_back({"dynamics", "/api/solve", Json{{"model", steel}, {"steps", 361}, {"dynamics", true}}.dump(), 15, 200,
                 "\"complete\": true"});
  mix.push_back({"stress", "/api/stress", Json{{"model", steel}, {"steps", 73}}.dump(), 10, 200, "\"von_mises\""});
  mix.push_back({"five-point", "/api/synth/five-point", Json{{"task", task}}.dump(), 5, 200, "\"designs\""});
  // Over the limits: a body of 1.5 MiB (the limit is 1 MiB), and 200 000 steps (100 001).
  mix.push_back({"reject-body", "/api/check", Json{{"model", fourbar + std::string(1536 * 1024, '#')}}.dump(), 5, 413,
                 "\"body_too_large\""});
  mix.push_back(
      {"reject-steps", "/api/solve", Json{{"model", fourbar}, {"steps", 200000}}.dump(), 5, 413, "\"limit_exceeded\""});
  return mix;
}

// The answer of each kind once, read whole: what the markers stand for is really there.
void check_answers_once(httplib::Client& client, const std::vector<Kind>& mix) {
  for (const Kind& k : mix) {
    const auto r = client.Post(k.path.c_str(), k.body, "application/json");
    if (!r) usage(k.name + ": no answer");
    if (r->status != k.expected_status)
      usage(k.name + ": status " + std::to_string(r->status) + ": " + r->body.substr(0, 300));
    const Json j = Json::parse(r->body);
    bool right = false;
    if (k.name == "check") right = j.at("loops").at(0).at("grashof") == "crank-rocker";
    if (k.name == "solve" || k.name == "dynamics") right = j.at("rows").size() == 361 && j.at("complete") == true;
    if (k.name == "dynamics") right = right && j.at("columns").dump().find("crank.torque") != std::string::npos;
    if (k.name == "stress") right = !j.at("links").empty();
    if (k.name == "five-point") right = !j.at("designs").empty();
    if (k.expected_status == 413) right = j.at("error").contains("kind");
    if (!right) usage(k.name + ": unexpected answer: " + r->body.substr(0, 300));
  }
}

// ----------------------------------------------------------------------------- the clients

struct Tally {
  std::vector<double> latencies_ms;  // answers as expected
  long errors = 0;                   // anything else: wrong status, no answer, wrong body
  long busy = 0;                     // of the errors, 503 too_many_jobs
};

struct Shared {
  std::mutex mutex;
  std::map<std::string, Tally> tallies;
  std::vector<std::string> error_samples;
};

void run_client(int index, const Settings& s, int port, const std::vector<Kind>& mix, Clock::time_point end,
                Shared& shared) {
  std::mt19937_64 rng(1000 + static_cast<unsigned>(index));
  std::vector<int> weights;
  for (const Kind& k : mix) weights.push_back(k.weight);
  std::discrete_distribution<int> pick(weights.begin(), weights.end());
  std::uniform_real_distribution<double> think(0, 2 * s.think_ms);
  std::map<std::string, Tally> mine;
  std::vector<std::string> samples;
  httplib::Client client(kHost, port);
  client.set_keep_alive(s.keep_alive);
  client.set_tcp_nodelay(true);  // as browsers do
  client.set_connection_timeout(10, 0);
  client.set_read_timeout(120, 0);
  client.set_write_timeout(30, 0);
  // Clients do not start in step.
  std::this_thread::sleep_for(std::chrono::duration<double, std::milli>(think(rng) / 2));
  while (Clock::now() < end) {
    const Kind& k = mix[static_cast<std::size_t>(pick(rng))];
    const auto start = Clock::now();
    const auto r = client.Post(k.path.c_str(), k.body, "application/json");
    const double ms = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
    Tally& t = mine[k.name];
    std::string problem;
    if (!r)
      problem = "no answer: " + httplib::to_string(r.error());
    else if (r->status != k.expected_status)
      problem = "status " + std::to_string(r->status) + ": " + r->body.substr(0, 200);
    else if (r->body.find(k.expected_marker) == std::string::npos)
      problem = "answer without " + k.expected_marker;
    if (problem.empty()) {
      t.latencies_ms.push_back(ms);
    } else {
      ++t.errors;
      if (r && r->status == 503) ++t.busy;
      if (samples.size() < 3) samples.push_back(k.name + ": " + problem);
    }
    std::this_thread::sleep_for(std::chrono::duration<double, std::milli>(think(rng)));
  }
  const std::lock_guard lock(shared.mutex);
  for (auto& [name, t] : mine) {
    Tally& all = shared.tallies[name];
    all.latencies_ms.insert(all.latencies_ms.end(), t.latencies_ms.begin(), t.latencies_ms.end());
    all.errors += t.errors;
    all.busy += t.busy;
  }
  for (std::string& e : samples)
    if (shared.error_samples.size() < 20) shared.error_samples.push_back(std::move(e));
}

double percentile(std::vector<double>& v, double p) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const std::size_t i = std::min(v.size() - 1, static_cast<std::size_t>(p / 100.0 * static_cast<double>(v.size())));
  return v[i];
}

}  // namespace

int main(int argc, char** argv) {
  const Settings s = parse_arguments(argc, argv);
  std::signal(SIGPIPE, SIG_IGN);
  std::optional<Server> server;
  int port = s.port;
  if (!s.nbar.empty()) {
    server = start_server(s);
    port = server->port;
  }
  httplib::Client probe(kHost, port);
  probe.set_read_timeout(60, 0);
  for (int i = 0; i < 100 && !probe.Get("/api/health"); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(50));
  const std::vector<Kind> mix = request_mix(probe);
  check_answers_once(probe, mix);
  const auto memory_start = server ? memory_kib(server->pid) : std::pair<long, long>{0, 0};

  std::cout << "web_load: " << s.clients << " clients for " << s.seconds << " s on " << kHost << ":" << port
            << ", think time uniform in [0, " << 2 * s.think_ms << "] ms, keep-alive " << (s.keep_alive ? "on" : "off")
            << ", " << std::thread::hardware_concurrency() << " cores\n";
  Shared shared;
  const auto begin = Clock::now();
  const auto end = begin + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(s.seconds));
  std::atomic<long> peak_rss{memory_start.first};
  std::atomic<bool> done{false};
  std::thread sampler([&] {
    while (server && !done) {
      peak_rss = std::max(peak_rss.load(), memory_kib(server->pid).first);
      std::this_thread::sleep_for(std::chrono::milliseconds(250));
    }
  });
  std::vector<std::thread> clients;
  for (int i = 0; i < s.clients; ++i)
    clients.emplace_back(run_client, i, std::cref(s), port, std::cref(mix), end, std::ref(shared));
  for (std::thread& c : clients) c.join();
  const double elapsed = std::chrono::duration<double>(Clock::now() - begin).count();
  done = true;
  sampler.join();

  const auto health = probe.Get("/api/health");
  const bool alive = health && health->status == 200;
  const auto memory_end = server ? memory_kib(server->pid) : std::pair<long, long>{0, 0};

  long answered = 0, errors = 0, busy = 0, rejected = 0;
  std::printf("%-13s %8s %7s %9s %9s %9s %9s\n", "kind", "answers", "errors", "p50 ms", "p90 ms", "p99 ms", "max ms");
  std::map<std::string, double> p99;
  for (const Kind& k : mix) {
    Tally& t = shared.tallies[k.name];
    const long n = static_cast<long>(t.latencies_ms.size());
    answered += n;
    errors += t.errors;
    busy += t.busy;
    if (k.expected_status != 200) rejected += n;
    p99[k.name] = percentile(t.latencies_ms, 99);
    std::printf("%-13s %8ld %7ld %9.1f %9.1f %9.1f %9.1f\n", k.name.c_str(), n, t.errors,
                percentile(t.latencies_ms, 50), percentile(t.latencies_ms, 90), p99[k.name],
                t.latencies_ms.empty() ? 0.0 : t.latencies_ms.back());
  }
  std::printf("answers: %ld in %.1f s (%.1f per second), of which %ld intended 413 rejections\n", answered, elapsed,
              static_cast<double>(answered) / elapsed, rejected);
  std::printf("errors: %ld (503 busy: %ld)\n", errors, busy);
  for (const std::string& e : shared.error_samples) std::printf("  e.g. %s\n", e.c_str());
  if (server)
    std::printf("server memory: VmRSS %.1f MiB at start, %.1f MiB at the end (sampled peak %.1f MiB), VmHWM %.1f MiB\n",
                memory_start.first / 1024.0, memory_end.first / 1024.0, peak_rss / 1024.0, memory_end.second / 1024.0);
  std::printf("targets: solve p99 %.1f ms (< 200: %s), five-point p99 %.1f ms (< 1000: %s)\n", p99["solve"],
              p99["solve"] < 200 ? "met" : "MISSED", p99["five-point"], p99["five-point"] < 1000 ? "met" : "MISSED");
  std::printf("server after the run: %s\n", alive ? "answering" : "NOT ANSWERING");

  if (server) {
    ::kill(server->pid, SIGTERM);
    int status = 0;
    ::waitpid(server->pid, &status, 0);
    server->drain.join();
  }
  return errors == 0 && alive ? 0 : 1;
}
