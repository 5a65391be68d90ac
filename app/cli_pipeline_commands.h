#pragma once
// mostyle-cli subcommands of the style pipeline: dtw, align, decompose, blend.
#include <CLI/CLI.hpp>
#include <functional>

namespace mostyle::cli {

void add_dtw_command(CLI::App& app, std::function<int()>* run);
void add_align_command(CLI::App& app, std::function<int()>* run);
void add_decompose_command(CLI::App& app, std::function<int()>* run);
void add_blend_command(CLI::App& app, std::function<int()>* run);

}  // namespace mostyle::cli
