#include <cstdio>
#include <stdexcept>

#include <fmt/format.h>

#include "Commands.h"
#include "PlanViewer.h"
#include "kautham/core/InputError.h"

namespace kautham::apps {

int runReportingErrors(const std::function<int()>& work) {
  try {
    return work();
  } catch (const core::InputError& e) {
    fmt::print(stderr, "error: {}\n", e.what());
  } catch (const ViewError& e) {
    fmt::print(stderr, "error: {}\n", e.what());
  } catch (const std::invalid_argument& e) {  // a command-line value the planner rejects
    fmt::print(stderr, "error: {}\n", e.what());
  } catch (const std::exception& e) {
    fmt::print(stderr, "error: {}\n", e.what());
    return kExitNotSolved;
  }
  return kExitBadInput;
}

}  // namespace kautham::apps
