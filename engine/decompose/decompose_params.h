#pragma once
// What a decomposition is asked for (the stage after prepare_takes): shared components of the
// takes (mix_palette.h, any number of takes) or the paper's own decomposition of each of two takes,
// with or without basic motions (decompose_takes.h).
#include <vector>

#include "engine/decompose/decomposition.h"

namespace mostyle {

enum class DecompositionMode { kShared, kPaper };
const char* decomposition_mode_name(DecompositionMode mode);  // "shared", "paper"

struct DecomposeParams {
  DecompositionMode mode = DecompositionMode::kShared;
  int components = 10;     // k
  double sparsity = 0.1;   // fraction of non-zeros kept in C (the paper's figures use 0.1)
  int max_iterations = 100;
  double tolerance = 1e-6;  // stop on a relative objective change below this (0: run to the cap)
  // Paper mode only: m > 0 decomposes each take into m basic motions (paper 3.5) with these
  // sparsities (missing entries take `sparsity`) instead of one decomposition.
  int basic_motions = 0;
  std::vector<double> basic_sparsities;
  // Shared mode: local components, each one connected piece of the skeleton (decomposition.h
  // locality_parents), so that a component is a body part. Paper mode is never local (the
  // paper's decomposition keeps the largest entries anywhere).
  bool local = true;
  void Validate(int channels) const;  // throws InputError
  // The decomposition's options: k, sparsity, iterations, tolerance, and the skeleton's parents
  // (within the shared joints) when components are local.
  DecompositionOptions options(const std::vector<int>& parents) const;
};

}  // namespace mostyle
