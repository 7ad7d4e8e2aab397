// SPDX-License-Identifier: MIT
#pragma once
#include <string>
#include <vector>

#include "runnel/io/images.hpp"

namespace runnel {

struct PlotColour {
  unsigned char r, g, b;
};
inline constexpr PlotColour kPlotReference{20, 20, 20};    // measurements, analytic values
inline constexpr PlotColour kPlotSimulation{200, 60, 30};  // runnel
inline constexpr PlotColour kPlotSecondary{40, 90, 200};   // a second series or reading
inline constexpr PlotColour kPlotPeer{30, 150, 60};        // another code's result
// The k-th of several series of one kind (the runs of a case, the models of a comparison),
// starting with the three above and cycling through nine.
inline PlotColour plot_series_colour(std::size_t k) {
  static constexpr PlotColour kSeries[] = {kPlotSimulation, kPlotSecondary, kPlotPeer,
                                           {150, 60, 170},  {220, 150, 20}, {20, 160, 170},
                                           {120, 120, 120}, {170, 40, 90},  {90, 60, 20}};
  return kSeries[k % (sizeof kSeries / sizeof kSeries[0])];
}

// A small x–y chart for validation figures (front.png, pressure.png): axes with round ticks,
// lines and marked points, a legend. The axes span every series given, with 5 % padding.
class Plot {
 public:
  Plot(std::string title, std::string x_label, std::string y_label)
      : title_(std::move(title)), x_label_(std::move(x_label)), y_label_(std::move(y_label)) {}
  // A polyline through the points, in order.
  void line(const std::vector<double>& x, const std::vector<double>& y, PlotColour colour,
            const std::string& label);
  // Marked points (small squares), unconnected.
  void points(const std::vector<double>& x, const std::vector<double>& y, PlotColour colour,
              const std::string& label);
  RgbImage render(int width = 900, int height = 640) const;
  void write(const std::string& path) const;

 private:
  struct Series {
    std::vector<double> x, y;
    PlotColour colour;
    std::string label;
    bool connected;
  };
  std::string title_, x_label_, y_label_;
  std::vector<Series> series_;
};

}  // namespace runnel
