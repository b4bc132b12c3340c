#include "python/campaign_in_store.hpp"

#include <string>
#include <system_error>

#include "campaign/sweep.hpp"
#include "io/atomic_file.hpp"
#include "io/input_error.hpp"
#include "report/output_dir.hpp"

namespace asperity::python {

namespace fs = std::filesystem;

namespace {

// A relative scene path as an absolute one against `base`; anything else as it is (the
// campaign loader names what is wrong with it).
void absolute_scene(YAML::Node node, const fs::path& base) {
  if (!node.IsScalar()) return;
  const fs::path p(node.Scalar());
  if (!p.empty() && p.is_relative()) node = (fs::absolute(base) / p).lexically_normal().string();
}

}  // namespace

fs::path campaign_into_store(YAML::Node tree, const fs::path& base, const fs::path& store) {
  if (store.empty())
    throw io::InputError("", 0, "out", "a campaign given as a dict needs out= (the store folder, which keeps it)");
  if (!tree.IsMap()) throw io::InputError("", 0, "campaign", "expected a dict of a campaign file's keys");
  const YAML::Node& lookup = tree;  // const: a missing key is not added
  if (lookup["scene"]) absolute_scene(tree["scene"], base);
  if (lookup["scenes"] && lookup["scenes"].IsSequence()) {
    YAML::Node many = tree["scenes"];
    for (std::size_t i = 0; i < many.size(); ++i) absolute_scene(many[i], base);
  }
  YAML::Emitter out;
  out << tree;
  const std::string text =
      "# a campaign given to asperity.sweep as a dict (scene paths made absolute)\n" + std::string(out.c_str()) + "\n";

  check_ours(store, "sweep", "out", is_sweep_store_folder);
  const fs::path file = store / "campaign.yaml";
  std::error_code ec;
  const auto st = fs::symlink_status(file, ec);
  if (fs::is_symlink(st)) throw io::InputError(file.string(), 0, "out", "refusing to write through a symbolic link");
  if (fs::exists(st)) {
    if (io::read_file_text(file) == text) return file;  // the same campaign: a resume
    throw io::InputError(
        store.string(), 0, "out",
        "holds the store of another campaign (its campaign.yaml differs); choose a new or empty folder");
  }
  fs::create_directories(store);
  io::write_file_durably(file, text);
  return file;
}

}  // namespace asperity::python
