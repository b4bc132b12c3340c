#pragma once
// Tangential elastic interaction of junctions through the elastomer half-space (E, ν), shear
// along x (docs/model.md §8): the tangential surface displacement at junction i per unit tangential
// force at junction j. Pure functions, SI units; the kernel of the interacting model.
namespace asperity {

// How the tangential traction is spread over a junction's disc, both for the load a junction
// exerts and for the displacement it feels (the weights of the double average):
//  - uniform: a constant traction (the mean displacement over the disc);
//  - rigid: Mindlin's rigid-punch traction q(r) = T / (2πa sqrt(a² − r²)) (Johnson §7.2), whose
//    own displacement is uniform over the disc, (2 − ν)/(8Ga) per unit force: the junction's
//    own compliance. Weighting its neighbours' displacement the same way (by work
//    conjugacy) is the consistent off-diagonal; uniform understates near neighbours (by up to
//    ~10 % at touching, along y).
enum class TractionWeighting { uniform, rigid };

// The radial moment μ_m = ⟨|ξ|^2m⟩ / a^2m of a junction's tangential traction over its disc of
// radius a (ξ drawn with the traction's density): 1/(m + 1) uniform, 2^m m!/(2m + 1)!! rigid.
// It sets the disc-averaging operator S_a = Σ_m a^2m μ_m / (4^m m!²) ∇^2m (for a function whose
// mean over a circle is its Taylor series' isotropic part), whose pair product S_i S_j K is the
// series of disc_compliance below.
double traction_radial_moment(int m, TractionWeighting weighting);

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
//
// With rigid weighting the same series holds with the rigid punch's radial moments,
// ⟨|ξ|^2k⟩ = a^2k 2^k k!/(2k+1)!! instead of a^2k/(k+1) (ξ a point of the disc drawn with the
// traction's density): the edge carries more weight, so near touching the series needs more terms.
double disc_compliance(double dx_m, double dy_m, double a_i_m, double a_j_m, double E_pa, double nu,
                       TractionWeighting weighting = TractionWeighting::uniform);

// disc_compliance for a caller that already has the centres' distance d_m = std::hypot(dx_m,
// dy_m) (the interaction matrix's fill): the same value bit for bit, one hypot fewer per pair.
double disc_compliance_at_distance(double dx_m, double dy_m, double d_m, double a_i_m, double a_j_m, double E_pa,
                                   double nu, TractionWeighting weighting);

// The x-displacement [m] at (x, y) (|(x, y)| < a, from the disc's centre) under a unit x-force
// spread over a disc of radius a [m] as the rigid punch's traction, by Cerruti's kernel: the
// integral along each ray from the point is closed-form, leaving a smooth periodic integral in
// the ray's angle (trapezoidal rule, n_angles nodes: spectrally accurate). Equal to Mindlin's
// (2 − ν)/(8Ga) everywhere in the disc: the check that rigid weighting keeps the diagonal.
double rigid_punch_displacement(double x_m, double y_m, double a_m, double E_pa, double nu, int n_angles = 256);

}  // namespace asperity
