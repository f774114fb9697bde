// A URDF link's mass and inertia as written: a value that is not a finite number is refused at
// its line, never taken (urdfdom read a "nan" mass as zero, and kept an infinite inertia).

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "kautham/core/InputError.h"
#include "kautham/core/UrdfLoader.h"

namespace kautham::core {
namespace {

namespace fs = std::filesystem;

/// The error loading a one-link URDF whose <inertial> holds `mass` and `ixx` gives ("" if none).
std::string errorLoading(const std::string& mass, const std::string& ixx) {
  const fs::path file =
      fs::temp_directory_path() / ("kautham_inertial_" + std::to_string(getpid()) + ".urdf");
  std::ofstream(file) << "<?xml version=\"1.0\"?>\n<robot name=\"r\">\n  <link name=\"body\">\n"
                      << "    <inertial>\n      <mass value=\"" << mass << "\"/>\n"
                      << "      <inertia ixx=\"" << ixx
                      << "\" ixy=\"0\" ixz=\"0\" iyy=\"0.01\" iyz=\"0\" izz=\"0.01\"/>\n"
                      << "    </inertial>\n"
                      << "    <collision><geometry><box size=\"0.1 0.1 0.1\"/></geometry>"
                      << "</collision>\n  </link>\n</robot>\n";
  std::string error;
  try {
    loadUrdf(file, 1.0, {});
  } catch (const InputError& e) {
    error = e.what();
  }
  fs::remove(file);
  return error;
}

TEST(UrdfInertial, FiniteMassAndInertiaLoad) { EXPECT_EQ(errorLoading("0.5", "0.01"), ""); }

TEST(UrdfInertial, AMassThatIsNotANumberIsRefusedAtItsLine) {
  const std::string error = errorLoading("nan", "0.01");
  EXPECT_NE(error.find(":5: link 'body': <mass> value=\"nan\" must be a finite number"),
            std::string::npos)
      << error;
}

TEST(UrdfInertial, AnInfiniteInertiaIsRefusedAtItsLine) {
  const std::string error = errorLoading("0.5", "inf");
  EXPECT_NE(error.find(":6: link 'body': <inertia> ixx=\"inf\" must be a finite number"),
            std::string::npos)
      << error;
}

}  // namespace
}  // namespace kautham::core
