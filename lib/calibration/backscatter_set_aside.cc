#include "lib/calibration/backscatter_set_aside.h"

#include "lib/raycast/forward_scatter_removal.h"

namespace lutex {

cv::Mat BackscatterSetAside::For(const GeometryMaps& maps, const std::filesystem::path& images_dir,
                                 const std::string& name) const {
  if (lut == nullptr) return cv::Mat();
  return BackscatterAtSurfaces(*lut, maps, exposure ? exposure->GainOf(images_dir, name) : 1.0);
}

}  // namespace lutex
