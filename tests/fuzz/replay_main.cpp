// The main() of a fuzz harness in the normal (GCC) build: runs LLVMFuzzerTestOneInput once on
// every file given and on every file of every folder given (the seed corpus, the regression
// inputs), so that the harnesses and their property checks run in every test suite without
// libFuzzer. Every input named regression-* (a finding of issue 14) or reject-* (an invalid
// seed written to be rejected) must be rejected by the parser. Exit 0 when every input was run
// and every such input rejected (a violated property aborts).

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace fs = std::filesystem;

int main(int argc, char** argv) {
  std::vector<fs::path> inputs;
  for (int i = 1; i < argc; ++i) {
    const fs::path arg = argv[i];
    if (fs::is_directory(arg)) {
      for (const auto& entry : fs::recursive_directory_iterator(arg))
        if (entry.is_regular_file()) inputs.push_back(entry.path());
    } else {
      inputs.push_back(arg);
    }
  }
  std::sort(inputs.begin(), inputs.end());
  if (inputs.empty()) {
    std::fprintf(stderr, "usage: %s CORPUS_DIR_OR_FILE...\n", argv[0]);
    return 2;
  }
  std::size_t regressions = 0, accepted_regressions = 0, accepted_others = 0;
  for (const fs::path& path : inputs) {
    std::ifstream in(path, std::ios::binary);
    const std::vector<char> bytes((std::istreambuf_iterator<char>(in)),
                                  std::istreambuf_iterator<char>());
    litamin2::fuzz::accepted() = false;
    LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
    const std::string name = path.filename().string();
    if (name.rfind("regression-", 0) != 0 && name.rfind("reject-", 0) != 0) {
      accepted_others += litamin2::fuzz::accepted();
      continue;
    }
    ++regressions;
    if (litamin2::fuzz::accepted()) {
      std::fprintf(stderr, "%s: accepted, but it must be rejected\n", path.c_str());
      ++accepted_regressions;
    }
  }
  std::printf(
      "%s: %zu input(s) replayed: %zu of %zu seed(s) accepted, %zu of %zu regression "
      "input(s) accepted\n",
      argv[0], inputs.size(), accepted_others, inputs.size() - regressions, accepted_regressions,
      regressions);
  return accepted_regressions == 0 ? 0 : 1;
}
