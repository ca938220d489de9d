#include "runtime/image/log_log_plot.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>

#include "engine/core/error.h"
#include "engine/core/log.h"

namespace lantern::runtime {
namespace {

namespace fs = std::filesystem;

constexpr const char* kFont = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";

struct Axis {
  double lo_decade = 0.0;  // floor(log10(min))
  double hi_decade = 1.0;  // ceil(log10(max))
  int pixel_lo = 0;
  int pixel_hi = 1;
  int to_pixel(double v) const {
    const double t = (std::log10(v) - lo_decade) / (hi_decade - lo_decade);
    return static_cast<int>(std::lround(pixel_lo + t * (pixel_hi - pixel_lo)));
  }
};

Axis make_axis(double lo, double hi, int pixel_lo, int pixel_hi) {
  Axis a;
  a.lo_decade = std::floor(std::log10(lo));
  a.hi_decade = std::ceil(std::log10(hi));
  if (a.hi_decade <= a.lo_decade) a.hi_decade = a.lo_decade + 1.0;
  a.pixel_lo = pixel_lo;
  a.pixel_hi = pixel_hi;
  return a;
}

bool usable(double v) { return std::isfinite(v) && v > 0.0; }

}  // namespace

void write_log_log_plot(const fs::path& path, const LogLogPlot& plot, int width, int height) {
  double x_lo = 1e300, x_hi = 0.0, y_lo = 1e300, y_hi = 0.0;
  for (const PlotPoint& p : plot.points) {
    if (!usable(p.x) || !usable(p.y)) continue;
    x_lo = std::min(x_lo, p.x);
    x_hi = std::max(x_hi, p.x);
    y_lo = std::min(y_lo, p.y);
    y_hi = std::max(y_hi, p.y);
  }
  if (x_hi == 0.0) throw InputError(fmt::format("{}: no positive point to plot", path.string()));
  const bool text = fs::exists(kFont);
  if (!text) log::warn("{} not found (Debian: fonts-dejavu-core): plot without text", kFont);

  const int left = 90, right = width - 170, top = 50, bottom = height - 60;
  const Axis ax = make_axis(x_lo, x_hi, left, right);
  const Axis ay = make_axis(y_lo, y_hi, bottom, top);  // up is larger
  OIIO::ImageBuf img(OIIO::ImageSpec(width, height, 3, OIIO::TypeDesc::UINT8));
  const float white[3] = {1.0f, 1.0f, 1.0f}, grid[3] = {0.88f, 0.88f, 0.88f},
              ink[3] = {0.1f, 0.1f, 0.1f}, front[3] = {0.85f, 0.25f, 0.1f},
              dot[3] = {0.15f, 0.35f, 0.75f};
  OIIO::ImageBufAlgo::fill(img, white);
  auto label = [&](int x, int y, const std::string& s, int size, const float* color,
                   OIIO::ImageBufAlgo::TextAlignX align = OIIO::ImageBufAlgo::TextAlignX::Left) {
    if (text) {
      OIIO::ImageBufAlgo::render_text(img, x, y, s, size, kFont, {color, 3}, align);
    }
  };
  // Decade grid and tick labels.
  for (double d = ax.lo_decade; d <= ax.hi_decade + 1e-9; d += 1.0) {
    const int x = ax.to_pixel(std::pow(10.0, d));
    OIIO::ImageBufAlgo::render_line(img, x, top, x, bottom, {grid, 3});
    label(x, bottom + 20, fmt::format("1e{:g}", d), 14, ink, OIIO::ImageBufAlgo::TextAlignX::Center);
  }
  for (double d = ay.lo_decade; d <= ay.hi_decade + 1e-9; d += 1.0) {
    const int y = ay.to_pixel(std::pow(10.0, d));
    OIIO::ImageBufAlgo::render_line(img, left, y, right, y, {grid, 3});
    label(left - 8, y + 5, fmt::format("1e{:g}", d), 14, ink, OIIO::ImageBufAlgo::TextAlignX::Right);
  }
  OIIO::ImageBufAlgo::render_box(img, left, top, right, bottom, {ink, 3});
  label(width / 2, 30, plot.title, 18, ink, OIIO::ImageBufAlgo::TextAlignX::Center);
  label((left + right) / 2, height - 18, plot.x_label, 15, ink,
        OIIO::ImageBufAlgo::TextAlignX::Center);
  label(10, top - 12, plot.y_label, 15, ink);

  // The front, then the points and their labels.
  for (std::size_t i = 1; i < plot.line.size(); ++i) {
    const auto [x0, y0] = plot.line[i - 1];
    const auto [x1, y1] = plot.line[i];
    if (!usable(x0) || !usable(y0) || !usable(x1) || !usable(y1)) continue;
    for (int w = -1; w <= 1; ++w) {
      OIIO::ImageBufAlgo::render_line(img, ax.to_pixel(x0), ay.to_pixel(y0) + w, ax.to_pixel(x1),
                                      ay.to_pixel(y1) + w, {front, 3});
    }
  }
  for (const PlotPoint& p : plot.points) {
    if (!usable(p.x) || !usable(p.y)) continue;
    const int x = ax.to_pixel(p.x), y = ay.to_pixel(p.y);
    const int r = p.highlighted ? 6 : 4;
    OIIO::ImageBufAlgo::render_box(img, x - r, y - r, x + r, y + r,
                                   {p.highlighted ? front : dot, 3}, true);
    label(x + 10, y - 6, p.label, 14, ink);
  }

  const fs::path dir = path.has_parent_path() ? path.parent_path() : fs::path(".");
  const fs::path temp = dir / fmt::format(".{}.{}.partial", path.filename().string(), getpid());
  OIIO::ImageSpec& spec = img.specmod();
  spec.attribute("DateTime", "");
  if (!img.write(temp.string(), OIIO::TypeDesc::UINT8, "png")) {
    std::error_code ignored;
    fs::remove(temp, ignored);
    throw RuntimeError(fmt::format("{}: could not write plot: {}", path.string(), img.geterror()));
  }
  std::error_code ec;
  fs::rename(temp, path, ec);
  if (ec) {
    fs::remove(temp, ec);
    throw RuntimeError(fmt::format("{}: could not move plot into place", path.string()));
  }
}

}  // namespace lantern::runtime
