#pragma once

namespace kautham::core {

/// The project's version, from CMake's project() call.
const char* version();

}  // namespace kautham::core
