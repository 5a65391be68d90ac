#pragma once
// mostyle-cli subcommands for live streams in Axis Neuron's "BVH broadcasting" format
// (engine/live/axis_stream.h): live (a style put on a stream and served on) and live-send (a take
// served as such a stream, the stand-in for Axis Neuron in tests and demos).
#include <CLI/CLI.hpp>
#include <functional>

namespace mostyle::cli {

void add_live_command(CLI::App& app, std::function<int()>* run);
void add_live_send_command(CLI::App& app, std::function<int()>* run);

}  // namespace mostyle::cli
