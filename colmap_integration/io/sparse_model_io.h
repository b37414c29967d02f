#pragma once

// Reading and writing a whole sparse model folder, binary or text, detected from the files present
// (binary wins when both exist, as in COLMAP). points3D is optional on reading (an empty model is
// returned for it); `rigs` and `frames` files of COLMAP >= 3.12 are ignored: poses come from `images`.

#include <filesystem>

#include "lib/geometry/sparse_model.h"

namespace lutex {

// Throws std::runtime_error naming `folder` when it holds neither cameras.bin nor cameras.txt.
SparseFormat DetectSparseFormat(const std::filesystem::path& folder);

// Reads and validates (SparseModel::Check) the model in `folder`.
SparseModel ReadSparseModel(const std::filesystem::path& folder);

// Writes the three files into `folder` (created if needed), each to a temporary name first.
void WriteSparseModel(const SparseModel& model, const std::filesystem::path& folder, SparseFormat format);

}  // namespace lutex
