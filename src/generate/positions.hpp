#pragma once
// Junction centres for the stand-ins (docs/model.md §8 needs positions): non-overlapping discs (radius
// sqrt(A0/π)) inside an apparent contact disc of radius R, with a number density that follows
// the pressure of a sphere-on-plane (Hertz) contact, ∝ sqrt(1 − r²/R²): where the pressure is
// higher, more asperities touch. Seeded, and byte-reproducible on any IEEE machine (only +, ×,
// sqrt: no libm function whose last bit may differ).
#include <cstdint>
#include <vector>

namespace asperity {

struct Positions {
  std::vector<double> x_m, y_m;  // centres, in the order of the areas given
};

// Random sequential addition, largest junction first: each centre is drawn from the density
// above (a uniform point of the disc, kept with probability sqrt(1 − r²/R²)) until it overlaps
// no junction placed before; std::invalid_argument when a junction finds no room in
// `max_tries` draws (R too small for the areas) or R is not > 0.
Positions place_in_contact_disc(const std::vector<double>& areas_m2, double contact_radius_m, std::uint64_t seed,
                                int max_tries = 100000);

}  // namespace asperity
