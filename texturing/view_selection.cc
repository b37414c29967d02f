#include "texturing/view_selection.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace lutex {

namespace {

// Labels of faces not solved yet: waiting for a region, or in the region being solved.
constexpr std::uint32_t kUnsolved = kNoView - 1;
constexpr std::uint32_t kInRegion = kNoView - 2;

// A face's labels index its candidates, at most 255 of them.
constexpr std::uint8_t kNoLabel = 255;

bool IsView(std::uint32_t label) { return label < kChooseView; }

double DataCost(const FaceViewCandidates& candidates, std::uint32_t f, std::size_t i, double max_data_cost) {
  return std::min(max_data_cost, std::log(double(candidates.Quality(f, 0)) / double(candidates.Quality(f, i))));
}

// One region's MRF, solved by belief propagation: its faces in ascending order (a face's local index is its
// position), the edges between them, and data terms that hold the Potts terms of neighbours solved before.
class Region {
 public:
  // Grows the region breadth-first from `seed` (kUnsolved) over kUnsolved faces, marking them kInRegion.
  Region(const FaceViewCandidates& candidates, const FaceAdjacency& adjacency, const ViewSelectionOptions& options,
         std::uint32_t seed, std::vector<std::uint32_t>& labels)
      : candidates_(candidates), smoothness_(options.smoothness) {
    faces_.push_back(seed);
    labels[seed] = kInRegion;
    for (std::size_t next = 0; next < faces_.size(); ++next) {
      for (const std::uint32_t* n = adjacency.begin(faces_[next]); n != adjacency.end(faces_[next]); ++n) {
        if (faces_.size() >= options.max_region_faces) break;
        if (labels[*n] != kUnsolved) continue;
        labels[*n] = kInRegion;
        faces_.push_back(*n);
      }
    }
    std::sort(faces_.begin(), faces_.end());
    const std::size_t num_faces = faces_.size();
    data_offsets_.assign(num_faces + 1, 0);
    neighbour_offsets_.assign(num_faces + 1, 0);
    for (std::uint32_t i = 0; i < num_faces; ++i) {
      const std::uint32_t f = faces_[i];
      const std::size_t num_labels = candidates.NumViews(f);
      data_offsets_[i + 1] = data_offsets_[i] + num_labels;
      for (std::size_t l = 0; l < num_labels; ++l) {
        double cost = DataCost(candidates, f, l, options.max_data_cost);
        for (const std::uint32_t* n = adjacency.begin(f); n != adjacency.end(f); ++n) {
          if (IsView(labels[*n]) && labels[*n] != candidates.Views(f)[l]) cost += smoothness_;
        }
        data_.push_back(static_cast<float>(cost));
      }
      for (const std::uint32_t* n = adjacency.begin(f); n != adjacency.end(f); ++n) {
        if (labels[*n] == kInRegion) neighbours_.push_back(LocalIndex(*n));
      }
      neighbour_offsets_[i + 1] = neighbours_.size();
      std::sort(neighbours_.begin() + neighbour_offsets_[i], neighbours_.end());
    }
    // Incoming messages of face g: one block of its labels per neighbour slot. For each message value, the
    // sender's label of the same view (Potts: the only label that costs no seam), and for each slot, the
    // slot the receiver has in the sender's list.
    message_offsets_.assign(num_faces + 1, 0);
    for (std::uint32_t g = 0; g < num_faces; ++g) {
      message_offsets_[g + 1] = message_offsets_[g] + Degree(g) * NumLabels(g);
    }
    messages_.assign(message_offsets_.back(), 0.0f);
    same_view_label_.assign(message_offsets_.back(), kNoLabel);
    slot_in_neighbour_.resize(neighbours_.size());
    for (std::uint32_t g = 0; g < num_faces; ++g) {
      for (std::size_t slot = 0; slot < Degree(g); ++slot) {
        const std::uint32_t i = neighbours_[neighbour_offsets_[g] + slot];
        const std::uint32_t* i_first = neighbours_.data() + neighbour_offsets_[i];
        slot_in_neighbour_[neighbour_offsets_[g] + slot] =
            static_cast<std::uint32_t>(std::lower_bound(i_first, i_first + Degree(i), g) - i_first);
        std::uint8_t* same = same_view_label_.data() + message_offsets_[g] + slot * NumLabels(g);
        for (std::size_t lg = 0; lg < NumLabels(g); ++lg) {
          for (std::size_t l = 0; l < NumLabels(i); ++l) {
            if (Views(i)[l] == Views(g)[lg]) same[lg] = static_cast<std::uint8_t>(l);
          }
        }
      }
    }
  }

  // Sweeps until converged (see view_selection.h) and writes the region's labels into `labels`. Returns
  // the number of sweeps.
  int Solve(const ViewSelectionOptions& options, std::vector<std::uint32_t>& labels) {
    const auto num_faces = static_cast<std::uint32_t>(faces_.size());
    std::vector<float> belief;
    std::vector<std::size_t> label(num_faces, 0);
    int sweeps = 0;
    for (int iteration = 0; iteration < options.max_iterations; ++iteration) {
      for (std::uint32_t i = 0; i < num_faces; ++i) SendMessages(i, belief);
      for (std::uint32_t i = num_faces; i-- > 0;) SendMessages(i, belief);
      sweeps = iteration + 1;
      std::size_t changed = 0;
      for (std::uint32_t i = 0; i < num_faces; ++i) {
        const std::size_t new_label = Label(i, belief);
        changed += new_label != label[i];
        label[i] = new_label;
      }
      // Converged when (almost) no label changes; a few faces may keep flipping between equal choices.
      if (iteration > 0 && double(changed) <= options.converged_fraction * num_faces) break;
    }
    for (std::uint32_t i = 0; i < num_faces; ++i) labels[faces_[i]] = candidates_.Views(faces_[i])[label[i]];
    return sweeps;
  }

 private:
  std::uint32_t LocalIndex(std::uint32_t face) const {
    return static_cast<std::uint32_t>(std::lower_bound(faces_.begin(), faces_.end(), face) - faces_.begin());
  }
  std::size_t NumLabels(std::uint32_t i) const { return data_offsets_[i + 1] - data_offsets_[i]; }
  std::size_t Degree(std::uint32_t i) const { return neighbour_offsets_[i + 1] - neighbour_offsets_[i]; }
  const std::uint32_t* Views(std::uint32_t i) const { return candidates_.Views(faces_[i]); }

  // Sends every message of face i to its neighbours (using the messages i has received so far).
  void SendMessages(std::uint32_t i, std::vector<float>& belief) {
    const std::size_t num_labels = NumLabels(i);
    Belief(i, belief);
    for (std::size_t slot = 0; slot < Degree(i); ++slot) {
      const std::uint32_t g = neighbours_[neighbour_offsets_[i] + slot];
      const std::size_t g_labels = NumLabels(g);
      // h(l) = belief of i without what g told i.
      const float* from_g = messages_.data() + message_offsets_[i] + slot * num_labels;
      float h_min = std::numeric_limits<float>::infinity();
      for (std::size_t l = 0; l < num_labels; ++l) h_min = std::min(h_min, belief[l] - from_g[l]);
      const std::size_t to_g_first = message_offsets_[g] + slot_in_neighbour_[neighbour_offsets_[i] + slot] * g_labels;
      float* to_g = messages_.data() + to_g_first;
      const std::uint8_t* same = same_view_label_.data() + to_g_first;
      float to_min = std::numeric_limits<float>::infinity();
      for (std::size_t lg = 0; lg < g_labels; ++lg) {
        float value = h_min + static_cast<float>(smoothness_);
        if (same[lg] != kNoLabel) value = std::min(value, belief[same[lg]] - from_g[same[lg]]);
        to_g[lg] = value;
        to_min = std::min(to_min, value);
      }
      for (std::size_t lg = 0; lg < g_labels; ++lg) to_g[lg] -= to_min;
    }
  }

  // Label (index into i's candidates) with the least belief; ties to the better view.
  std::size_t Label(std::uint32_t i, std::vector<float>& belief) const {
    Belief(i, belief);
    return static_cast<std::size_t>(std::min_element(belief.begin(), belief.begin() + NumLabels(i)) - belief.begin());
  }

  void Belief(std::uint32_t i, std::vector<float>& belief) const {
    const std::size_t num_labels = NumLabels(i);
    belief.assign(data_.begin() + data_offsets_[i], data_.begin() + data_offsets_[i + 1]);
    const float* incoming = messages_.data() + message_offsets_[i];
    for (std::size_t slot = 0; slot < Degree(i); ++slot) {
      for (std::size_t l = 0; l < num_labels; ++l) belief[l] += incoming[slot * num_labels + l];
    }
  }

  const FaceViewCandidates& candidates_;
  double smoothness_;
  std::vector<std::uint32_t> faces_;
  std::vector<std::size_t> data_offsets_;
  std::vector<float> data_;
  std::vector<std::size_t> neighbour_offsets_;
  std::vector<std::uint32_t> neighbours_;
  std::vector<std::size_t> message_offsets_;
  std::vector<float> messages_;
  std::vector<std::uint8_t> same_view_label_;    // kNoLabel: the sender has no label of that view
  std::vector<std::uint32_t> slot_in_neighbour_;  // parallel to neighbours_
};

// Data and Potts energy of the labelling that gives face f (with candidates) its `label_index(f)`-th
// candidate.
// Only the faces `solved` says (all with an empty `solved`).
template <typename LabelIndex>
void AddEnergy(const FaceViewCandidates& candidates, const FaceAdjacency& adjacency, const ViewSelectionOptions& options,
               const std::vector<bool>& solved, const LabelIndex& label_index, double* data_cost,
               double* smoothness_cost) {
  *data_cost = 0.0;
  *smoothness_cost = 0.0;
  const auto counted = [&](std::uint32_t f) { return candidates.NumViews(f) > 0 && (solved.empty() || solved[f]); };
  for (std::uint32_t f = 0; f < candidates.NumFaces(); ++f) {
    if (!counted(f)) continue;
    const std::size_t l = label_index(f);
    *data_cost += DataCost(candidates, f, l, options.max_data_cost);
    for (const std::uint32_t* n = adjacency.begin(f); n != adjacency.end(f); ++n) {
      if (*n > f && counted(*n) && candidates.Views(f)[l] != candidates.Views(*n)[label_index(*n)]) {
        *smoothness_cost += options.smoothness;
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
  if (max_region_faces < 1) throw std::invalid_argument("a view selection region must hold at least one face");
}

ViewSelection SelectViews(const FaceViewCandidates& candidates, const FaceAdjacency& adjacency,
                          const ViewSelectionOptions& options, const std::vector<std::uint32_t>& given) {
  options.Check();
  if (adjacency.NumFaces() != candidates.NumFaces()) {
    throw std::invalid_argument("view selection: adjacency and candidates are for different meshes");
  }
  if (!given.empty() && given.size() != candidates.NumFaces()) {
    throw std::invalid_argument("view selection: one given label per face needed");
  }
  const auto num_faces = static_cast<std::uint32_t>(candidates.NumFaces());
  ViewSelection selection;
  std::vector<std::uint32_t>& labels = selection.view_of_face;
  labels.resize(num_faces);
  std::vector<bool> solved;
  if (!given.empty()) solved.resize(num_faces);
  for (std::uint32_t f = 0; f < num_faces; ++f) {
    const bool choose = given.empty() || given[f] == kChooseView;
    if (!given.empty()) solved[f] = choose;
    labels[f] = !choose ? given[f] : candidates.NumViews(f) > 0 ? kUnsolved : kNoView;
  }
  for (std::uint32_t seed = 0; seed < num_faces; ++seed) {
    if (labels[seed] != kUnsolved) continue;
    Region region(candidates, adjacency, options, seed, labels);
    selection.iterations = std::max(selection.iterations, region.Solve(options, labels));
    ++selection.num_regions;
  }
  const auto chosen = [&](std::uint32_t f) {
    std::size_t l = 0;
    while (candidates.Views(f)[l] != labels[f]) ++l;
    return l;
  };
  AddEnergy(candidates, adjacency, options, solved, chosen, &selection.data_cost, &selection.smoothness_cost);
  AddEnergy(candidates, adjacency, options, solved, [](std::uint32_t) { return std::size_t{0}; },
            &selection.best_view_data_cost, &selection.best_view_smoothness_cost);
  return selection;
}

}  // namespace lutex
