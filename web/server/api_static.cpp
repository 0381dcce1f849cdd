// What a GET reads: the bundled examples and templates, the server's health and limits, and the
// web app's files, all built into the program (embed.cmake): nothing a request says reaches the
// file system.
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <map>
#include <tuple>

#include "endpoints.hpp"
#include "io/json_text.hpp"
#include "nbar/render/animation.hpp"
#include "nbar/version.hpp"
#include "nbar/web/embedded.hpp"

namespace nbar::web {

namespace {

struct Example {
  std::string name, kind, task, file, title, description;
  std::string_view text;
};

// The comment lines at the top of a file, joined.
std::string leading_comment(std::string_view text) {
  std::string out;
  std::size_t at = 0;
  while (at < text.size() && text[at] == '#') {
    std::size_t end = text.find('\n', at);
    if (end == std::string_view::npos) end = text.size();
    std::string line(text.substr(at + 1, end - at - 1));
    if (!line.empty() && line[0] == ' ') line.erase(0, 1);
    if (line.rfind("  nbar ", 0) != 0) out += (out.empty() ? "" : " ") + line;
    at = end + 1;
  }
  return out;
}

const std::vector<Example>& examples() {
  static const std::vector<Example> list = [] {
    std::vector<Example> out;
    for (const EmbeddedFile& f : example_files()) {
      Example e;
      std::string path(f.path);
      e.file = "examples/" + path;
      const std::size_t slash = path.rfind('/');
      e.name = path.substr(slash == std::string::npos ? 0 : slash + 1);
      if (e.name.size() > 5 && e.name.ends_with(".yaml")) e.name.resize(e.name.size() - 5);
      e.text = f.data;
      // A template (examples/templates/) is a small model to start a new one from; its name
      // is prefixed so that it never clashes with an example's.
      const bool is_template = path.starts_with("templates/");
      if (is_template) e.name = "template-" + e.name;
      try {
        const YAML::Node node = YAML::Load(std::string(f.data));
        if (is_template) {
          e.kind = "template";
        } else if (node["task"]) {
          e.kind = "task";
          e.task = node["task"].as<std::string>();
        } else {
          e.kind = "model";
        }
        if (node["name"]) e.title = node["name"].as<std::string>();
        if (node["description"]) e.description = node["description"].as<std::string>();
      } catch (const YAML::Exception&) {
        e.kind = is_template ? "template" : "model";
      }
      if (e.description.empty()) e.description = leading_comment(f.data);
      out.push_back(std::move(e));
    }
    // Models first, then tasks, then templates, each by name.
    std::stable_sort(out.begin(), out.end(), [](const Example& a, const Example& b) {
      return std::tie(a.kind, a.name) < std::tie(b.kind, b.name);
    });
    return out;
  }();
  return list;
}

std::string content_type_of(std::string_view path) {
  const std::size_t dot = path.rfind('.');
  const std::string_view ext = dot == std::string_view::npos ? std::string_view() : path.substr(dot + 1);
  static const std::map<std::string_view, const char*> types = {{"html", "text/html; charset=utf-8"},
                                                                {"css", "text/css; charset=utf-8"},
                                                                {"js", "text/javascript; charset=utf-8"},
                                                                {"json", "application/json"},
                                                                {"svg", "image/svg+xml"},
                                                                {"png", "image/png"},
                                                                {"ico", "image/x-icon"},
                                                                {"woff2", "font/woff2"},
                                                                {"txt", "text/plain; charset=utf-8"},
                                                                {"yaml", "application/yaml; charset=utf-8"}};
  const auto it = types.find(ext);
  return it == types.end() ? "application/octet-stream" : it->second;
}

}  // namespace

ApiResponse api_examples() {
  Json list = Json::array();
  for (const Example& e : examples()) {
    Json item = {{"name", e.name}, {"kind", e.kind}};
    if (!e.task.empty()) item["task"] = e.task;
    item["title"] = e.title;
    item["description"] = e.description;
    item["file"] = e.file;
    list.push_back(item);
  }
  return answer(io::json_text(Json{{"examples", list}}, 2) + '\n');
}

// Only a name from the embedded list: nothing a request says ever reaches the file system.
ApiResponse api_example(const std::string& name) {
  for (const Example& e : examples())
    if (e.name == name) return answer(std::string(e.text), "application/yaml; charset=utf-8");
  throw ApiError(ApiErrorKind::NotFound, "no example named '" + name + "'; GET /api/examples lists them");
}

ApiResponse api_health(const ServerConfig& config) {
  const Limits& l = config.limits;
  Json limits = {{"max_body_bytes", l.max_body_bytes},
                 {"max_points", l.max_points},
                 {"max_bodies", l.max_bodies},
                 {"max_steps", l.max_steps},
                 {"max_order", 5},
                 {"max_table_values", json_number(l.max_table_values)},
                 {"max_sections", l.max_sections},
                 {"max_fe_nodes", l.max_fe_nodes},
                 {"max_explain_points", l.max_explain_points},
                 {"max_explain_bodies", l.max_explain_bodies},
                 {"max_frames", l.max_frames},
                 {"max_pixels", l.max_pixels},
                 {"max_animation_pixels", json_number(l.max_animation_pixels)},
                 {"max_synthesis_top", l.max_synthesis_top},
                 {"max_synthesis_threads", l.max_synthesis_threads},
                 {"max_curve_samples", json_number(l.max_curve_samples)},
                 {"time_budget_seconds", json_number(l.time_budget_seconds)},
                 {"max_jobs", config.jobs->total()},
                 {"max_light_jobs", config.light_jobs->total()},
                 {"light_table_values", config.light_table_values},
                 {"queue_wait_seconds", json_number(config.queue_wait_seconds)}};
  Json j = {{"status", "ok"},
            {"version", kVersion},
            {"jobs",
             {{"running", config.jobs->in_use()}, {"waiting", config.jobs->waiting()}, {"max", config.jobs->total()}}},
            {"light_jobs",
             {{"running", config.light_jobs->in_use()},
              {"waiting", config.light_jobs->waiting()},
              {"max", config.light_jobs->total()}}},
            {"mp4", render::Animation::program_available("ffmpeg")},
            {"limits", limits}};
  return answer(io::json_text(j, 2) + '\n');
}

ApiResponse static_file(const std::string& path) {
  const std::string wanted = path == "/" ? "index.html" : path.substr(1);
  for (const EmbeddedFile& f : static_files())
    if (f.path == wanted) return answer(std::string(f.data), content_type_of(f.path));
  throw ApiError(ApiErrorKind::NotFound, "no page at " + path);
}

}  // namespace nbar::web
