#include "lib/calibration/albedo_span.h"

#include <algorithm>
#include <cstdio>

namespace lutex {

namespace {

constexpr double kBrightestNeeded = 0.25;
constexpr double kDifferenceNeeded = 0.15;

}  // namespace

AlbedoSpan SpanOfKnownColours(const std::vector<KnownColorObservation>& known_colors) {
  AlbedoSpan span;
  span.count = known_colors.size();
  if (known_colors.empty()) return span;
  span.lowest = span.highest = known_colors.front().albedo;
  for (const KnownColorObservation& observation : known_colors) {
    span.lowest = span.lowest.cwiseMin(observation.albedo);
    span.highest = span.highest.cwiseMax(observation.albedo);
  }
  return span;
}

std::vector<std::string> NarrowSpanWarnings(const AlbedoSpan& span, bool in_air, bool has_pure_water,
                                            bool has_correspondences) {
  std::vector<std::string> warnings;
  if (span.count == 0) return warnings;
  static const char* const kNames[3] = {"red", "green", "blue"};
  for (int c = 0; c < 3; ++c) {
    const bool dark = span.highest[c] < kBrightestNeeded;
    const bool flat = !in_air && span.highest[c] - span.lowest[c] < kDifferenceNeeded;
    if (!dark && !flat) continue;
    std::string fixes = std::string("a target bright in ") + kNames[c] + " (white, or " +
                        (c == 0 ? "red" : c == 1 ? "green" : "blue") + ")";
    if (!has_pure_water && !in_air) fixes += ", pure-water images (--pure-water) to pin backscatter";
    if (!has_correspondences) fixes += ", survey correspondences (--correspondences)";
    char text[512];
    std::snprintf(text, sizeof(text),
                  "%s: the targets span albedo %.3f to %.3f only, so %s; what would fix it: %s", kNames[c],
                  span.lowest[c], span.highest[c],
                  dark ? "alpha for brighter surfaces is extrapolated and they may restore too bright or too dark"
                       : "alpha and backscatter are hard to tell apart",
                  fixes.c_str());
    warnings.push_back(text);
  }
  return warnings;
}

}  // namespace lutex
