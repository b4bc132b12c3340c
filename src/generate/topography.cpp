#include "generate/topography.hpp"

#include "io/atomic_file.hpp"
#include "io/csv.hpp"
#include "io/digest.hpp"
#include "io/input_error.hpp"
#include "io/numbers.hpp"
#include "io/yaml_util.hpp"
#include "scene/load.hpp"

namespace asperity {

namespace fs = std::filesystem;

namespace {

// One line of the provenance header per call: "# " + text.
void comment(std::string& s, const std::string& text) { s += "# " + text + "\n"; }

}  // namespace

TopographyJunctions build_topography_junctions(const TopographyRecipe& r, int threads) {
  TopographyJunctions t;
  t.recipe_sha256 = io::sha256_hex(io::read_input_file(r.file, io::input_path(r.file), io::kMaxYamlBytes));
  static_cast<TopographyContact&>(t) = solve_topography_contact(r, threads);
  t.experiment = topography_experiment(r, t,
                                       "Written by `asperity generate` from " + r.file.filename().string() +
                                           "; provenance in the header of junctions.csv.");
  return t;
}

std::string topography_junctions_csv(const TopographyRecipe& r, const TopographyJunctions& t) {
  const JunctionPopulation& J = t.experiment.junctions;
  double total = 0;
  for (const double A : J.area_m2) total += A;
  const std::size_t n = t.n;
  std::string s;
  comment(s, "Junctions from topography: written by `asperity generate` from " + r.file.filename().string() +
                 "; regenerate rather than edit.");
  comment(s, "recipe_sha256: " + t.recipe_sha256);
  comment(s, "surface: " + topography_surface_text(r));
  comment(
      s, std::string("seed: ") + (r.kind == TopographyKind::self_affine ? std::to_string(r.self_affine.seed) : "none"));
  comment(s, "n: " + std::to_string(n) + ", pixel_m: " + io::format_double(t.pixel_m) +
                 ", size_m: " + io::format_double(t.pixel_m * static_cast<double>(n)));
  comment(s, "rms_height_m: " + io::format_double(t.rms_height_m) + ", rms_slope: " + io::format_double(t.rms_slope) +
                 " (before the sphere; heights sha256 " + t.heights_sha256 + ", float64 LE row-major)");
  comment(s, "sphere_radius_m: " + io::format_double(r.sphere_radius_m) + ", E: " + io::format_double(r.E_Pa) +
                 " Pa, nu: " + io::format_double(r.nu) + ", rigid counter-surface");
  comment(s, "load_N: " + io::format_double(r.load_N) + ", solver iterations: " + std::to_string(t.iterations) +
                 ", residual: " + io::format_double(t.residual) + " (tolerance " + io::format_double(r.tolerance) +
                 ")");
  comment(s, "clusters: " + std::to_string(t.clusters) + " (connectivity " +
                 (r.connectivity == Connectivity::four ? "4" : "8") +
                 "), merges of overlapping equivalent discs: " + std::to_string(t.merges));
  comment(s, "junctions: " + std::to_string(J.size()) + ", total area_m2: " + io::format_double(total));
  s += "area_m2,x_m,y_m\n";
  for (std::size_t i = 0; i < J.size(); ++i)
    s += io::csv_number(J.area_m2[i]) + ',' + io::csv_number(J.x_m[i]) + ',' + io::csv_number(J.y_m[i]) + '\n';
  return s;
}

void write_topography_experiment(const TopographyRecipe& r, const TopographyJunctions& t, const fs::path& out_dir) {
  fs::create_directories(out_dir);
  io::write_file_atomically(out_dir / "junctions.csv", topography_junctions_csv(r, t), io::Durability::unsynced);
  io::write_file_atomically(out_dir / "experiment.yaml", experiment_to_yaml(t.experiment, "junctions.csv", ""),
                            io::Durability::unsynced);
}

}  // namespace asperity
