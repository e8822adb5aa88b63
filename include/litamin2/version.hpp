#pragma once

namespace litamin2 {
/// The project version, as set in CMakeLists.txt.
const char* version();
}  // namespace litamin2
