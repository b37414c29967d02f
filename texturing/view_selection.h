#pragma once

// Which view textures each face: a Markov random field over the faces, solved by min-sum loopy belief
// propagation.
//
//   E(labels) = sum_f D_f(label_f) + smoothness * #{edges (f, g) : label_f != label_g}    (Potts)
//   D_f(v)    = min(max_data_cost, ln(quality of f's best view / quality of v))
//
// The data term is 0 for a face's best view and grows with the log of how much worse another view is;
// the Potts term prefers large charts of one view, whose seams are fewer and fall where views agree.
// Labels are restricted to each face's candidates (FaceViewCandidates). Messages are updated face by
// face in a forward then a backward sweep (deterministic, no dependence on threads), until at most
// `converged_fraction` of the labels change in a sweep, or `max_iterations` sweeps.
//
// A dive's mesh is solved one region at a time, so that the messages (about 150 bytes per face) are held
// for one region, not for the whole mesh: regions of at most `max_region_faces` faces are grown
// breadth-first along the surface from the lowest-numbered face not yet labelled, and solved in the
// order they are grown. A face of a region next to a face of a region solved before sees that face's
// label as fixed: its Potts term joins the face's data term. Labels therefore agree across region
// borders as they do inside a region, and what is held for the whole mesh is the labels (4 bytes a
// face). A mesh of at most `max_region_faces` faces is one region: the whole MRF at once.

#include <cstdint>
#include <limits>
#include <vector>

#include "texturing/face_adjacency.h"
#include "texturing/face_view_candidates.h"

namespace lutex {

constexpr std::uint32_t kNoView = std::numeric_limits<std::uint32_t>::max();

struct ViewSelectionOptions {
  // Cost of one pair of adjacent faces textured from different views, in units of the data term (a
  // view e^smoothness times worse than the best is worth it to avoid one seam edge).
  double smoothness = 0.5;
  double max_data_cost = 4.0;
  int max_iterations = 20;
  // Sweeps stop when at most this fraction of the faces changed label in the last one.
  double converged_fraction = 0.001;
  // Most faces solved together (see above); at least 1.
  std::size_t max_region_faces = 131072;
  void Check() const;
};

struct ViewSelection {
  std::vector<std::uint32_t> view_of_face;  // kNoView for faces no view sees
  double data_cost = 0.0;
  double smoothness_cost = 0.0;
  // The same energy with every face on its best view (no smoothness): what the MRF trades against.
  double best_view_data_cost = 0.0;
  double best_view_smoothness_cost = 0.0;
  int iterations = 0;    // sweeps, the most over the regions
  std::size_t num_regions = 0;
};

// `given`, for a part of a larger mesh solved piece by piece (one tile of a tiled bake with the surface
// around it): empty, or one entry per face, kChooseView for the faces to label here and otherwise the
// face's label as it is already known: a view (chosen with the pieces solved before; its Potts terms join
// its neighbours' data terms, as between regions) or kNoView (not labelled here, and no neighbour of the
// faces solved). The result keeps the given labels; its energies are those of the faces labelled here.
constexpr std::uint32_t kChooseView = kNoView - 3;
ViewSelection SelectViews(const FaceViewCandidates& candidates, const FaceAdjacency& adjacency,
                          const ViewSelectionOptions& options, const std::vector<std::uint32_t>& given = {});

}  // namespace lutex
