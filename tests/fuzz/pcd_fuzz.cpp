// Fuzz harness: io::read_pcd on any bytes (ASCII and binary PCD). Properties: only IoError is
// thrown; an accepted cloud holds finite points and one finite intensity per point or none.

#include "fuzz_support.hpp"
#include "litamin2/io/io_error.hpp"
#include "litamin2/io/pcd.hpp"

using namespace litamin2;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    fuzz::check_cloud(io::read_pcd(fuzz::as_file(data, size)));
    fuzz::accepted() = true;
  } catch (const io::IoError&) {
  }
  return 0;
}
