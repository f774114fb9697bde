#include "OutputFile.h"

#include <fstream>
#include <stdexcept>
#include <system_error>

namespace fs = std::filesystem;

namespace kautham::apps {

namespace {
/// /dev and /proc hold devices and the links to a process's streams (/dev/stdout): a file
/// written there through a temporary and a rename would replace them.
bool isUnderSystemFolder(const fs::path& path) {
  if (!path.is_absolute()) return false;
  auto first = path.begin();  // the root "/", then the first folder
  if (++first == path.end()) return false;
  return *first == "dev" || *first == "proc";
}

/// Whether `path`, as given or through its links, lies under /dev or /proc.
bool amongSystemDevices(const fs::path& path) {
  std::error_code ignored;
  return isUnderSystemFolder(fs::absolute(path, ignored)) ||
         isUnderSystemFolder(fs::weakly_canonical(path, ignored));
}

/// Refuses (through `refuse`) when the nearest folder on `path`'s way that exists is not one:
/// the rest are created.
template <typename Refuse>
void requireFolderOnTheWay(const fs::path& path, const Refuse& refuse) {
  std::error_code ignored;
  for (fs::path folder = path.parent_path(); !folder.empty(); folder = folder.parent_path()) {
    const fs::file_status s = fs::status(folder, ignored);
    if (fs::exists(s)) {
      if (!fs::is_directory(s)) refuse("'" + folder.string() + "' is not a folder");
      return;
    }
    if (folder == folder.parent_path()) return;
  }
}
}  // namespace

void requireOutputFolder(const fs::path& folder, const std::string& option) {
  const auto refuse = [&](const std::string& why) {
    throw std::invalid_argument(option + " " + folder.string() + ": " + why);
  };
  if (folder.empty()) refuse("give the name of a folder to write the results in");
  if (amongSystemDevices(folder))
    refuse("lies among the system's devices (/dev, /proc); give the name of a folder");
  std::error_code ignored;
  const fs::file_status status = fs::status(folder, ignored);  // through symbolic links
  if (fs::exists(status) && !fs::is_directory(status))
    refuse("is a file, not a folder; give the name of a folder to write the results in");
  requireFolderOnTheWay(folder, refuse);
}

void requireOutputFile(const fs::path& file, const std::string& option) {
  const auto refuse = [&](const std::string& why) {
    throw std::invalid_argument(option + " " + file.string() + ": " + why);
  };
  if (file.empty() || file.filename().empty()) refuse("give the name of a file to write");
  std::error_code ignored;
  if (amongSystemDevices(file))
    refuse(
        "lies among the system's devices (/dev, /proc), which writing would replace; give the "
        "name of a file");
  if (fs::exists(fs::symlink_status(file, ignored))) {
    const fs::file_status target = fs::status(file, ignored);  // through symbolic links
    if (fs::is_directory(target)) refuse("is a folder; give the name of a file to write in it");
    if (!fs::is_regular_file(target))
      refuse(
          "is not a regular file (a device, a pipe or a link to nothing) and writing would "
          "replace it; give the name of a file");
  }
  requireFolderOnTheWay(file, refuse);
}

void writeTextFile(const fs::path& given, const std::string& text) {
  requireOutputFile(given, "cannot write");
  // Through a symbolic link, the file it leads to is replaced, and the link kept.
  std::error_code ignored;
  const fs::path file =
      fs::is_symlink(fs::symlink_status(given, ignored)) ? fs::canonical(given) : given;
  const fs::path temporary = file.string() + ".tmp";
  try {
    if (file.has_parent_path()) fs::create_directories(file.parent_path());
    {
      std::ofstream out(temporary, std::ios::binary);
      if (!out) throw std::runtime_error("cannot create '" + temporary.string() + "'");
      out << text;
      out.flush();
      if (!out) throw std::runtime_error("writing '" + temporary.string() + "' failed");
    }
    fs::rename(temporary, file);
  } catch (const std::exception& e) {
    fs::remove(temporary, ignored);
    throw std::runtime_error("cannot write '" + given.string() + "': " + e.what());
  }
}

}  // namespace kautham::apps
