// SPDX-License-Identifier: MIT
#include "runnel/io/plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "runnel/core/error.hpp"

namespace runnel {
namespace {

// Tick spacing of 1, 2 or 5 × 10^k giving about `target` intervals over [lo, hi].
double tick_step(double lo, double hi, int target) {
  const double raw = (hi - lo) / target;
  const double base = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0}) {
    if (m * base >= raw) return m * base;
  }
  return 10.0 * base;
}

std::string tick_label(double v, double step) {
  char buf[32];
  const int decimals = std::max(0, static_cast<int>(-std::floor(std::log10(step) + 1e-9)));
  if (std::fabs(v) >= 1e5 || (v != 0 && std::fabs(v) < 1e-3))
    std::snprintf(buf, sizeof buf, "%.1e", v);
  else
    std::snprintf(buf, sizeof buf, "%.*f", decimals, std::fabs(v) < 0.5 * step ? 0.0 : v);
  return buf;
}

// Bresenham line, 2 pixels wide.
void draw_line(RgbImage& img, int x0, int y0, int x1, int y1, PlotColour c) {
  const int dx = std::abs(x1 - x0), dy = -std::abs(y1 - y0);
  const int sx = x0 < x1 ? 1 : -1, sy = y0 < y1 ? 1 : -1;
  int err = dx + dy;
  for (int guard = 0; guard < 100000; ++guard) {
    img.set(x0, y0, c.r, c.g, c.b);
    img.set(x0 + 1, y0, c.r, c.g, c.b);
    img.set(x0, y0 + 1, c.r, c.g, c.b);
    if (x0 == x1 && y0 == y1) break;
    const int e2 = 2 * err;
    if (e2 >= dy) err += dy, x0 += sx;
    if (e2 <= dx) err += dx, y0 += sy;
  }
}

void draw_marker(RgbImage& img, int x, int y, PlotColour c) {
  for (int a = -4; a <= 4; ++a) {
    for (int b = -4; b <= 4; ++b) {
      const bool edge = std::abs(a) >= 3 || std::abs(b) >= 3;
      if (edge) img.set(x + a, y + b, c.r, c.g, c.b);
    }
  }
}

}  // namespace

void Plot::line(const std::vector<double>& x, const std::vector<double>& y, PlotColour colour,
                const std::string& label) {
  series_.push_back({x, y, colour, label, true});
}

void Plot::points(const std::vector<double>& x, const std::vector<double>& y, PlotColour colour,
                  const std::string& label) {
  series_.push_back({x, y, colour, label, false});
}

RgbImage Plot::render(int width, int height) const {
  double x_lo = INFINITY, x_hi = -INFINITY, y_lo = INFINITY, y_hi = -INFINITY;
  for (const Series& s : series_) {
    for (std::size_t k = 0; k < std::min(s.x.size(), s.y.size()); ++k) {
      if (!std::isfinite(s.x[k]) || !std::isfinite(s.y[k])) continue;
      x_lo = std::min(x_lo, s.x[k]), x_hi = std::max(x_hi, s.x[k]);
      y_lo = std::min(y_lo, s.y[k]), y_hi = std::max(y_hi, s.y[k]);
    }
  }
  if (!(x_hi > x_lo)) x_lo -= 0.5, x_hi += 0.5;
  if (!(y_hi > y_lo)) y_lo -= 0.5, y_hi += 0.5;
  const double px = 0.05 * (x_hi - x_lo), py = 0.05 * (y_hi - y_lo);
  x_lo -= px, x_hi += px, y_lo -= py, y_hi += py;

  RgbImage img(width, height);
  const int left = 110, right = width - 30, top = 50, bottom = height - 80;
  auto to_px = [&](double x) {
    return left + static_cast<int>((x - x_lo) / (x_hi - x_lo) * (right - left));
  };
  auto to_py = [&](double y) {
    return bottom - static_cast<int>((y - y_lo) / (y_hi - y_lo) * (bottom - top));
  };
  draw_text(img, left, 14, title_, 2);
  const PlotColour grid{225, 225, 225}, axis{60, 60, 60};
  const double xs = tick_step(x_lo, x_hi, 8), ys = tick_step(y_lo, y_hi, 6);
  for (double t = std::ceil(x_lo / xs) * xs; t <= x_hi; t += xs) {
    const int X = to_px(t);
    for (int Y = top; Y <= bottom; ++Y) img.set(X, Y, grid.r, grid.g, grid.b);
    const std::string l = tick_label(t, xs);
    draw_text(img, X - text_width(l, 2) / 2, bottom + 8, l, 2, axis.r, axis.g, axis.b);
  }
  for (double t = std::ceil(y_lo / ys) * ys; t <= y_hi; t += ys) {
    const int Y = to_py(t);
    for (int X = left; X <= right; ++X) img.set(X, Y, grid.r, grid.g, grid.b);
    const std::string l = tick_label(t, ys);
    draw_text(img, left - 8 - text_width(l, 2), Y - 7, l, 2, axis.r, axis.g, axis.b);
  }
  draw_line(img, left, bottom, right, bottom, {axis.r, axis.g, axis.b});
  draw_line(img, left, top, left, bottom, {axis.r, axis.g, axis.b});
  draw_text(img, (left + right - text_width(x_label_, 2)) / 2, bottom + 36, x_label_, 2);
  draw_text(img, 8, top - 24, y_label_, 2);

  int legend_y = top + 8;
  for (const Series& s : series_) {
    const std::size_t n = std::min(s.x.size(), s.y.size());
    for (std::size_t k = 0; k < n; ++k) {
      if (!std::isfinite(s.x[k]) || !std::isfinite(s.y[k])) continue;
      if (s.connected && k > 0 && std::isfinite(s.x[k - 1]) && std::isfinite(s.y[k - 1]))
        draw_line(img, to_px(s.x[k - 1]), to_py(s.y[k - 1]), to_px(s.x[k]), to_py(s.y[k]),
                  s.colour);
      if (!s.connected) draw_marker(img, to_px(s.x[k]), to_py(s.y[k]), s.colour);
    }
    const int lx = left + 16;
    if (s.connected)
      draw_line(img, lx, legend_y + 7, lx + 30, legend_y + 7, s.colour);
    else
      draw_marker(img, lx + 15, legend_y + 7, s.colour);
    draw_text(img, lx + 40, legend_y, s.label, 2, s.colour.r, s.colour.g, s.colour.b);
    legend_y += 24;
  }
  return img;
}

void Plot::write(const std::string& path) const {
  write_png_rgb(path, render());
}

}  // namespace runnel
