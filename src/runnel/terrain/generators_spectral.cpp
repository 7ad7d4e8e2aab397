// SPDX-License-Identifier: MIT
// Spectral synthesis (Fourier filtering; Voss 1985, Jourdan 2008): random complex amplitudes with
// |A(k)| ∝ |k|^−(H+1), so the power spectrum falls as |k|^−(2H+2), transformed back by an inverse
// FFT (KissFFT). The FFT's grid is periodic, so the terrain tiles: its period is (nx − 1) × (ny −
// 1) cells and the last row and column repeat the first, equal in height and in slope.
// docs/generators.md.
#include <kissfft/kiss_fftnd.h>

#include <memory>
#include <vector>

#include "runnel/core/error.hpp"
#include "runnel/core/rng.hpp"
#include "runnel/terrain/generator_util.hpp"

namespace runnel::generator_util {

Heightmap spectral(const GeneratorRequest& r) {
  constexpr std::uint64_t kStream = 0x535045ULL << 8;  // "SPE"
  const int px = r.nx - 1, pz = r.ny - 1;              // the period in cells
  if (px < 2 || pz < 2)
    throw input_error("--size: the spectral generator needs 3 x 3 vertices or more");
  const double hurst = r.values.at("hurst");
  const double cutoff = r.values.at("min_wavelength");  // cells
  std::vector<kiss_fft_cpx> spectrum(static_cast<std::size_t>(px) * pz), field(spectrum.size());
  for (int v = 0; v < pz; ++v) {
    for (int u = 0; u < px; ++u) {
      // Signed frequencies in cycles per period, then per cell (so anisotropic grids stay
      // isotropic).
      const double fu = (u <= px / 2 ? u : u - px) / static_cast<double>(px);
      const double fv = (v <= pz / 2 ? v : v - pz) / static_cast<double>(pz);
      const double f = std::sqrt(fu * fu + fv * fv);
      const std::size_t k = static_cast<std::size_t>(v) * px + u;
      if (f == 0.0 || f > 1.0 / cutoff) {
        spectrum[k] = {0.0f, 0.0f};
        continue;
      }
      // A complex Gaussian (Box–Muller from two counter-based uniforms) times the amplitude law.
      const double u1 = 1.0 - rng_uniform_double(r.seed, kStream, 2 * k);
      const double u2 = rng_uniform_double(r.seed, kStream, 2 * k + 1);
      const double radius = std::sqrt(-2.0 * std::log(u1)) * std::pow(f, -(hurst + 1.0));
      spectrum[k] = {static_cast<float>(radius * std::cos(2 * M_PI * u2)),
                     static_cast<float>(radius * std::sin(2 * M_PI * u2))};
    }
  }
  const int dims[2] = {pz, px};
  std::unique_ptr<std::remove_pointer_t<kiss_fftnd_cfg>, decltype(&kiss_fft_free)> cfg(
      kiss_fftnd_alloc(dims, 2, 1, nullptr, nullptr), &kiss_fft_free);
  if (!cfg) throw runtime_error("spectral: cannot allocate the FFT");
  kiss_fftnd(cfg.get(), spectrum.data(), field.data());
  // The real part: a real Gaussian field with the same (isotropic) power spectrum.
  Heightmap t(r.nx, r.ny, r.cell);
  for (int j = 0; j < r.ny; ++j)
    for (int i = 0; i < r.nx; ++i)
      t.at(i, j) = field[static_cast<std::size_t>(j % pz) * px + (i % px)].r;
  normalise(t, r.values.at("relief") * extent(r));
  return t;
}

}  // namespace runnel::generator_util
