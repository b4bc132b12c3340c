// Uses the installed library: loads a scene, builds its Problem, and checks the initial
// stiffness K0 against the closed form of Mindlin's circle, Σ 8 G a_i / (2 − ν) with
// a_i = sqrt(A0_i/π), G = E / (2(1 + ν)) (at t = 0 every elliptic junction is a circle).
//   consumer SCENE.yaml   → prints "OK ..." and exits 0, or "FAIL ..." and exits 1
#include <cmath>
#include <cstdio>

#include "scene/load.hpp"
#include "solve/core/problem.hpp"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: consumer SCENE.yaml\n");
    return 2;
  }
  const asperity::Scene scene = asperity::load_scene(argv[1]);
  const asperity::Problem p = asperity::make_problem(scene);
  const double E = scene.experiment.E, nu = scene.experiment.nu, G = E / (2 * (1 + nu));
  double K0 = 0;
  for (const double A0 : scene.experiment.junctions.area_m2) K0 += 8 * G * std::sqrt(A0 / M_PI) / (2 - nu);
  const double rel = std::abs(p.K0 / K0 - 1);
  std::printf("%s: N = %zu, K0 = %.17g N/m, closed form %.17g N/m, relative difference %.3g\n",
              rel < 1e-12 ? "OK" : "FAIL", p.size(), p.K0, K0, rel);
  return rel < 1e-12 ? 0 : 1;
}
