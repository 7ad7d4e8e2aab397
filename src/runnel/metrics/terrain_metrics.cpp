// SPDX-License-Identifier: MIT
#include "runnel/metrics/terrain_metrics.hpp"

#include "runnel/landscape/flow_routing.hpp"
#include "runnel/terrain/terrain_normals.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <numeric>

namespace runnel::metrics {
namespace {

constexpr int kDi[8] = {1, 1, 0, -1, -1, -1, 0, 1};
constexpr int kDj[8] = {0, 1, 1, 1, 0, -1, -1, -1};

// Least-squares slope of y on x.
double fit_slope(const std::vector<double>& x, const std::vector<double>& y) {
  const double n = static_cast<double>(x.size());
  const double mx = std::accumulate(x.begin(), x.end(), 0.0) / n,
               my = std::accumulate(y.begin(), y.end(), 0.0) / n;
  double sxy = 0, sxx = 0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    sxy += (x[k] - mx) * (y[k] - my);
    sxx += (x[k] - mx) * (x[k] - mx);
  }
  return sxx > 0 ? sxy / sxx : NAN;
}

std::vector<double> ranks(const std::vector<double>& v) {
  std::vector<std::size_t> order(v.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return v[a] < v[b]; });
  std::vector<double> r(v.size());
  for (std::size_t k = 0; k < order.size();) {  // ties share their mean rank
    std::size_t e = k;
    while (e + 1 < order.size() && v[order[e + 1]] == v[order[k]]) ++e;
    for (std::size_t m = k; m <= e; ++m) r[order[m]] = 0.5 * (k + e);
    k = e + 1;
  }
  return r;
}

// Spearman's rank correlation: Pearson's correlation of the ranks.
double spearman(const std::vector<double>& a, const std::vector<double>& b) {
  const auto ra = ranks(a), rb = ranks(b);
  const double m = (static_cast<double>(ra.size()) - 1) / 2.0;
  double num = 0, da = 0, db = 0;
  for (std::size_t k = 0; k < ra.size(); ++k) {
    num += (ra[k] - m) * (rb[k] - m);
    da += (ra[k] - m) * (ra[k] - m);
    db += (rb[k] - m) * (rb[k] - m);
  }
  return da > 0 && db > 0 ? num / std::sqrt(da * db) : NAN;
}

// In-place iterative radix-2 FFT (n a power of two).
void fft(std::vector<std::complex<double>>& a, bool inverse) {
  const std::size_t n = a.size();
  for (std::size_t i = 1, j = 0; i < n; ++i) {
    std::size_t bit = n >> 1;
    for (; j & bit; bit >>= 1) j ^= bit;
    j ^= bit;
    if (i < j) std::swap(a[i], a[j]);
  }
  for (std::size_t len = 2; len <= n; len <<= 1) {
    const double angle = 2 * M_PI / static_cast<double>(len) * (inverse ? 1 : -1);
    const std::complex<double> w(std::cos(angle), std::sin(angle));
    for (std::size_t i = 0; i < n; i += len) {
      std::complex<double> wn(1);
      for (std::size_t j = 0; j < len / 2; ++j) {
        const auto u = a[i + j], v = a[i + j + len / 2] * wn;
        a[i + j] = u + v;
        a[i + j + len / 2] = u - v;
        wn *= w;
      }
    }
  }
}

}  // namespace

double pearson_correlation(const std::vector<double>& a, const std::vector<double>& b) {
  double ma = 0, mb = 0;
  for (std::size_t k = 0; k < a.size(); ++k) ma += a[k], mb += b[k];
  ma /= a.size(), mb /= b.size();
  double sab = 0, saa = 0, sbb = 0;
  for (std::size_t k = 0; k < a.size(); ++k) {
    sab += (a[k] - ma) * (b[k] - mb);
    saa += (a[k] - ma) * (a[k] - ma);
    sbb += (b[k] - mb) * (b[k] - mb);
  }
  return saa > 0 && sbb > 0 ? sab / std::sqrt(saa * sbb) : 0.0;
}

double hypsometric_integral(const Heightmap& t) {
  const double lo = t.min_height(), hi = t.max_height();
  if (!(hi > lo)) return NAN;
  double mean = 0;
  for (float v : t.h) mean += v;
  mean /= static_cast<double>(t.size());
  return (mean - lo) / (hi - lo);
}

std::vector<double> slope_degrees(const Heightmap& t) {
  // The angle between the vertex normal (central differences) and the vertical.
  const std::vector<float> normal = terrain_normals_reference(t);
  std::vector<double> s(t.size());
  for (std::size_t k = 0; k < s.size(); ++k)
    s[k] = std::acos(std::clamp<double>(normal[3 * k + 1], -1, 1)) * 180.0 / M_PI;
  return s;
}

double mean_slope_degrees(const Heightmap& t) {
  const auto s = slope_degrees(t);
  return std::accumulate(s.begin(), s.end(), 0.0) / static_cast<double>(s.size());
}

std::vector<long long> slope_histogram(const Heightmap& t, double bin) {
  std::vector<long long> h(static_cast<std::size_t>(std::ceil(90.0 / bin)), 0);
  for (double s : slope_degrees(t)) h[std::min(h.size() - 1, static_cast<std::size_t>(s / bin))]++;
  return h;
}

double erosion_score(const Heightmap& t) {
  std::vector<double> s;
  for (int j = 1; j + 1 < t.ny; ++j) {
    for (int i = 1; i + 1 < t.nx; ++i) {
      const double h = t.at(i, j);
      s.push_back(std::max({std::fabs(h - t.at(i - 1, j)), std::fabs(h - t.at(i + 1, j)),
                            std::fabs(h - t.at(i, j - 1)), std::fabs(h - t.at(i, j + 1))}));
    }
  }
  if (s.empty()) return NAN;
  const double mean = std::accumulate(s.begin(), s.end(), 0.0) / static_cast<double>(s.size());
  double var = 0;
  for (double v : s) var += (v - mean) * (v - mean);
  return mean > 0 ? std::sqrt(var / static_cast<double>(s.size())) / mean : NAN;
}

std::vector<double> fill_depressions(const Heightmap& t) {
  // ε relative to the relief, so flats drain whatever the heights' scale.
  std::vector<double> h(t.h.begin(), t.h.end());
  const double eps = 1e-7 * std::max(1.0, double(t.max_height()) - t.min_height());
  priority_flood(
      h, t.nx, t.ny,
      [&](int i, int j) { return i == 0 || j == 0 || i == t.nx - 1 || j == t.ny - 1; }, eps);
  return h;
}

std::vector<long long> d8_receivers(const Heightmap& t, const std::vector<double>& h) {
  std::vector<long long> r(t.size(), -1);
  for (int j = 0; j < t.ny; ++j) {
    for (int i = 0; i < t.nx; ++i) {
      const std::size_t k = static_cast<std::size_t>(j) * t.nx + i;
      if (i == 0 || j == 0 || i == t.nx - 1 || j == t.ny - 1)
        continue;  // border vertices are outlets
      double steepest = 0;
      for (int d = 0; d < 8; ++d) {
        const int a = i + kDi[d], b = j + kDj[d];
        const std::size_t m = static_cast<std::size_t>(b) * t.nx + a;
        const double drop = (h[k] - h[m]) / (t.cell * ((d % 2) ? M_SQRT2 : 1.0));
        if (drop > steepest) {
          steepest = drop;
          r[k] = static_cast<long long>(m);
        }
      }
    }
  }
  return r;
}

std::vector<double> flow_accumulation(const Heightmap& t) {
  const std::vector<double> filled = fill_depressions(t);
  const std::vector<long long> receiver = d8_receivers(t, filled);
  std::vector<std::size_t> order(t.size());
  std::iota(order.begin(), order.end(), 0);
  // Highest first: every donor is handled before its receiver.
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return filled[a] > filled[b]; });
  std::vector<double> area(t.size(), t.cell * t.cell);
  for (std::size_t k : order) {
    if (receiver[k] >= 0) area[static_cast<std::size_t>(receiver[k])] += area[k];
  }
  return area;
}

double drainage_density(const Heightmap& t, const std::vector<double>& area, double threshold) {
  const std::vector<long long> receiver = d8_receivers(t, fill_depressions(t));
  double length = 0;
  for (std::size_t k = 0; k < t.size(); ++k) {
    if (area[k] < threshold || receiver[k] < 0) continue;
    const long long d = receiver[k] - static_cast<long long>(k);
    const bool diagonal = d != 1 && d != -1 && d != t.nx && d != -t.nx;
    length += t.cell * (diagonal ? M_SQRT2 : 1.0);
  }
  return length / ((t.nx - 1) * t.cell * (t.ny - 1) * t.cell);
}

double concavity(const Heightmap& t, const std::vector<double>& area, double threshold) {
  const std::vector<double> filled = fill_depressions(t);
  const std::vector<long long> receiver = d8_receivers(t, filled);
  std::vector<double> log_a, log_s;
  for (std::size_t k = 0; k < t.size(); ++k) {
    if (area[k] < threshold || receiver[k] < 0) continue;
    const std::size_t m = static_cast<std::size_t>(receiver[k]);
    const long long d = static_cast<long long>(m) - static_cast<long long>(k);
    const double run = t.cell * ((d != 1 && d != -1 && d != t.nx && d != -t.nx) ? M_SQRT2 : 1.0);
    const double slope =
        (double(t.h[k]) - t.h[m]) / run;  // on the real surface, not the filled one
    if (slope <= 0) continue;
    log_a.push_back(std::log(area[k]));
    log_s.push_back(std::log(slope));
  }
  if (log_a.size() < 10) return NAN;
  return -fit_slope(log_a, log_s);
}

// The 2-D FFT (in place) of a px × pz grid, px and pz powers of two, row-major.
void fft2(std::vector<std::complex<double>>& grid, std::size_t px, std::size_t pz) {
  std::vector<std::complex<double>> line;
  for (std::size_t j = 0; j < pz; ++j) {  // rows
    line.assign(grid.begin() + j * px, grid.begin() + (j + 1) * px);
    fft(line, false);
    std::copy(line.begin(), line.end(), grid.begin() + j * px);
  }
  line.resize(pz);
  for (std::size_t i = 0; i < px; ++i) {  // columns
    for (std::size_t j = 0; j < pz; ++j) line[j] = grid[j * px + i];
    fft(line, false);
    for (std::size_t j = 0; j < pz; ++j) grid[j * px + i] = line[j];
  }
}

std::size_t next_power_of_two(int n) {
  std::size_t p = 1;
  while (p < static_cast<std::size_t>(n)) p <<= 1;
  return p;
}

double hann(int i, int n) {
  return 0.5 * (1 - std::cos(2 * M_PI * i / (n - 1)));
}

// Cycles per sample of FFT bin i of n.
double frequency(std::size_t i, std::size_t n) {
  return (i <= n / 2 ? double(i) : double(i) - n) / n;
}

namespace {

// The transform of a centred field over the grid, Hann-windowed and zero-padded to powers of two
// (Perron et al. 2008); the window removes the jump between opposite borders that a periodic
// transform would read as short waves.
struct Spectrum {
  std::size_t px, pz;
  std::vector<std::complex<double>> bins;
  double power(std::size_t i, std::size_t j) const { return std::norm(bins[j * px + i]); }
  double wavenumber(std::size_t i, std::size_t j) const {  // cycles per sample
    return std::hypot(frequency(i, px), frequency(j, pz));
  }
};

template <typename Field>
Spectrum windowed_spectrum(int nx, int ny, Field centred) {
  Spectrum s{next_power_of_two(nx), next_power_of_two(ny), {}};
  s.bins.resize(s.px * s.pz);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i)
      s.bins[static_cast<std::size_t>(j) * s.px + i] = centred(i, j) * hann(i, nx) * hann(j, ny);
  fft2(s.bins, s.px, s.pz);
  return s;
}

}  // namespace

double spectral_slope(const Heightmap& t) {
  // Detrend: remove the least-squares plane.
  const int nx = t.nx, ny = t.ny;
  double sx = 0, sz = 0, sh = 0, sxx = 0, szz = 0, sxh = 0, szh = 0;
  const double n = static_cast<double>(t.size());
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const double h = t.at(i, j);
      sx += i, sz += j, sh += h, sxx += double(i) * i, szz += double(j) * j, sxh += i * h,
          szh += j * h;
    }
  }
  const double mx = sx / n, mz = sz / n, mh = sh / n;
  const double bx = (sxh / n - mx * mh) / (sxx / n - mx * mx),
               bz = (szh / n - mz * mh) / (szz / n - mz * mz);
  const Spectrum spectrum = windowed_spectrum(
      nx, ny, [&](int i, int j) { return t.at(i, j) - (mh + bx * (i - mx) + bz * (j - mz)); });
  // Radial average in log-spaced bins of the wavenumber, between 2 cycles per map and Nyquist/2.
  const int bins = 24;
  std::vector<double> sum(bins, 0), count(bins, 0);
  const double k_min = 2.0 / std::max(spectrum.px, spectrum.pz), k_max = 0.25;  // cycles per sample
  for (std::size_t j = 0; j < spectrum.pz; ++j) {
    for (std::size_t i = 0; i < spectrum.px; ++i) {
      const double k = spectrum.wavenumber(i, j);
      if (k < k_min || k > k_max) continue;
      const int b = std::min(
          bins - 1, static_cast<int>(bins * std::log(k / k_min) / std::log(k_max / k_min)));
      sum[b] += spectrum.power(i, j);
      count[b] += 1;
    }
  }
  std::vector<double> lk, lp;
  for (int b = 0; b < bins; ++b) {
    if (count[b] == 0 || sum[b] <= 0) continue;
    lk.push_back(std::log(k_min) + (b + 0.5) * std::log(k_max / k_min) / bins);
    lp.push_back(std::log(sum[b] / count[b]));
  }
  return lk.size() >= 4 ? fit_slope(lk, lp) : NAN;
}

double erosion_flow_correlation(const Heightmap& before, const Heightmap& after) {
  return erosion_flow_correlation(before, after, flow_accumulation(after));
}

double erosion_flow_correlation(const Heightmap& before, const Heightmap& after,
                                const std::vector<double>& area) {
  std::vector<double> eroded, log_area;
  for (std::size_t k = 0; k < after.size(); ++k) {
    const double e = double(before.h[k]) - after.h[k];
    if (e <= 0) continue;
    eroded.push_back(e);
    log_area.push_back(std::log(area[k]));
  }
  if (eroded.size() < 3) return NAN;
  return spearman(eroded, log_area);
}

double stream_power_correlation(const Heightmap& before, const Heightmap& after) {
  const std::vector<double> area = flow_accumulation(before);
  const std::vector<double> slope = slope_degrees(before);
  std::vector<double> eroded, index;
  for (std::size_t k = 0; k < after.size(); ++k) {
    const double e = double(before.h[k]) - after.h[k];
    const double s = std::tan(slope[k] * M_PI / 180.0);
    if (e <= 0 || s <= 0) continue;
    eroded.push_back(e);
    index.push_back(std::log(std::sqrt(area[k]) * s));
  }
  if (eroded.size() < 3) return NAN;
  return spearman(eroded, index);
}

namespace {
// The plateaus (8-connected sets of vertices of one height; most are single vertices) that lie off
// the border and whose every outside neighbour their height compares `beyond`. A DEM quantised to
// whole metres has flat-bottomed hollows and flat tops: counted by vertices, such a hollow is no
// depression until erosion tilts its floor by a micrometre, and then it is a new one.
template <typename Beyond>
long long extreme_plateaus(const Heightmap& t, Beyond beyond) {
  const GridNeighbours around(t.nx, t.ny);
  std::vector<char> seen(t.size(), 0);
  std::vector<std::int32_t> stack;
  long long count = 0;
  for (std::int32_t start = 0; start < static_cast<std::int32_t>(t.size()); ++start) {
    if (seen[start]) continue;
    const float level = t.h[start];
    bool extreme = true;
    seen[start] = 1;
    stack.assign(1, start);
    while (!stack.empty()) {  // the whole plateau is visited, whatever it turns out to be
      const std::int32_t k = stack.back();
      stack.pop_back();
      if (around.on_edge(k)) extreme = false;  // drains off the map
      around.visit(k, [&](std::int32_t n, int) {
        if (t.h[n] != level) {
          extreme = extreme && beyond(level, t.h[n]);
        } else if (!seen[n]) {
          seen[n] = 1;
          stack.push_back(n);
        }
      });
    }
    count += extreme;
  }
  return count;
}
}  // namespace

long long closed_depressions(const Heightmap& t) {
  return extreme_plateaus(t, [](float h, float other) { return h < other; });
}

long long local_peaks(const Heightmap& t) {
  return extreme_plateaus(t, [](float h, float other) { return h > other; });
}

namespace {

struct SpectralPower {
  double short_waves = 0, total = 0;
};

// The power of a field over the grid (its mean removed, through windowed_spectrum) beyond
// 1/cells cycles per sample, and in all.
template <typename Field>
SpectralPower short_wavelength_power(int nx, int ny, double cells, Field field) {
  double mean = 0;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) mean += field(i, j);
  mean /= static_cast<double>(nx) * ny;
  const Spectrum spectrum =
      windowed_spectrum(nx, ny, [&](int i, int j) { return field(i, j) - mean; });
  SpectralPower power;
  for (std::size_t j = 0; j < spectrum.pz; ++j) {
    for (std::size_t i = 0; i < spectrum.px; ++i) {
      const double p = spectrum.power(i, j);
      power.total += p;
      if (spectrum.wavenumber(i, j) > 1.0 / cells) power.short_waves += p;
    }
  }
  return power;
}

}  // namespace

double short_wavelength_share(const Heightmap& before, const Heightmap& after, double cells) {
  const SpectralPower dh = short_wavelength_power(after.nx, after.ny, cells, [&](int i, int j) {
    return double(after.at(i, j)) - before.at(i, j);
  });
  return dh.total > 0 ? dh.short_waves / dh.total : 0.0;
}

double short_wavelength_power_ratio(const Heightmap& before, const Heightmap& after, double cells) {
  auto short_power = [&](const Heightmap& t) {
    return short_wavelength_power(t.nx, t.ny, cells,
                                  [&](int i, int j) { return double(t.at(i, j)); })
        .short_waves;
  };
  const double initial = short_power(before);
  return initial > 0 ? short_power(after) / initial : NAN;
}

std::vector<std::pair<std::string, double>> terrain_metric_values(const Heightmap& before,
                                                                  const Heightmap& after) {
  return terrain_metric_values(before, after, flow_accumulation(after));
}

std::vector<std::pair<std::string, double>> terrain_metric_values(const Heightmap& before,
                                                                  const Heightmap& after_run,
                                                                  const std::vector<double>& area) {
  // The source's NODATA holes keep their filled initial heights: nothing a model invented there
  // is measured. (A copy only for a terrain that has holes.)
  Heightmap kept;
  if (!after_run.georef.holes.empty()) {
    kept = after_run;
    for (std::size_t k = 0; k < kept.h.size() && k < before.h.size(); ++k)
      if (kept.georef.hole(k)) kept.h[k] = before.h[k];
  }
  const Heightmap& after = after_run.georef.holes.empty() ? after_run : kept;
  // Channels: vertices draining at least 1 % of the terrain (and at least 20 cells).
  const double total = (after.nx - 1) * after.cell * (after.ny - 1) * after.cell;
  const double threshold = std::max(0.01 * total, 20.0 * after.cell * after.cell);
  return {{"hypsometric_integral", hypsometric_integral(after)},
          {"hypsometric_integral_initial", hypsometric_integral(before)},
          {"erosion_score", erosion_score(after)},
          {"erosion_score_initial", erosion_score(before)},
          {"mean_slope_deg", mean_slope_degrees(after)},
          {"channel_threshold_m2", threshold},
          {"drainage_density_per_m", drainage_density(after, area, threshold)},
          {"concavity_theta", concavity(after, area, threshold)},
          {"spectral_slope", spectral_slope(after)},
          {"erosion_flow_correlation", erosion_flow_correlation(before, after, area)},
          {"stream_power_correlation", stream_power_correlation(before, after)},
          {"closed_depressions", static_cast<double>(closed_depressions(after))},
          {"closed_depressions_initial", static_cast<double>(closed_depressions(before))},
          {"local_peaks", static_cast<double>(local_peaks(after))},
          {"local_peaks_initial", static_cast<double>(local_peaks(before))},
          {"short_wavelength_dh_share", short_wavelength_share(before, after)},
          {"short_wavelength_power_ratio", short_wavelength_power_ratio(before, after)}};
}

JsonObject terrain_metrics_json(const std::vector<std::pair<std::string, double>>& values,
                                const Heightmap& after) {
  JsonObject o;
  for (auto& [name, value] : values) o.add(name, value);
  o.add("slope_histogram_5deg", JsonObject::Document(slope_histogram(after)));
  return o;
}

JsonObject terrain_metrics(const Heightmap& before, const Heightmap& after) {
  return terrain_metrics_json(terrain_metric_values(before, after), after);
}

}  // namespace runnel::metrics
