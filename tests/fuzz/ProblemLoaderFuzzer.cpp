// libFuzzer target: any bytes given to the problem loader either load or raise InputError.
// Anything else (a crash, a sanitizer report, another exception) is a bug the fuzzer reports.
// Build and run with scripts/fuzz.sh.

#include <unistd.h>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <system_error>

#include "kautham/core/InputError.h"
#include "kautham/core/ProblemLoader.h"

namespace {

/// One scratch folder per process, beside which the repository's models are searched; removed
/// when the fuzzer exits (libFuzzer ends its runs with exit(), which runs static destructors), so
/// that runs do not pile folders up in the temporary directory.
struct ScratchFolder {
  std::filesystem::path folder =
      std::filesystem::temp_directory_path() / ("kautham_fuzz_" + std::to_string(::getpid()));
  ScratchFolder() { std::filesystem::create_directories(folder); }
  ~ScratchFolder() {
    std::error_code ignored;
    std::filesystem::remove_all(folder, ignored);
  }
  ScratchFolder(const ScratchFolder&) = delete;
  ScratchFolder& operator=(const ScratchFolder&) = delete;
};

const std::filesystem::path& scratchFile() {
  static const ScratchFolder scratch;
  static const std::filesystem::path file = scratch.folder / "problem.xml";
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
