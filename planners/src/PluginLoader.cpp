#include "kautham/planners/PluginLoader.h"

#include <dlfcn.h>
#include <elf.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <exception>
#include <fstream>
#include <iterator>
#include <map>
#include <optional>
#include <set>
#include <sstream>

#include "kautham/core/InputError.h"
#include "kautham/planners/Plugin.h"

namespace kautham::planners {

namespace {

namespace fs = std::filesystem;

/// What was loaded: files in order, and which file registered each plugin planner.
struct Loaded {
  std::vector<fs::path> files;
  std::map<std::string, fs::path> plannerFiles;
};

Loaded& loaded() {
  static Loaded state;
  return state;
}

[[noreturn]] void fail(const fs::path& file, const std::string& why) {
  throw core::InputError({file, 0}, "planner plugin: " + why);
}

fs::path absolutePath(const fs::path& file) {
  std::error_code error;
  const fs::path canonical = fs::weakly_canonical(fs::absolute(file), error);
  return error ? fs::absolute(file) : canonical;
}

/// Whether the ELF file `bytes` (the whole file) holds every byte its headers say it has, for
/// one ELF class (Header, Segment: Elf64_Ehdr and Elf64_Phdr, or the 32-bit ones).
template <typename Header, typename Segment>
bool elfComplete(const std::string& bytes) {
  const auto within = [&](std::uint64_t offset, std::uint64_t length) {
    return offset <= bytes.size() && length <= bytes.size() - offset;
  };
  if (bytes.size() < sizeof(Header)) return false;
  Header header;
  std::memcpy(&header, bytes.data(), sizeof header);
  if (header.e_shoff != 0 &&
      !within(header.e_shoff, std::uint64_t{header.e_shnum} * header.e_shentsize))
    return false;
  if (header.e_phentsize != sizeof(Segment) ||
      !within(header.e_phoff, std::uint64_t{header.e_phnum} * sizeof(Segment)))
    return false;
  for (std::size_t i = 0; i < header.e_phnum; ++i) {
    Segment segment;
    std::memcpy(&segment, bytes.data() + header.e_phoff + i * sizeof(Segment), sizeof segment);
    if (segment.p_type == PT_LOAD && !within(segment.p_offset, segment.p_filesz)) return false;
  }
  return true;
}

/// Why a file that starts as an ELF file cannot be a whole one (cut short, as by a copy
/// interrupted), if it cannot: dlopen maps the segments its headers name, and touching a page
/// past the file's end kills the process with SIGBUS instead of returning an error.
std::optional<std::string> truncatedElf(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (bytes.size() < EI_NIDENT || std::memcmp(bytes.data(), ELFMAG, SELFMAG) != 0)
    return std::nullopt;  // not ELF at all: dlopen says so itself
  const bool complete = bytes[EI_CLASS] == ELFCLASS64   ? elfComplete<Elf64_Ehdr, Elf64_Phdr>(bytes)
                        : bytes[EI_CLASS] == ELFCLASS32 ? elfComplete<Elf32_Ehdr, Elf32_Phdr>(bytes)
                                                        : true;
  if (complete) return std::nullopt;
  return "not a loadable shared library: the file is cut short (" + std::to_string(bytes.size()) +
         " bytes, fewer than its ELF headers name); copy or build it again";
}

/// Runs the plugin's registration into a registry of its own; returns the plugin's version.
unsigned registerInto(const fs::path& file, KauthamRegisterPlanners registerPlanners,
                      PlannerRegistry& staging) {
  try {
    return registerPlanners(KAUTHAM_PLUGIN_ABI_VERSION, &staging);
  } catch (const std::exception& e) {
    fail(file, std::string("its registration failed: ") + e.what());
  } catch (...) {
    fail(file, "its registration failed with an exception that is not a std::exception");
  }
}

void addFolder(const fs::path& folder, std::vector<fs::path>& files) {
  std::vector<fs::path> found;
  for (const fs::directory_entry& entry : fs::directory_iterator(folder))
    if (entry.is_regular_file() && entry.path().extension() == ".so") found.push_back(entry);
  std::sort(found.begin(), found.end());
  files.insert(files.end(), found.begin(), found.end());
}

void addPath(const fs::path& path, std::vector<fs::path>& files, const std::string& from) {
  if (fs::is_directory(path))
    addFolder(path, files);
  else if (fs::exists(path))
    files.push_back(path);
  else
    fail(path, "no such file or folder (" + from + ")");
}

}  // namespace

void loadPlannerPlugin(const fs::path& given, PlannerRegistry& registry) {
  const fs::path file = absolutePath(given);
  Loaded& state = loaded();
  if (std::find(state.files.begin(), state.files.end(), file) != state.files.end()) return;
  if (!fs::exists(file)) fail(file, "no such file");
  if (fs::is_directory(file)) fail(file, "a folder, not a library");

  if (const std::optional<std::string> why = truncatedElf(file)) fail(file, *why);

  // The library stays loaded to the end of the program: its planners' code is in it. A failed
  // plugin is not closed either (what it registered into the staging registry is destroyed
  // first, and the program ends soon after).
  dlerror();
  void* library = ::dlopen(file.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (library == nullptr) {
    const char* why = dlerror();
    fail(file, std::string("not a loadable shared library: ") + (why ? why : "dlopen failed"));
  }
  const auto registerPlanners =
      reinterpret_cast<KauthamRegisterPlanners>(::dlsym(library, KAUTHAM_PLUGIN_SYMBOL));
  if (registerPlanners == nullptr)
    fail(file, "not a kautham planner plugin: it exports no function " KAUTHAM_PLUGIN_SYMBOL
               " (define one with KAUTHAM_PLANNER_PLUGIN, see docs/plugins.md)");

  PlannerRegistry staging;
  const unsigned abi = registerInto(file, registerPlanners, staging);
  if (abi != KAUTHAM_PLUGIN_ABI_VERSION) {
    std::ostringstream why;
    why << "built for plugin ABI version " << abi << ", but this kautham has version "
        << KAUTHAM_PLUGIN_ABI_VERSION << ": rebuild the plugin against this kautham's SDK";
    fail(file, why.str());
  }
  const std::vector<const PlannerRegistry::Entry*> entries = staging.entries();
  if (entries.empty()) fail(file, "it registers no planner");
  for (const PlannerRegistry::Entry* entry : entries)
    if (registry.find(entry->name)) {
      const auto other = state.plannerFiles.find(entry->name);
      fail(file, "it registers planner '" + entry->name + "', a name already taken by " +
                     (other == state.plannerFiles.end() ? std::string("a built-in planner")
                                                        : "plugin " + other->second.string()));
    }
  for (const PlannerRegistry::Entry* entry : entries) {
    registry.add(*entry);
    state.plannerFiles[entry->name] = file;
  }
  state.files.push_back(file);
}

std::vector<fs::path> pluginFiles(const std::vector<std::string>& options,
                                  const std::string& pluginPath, const fs::path& programFolder) {
  std::vector<fs::path> files;
  for (const std::string& option : options) addPath(option, files, "--plugin");
  std::istringstream entries(pluginPath);
  for (std::string entry; std::getline(entries, entry, ':');)
    if (!entry.empty()) addPath(entry, files, "KAUTHAM_PLUGIN_PATH");
  const fs::path folder = pluginFolderOf(programFolder);
  if (!programFolder.empty() && fs::is_directory(folder)) addFolder(folder, files);

  std::vector<fs::path> distinct;
  std::set<fs::path> seen;
  for (const fs::path& file : files)
    if (seen.insert(absolutePath(file)).second) distinct.push_back(file);
  return distinct;
}

fs::path pluginFolderOf(const fs::path& programFolder) {
  return programFolder / ".." / "lib" / "kautham" / "plugins";
}

std::vector<fs::path> loadedPlugins() { return loaded().files; }

fs::path pluginOfPlanner(const std::string& name) {
  const auto it = loaded().plannerFiles.find(name);
  return it == loaded().plannerFiles.end() ? fs::path() : it->second;
}

}  // namespace kautham::planners
