#pragma once
// Tangential elastic interaction of junctions through the elastomer half-space (E, ν), shear
// along x (MODEL.md §8): the tangential surface displacement at junction i per unit tangential
// force at junction j. Pure functions, SI units; the kernel of the interacting model.
namespace asperity {

// Cerruti's point-force compliance [m/N] at offset (dx, dy) = (x_i − x_j, y_i − y_j), r > 0
// (Johnson, Contact Mechanics §3.2): (1+ν)/(2πE) · [2(1−ν)/r + 2ν dx²/r³].
double cerruti_compliance(double dx_m, double dy_m, double E_pa, double nu);

// The same kernel averaged over two junctions seen as discs of radii a_i, a_j [m]: the mean
// x-displacement over disc i under a unit x-force spread uniformly over disc j. It is symmetric
// in (i, j) (Betti), so the interacting compliance matrix stays symmetric, and it is finite and
// smooth up to touching discs, where the point form underestimates the coupling of near
// neighbours (equal touching discs, ν = 0.5: by 1 % side by side along x, by 25 % along y). Needs d ≥ a_i + a_j (no overlap).
//
// Evaluated exactly as its multipole series: with u = ξ − η the offset of two points of the
// discs and K = c[(2−ν)/r + ν cos2θ/r] (c = (1+ν)/(2πE)), the isotropic average gives
//   ⟨K⟩ = c Σ_m ⟨|u|^2m⟩ / (4^m m!²) · ∇^2m K(d),
//   ∇^2m (1/r) = ((2m−1)!!)² / r^(2m+1),  ∇^2m (cos2θ/r) = Π_{k≤m} ((2k−1)² − 4) · cos2θ / r^(2m+1),
//   ⟨|u|^2m⟩ = Σ_p C(m,p)² a_i^2p a_j^2(m−p) / ((p+1)(m−p+1)),
// which converges for d ≥ a_i + a_j; summed until a term is below 1e-17 of the sum (a few terms
// for d > 3(a_i + a_j); at most 2,000 at touching, where the last ~1e-5 converges slowly).
double disc_compliance(double dx_m, double dy_m, double a_i_m, double a_j_m, double E_pa, double nu);

}  // namespace asperity
