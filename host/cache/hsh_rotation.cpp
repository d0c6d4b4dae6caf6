#include "cache/hsh_rotation.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <numbers>

#include "kernels/hsh.h"
#include "util/error.h"

namespace rcsplat {
namespace {


// All n^2 basis functions at a direction (x, y, z), z = cos(theta).
void basis_at(int order, double x, double y, double z, std::vector<double>& out) {
  double phi = std::atan2(y, x);
  for (int l = 0; l < order; ++l)
    for (int m = -l; m <= l; ++m) out[size_t(hsh_index(l, m))] = hsh_basis_double(l, m, z, phi);
}

HshRotationDerivatives compute(int order) {
  const int n2 = order * order;
  HshRotationDerivatives d;
  d.order = order;
  std::vector<double> dx(size_t(n2) * size_t(n2), 0.0), dy(dx.size(), 0.0);
  HemisphereQuadrature q = hemisphere_quadrature(64, 64);
  // Central differences of the rotated basis, in double. The step moves a direction by far less than the lowest
  // node's height above the horizon (cos theta ~ 1e-7), so no difference reaches below it.
  const double eps = 1e-9, ce = std::cos(eps), se = std::sin(eps);
  const size_t count = size_t(n2);
  std::vector<double> at(count), xp(count), xm(count), yp(count), ym(count);
  for (size_t i = 0; i < q.weight.size(); ++i) {
    double x = q.x[i], y = q.y[i], z = q.z[i];
    basis_at(order, x, y, z, at);
    // The frame turned by a about its x axis sees direction (x, y, z) of its own where the old frame saw
    // R_x(a) (x, y, z): lambda'_k = integral of H_k(w) L(R w), so d/da at 0 needs H_j(R_x(+-eps) w).
    basis_at(order, x, ce * y - se * z, se * y + ce * z, xp);
    basis_at(order, x, ce * y + se * z, -se * y + ce * z, xm);
    basis_at(order, ce * x + se * z, y, -se * x + ce * z, yp);
    basis_at(order, ce * x - se * z, y, se * x + ce * z, ym);
    for (int k = 0; k < n2; ++k) {
      double hk = q.weight[i] * at[size_t(k)];
      for (int j = 0; j < n2; ++j) {
        dx[size_t(k) * count + size_t(j)] += hk * (xp[size_t(j)] - xm[size_t(j)]) / (2.0 * eps);
        dy[size_t(k) * count + size_t(j)] += hk * (yp[size_t(j)] - ym[size_t(j)]) / (2.0 * eps);
      }
    }
  }
  d.dx.assign(dx.begin(), dx.end());
  d.dy.assign(dy.begin(), dy.end());
  return d;
}

}  // namespace

void gauss_legendre(int n, double a, double b, std::vector<double>& nodes, std::vector<double>& weights) {
  nodes.clear();
  weights.clear();
  for (int i = 0; i < n; ++i) {
    double x = std::cos(std::numbers::pi * (i + 0.75) / (n + 0.5)), dp = 1.0;
    for (int it = 0; it < 100; ++it) {
      double p0 = 1.0, p1 = x;
      for (int k = 2; k <= n; ++k) {
        double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      dp = n * (x * p1 - p0) / (x * x - 1.0);
      double step = p1 / dp;
      x -= step;
      if (std::abs(step) < 1e-16) break;
    }
    nodes.push_back(0.5 * (a + b) + 0.5 * (b - a) * x);
    weights.push_back((b - a) / ((1.0 - x * x) * dp * dp));
  }
}

HemisphereQuadrature hemisphere_quadrature(int psi_nodes, int phi_steps) {
  std::vector<double> psi, w_psi;
  gauss_legendre(psi_nodes, 0.0, std::numbers::pi / 2.0, psi, w_psi);
  HemisphereQuadrature q;
  for (size_t i = 0; i < psi.size(); ++i) {
    double c = std::sin(psi[i]) * std::sin(psi[i]), s = std::sqrt(1.0 - c * c);
    // d omega = d cos(theta) d phi = 2 sin(psi) cos(psi) d psi d phi
    double weight = w_psi[i] * 2.0 * std::sin(psi[i]) * std::cos(psi[i]) * (2.0 * std::numbers::pi / phi_steps);
    for (int j = 0; j < phi_steps; ++j) {
      double phi = 2.0 * std::numbers::pi * (j + 0.5) / phi_steps;
      q.x.push_back(s * std::cos(phi));
      q.y.push_back(s * std::sin(phi));
      q.z.push_back(c);
      q.weight.push_back(weight);
    }
  }
  return q;
}

double hsh_basis_double(int l, int m, double cos_theta, double phi) {
  int am = std::abs(m);
  double x = std::clamp(2.0 * cos_theta - 1.0, -1.0, 1.0);
  double k = std::sqrt((2.0 * l + 1.0) / (2.0 * std::numbers::pi) * std::exp(std::lgamma(l - am + 1.0) - std::lgamma(l + am + 1.0)));
  double p = std::assoc_legendre(unsigned(l), unsigned(am), x);  // no Condon-Shortley phase, as kernels/hsh.h
  if (m == 0) return k * p;
  return std::sqrt(2.0) * k * p * (m > 0 ? std::cos(m * phi) : std::sin(am * phi));
}

const HshRotationDerivatives& hsh_rotation_derivatives(int order) {
  if (order < 1 || order > HSH_MAX_ORDER) throw Error("HSH order must be 1.." + std::to_string(HSH_MAX_ORDER));
  static std::mutex mutex;
  static std::map<int, HshRotationDerivatives> computed;
  std::lock_guard<std::mutex> lock(mutex);
  auto it = computed.find(order);
  if (it == computed.end()) it = computed.emplace(order, compute(order)).first;
  return it->second;
}

}  // namespace rcsplat
