// Moving pictures of a sweep: an animated GIF, an SVG animated with SMIL, a self-contained HTML
// page with play, pause and a slider, and an MP4 video made by the ffmpeg program.
//
// Every format shows the same frames: `frames` evenly spaced samples of the sweep (by default
// every sample, at most 120), on one view that fits every pose, `fps` frames a second. When the
// sweep ends where it began (a crank turned through a whole turn) its last sample is left out,
// so that the loop does not stop for a frame.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "nbar/analysis/analysis.hpp"
#include "nbar/kinematics/sweep.hpp"
#include "nbar/model/run_control.hpp"
#include "nbar/render/drawing.hpp"
#include "nbar/render/image_canvas.hpp"

namespace nbar::render {

class Animation {
 public:
  // Shares the mechanism and keeps the positions of the sweep (not the sweep itself), so it may
  // outlive both the caller's pointer and the SweepResult. frames <= 0: the default.
  // Throws Error(ErrorKind::BadInput) when the sweep has no sample or fps is not positive.
  Animation(std::shared_ptr<const Mechanism> mech, const SweepResult& sweep, const DrawOptions& options, int frames = 0,
            double fps = 24.0);

  static constexpr int kDefaultMaxFrames = 120;

  // Checked between frames by every writer (stage "frames"): a cancelled control or a passed
  // deadline stops the writer with Error(ErrorKind::Cancelled), and no file is left behind.
  void set_control(RunControl control) { control_ = std::move(control); }

  // Colours every link with a shape by its von Mises stress in every frame (the analysis's
  // finite-element stage, which must have solved this sweep), on one scale for the whole sweep:
  // the colours change as the loads do. Only GIF and MP4 draw frames whole: the SVG and HTML
  // writers then throw Error(ErrorKind::BadInput). Throws Error(BadInput) without that stage.
  void show_stresses(const Analysis& analysis);
  bool shows_stresses() const { return !frame_stress_.empty(); }

  int frame_count() const { return static_cast<int>(steps_.size()); }
  const std::vector<int>& steps() const { return steps_; }  // the sample shown by each frame
  bool periodic() const { return periodic_; }               // the last frame runs on into the first
  double fps() const { return fps_; }
  double duration() const { return frame_count() / fps_; }  // s, one loop
  const View& view() const { return view_; }

  // One frame, drawn whole.
  ImageCanvas render_frame(int frame, bool antialias = true) const;

  // Each writer throws Error(ErrorKind::Internal) naming the file when it cannot be written.
  // GIF: frames drawn without antialiasing, one palette of the colours used, looping forever.
  void write_gif(const std::string& path) const;
  std::vector<std::uint8_t> gif_bytes() const;
  // SVG: drawn once at the first frame; every body group moved by animateTransform.
  std::string svg_animation() const;
  void write_svg_animation(const std::string& path) const;
  // HTML: the SVG drawn once and moved by a script; play/pause, a slider, a frame counter and
  // the time and driver values of the frame. Needs nothing from the network.
  std::string html_animation() const;
  void write_html_animation(const std::string& path) const;
  // MP4 (H.264 by ffmpeg's defaults, yuv420p). Throws Error(ErrorKind::Internal) when the ffmpeg
  // program is not on the PATH.
  void write_mp4(const std::string& path) const;
  std::vector<std::uint8_t> mp4_bytes() const;

  // Whether a program of that name is on the PATH.
  static bool program_available(const std::string& name);

 private:
  // Per frame and body, the motion from the first frame, with angles made continuous; one
  // more entry than frames: where the last frame goes on to (the first again, or itself).
  std::vector<std::vector<PixelTransform>> transforms() const;
  std::vector<std::string> body_group_ids() const;
  std::string readout(int frame) const;

  std::shared_ptr<const Mechanism> mechanism_;
  const Mechanism& mech_;
  SweepResult sweep_;  // the positions of every sample (Taylor coefficients of order 0 only)
  DrawOptions options_;
  double fps_;
  View view_;
  bool periodic_ = false;
  std::vector<int> steps_;
  std::vector<std::vector<Eigen::Vector2d>> points_;  // per frame
  RunControl control_;
  std::vector<std::vector<StressMap>> frame_stress_;  // per frame, when show_stresses was called
  std::vector<std::vector<Marker>> frame_markers_;    // the options' markers and each frame's peaks
};

}  // namespace nbar::render
