// Fuzz harness: io::read_ply_points on any bytes (ASCII, binary little- and big-endian PLY,
// vertex and other elements, list properties). Properties: only IoError is thrown; an accepted
// cloud holds finite points and one finite intensity per point or none.

#include "fuzz_support.hpp"
#include "litamin2/io/io_error.hpp"
#include "litamin2/io/ply.hpp"

using namespace litamin2;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    fuzz::check_cloud(io::read_ply_points(fuzz::as_file(data, size)));
    fuzz::accepted() = true;
  } catch (const io::IoError&) {
  }
  return 0;
}
