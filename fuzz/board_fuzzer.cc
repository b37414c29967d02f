// Board files of lutex calibrate --board: a chessboard (lib/calibration/chessboard_target.h) or a ChArUco
// board with coloured patches (lib/calibration/charuco_target.h). Calibrate picks the reader by the file's
// top-level key; here every input goes through both. A ChArUco board the reader accepts is laid out too,
// as calibrate does before looking for it: what the reader lets through must be a board OpenCV can build.

#include <cstddef>
#include <cstdint>
#include <stdexcept>

#include "fuzz/fuzz_input.h"
#include "lib/calibration/charuco_target.h"
#include "lib/calibration/chessboard_target.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = lutex::WriteFuzzFile("board.json", lutex::FuzzBytes(data, size));
  try {
    lutex::ReadChessboardSpec(path);
  } catch (const std::runtime_error&) {
  } catch (const std::invalid_argument&) {
  }
  try {
    lutex::CharucoBoardLayout(lutex::ReadCharucoSpec(path));
  } catch (const std::runtime_error&) {
  } catch (const std::invalid_argument&) {
  }
  return 0;
}
