// libFuzzer target: any bytes given to the problem loader either load or raise InputError.
// Anything else (a crash, a sanitizer report, another exception) is a bug the fuzzer reports.
// Build and run with scripts/fuzz.sh.

#include <unistd.h>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>

#include "kautham/core/InputError.h"
#include "kautham/core/ProblemLoader.h"

namespace {

/// One scratch folder per process, beside which the repository's models are searched.
const std::filesystem::path& scratchFile() {
  static const std::filesystem::path file = [] {
    const auto folder =
        std::filesystem::temp_directory_path() / ("kautham_fuzz_" + std::to_string(::getpid()));
    std::filesystem::create_directories(folder);
    return folder / "problem.xml";
  }();
  return file;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  {
    std::ofstream out(scratchFile(), std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  try {
    kautham::core::loadProblem(scratchFile(),
                               {std::filesystem::path(KAUTHAM_SOURCE_DIR) / "models"});
  } catch (const kautham::core::InputError&) {
    // The expected answer to bad input.
  }
  return 0;
}
