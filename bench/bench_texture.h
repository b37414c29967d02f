#pragma once

// `lutex texture` of a simulated dive's own images (the unrestored ones: the benchmarks measure the work,
// not the colours), with default options, timed.

#include <chrono>
#include <filesystem>

#include "bench/bench_options.h"
#include "colmap_integration/stages/texture_workspace.h"

namespace lutex::bench {

// Textures `workspace` (its scene/mesh.ply, from its images/) into `output`; `seconds` gets the time.
inline TextureSummary TextureOwnImages(const std::filesystem::path& workspace, const std::filesystem::path& output,
                                       int num_threads, double* seconds) {
  TextureOptions options;
  options.workspace = workspace;
  options.mesh = workspace / "scene" / "mesh.ply";
  options.views.images = workspace / "images";
  options.output = output;
  options.baking.num_threads = num_threads;
  const auto start = std::chrono::steady_clock::now();
  TextureSummary summary = TextureWorkspace(options);
  *seconds = SecondsSince(start);
  return summary;
}

}  // namespace lutex::bench
