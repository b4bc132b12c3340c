#include "cli/options.hpp"

#include <stdexcept>

#include "io/arguments.hpp"

namespace asperity::cli {

int threads_or_all(int threads) { return threads > 0 ? threads : io::hardware_threads(); }

void add_threads_option(CLI::App* sub, int& threads, const std::string& what) {
  const std::string fallback = threads > 0 ? std::to_string(threads) : "all " + std::to_string(io::hardware_threads());
  // The range and message of io/arguments.hpp, which the Python module checks too; CLI11 then
  // converts the count as checked (plain decimal).
  sub->add_option("-j,--threads", threads, what + " (default: " + fallback + ")")
      ->check(CLI::Validator(
          [](std::string& v) {
            std::string why = io::threads_problem(v);
            if (why.empty()) v = std::to_string(io::checked_threads(v, "--threads"));
            return why;
          },
          "INT in [" + std::to_string(io::kMinThreads) + " - " + std::to_string(io::kMaxThreads) + "]"));
}

void add_set_option(CLI::App* sub, std::vector<std::string>& sets, const std::string& what) {
  sub->add_option("-s,--set", sets, "Set a scene value KEY=VALUE " + what + ", e.g. --set model.eta=50 (repeatable)")
      ->allow_extra_args(false);  // one value per --set: never swallows a positional argument
}

void add_figures_option(CLI::App* sub, FigureFormats& formats) {
  sub->add_option_function<std::string>(
         "--figures", [&formats](const std::string& v) { formats = parse_figure_formats(v); },
         "Figure formats, comma-separated: png, svg, pdf (default png; SVG and PDF sized for a journal column)")
      ->type_name("LIST")
      ->check(CLI::Validator(
          [](std::string& v) {
            try {
              parse_figure_formats(v);
            } catch (const std::invalid_argument& e) {
              return std::string(e.what());
            }
            return std::string();
          },
          "LIST"));
}

void add_quiet_flag(CLI::App* sub, bool& quiet) { sub->add_flag("-q,--quiet", quiet, "Print nothing on success"); }

}  // namespace asperity::cli
