// SPDX-License-Identifier: MIT
// The filters of the terrain graph (Jourdan 2008's chain, with the usual scale, smooth, terrace and
// blend). docs/generators.md.
#include "runnel/terrain/filters.hpp"

#include <algorithm>
#include <cmath>

namespace runnel {
namespace {

// `t` ↦ shape(t) on the heights mapped to [0, 1] by the input's own range, then mapped back.
template <typename Shape>
Heightmap reshape(const Heightmap& in, Shape shape) {
  Heightmap out = in;
  const double lo = in.min_height(), range = in.max_height() - lo;
  if (!(range > 0)) return out;
  for (float& v : out.h) v = static_cast<float>(lo + range * shape((v - lo) / range));
  return out;
}

Heightmap scale(const std::vector<const Heightmap*>& in, const std::map<std::string, double>& p) {
  Heightmap out = *in[0];
  for (float& v : out.h) v = static_cast<float>(v * p.at("factor") + p.at("offset"));
  return out;
}

Heightmap normalise_filter(const std::vector<const Heightmap*>& in,
                           const std::map<std::string, double>& p) {
  const double lo = p.at("min"), hi = p.at("max");
  Heightmap out = *in[0];
  const double a = in[0]->min_height(), range = in[0]->max_height() - a;
  for (float& v : out.h) v = static_cast<float>(range > 0 ? lo + (hi - lo) * (v - a) / range : lo);
  return out;
}

Heightmap power(const std::vector<const Heightmap*>& in, const std::map<std::string, double>& p) {
  const double e = p.at("exponent");
  return reshape(*in[0], [&](double t) { return std::pow(t, e); });
}

Heightmap smoothstep(const std::vector<const Heightmap*>& in,
                     const std::map<std::string, double>&) {
  return reshape(*in[0], [](double t) { return t * t * (3 - 2 * t); });
}

Heightmap abs_filter(const std::vector<const Heightmap*>& in,
                     const std::map<std::string, double>& p) {
  // |t − level|: a crease (a sharp valley) where the input crossed `level`.
  const double level = p.at("level"), span = std::max(level, 1 - level);
  return reshape(*in[0], [&](double t) { return std::fabs(t - level) / span; });
}

Heightmap smooth(const std::vector<const Heightmap*>& in, const std::map<std::string, double>& p) {
  Heightmap out = *in[0];
  const int nx = out.nx, ny = out.ny;
  std::vector<float> next(out.h.size());
  for (int pass = 0; pass < static_cast<int>(p.at("passes")); ++pass) {
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        double sum = 0;
        int count = 0;
        for (int b = std::max(0, j - 1); b <= std::min(ny - 1, j + 1); ++b)
          for (int a = std::max(0, i - 1); a <= std::min(nx - 1, i + 1); ++a)
            sum += out.at(a, b), ++count;
        next[static_cast<std::size_t>(j) * nx + i] = static_cast<float>(sum / count);
      }
    out.h.swap(next);
  }
  return out;
}

Heightmap terrace(const std::vector<const Heightmap*>& in, const std::map<std::string, double>& p) {
  // `steps` flat treads; within each step the rise is squeezed into its last (1 − sharpness).
  const double steps = p.at("steps"), sharp = p.at("sharpness");
  return reshape(*in[0], [&](double t) {
    const double k = std::min(std::floor(t * steps), steps - 1), f = t * steps - k;
    return (k + std::clamp((f - sharp) / std::max(1e-9, 1 - sharp), 0.0, 1.0)) / steps;
  });
}

Heightmap blend(const std::vector<const Heightmap*>& in, const std::map<std::string, double>&) {
  // a·(1 − w) + b·w with w the mask mapped to [0, 1] by its own range.
  const Heightmap &a = *in[0], &b = *in[1], &mask = *in[2];
  const double lo = mask.min_height(), range = mask.max_height() - lo;
  Heightmap out = a;
  for (std::size_t k = 0; k < out.h.size(); ++k) {
    const double w = range > 0 ? (mask.h[k] - lo) / range : 0.5;
    out.h[k] = static_cast<float>(a.h[k] * (1 - w) + b.h[k] * w);
  }
  return out;
}

template <typename Combine>
Heightmap per_vertex(const std::vector<const Heightmap*>& in, Combine combine) {
  Heightmap out = *in[0];
  std::vector<float> values(in.size());
  for (std::size_t k = 0; k < out.h.size(); ++k) {
    for (std::size_t m = 0; m < in.size(); ++m) values[m] = in[m]->h[k];
    out.h[k] = combine(values);
  }
  return out;
}

Heightmap max_filter(const std::vector<const Heightmap*>& in,
                     const std::map<std::string, double>&) {
  return per_vertex(in,
                    [](std::vector<float>& v) { return *std::max_element(v.begin(), v.end()); });
}
Heightmap min_filter(const std::vector<const Heightmap*>& in,
                     const std::map<std::string, double>&) {
  return per_vertex(in,
                    [](std::vector<float>& v) { return *std::min_element(v.begin(), v.end()); });
}
Heightmap add(const std::vector<const Heightmap*>& in, const std::map<std::string, double>&) {
  return per_vertex(in, [](std::vector<float>& v) {
    double s = 0;
    for (float x : v) s += x;
    return static_cast<float>(s);
  });
}
Heightmap median(const std::vector<const Heightmap*>& in, const std::map<std::string, double>&) {
  return per_vertex(in, [](std::vector<float>& v) {
    std::sort(v.begin(), v.end());
    const std::size_t m = v.size() / 2;
    return v.size() % 2 ? v[m] : 0.5f * (v[m - 1] + v[m]);
  });
}

}  // namespace

const std::vector<FilterSpec>& filters() {
  static const std::vector<FilterSpec> specs = {
      {"scale",
       "h·factor + offset",
       1,
       1,
       {{"factor", 1.0, "1", "multiplies the heights", -1e6, 1e6},
        {"offset", 0.0, "m", "then added", -1e7, 1e7}},
       scale},
      {"normalise",
       "heights mapped linearly onto [min, max]",
       1,
       1,
       {{"min", 0.0, "m", "lowest height", -1e7, 1e7},
        {"max", 100.0, "m", "highest height", -1e7, 1e7}},
       normalise_filter},
      {"power",
       "t^exponent (t the height in [0, 1] of the input's range): flat valleys, steep peaks",
       1,
       1,
       {{"exponent", 2.0, "1", "exponent p", 0.01, 100.0}},
       power},
      {"smoothstep",
       "t²(3 − 2t): flattens the lowest and the highest ground",
       1,
       1,
       {},
       smoothstep},
      {"abs",
       "|t − level|: creases where the input crossed level",
       1,
       1,
       {{"level", 0.5, "1", "the level folded to 0, in [0, 1] of the input's range", 0.0, 1.0}},
       abs_filter},
      {"smooth",
       "passes of a 3 × 3 box filter",
       1,
       1,
       {{"passes", 1, "1", "number of passes", 0, 10000}},
       smooth},
      {"terrace",
       "flat steps",
       1,
       1,
       {{"steps", 8, "1", "number of steps", 1, 10000},
        {"sharpness", 0.7, "1", "share of each step that is flat", 0.0, 0.999}},
       terrace},
      {"blend",
       "a·(1 − w) + b·w, w the third input (the mask) in [0, 1] of its range",
       3,
       3,
       {},
       blend},
      {"max", "per vertex, the highest of the inputs", 2, 64, {}, max_filter},
      {"min", "per vertex, the lowest of the inputs", 2, 64, {}, min_filter},
      {"median", "per vertex, the median of the inputs", 2, 64, {}, median},
      {"add", "per vertex, the sum of the inputs", 2, 64, {}, add},
  };
  return specs;
}

const FilterSpec* find_filter(const std::string& name) {
  for (const FilterSpec& f : filters())
    if (f.name == name) return &f;
  return nullptr;
}

}  // namespace runnel
