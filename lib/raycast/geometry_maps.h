#pragma once

// What the ray caster sees through each pixel of one image.

#include <opencv2/core.hpp>

namespace lutex {

// Each map covers the image, or the window of it that was rendered (GeometryMapsOptions::window): pixel
// (col, row) of the image is then at (col - window.x, row - window.y) of the maps.
struct GeometryMaps {
  // Planar depth z in the camera frame (scene units), CV_32F; NaN where the ray hits nothing.
  cv::Mat depth;
  // Unit shading normal in the camera frame, CV_32FC3 as (x, y, z): the mesh's vertex normals
  // interpolated at the hit where it has them (photogrammetry meshes do), else the face's geometric
  // normal; on the side the face is seen from (the geometric normal faces the camera, n . ray < 0; a
  // smooth one may face slightly away near a silhouette). NaN where nothing is hit. Empty when not
  // requested.
  cv::Mat normal;
  // Index of the hit face in the mesh, CV_32S; -1 where nothing is hit. Always produced (ray casting
  // works on it).
  cv::Mat face_id;
  // Barycentric coordinates (b1, b2) of the hit in its face, CV_32FC2: the point is
  // (1 - b1 - b2) * v0 + b1 * v1 + b2 * v2. Empty when not requested.
  cv::Mat barycentrics;
  // The image pixel at (0, 0) of the maps: the window's corner, (0, 0) for the whole image.
  cv::Point origin;
};

struct GeometryMapsOptions {
  // Which optional maps to produce (depth and face ids are always produced).
  bool normal = true;
  bool barycentrics = false;
  // Cast every second pixel in each direction first; fill the pixels between four samples without
  // casting where the samples hit one triangle (its plane, intersected analytically: exact for any camera
  // model) or up to four triangles that pairwise share a vertex (the nearest of them that the pixel's ray
  // meets inside the triangle), and cast the rest. On a survey mesh whose triangles span several pixels
  // about a quarter of the pixels are cast. What it can miss: a surface narrower than two pixels that
  // falls entirely between four samples, in front of the surface they hit.
  bool adaptive = true;
  // Threads over tiles of the image; <= 0 means all cores. Results do not depend on it.
  int num_threads = 0;
  // The pixels to render, when only part of the image is needed (a texturer that samples a few faces of a
  // 12 MP view casts their rectangle, not the image); empty: the whole image. Clipped to the image. The
  // samples of the adaptive cast stay on the whole image's grid (the window's corner is moved to even
  // coordinates, which GeometryMaps::origin tells), so a pixel renders as it does in the whole image
  // except within two pixels of the window's far edges.
  cv::Rect window;
};

}  // namespace lutex
