#pragma once
// mostyle-cli subcommands that synthesize, all through one command path: blend (two takes and an
// alpha), mix (2 to 16 takes with weights, the style palette) and transfer (a style change put
// on a take of one's own). Each prepares its takes (prepare_takes), decomposes them
// (decompose_takes) and mixes them (mix_palette) the same way; only their words differ.
#include <CLI/CLI.hpp>
#include <functional>

namespace mostyle::cli {

void add_blend_command(CLI::App& app, std::function<int()>* run);
void add_mix_command(CLI::App& app, std::function<int()>* run);
void add_transfer_command(CLI::App& app, std::function<int()>* run);

}  // namespace mostyle::cli
