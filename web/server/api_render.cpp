// The pictures: /api/render draws one pose, animates the sweep, plots columns or writes the
// links' plates for cutting.
#include "endpoints.hpp"
#include "nbar/render/animation.hpp"
#include "nbar/render/image_canvas.hpp"
#include "nbar/render/pictures.hpp"
#include "nbar/render/plot.hpp"
#include "nbar/render/scene.hpp"
#include "nbar/render/stress_map.hpp"
#include "nbar/request/requests.hpp"

namespace nbar::web {

namespace {

// The picture's size within this server's limit.
void check_picture_size(const Job& job, int width, int height) {
  check_limit("pixels", width, job.limits.max_pixels, "width");
  check_limit("pixels", height, job.limits.max_pixels, "height");
}

// A PNG or GIF where this build draws none (the WebAssembly engine: the browser draws them).
void check_raster_format(const std::string& format) {
  if (render::raster_pictures_available()) return;
  throw ApiError(ApiErrorKind::NotImplemented,
                 format + " pictures are drawn by the native nbar program (nbar serve); this engine draws SVG, HTML, " +
                     "the web app's scene and DXF");
}

// The links' plates for cutting, as `nbar export --dxf/--svg [--at]` writes them.
ApiResponse render_plates(Job& job, const std::string& text) {
  const RequestBody body(text, request::ExportRequest::rules(), {"model", "kind"});
  const auto plates = read_request<request::ExportRequest>(body, {"model", "kind"});
  load_model(job, body.text("model", true));
  const Mechanism& mech = *job.mechanism;
  job.start(Weight::Light);
  const std::string drawing = plates.plates(mech, plates.points(mech, job.control));
  return answer(drawing, plates.format == "dxf" ? "image/vnd.dxf" : "image/svg+xml");
}

ApiResponse render_draw(Job& job, const std::string& text) {
  const RequestBody body(text, request::DrawRequest::rules(), {"model", "kind"});
  const auto draw = read_request<request::DrawRequest>(body, {"model", "kind"});
  if (draw.format == "png") check_raster_format("PNG");
  load_model(job, body.text("model", true));
  check_picture_size(job, draw.picture.width, draw.picture.height);
  const Mechanism& mech = *job.mechanism;
  render::DrawOptions options = draw.picture.draw_options(mech.model());
  check_sweep_size(job, draw.sweep.steps);
  AnalysisOptions analysis_options = draw.analysis_options(mech.model());
  analysis_options.fe.max_nodes = job.limits.max_fe_nodes;
  // A scene carries every sample's positions: a table as large as a solve's of positions.
  if (draw.format == "scene") check_table_size(job, analysis_options);
  const Analysis analysis = run_analysis(job, analysis_options);
  // A stress map and a scene are refused at `at` (DrawRequest::read): their pose is a sample.
  const request::DrawRequest::Pose pose = draw.pose(analysis, job.control);
  if (draw.stress) render::add_stress_maps(options, analysis, pose.step.value());
  job.checkpoint("render");
  if (draw.format == "scene")
    return answer(render::drawing_scene_json(mech, analysis.sweep, options, pose.step.value()));
  if (draw.format == "svg")
    return answer(render::drawing_svg(mech, analysis.sweep, pose.points, options), "image/svg+xml");
  return answer_bytes(render::drawing_png(mech, analysis.sweep, pose.points, options), "image/png");
}

ApiResponse render_animate(Job& job, const std::string& text) {
  const RequestBody body(text, request::AnimateRequest::rules(), {"model", "kind"});
  const auto animate = read_request<request::AnimateRequest>(body, {"model", "kind"});
  if (animate.format == "gif" || animate.format == "mp4") check_raster_format(animate.format == "gif" ? "GIF" : "MP4");
  if (animate.format == "mp4" && !render::Animation::program_available("ffmpeg"))
    throw ApiError(
        ApiErrorKind::NotImplemented,
        "MP4 needs the ffmpeg program on the server (apt-get install ffmpeg); GIF, SVG and HTML work without it");
  load_model(job, body.text("model", true));
  check_picture_size(job, animate.picture.width, animate.picture.height);
  const render::DrawOptions draw = animate.picture.draw_options(job.mechanism->model());
  if (animate.frames)
    check_limit("frames", static_cast<double>(*animate.frames), job.limits.max_frames, "the number of frames");
  check_sweep_size(job, animate.sweep.steps);
  job.start(Weight::Heavy);  // the frames
  AnalysisOptions analysis_options = animate.analysis_options(job.mechanism->model());
  analysis_options.fe.max_nodes = job.limits.max_fe_nodes;
  const Analysis analysis = run_analysis(job, analysis_options);
  if (analysis.sweep.samples.empty()) bad_input("the sweep has no sample to show");
  render::Animation animation(analysis.mechanism, analysis.sweep, draw, animate.frames.value_or(0), animate.fps);
  animation.set_control(job.control);  // every format checks the deadline between frames
  check_limit("animation_pixels", static_cast<double>(animation.frame_count()) * draw.width * draw.height,
              job.limits.max_animation_pixels, "frames x width x height");
  if (animate.stress) animation.show_stresses(analysis);
  job.checkpoint("render");
  if (animate.format == "gif") return answer_bytes(animation.gif_bytes(), "image/gif");
  if (animate.format == "svg") return answer(animation.svg_animation(), "image/svg+xml");
  if (animate.format == "html") return answer_html(animation.html_animation());
  return answer_bytes(animation.mp4_bytes(), "video/mp4");
}

ApiResponse render_plot(Job& job, const std::string& text) {
  const RequestBody body(text, request::PlotRequest::rules(), {"model", "kind"});
  const auto plot = read_request<request::PlotRequest>(body, {"model", "kind"});
  if (plot.format == "png") check_raster_format("PNG");
  load_model(job, body.text("model", true));
  check_picture_size(job, plot.width, plot.height);
  const AnalysisOptions options = plot.analysis_options(*job.mechanism);
  check_sweep_size(job, plot.sweep.steps);
  check_table_size(job, options);
  const Analysis analysis = run_analysis(job, options);
  const render::PlotSpec spec = plot.plot(analysis, kModelFile);
  job.checkpoint("render");
  if (plot.format == "svg") {
    render::SvgCanvas canvas(spec.width, spec.height);
    render::draw_plot(canvas, spec);
    return answer(canvas.document(), "image/svg+xml");
  }
  render::ImageCanvas canvas(spec.width, spec.height);
  render::draw_plot(canvas, spec);
  return answer_bytes(canvas.png_bytes(), "image/png");
}

}  // namespace

ApiResponse api_render(Job& job, const std::string& request) {
  // The kind decides which options are known; read it first, leniently.
  std::string kind = "draw";
  try {
    const nlohmann::json j = parse_request(request);
    if (j.is_object() && j.contains("kind")) {
      if (!j["kind"].is_string()) bad_input("'kind' must be draw, animate, plot or plates");
      kind = j["kind"].get<std::string>();
    }
  } catch (const nlohmann::json::exception&) {
    // Body reports it, with its place when there is one.
  }
  if (kind == "draw") return render_draw(job, request);
  if (kind == "animate") return render_animate(job, request);
  if (kind == "plot") return render_plot(job, request);
  if (kind == "plates") return render_plates(job, request);
  bad_input("'kind' must be draw, animate, plot or plates; it is '" + kind + "'");
}

}  // namespace nbar::web
