#include "lib/calibration/observations.h"

#include <map>

namespace lutex {

void MergeObservations(ObservationSet part, ObservationSet* into) {
  std::map<std::filesystem::path, int> index_of;
  for (std::size_t i = 0; i < into->images.size(); ++i) index_of.emplace(into->images[i], static_cast<int>(i));
  std::vector<int> renumbered(part.images.size());
  for (std::size_t i = 0; i < part.images.size(); ++i) {
    const auto [found, added] = index_of.emplace(part.images[i], static_cast<int>(into->images.size()));
    if (added) into->images.push_back(part.images[i]);
    renumbered[i] = found->second;
  }
  const auto renumber = [&](int* image) {
    if (*image >= 0 && static_cast<std::size_t>(*image) < renumbered.size()) {
      *image = renumbered[static_cast<std::size_t>(*image)];
    } else {
      *image = -1;
    }
  };
  for (KnownColorObservation& o : part.known_colors) {
    renumber(&o.image);
    into->known_colors.push_back(std::move(o));
  }
  for (PureWaterObservation& o : part.pure_water) {
    renumber(&o.image);
    into->pure_water.push_back(std::move(o));
  }
  for (CorrespondenceObservation& o : part.correspondences) {
    renumber(&o.first.image);
    renumber(&o.second.image);
    into->correspondences.push_back(std::move(o));
  }
}

}  // namespace lutex
