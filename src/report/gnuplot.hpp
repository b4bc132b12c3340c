#pragma once
// Runs a gnuplot script (the plots of every command go through here). Data travel inside the
// script as named data blocks ($name << EOD), so a figure needs no side files.
#include <filesystem>
#include <string>
#include <vector>

#include "observe/sample.hpp"

namespace asperity {

// True when `gnuplot` is on the PATH.
bool gnuplot_available();

// A data block `$name << EOD ... EOD` with one row per entry of `rows` (values %.10g; NaN rows
// are written as blank lines, which gnuplot draws as gaps).
std::string gnuplot_block(const std::string& name, const std::vector<std::vector<double>>& rows);

// Runs `script` with `workdir` as current directory. Throws std::runtime_error naming the
// script's first output line and gnuplot's exit status when gnuplot is missing or fails.
void run_gnuplot(const std::filesystem::path& workdir, const std::string& script);

}  // namespace asperity
