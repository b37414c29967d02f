#include "texturing/view_selection.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace lutex {

namespace {

class BeliefPropagation {
 public:
  BeliefPropagation(const FaceViewCandidates& candidates, const FaceAdjacency& adjacency,
                    const ViewSelectionOptions& options)
      : candidates_(candidates), adjacency_(adjacency), smoothness_(options.smoothness) {
    const std::size_t num_faces = candidates.NumFaces();
    data_offsets_.assign(num_faces + 1, 0);
    for (std::uint32_t f = 0; f < num_faces; ++f) data_offsets_[f + 1] = data_offsets_[f] + candidates.NumViews(f);
    data_.resize(data_offsets_.back());
    for (std::uint32_t f = 0; f < num_faces; ++f) {
      const FaceViewCandidate* first = candidates.begin(f);
      for (std::size_t i = 0; i < candidates.NumViews(f); ++i) {
        data_[data_offsets_[f] + i] = static_cast<float>(
            std::min(options.max_data_cost, std::log(double(first[0].quality) / double(first[i].quality))));
      }
    }
    // Incoming messages of face g: one block of NumViews(g) values per neighbour slot.
    message_offsets_.assign(num_faces + 1, 0);
    for (std::uint32_t g = 0; g < num_faces; ++g) {
      message_offsets_[g + 1] = message_offsets_[g] + adjacency.Degree(g) * candidates.NumViews(g);
    }
    messages_.assign(message_offsets_.back(), 0.0f);
  }

  // Sends every message of face f to its neighbours (using the messages f has received so far).
  void SendMessages(std::uint32_t f, std::vector<float>& belief) {
    const std::size_t num_labels = candidates_.NumViews(f);
    if (num_labels == 0) return;
    Belief(f, belief);
    std::size_t slot = 0;
    for (const std::uint32_t* n = adjacency_.begin(f); n != adjacency_.end(f); ++n, ++slot) {
      const std::uint32_t g = *n;
      const std::size_t g_labels = candidates_.NumViews(g);
      if (g_labels == 0) continue;
      // h(l) = belief of f without what g told f.
      const float* from_g = messages_.data() + message_offsets_[f] + slot * num_labels;
      float h_min = std::numeric_limits<float>::infinity();
      for (std::size_t l = 0; l < num_labels; ++l) h_min = std::min(h_min, belief[l] - from_g[l]);
      const std::size_t slot_in_g = static_cast<std::size_t>(
          std::lower_bound(adjacency_.begin(g), adjacency_.end(g), f) - adjacency_.begin(g));
      float* to_g = messages_.data() + message_offsets_[g] + slot_in_g * g_labels;
      const FaceViewCandidate* f_views = candidates_.begin(f);
      const FaceViewCandidate* g_views = candidates_.begin(g);
      float to_min = std::numeric_limits<float>::infinity();
      for (std::size_t lg = 0; lg < g_labels; ++lg) {
        float value = h_min + static_cast<float>(smoothness_);
        for (std::size_t l = 0; l < num_labels; ++l) {
          if (f_views[l].view == g_views[lg].view) value = std::min(value, belief[l] - from_g[l]);
        }
        to_g[lg] = value;
        to_min = std::min(to_min, value);
      }
      for (std::size_t lg = 0; lg < g_labels; ++lg) to_g[lg] -= to_min;
    }
  }

  // Label (index into f's candidates) with the least belief; ties to the better view.
  std::size_t Label(std::uint32_t f, std::vector<float>& belief) const {
    Belief(f, belief);
    return static_cast<std::size_t>(std::min_element(belief.begin(), belief.begin() + candidates_.NumViews(f)) -
                                    belief.begin());
  }

  double DataCost(std::uint32_t f, std::size_t label) const { return data_[data_offsets_[f] + label]; }

 private:
  void Belief(std::uint32_t f, std::vector<float>& belief) const {
    const std::size_t num_labels = candidates_.NumViews(f);
    belief.assign(data_.begin() + data_offsets_[f], data_.begin() + data_offsets_[f + 1]);
    const float* incoming = messages_.data() + message_offsets_[f];
    for (std::size_t slot = 0; slot < adjacency_.Degree(f); ++slot) {
      for (std::size_t l = 0; l < num_labels; ++l) belief[l] += incoming[slot * num_labels + l];
    }
  }

  const FaceViewCandidates& candidates_;
  const FaceAdjacency& adjacency_;
  double smoothness_;
  std::vector<std::size_t> data_offsets_;
  std::vector<float> data_;
  std::vector<std::size_t> message_offsets_;
  std::vector<float> messages_;
};

// Data and Potts energy of a labelling.
void AddEnergy(const std::vector<std::uint32_t>& view_of_face, const std::vector<double>& data_cost_of_face,
               const FaceAdjacency& adjacency, double smoothness, double* data_cost, double* smoothness_cost) {
  *data_cost = 0.0;
  *smoothness_cost = 0.0;
  for (std::uint32_t f = 0; f < view_of_face.size(); ++f) {
    *data_cost += data_cost_of_face[f];
    for (const std::uint32_t* n = adjacency.begin(f); n != adjacency.end(f); ++n) {
      if (*n > f && view_of_face[f] != kNoView && view_of_face[*n] != kNoView && view_of_face[f] != view_of_face[*n]) {
        *smoothness_cost += smoothness;
      }
    }
  }
}

}  // namespace

void ViewSelectionOptions::Check() const {
  if (!(smoothness >= 0.0)) throw std::invalid_argument("the view smoothness must be >= 0");
  if (!(max_data_cost > 0.0)) throw std::invalid_argument("the maximum data cost must be > 0");
  if (max_iterations < 0) throw std::invalid_argument("the number of iterations must be >= 0");
  if (!(converged_fraction >= 0.0 && converged_fraction < 1.0)) {
    throw std::invalid_argument("the converged fraction must be in [0, 1)");
  }
}

ViewSelection SelectViews(const FaceViewCandidates& candidates, const FaceAdjacency& adjacency,
                          const ViewSelectionOptions& options) {
  options.Check();
  if (adjacency.NumFaces() != candidates.NumFaces()) {
    throw std::invalid_argument("view selection: adjacency and candidates are for different meshes");
  }
  const auto num_faces = static_cast<std::uint32_t>(candidates.NumFaces());
  BeliefPropagation propagation(candidates, adjacency, options);
  std::vector<float> belief;
  std::vector<std::size_t> label(num_faces, 0);
  ViewSelection selection;
  for (int iteration = 0; iteration < options.max_iterations; ++iteration) {
    for (std::uint32_t f = 0; f < num_faces; ++f) propagation.SendMessages(f, belief);
    for (std::uint32_t f = num_faces; f-- > 0;) propagation.SendMessages(f, belief);
    selection.iterations = iteration + 1;
    std::size_t changed = 0;
    for (std::uint32_t f = 0; f < num_faces; ++f) {
      if (candidates.NumViews(f) == 0) continue;
      const std::size_t new_label = propagation.Label(f, belief);
      changed += new_label != label[f];
      label[f] = new_label;
    }
    // Converged when (almost) no label changes; a few faces may keep flipping between equal choices.
    if (iteration > 0 && double(changed) <= options.converged_fraction * num_faces) break;
  }
  selection.view_of_face.assign(num_faces, kNoView);
  std::vector<std::uint32_t> best_view(num_faces, kNoView);
  std::vector<double> data_cost(num_faces, 0.0), best_data_cost(num_faces, 0.0);
  for (std::uint32_t f = 0; f < num_faces; ++f) {
    if (candidates.NumViews(f) == 0) continue;
    selection.view_of_face[f] = candidates.begin(f)[label[f]].view;
    best_view[f] = candidates.begin(f)[0].view;
    data_cost[f] = propagation.DataCost(f, label[f]);
  }
  AddEnergy(selection.view_of_face, data_cost, adjacency, options.smoothness, &selection.data_cost,
            &selection.smoothness_cost);
  AddEnergy(best_view, best_data_cost, adjacency, options.smoothness, &selection.best_view_data_cost,
            &selection.best_view_smoothness_cost);
  return selection;
}

}  // namespace lutex
