#include "scene/topography_recipe.hpp"

#include <cmath>
#include <stdexcept>

#include "io/numbers.hpp"
#include "io/yaml_util.hpp"  // yaml_quoted

namespace asperity {

namespace {}  // namespace

std::optional<RecipeProblem> topography_recipe_problem(const TopographyRecipe& r) {
  if (r.kind != TopographyKind::self_affine) return std::nullopt;
  const SelfAffineSpec& s = r.self_affine;
  const double lr = s.rolloff_wavelength_m > 0 ? s.rolloff_wavelength_m : s.length_m;
  const double ls = s.short_wavelength_m > 0 ? s.short_wavelength_m : 2 * r.pixel_m;
  if (s.rolloff_wavelength_m > 0 && lr > s.length_m * (1 + 1e-12))
    return RecipeProblem{"topography.self_affine.rolloff_wavelength_m",
                         "must be at most the map's size " + io::format_scene_number(s.length_m) + " m"};
  if (s.short_wavelength_m > 0 && (ls < 2 * r.pixel_m * (1 - 1e-12) || !(ls < lr)))
    return RecipeProblem{"topography.self_affine.short_wavelength_m",
                         "must be at least 2 pixels (" + io::format_scene_number(2 * r.pixel_m) +
                             " m) and below the roll-off wavelength " + io::format_scene_number(lr) + " m"};
  return std::nullopt;
}

std::string topography_number_problem(const std::string& key, double x) {
  // A value from Python may be NaN or infinite (a file's never reaches here so): shown as given,
  // where io::format_scene_number refuses it.
  const auto got = [](double v) { return std::isfinite(v) ? io::format_double(v) : io::format_printf("%g", v); };
  if (key == "sphere_radius_m" || key == "E" || key == "load_N")
    return x > 0.0 && std::isfinite(x) ? "" : "must be > 0, got " + got(x);
  if (key == "nu") return x >= 0.0 && x <= 0.5 ? "" : "must be in [0, 0.5], got " + got(x);
  if (key == "contact.tolerance") return x >= 1e-15 && x < 1 ? "" : "must be in [1e-15, 1)";
  const bool integer = std::isfinite(x) && x == std::floor(x);
  if (key == "contact.max_iterations")
    return integer && x >= 1 && x <= 1'000'000 ? "" : "must be in [1, 1000000], got " + got(x);
  if (key == "contact.connectivity") return integer && (x == 4 || x == 8) ? "" : "must be 4 or 8, got " + got(x);
  throw std::invalid_argument("topography_number_problem: no range for " + key);
}

std::string topography_section_yaml(const TopographyRecipe& r, bool with_slider) {
  std::string y;
  auto line = [&](int indent, const std::string& key, const std::string& value) {
    y += std::string(static_cast<std::size_t>(indent), ' ') + key + ":" + (value.empty() ? "" : " " + value) + "\n";
  };
  if (with_slider) line(2, "name", io::yaml_quoted(r.name));
  switch (r.kind) {
    case TopographyKind::smooth:
      line(2, "smooth", "");
      line(4, "n", std::to_string(r.n));
      line(4, "pixel_m", io::format_scene_number(r.pixel_m));
      break;
    case TopographyKind::self_affine: {
      const SelfAffineSpec& s = r.self_affine;
      line(2, "self_affine", "");
      line(4, "seed", std::to_string(s.seed));
      line(4, "n", std::to_string(s.n));
      line(4, "pixel_m", io::format_scene_number(r.pixel_m));
      line(4, "hurst", io::format_scene_number(s.hurst));
      if (s.rolloff_wavelength_m > 0) line(4, "rolloff_wavelength_m", io::format_scene_number(s.rolloff_wavelength_m));
      if (s.short_wavelength_m > 0) line(4, "short_wavelength_m", io::format_scene_number(s.short_wavelength_m));
      if (s.rms_height_m > 0)
        line(4, "rms_height_m", io::format_scene_number(s.rms_height_m));
      else
        line(4, "rms_slope", io::format_scene_number(s.rms_slope));
      break;
    }
    case TopographyKind::measured:
      // Absolute: the scene written elsewhere still finds its map.
      line(2, "file", io::yaml_quoted(std::filesystem::absolute(r.map_file).lexically_normal().string()));
      if (r.map_file.extension() == ".csv") line(2, "pixel_m", io::format_scene_number(r.pixel_m));
      break;
  }
  line(2, "sphere_radius_m", io::format_scene_number(r.sphere_radius_m));
  line(2, "E", io::format_scene_number(r.E_Pa));
  line(2, "nu", io::format_scene_number(r.nu));
  line(2, "load_N", io::format_scene_number(r.load_N));
  line(2, "contact", "");
  line(4, "tolerance", io::format_scene_number(r.tolerance));
  line(4, "max_iterations", std::to_string(r.max_iterations));
  line(4, "connectivity", r.connectivity == Connectivity::four ? "4" : "8");
  if (with_slider) {
    line(2, "slider", "");
    line(4, "gravity", io::format_scene_number(r.gravity));
    if (r.mass_kg > 0) line(4, "mass_kg", io::format_scene_number(r.mass_kg));
    line(4, "k_L", io::format_scene_number(r.k_L));
    line(4, "v", io::format_scene_number(r.v));
    line(4, "sigma_exp", io::format_scene_number(r.sigma_exp));
  }
  return y;
}

}  // namespace asperity
