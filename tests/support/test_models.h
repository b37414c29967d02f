#pragma once

// A sparse model with every field filled: one camera per model id in [0, num_models), images with
// 2-D points (some without 3-D point), 3-D points with tracks. Fixed seed.

#include "lib/geometry/sparse_model.h"

namespace lutex::testing {

SparseModel MakeTestModel(int num_models);

// Records a gtest failure for every field that differs by more than `relative_tolerance` (relative to
// max(1, |value|)); 0 demands bit-exact equality.
void ExpectModelsEqual(const SparseModel& expected, const SparseModel& actual, double relative_tolerance = 0.0);

}  // namespace lutex::testing
