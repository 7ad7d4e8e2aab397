// SPDX-License-Identifier: MIT
// The SPH smoothing kernel on the device: normalisation on a lattice, agreement with the C++
// reference, and the wall integrals against a brute-force sum over a fine lattice.
#include <gtest/gtest.h>

#include <cmath>

#include "runnel/compute/context.hpp"
#include "runnel/compute/kernel.hpp"
#include "runnel/compute/launch.hpp"
#include "runnel/models/parameter_table.hpp"
#include "runnel/sph/sph_reference.hpp"
#include "runnel/sph/sph_settings.hpp"
#include "test_support.hpp"

namespace runnel {
namespace {

constexpr double kH = 0.12;  // m, h = 1.2 dx with dx = 0.1

struct Probe {
  std::vector<float> w, grad, g, a, b, v;
};

Probe probe(const std::vector<float>& r, double h = kH) {
  ComputeContext& compute = test::compute();
  SphSettings s = SphSettings::from(default_parameters(), 0.1, 2.0);  // dx 0.1 m, c0 20 m/s
  s.h = h;
  Kernel k(compute,
           compute.program({"cl/common.cl", "cl/sph_kernel.cl", "cl/sph_kernel_probe.cl"},
                           s.build_options()),
           "sph_kernel_probe");
  const std::size_t n = r.size();
  auto& ctx = compute.context();
  cl::Buffer rb(ctx, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, n * 4, const_cast<float*>(r.data()));
  std::vector<cl::Buffer> out;
  for (int f = 0; f < 6; ++f) out.emplace_back(ctx, CL_MEM_WRITE_ONLY, n * 4);
  k.set("r", rb).set("n", static_cast<cl_uint>(n));
  const char* names[] = {"w", "grad", "wall_g", "wall_a", "wall_b", "wall_v"};
  for (int f = 0; f < 6; ++f) k.set(names[f], out[f]);
  k.launch(n);
  Probe p;
  std::vector<float>* fields[] = {&p.w, &p.grad, &p.g, &p.a, &p.b, &p.v};
  for (int f = 0; f < 6; ++f) {
    fields[f]->resize(n);
    compute.queue().enqueueReadBuffer(out[f], CL_TRUE, 0, n * 4, fields[f]->data());
  }
  return p;
}

// Σ_j W(x − x_j)·dx³ over a cubic lattice of spacing dx, for a point offset from a node.
double lattice_sum(double h_factor, double ox, double oy, double oz) {
  const double dx = 1.0, h = h_factor * dx;
  std::vector<float> r;
  for (int i = -4; i <= 4; ++i) {
    for (int j = -4; j <= 4; ++j) {
      for (int k = -4; k <= 4; ++k)
        r.push_back(static_cast<float>(
            std::sqrt((i + ox) * (i + ox) + (j + oy) * (j + oy) + (k + oz) * (k + oz))));
    }
  }
  const Probe p = probe(r, h);
  double sum = 0, reference = 0;
  for (std::size_t k = 0; k < r.size(); ++k) {
    sum += p.w[k];
    reference += sph_reference::wendland_w(r[k], h);
  }
  EXPECT_NEAR(sum, reference, 1e-5);
  return sum;
}

TEST(SphKernel, LatticeSumOfWTimesVolumeIsOne) {
  // Within 1 % wherever the point lies, from h = 1.3 dx on.
  for (double hf : {1.3, 1.5, 2.0}) {
    for (double off : {0.0, 0.25, 0.5})
      EXPECT_NEAR(lattice_sum(hf, off, 0.5 * off, 0.3 * off), 1.0, 0.01) << hf << " " << off;
  }
  // At the default h = 1.2 dx a point on a node sums to 1.0175 (the self term W(0) weighs in):
  // within 2 % there, and exactly 1 on average over positions in the cell (Poisson summation).
  EXPECT_NEAR(lattice_sum(1.2, 0, 0, 0), 1.0175, 0.001);
  double mean = 0;
  const int n = 4;
  for (int a = 0; a < n; ++a) {
    for (int b = 0; b < n; ++b) {
      for (int c = 0; c < n; ++c)
        mean += lattice_sum(1.2, (a + 0.5) / n, (b + 0.5) / n, (c + 0.5) / n);
    }
  }
  EXPECT_NEAR(mean / (n * n * n), 1.0, 0.002);
}

TEST(SphKernel, DeviceMatchesReferenceAndVanishesAtSupport) {
  std::vector<float> r;
  for (int k = 0; k <= 250; ++k) r.push_back(static_cast<float>(k * 2.5 * kH / 250));
  const Probe p = probe(r);
  for (std::size_t k = 0; k < r.size(); ++k) {
    const double w = sph_reference::wendland_w(r[k], kH),
                 f = sph_reference::wendland_grad_factor(r[k], kH);
    ASSERT_NEAR(p.w[k], w, 1e-5 * sph_reference::wendland_w(0, kH)) << r[k];
    ASSERT_NEAR(p.grad[k], f, 1e-5 * std::fabs(sph_reference::wendland_grad_factor(0, kH))) << r[k];
    ASSERT_NEAR(p.g[k], sph_reference::wall_integral(r[k], kH), 1e-4 / kH) << r[k];
    ASSERT_NEAR(p.a[k], sph_reference::wall_moment_normal(r[k], kH), 1e-5) << r[k];
    ASSERT_NEAR(p.b[k], sph_reference::wall_moment_tangent(r[k], kH), 1e-5) << r[k];
    ASSERT_NEAR(p.v[k], sph_reference::wall_volume(r[k], kH), 1e-5) << r[k];
    if (r[k] >= 2 * kH) {
      ASSERT_EQ(p.w[k], 0.0f);
      ASSERT_EQ(p.g[k], 0.0f);
      ASSERT_EQ(p.v[k], 0.0f);
    }
  }
  // The kernel's derivative is the gradient factor times r (finite difference).
  for (double r0 : {0.3 * kH, 0.9 * kH, 1.7 * kH}) {
    const double e = 1e-6;
    const double dw =
        (sph_reference::wendland_w(r0 + e, kH) - sph_reference::wendland_w(r0 - e, kH)) / (2 * e);
    EXPECT_NEAR(dw, sph_reference::wendland_grad_factor(r0, kH) * r0, 1e-6 * std::fabs(dw) + 1e-9);
  }
}

TEST(SphKernel, WallIntegralsEqualALatticeSumOverTheHalfSpace) {
  // G(d) = Σ_{beyond the wall} |∇W|·n V, a(d) = Σ |F| Δn² V, b(d) = Σ |F| Δt² V and
  // Γ(d) = Σ W V on a fine lattice.
  const double h = 1.0, step = h / 24;
  for (double d : {0.0, 0.3, 0.8, 1.5}) {
    if (d == 0.0) {
      EXPECT_NEAR(sph_reference::wall_volume(d, h), 0.5, 1e-12);  // half the kernel
    }
    double g = 0, a = 0, b = 0, vol = 0;
    const int m = static_cast<int>(2 * h / step) + 1;
    for (int i = -m; i <= m; ++i) {
      for (int j = -m; j <= m; ++j) {
        for (int k = 0; k <= m; ++k) {
          const double dn = d + (k + 0.5) * step, tx = (i + 0.5) * step, ty = (j + 0.5) * step;
          const double r = std::sqrt(dn * dn + tx * tx + ty * ty);
          const double f = -sph_reference::wendland_grad_factor(r, h);
          const double v = step * step * step;
          g += f * dn * v;
          a += f * dn * dn * v;
          b += f * tx * tx * v;
          vol += sph_reference::wendland_w(r, h) * v;
        }
      }
    }
    EXPECT_NEAR(g, sph_reference::wall_integral(d, h), 2e-3) << d;
    EXPECT_NEAR(a, sph_reference::wall_moment_normal(d, h), 2e-3) << d;
    EXPECT_NEAR(b, sph_reference::wall_moment_tangent(d, h), 2e-3) << d;
    EXPECT_NEAR(vol, sph_reference::wall_volume(d, h), 2e-3) << d;
  }
}

}  // namespace
}  // namespace runnel
