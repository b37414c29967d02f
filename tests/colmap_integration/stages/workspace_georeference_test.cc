#include "colmap_integration/stages/workspace_georeference.h"

#include <gtest/gtest.h>

#include "lib/util/option_error.h"
#include "tests/support/temp_dir.h"

namespace lutex {
namespace {

TEST(WorkspaceGeoreference, OptionsThenTheFileThenNone) {
  testing::TempDir dir;
  Workspace workspace;
  workspace.root = dir.path();
  GeoreferenceOptions options;
  EXPECT_FALSE(ResolveGeoreference(options, workspace).georeference.IsSet());

  Georeference enu;
  enu.frame = Georeference::Frame::kEnu;
  enu.origin = {54.3201, 10.1402, -30.0};
  WriteGeoreference(enu, workspace.GeoreferencePath());
  WorkspaceGeoreference resolved = ResolveGeoreference(options, workspace);
  EXPECT_EQ(resolved.georeference.frame, Georeference::Frame::kEnu);
  EXPECT_EQ(resolved.georeference.origin, enu.origin);
  EXPECT_EQ(resolved.source, workspace.GeoreferencePath().string());

  // --crs alone on an ENU workspace chooses its maps' CRS; it does not make the model projected.
  options.crs = "EPSG:25832";
  resolved = ResolveGeoreference(options, workspace);
  EXPECT_EQ(resolved.georeference.frame, Georeference::Frame::kEnu);
  EXPECT_EQ(resolved.georeference.crs, "EPSG:25832");
  EXPECT_EQ(resolved.georeference.origin, enu.origin);

  // With an origin the options say it all.
  options.crs_origin = "500000,6000000,-800";
  resolved = ResolveGeoreference(options, workspace);
  EXPECT_EQ(resolved.georeference.frame, Georeference::Frame::kProjected);
  EXPECT_EQ(resolved.georeference.origin, Eigen::Vector3d(500000, 6000000, -800));
  EXPECT_EQ(resolved.source, "the options");

  options.enu_origin = "54,10,0";
  EXPECT_THROW(ResolveGeoreference(options, workspace), OptionError);  // two frames at once
}

}  // namespace
}  // namespace lutex
