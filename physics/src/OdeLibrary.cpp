#include "kautham/physics/OdeLibrary.h"

#include <cstdarg>
#include <cstdio>
#include <mutex>
#include <string>

#include <ode/ode.h>

#include "kautham/core/Log.h"

namespace kautham::physics {

namespace {
std::mutex libraryMutex;
std::weak_ptr<OdeLibrary> current;
std::string format(const char* message, va_list arguments) {
  char text[1024];
  std::vsnprintf(text, sizeof text, message, arguments);
  return text;
}

/// ODE's warnings (dMessage) go to our log on stderr, each text once, not to ODE's stderr print.
void odeMessage(int number, const char* message, va_list arguments) {
  const std::string text = format(message, arguments);
  kautham::core::warnOnce(
      "ode\n" + text,
      "ODE: " + text + (number ? " (ODE message " + std::to_string(number) + ")" : std::string()));
}

/// ODE's debug and error handlers abort the program after them; say what happened first.
void odeFatal(int number, const char* message, va_list arguments) {
  std::fprintf(stderr, "error: ODE %d: %s\n", number, format(message, arguments).c_str());
  std::fflush(stderr);
}

}  // namespace

std::shared_ptr<OdeLibrary> OdeLibrary::acquire() {
  std::lock_guard<std::mutex> lock(libraryMutex);
  std::shared_ptr<OdeLibrary> library = current.lock();
  if (!library) {
    library.reset(new OdeLibrary());
    current = library;
  }
  // Collision detection needs per-thread data in every thread that steps a world.
  dAllocateODEDataForThread(dAllocateMaskAll);
  return library;
}

OdeLibrary::OdeLibrary() {
  dSetMessageHandler(odeMessage);
  dSetDebugHandler(odeFatal);
  dSetErrorHandler(odeFatal);
  dInitODE2(0);
}

OdeLibrary::~OdeLibrary() { dCloseODE(); }

const char* OdeLibrary::version() { return KAUTHAM_ODE_VERSION; }

}  // namespace kautham::physics
