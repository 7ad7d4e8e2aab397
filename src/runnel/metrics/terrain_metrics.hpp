// SPDX-License-Identifier: MIT
#pragma once
#include <string>
#include <utility>
#include <vector>

#include "runnel/core/heightmap.hpp"
#include "runnel/io/json.hpp"

// The terrain metrics every run reports (models.md, "Metrics"), computed on the host.
namespace runnel::metrics {

// Pearson's correlation of two series of one length; 0 when either is constant.
double pearson_correlation(const std::vector<double>& a, const std::vector<double>& b);

// (mean h − min h) / (max h − min h), Strahler 1952.
double hypsometric_integral(const Heightmap& t);

// Slope per vertex in degrees, central differences (one-sided at the border).
std::vector<double> slope_degrees(const Heightmap& t);
double mean_slope_degrees(const Heightmap& t);
// Counts of vertices per slope bin of `bin_degrees` from 0 to 90.
std::vector<long long> slope_histogram(const Heightmap& t, double bin_degrees = 5.0);

// Olsen 2004's erosion score: per interior vertex the largest absolute height difference to its
// four neighbours, s; score = std(s) / mean(s).
double erosion_score(const Heightmap& t);

// Heights after priority-flood depression filling (Barnes et al. 2014), so every cell drains to
// the border; flats get an ε gradient towards their outlet.
std::vector<double> fill_depressions(const Heightmap& t);
// D8 receiver of every vertex (index, or −1 for border outlets) on the filled surface.
std::vector<long long> d8_receivers(const Heightmap& t, const std::vector<double>& filled);
// Drainage area (m²) of every vertex: its own cell² plus everything that flows through it (D8).
std::vector<double> flow_accumulation(const Heightmap& t);

// Channel length (along D8 links of vertices whose drainage area ≥ threshold) per terrain area,
// 1/m.
double drainage_density(const Heightmap& t, const std::vector<double>& area, double threshold_m2);
// θ of S = k_s A^(−θ) fitted over channel vertices (Flint's law); NaN when fewer than 10 qualify.
double concavity(const Heightmap& t, const std::vector<double>& area, double threshold_m2);

// Slope of log power against log wavenumber of the radially averaged power spectrum of the
// detrended (plane removed), Hann-windowed heightmap (Perron et al. 2008). For a surface with
// P(k) ∝ k^−β it returns −β.
double spectral_slope(const Heightmap& t);

// Spearman rank correlation of eroded depth (h0 − h, eroded vertices only) with log drainage area.
double erosion_flow_correlation(const Heightmap& before, const Heightmap& after);
// The same with the drainage area of `after` already computed (flow_accumulation(after)). Where
// `after` has NODATA holes (its georef), their heights are taken as `before`'s: no change there.
double erosion_flow_correlation(const Heightmap& before, const Heightmap& after,
                                const std::vector<double>& area);

// Spearman correlation, over eroded vertices, of the height loss h0 − h with the stream-power index
// log(√A·S) of the initial terrain (A its D8 drainage area, S its slope as a gradient): erosion by
// running water grows with discharge and slope (models.md).
double stream_power_correlation(const Heightmap& before, const Heightmap& after);

// The bottoms of closed depressions (the tops of local peaks): plateaus of one height (most are
// single vertices), off the border, strictly lower (higher) than every vertex around them.
long long closed_depressions(const Heightmap& t);
long long local_peaks(const Heightmap& t);

// The share of the variance of Δh = after − before at wavelengths under `cells` cells (the power of
// the Hann-windowed, mean-removed Δh beyond 1/cells cycles per sample over its total): noise and
// spikes live there, carved valleys do not.
double short_wavelength_share(const Heightmap& before, const Heightmap& after, double cells = 4.0);

// The terrain's own power at wavelengths under `cells` cells after, over before (each Hann-windowed
// and mean-removed): above 1 the model roughened the terrain, below 1 it smoothed it. The share of
// Δh above cannot tell the two apart: talus collapsing a rough terrain's spikes puts most of its Δh
// at short wavelengths too. NaN when the initial terrain has no such power.
double short_wavelength_power_ratio(const Heightmap& before, const Heightmap& after,
                                    double cells = 4.0);

// Every scalar metric above for a terrain (and its initial state), by name, in a fixed order (the
// columns of runnel compare's metrics.csv).
std::vector<std::pair<std::string, double>> terrain_metric_values(const Heightmap& before,
                                                                  const Heightmap& after);
// The same with the drainage area of `after` already computed (flow_accumulation(after)).
std::vector<std::pair<std::string, double>> terrain_metric_values(const Heightmap& before,
                                                                  const Heightmap& after,
                                                                  const std::vector<double>& area);
// Those values plus the slope histogram, for metrics.json.
JsonObject terrain_metrics_json(const std::vector<std::pair<std::string, double>>& values,
                                const Heightmap& after);
JsonObject terrain_metrics(const Heightmap& before, const Heightmap& after);

}  // namespace runnel::metrics
