#pragma once

#include <memory>

namespace kautham::physics {

/// Keeps the ODE library initialised while any world exists (dInitODE2 .. dCloseODE).
/// ODE must outlive every object made with it, or the program crashes at exit: each World
/// holds a reference, so the library closes only after the last world is destroyed.
class OdeLibrary {
 public:
  static std::shared_ptr<OdeLibrary> acquire();
  ~OdeLibrary();
  OdeLibrary(const OdeLibrary&) = delete;
  OdeLibrary& operator=(const OdeLibrary&) = delete;

  /// Version of the ODE library the program was built with, e.g. "0.16.2".
  static const char* version();

 private:
  OdeLibrary();
};

}  // namespace kautham::physics
