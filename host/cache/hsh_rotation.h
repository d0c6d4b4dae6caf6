// Turning a record's hemispherical-harmonic coefficients into a pixel's frame (docs/ALGORITHM.md section 6). HSH are not
// closed under rotation (a tilted hemisphere is not the same hemisphere), so there is no exact finite rotation matrix;
// rcsplat uses Křivánek et al.'s small-angle approximation for the tilt between the record's normal and the pixel's,
//   lambda' = (I + alpha_x D_x + alpha_y D_y) lambda,
// with D_x, D_y the derivatives of re-projection under a rotation of the frame about its own x and y axes, computed
// here once per order in double precision, and an exact rotation about the normal (it only mixes each (m, -m) pair:
// kernels/hsh_frame.h). tests/hsh_rotation_test.cpp checks the result against re-projection in the rotated frame.
#pragma once
#include <vector>

namespace rcsplat {

// H_l^m(cos theta, phi) in double, from std::assoc_legendre and the definition (docs/ALGORITHM.md section 6): the
// reference the float basis (kernels/hsh.h) is checked against, and what the derivative matrices are built from.
double hsh_basis_double(int l, int m, double cos_theta, double phi);

// Gauss-Legendre nodes and weights on [a, b] (Newton on the Legendre polynomial).
void gauss_legendre(int n, double a, double b, std::vector<double>& nodes, std::vector<double>& weights);

// Directions over the hemisphere (+z) and their solid-angle weights: Gauss-Legendre in psi with cos(theta) =
// sin^2(psi), where the basis' square roots sqrt(cos theta) and sqrt(1 - cos theta) are sin(psi) and cos(psi), so
// the integrands stay smooth (in cos theta they are not, at the horizon and the pole), and equal steps in phi.
struct HemisphereQuadrature {
  std::vector<double> x, y, z, weight;
};
HemisphereQuadrature hemisphere_quadrature(int psi_nodes, int phi_steps);

struct HshRotationDerivatives {
  int order = 0;
  // Row-major n^2 x n^2, indexed by hsh_index: d lambda'_k / d alpha = sum_j d[k * n^2 + j] lambda_j, for a frame
  // turned by alpha about its own x axis (dx) or y axis (dy).
  std::vector<float> dx, dy;
};

// Computed on first use for each order and kept (about 0.1 s at order 10).
const HshRotationDerivatives& hsh_rotation_derivatives(int order);

}  // namespace rcsplat
