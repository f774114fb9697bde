#include "kautham/core/Log.h"

#include <cstdio>
#include <mutex>
#include <set>

namespace kautham::core {

namespace {

std::mutex logMutex;
WarningSink currentSink;
std::set<std::string> seenKeys;

void emitLocked(const std::string& message) {
  if (currentSink) {
    currentSink(message);
    return;
  }
  std::fprintf(stderr, "warning: %s\n", message.c_str());
  std::fflush(stderr);
}

}  // namespace

void warning(const std::string& message) {
  std::lock_guard<std::mutex> lock(logMutex);
  emitLocked(message);
}

void warnOnce(const std::string& key, const std::string& message) {
  std::lock_guard<std::mutex> lock(logMutex);
  if (!seenKeys.insert(key).second) return;
  emitLocked(message);
}

WarningSink setWarningSink(WarningSink sink) {
  std::lock_guard<std::mutex> lock(logMutex);
  WarningSink previous = std::move(currentSink);
  currentSink = std::move(sink);
  return previous;
}

void resetWarnOnce() {
  std::lock_guard<std::mutex> lock(logMutex);
  seenKeys.clear();
}

}  // namespace kautham::core
