#pragma once
// Small pieces every mostyle-cli subcommand shares: number formatting, CSV, output files.
#include <string>

namespace mostyle::cli {

// Shortest text that reads back as the same double.
std::string number(double v);

// Writes `content` atomically and says nothing; throws InputError on failure.
void write_output(const std::string& path, const std::string& content);

}  // namespace mostyle::cli
