// The GIF writer of Animation, with cgif: the one part of the animations that needs a raster
// image library (the WebAssembly build has none: render/raster_unavailable.cpp stands for it).
#include <cgif.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <unordered_map>
#include <utility>

#include "nbar/model/diagnostics.hpp"
#include "nbar/render/animation.hpp"

namespace nbar::render {

namespace {

std::uint32_t rgb_at(const std::uint8_t* p) {
  return (std::uint32_t{p[2]} << 16) | (std::uint32_t{p[1]} << 8) | std::uint32_t{p[0]};
}

int colour_distance(std::uint32_t a, std::uint32_t b) {
  const int dr = static_cast<int>((a >> 16) & 0xff) - static_cast<int>((b >> 16) & 0xff);
  const int dg = static_cast<int>((a >> 8) & 0xff) - static_cast<int>((b >> 8) & 0xff);
  const int db = static_cast<int>(a & 0xff) - static_cast<int>(b & 0xff);
  return 3 * dr * dr + 4 * dg * dg + 2 * db * db;  // rough perceptual weights
}

// A palette of at most 255 colours (one index stays free for cgif's transparency optimisation):
// the most used colours, and for every colour the index of the nearest one.
class Palette {
 public:
  void count(const ImageCanvas& image) {
    const std::uint8_t* data = image.data();
    for (int y = 0; y < image.height(); ++y) {
      const std::uint8_t* row = data + static_cast<std::ptrdiff_t>(y) * image.stride();
      std::uint32_t run_colour = rgb_at(row);
      std::uint64_t run = 0;
      for (int x = 0; x < image.width(); ++x) {
        const std::uint32_t c = rgb_at(row + 4 * x);
        if (c != run_colour) {
          counts_[run_colour] += run;
          run_colour = c;
          run = 0;
        }
        ++run;
      }
      counts_[run_colour] += run;
    }
  }

  void build() {
    std::vector<std::pair<std::uint64_t, std::uint32_t>> by_use;
    for (const auto& [colour, n] : counts_) by_use.push_back({n, colour});
    std::sort(by_use.begin(), by_use.end(), [](const auto& a, const auto& b) {
      return a.first != b.first ? a.first > b.first : a.second < b.second;
    });
    if (by_use.size() > kMaxColours) by_use.resize(kMaxColours);
    for (const auto& [n, colour] : by_use) {
      index_[colour] = static_cast<std::uint8_t>(colours_.size());
      colours_.push_back(colour);
    }
    if (colours_.empty()) colours_.push_back(0xffffff);
  }

  std::uint8_t index(std::uint32_t colour) {
    if (auto it = index_.find(colour); it != index_.end()) return it->second;
    std::size_t best = 0;
    int best_distance = std::numeric_limits<int>::max();
    for (std::size_t i = 0; i < colours_.size(); ++i) {
      const int d = colour_distance(colour, colours_[i]);
      if (d < best_distance) best_distance = d, best = i;
    }
    return index_[colour] = static_cast<std::uint8_t>(best);
  }

  std::vector<std::uint8_t> rgb_table() const {
    std::vector<std::uint8_t> table;
    for (std::uint32_t c : colours_) {
      table.push_back(static_cast<std::uint8_t>(c >> 16));
      table.push_back(static_cast<std::uint8_t>(c >> 8));
      table.push_back(static_cast<std::uint8_t>(c));
    }
    return table;
  }
  std::size_t size() const { return colours_.size(); }

 private:
  static constexpr std::size_t kMaxColours = 255;
  std::unordered_map<std::uint32_t, std::uint64_t> counts_;
  std::unordered_map<std::uint32_t, std::uint8_t> index_;
  std::vector<std::uint32_t> colours_;
};

// cgif's output, gathered in memory.
int append_bytes(void* context, const std::uint8_t* data, const std::size_t size) {
  auto* out = static_cast<std::vector<std::uint8_t>*>(context);
  out->insert(out->end(), data, data + size);
  return 0;
}

}  // namespace

std::vector<std::uint8_t> Animation::gif_bytes() const {
  const int w = options_.width, h = options_.height;
  if (w > 65535 || h > 65535) throw Error(ErrorKind::BadInput, "a GIF is at most 65535 pixels wide and high");
  // Two passes: the colours of every frame, then the frames in that palette. Without
  // antialiasing the colours are those drawn and the blends of translucent plates.
  Palette palette;
  for (int k = 0; k < frame_count(); ++k) {
    control_.checkpoint("frames", k, 2L * frame_count());
    palette.count(render_frame(k, false));
  }
  palette.build();
  std::vector<std::uint8_t> table = palette.rgb_table();

  CGIF_Config config;
  std::memset(&config, 0, sizeof config);
  config.pGlobalPalette = table.data();
  config.numGlobalPaletteEntries = static_cast<std::uint16_t>(palette.size());
  std::vector<std::uint8_t> bytes;
  config.pWriteFn = &append_bytes;
  config.pContext = &bytes;
  config.attrFlags = CGIF_ATTR_IS_ANIMATED;
  config.numLoops = CGIF_INFINITE_LOOP;
  config.width = static_cast<std::uint16_t>(w);
  config.height = static_cast<std::uint16_t>(h);
  CGIF* gif = cgif_newgif(&config);
  const std::string failure = "cannot make the GIF";
  if (!gif) throw Error(ErrorKind::Internal, failure);

  std::vector<std::uint8_t> indices(static_cast<std::size_t>(w) * h);
  int result = CGIF_OK;
  long shown_cs = 0;  // delays add up to the exact time, in hundredths of a second
  for (int k = 0; k < frame_count() && result == CGIF_OK; ++k) {
    if (control_.should_stop("frames", frame_count() + k, 2L * frame_count())) {
      cgif_close(gif);
      control_.throw_stopped("frames");
    }
    const ImageCanvas image = render_frame(k, false);
    const std::uint8_t* data = image.data();
    std::uint32_t last = 0xffffffff;
    std::uint8_t last_index = 0;
    for (int y = 0; y < h; ++y) {
      const std::uint8_t* row = data + static_cast<std::ptrdiff_t>(y) * image.stride();
      for (int x = 0; x < w; ++x) {
        const std::uint32_t c = rgb_at(row + 4 * x);
        if (c != last) last = c, last_index = palette.index(c);
        indices[static_cast<std::size_t>(y) * w + x] = last_index;
      }
    }
    const long until_cs = std::lround((k + 1) * 100.0 / fps_);
    const long delay = std::clamp(until_cs - shown_cs, 2L, 65535L);  // browsers slow delays below 2
    shown_cs += delay;
    CGIF_FrameConfig frame;
    std::memset(&frame, 0, sizeof frame);
    frame.pImageData = indices.data();
    frame.delay = static_cast<std::uint16_t>(delay);
    frame.genFlags = CGIF_FRAME_GEN_USE_TRANSPARENCY | CGIF_FRAME_GEN_USE_DIFF_WINDOW;
    result = cgif_addframe(gif, &frame);
  }
  const int closed = cgif_close(gif);
  if (result != CGIF_OK || closed != CGIF_OK) throw Error(ErrorKind::Internal, failure);
  return bytes;
}

}  // namespace nbar::render
