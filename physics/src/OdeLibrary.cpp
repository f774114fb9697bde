#include "kautham/physics/OdeLibrary.h"

#include <mutex>

#include <ode/ode.h>

namespace kautham::physics {

namespace {
std::mutex libraryMutex;
std::weak_ptr<OdeLibrary> current;
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

OdeLibrary::OdeLibrary() { dInitODE2(0); }

OdeLibrary::~OdeLibrary() { dCloseODE(); }

const char* OdeLibrary::version() { return KAUTHAM_ODE_VERSION; }

}  // namespace kautham::physics
