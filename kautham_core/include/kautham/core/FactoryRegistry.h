#pragma once

#include <functional>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "kautham/core/Parameter.h"

namespace kautham::core {

/// A registry of things created by name with typed parameters (planners, for one).
/// It knows nothing of what it creates: `Product` and `Args` are chosen by the part that uses
/// it, so the core stays free of planners and physics.
template <typename Product, typename... Args>
class FactoryRegistry {
 public:
  using Factory = std::function<Product(const ParameterSet&, Args...)>;

  struct Entry {
    std::string name;
    std::string summary;  ///< one line
    std::vector<ParameterSpec> parameters;
    Factory create;
  };

  /// Adds an entry. A second entry with the same name, an entry without a name, summary or
  /// factory, and malformed or clashing parameter specs (checkSpecs) are programming errors:
  /// std::logic_error naming the entry.
  void add(Entry entry) {
    const std::string key = entry.name;
    if (key.empty() || entry.summary.empty() || !entry.create)
      throw std::logic_error("registry: an entry needs a name, a summary and a factory ('" + key +
                             "')");
    try {
      checkSpecs(entry.parameters);
    } catch (const std::logic_error& e) {
      throw std::logic_error("registry: '" + key + "': " + e.what());
    }
    if (!entries_.emplace(key, std::move(entry)).second)
      throw std::logic_error("registry: '" + key + "' is registered twice");
  }

  const Entry* find(const std::string& name) const {
    auto it = entries_.find(name);
    return it == entries_.end() ? nullptr : &it->second;
  }

  /// The entry, or std::invalid_argument listing the registered names.
  const Entry& at(const std::string& name) const {
    if (const Entry* entry = find(name)) return *entry;
    std::string known;
    for (const auto& [key, value] : entries_) known += (known.empty() ? "" : ", ") + key;
    throw std::invalid_argument("unknown planner '" + name + "'; known: " + known);
  }

  /// A parameter set with the entry's defaults, ready for `set` calls.
  ParameterSet defaults(const std::string& name) const { return ParameterSet(at(name).parameters); }

  std::vector<const Entry*> entries() const {
    std::vector<const Entry*> all;
    for (const auto& [key, entry] : entries_) all.push_back(&entry);
    return all;
  }

 private:
  std::map<std::string, Entry> entries_;
};

}  // namespace kautham::core
