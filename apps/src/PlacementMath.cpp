#include "PlacementMath.h"

#include <fmt/format.h>

namespace kautham::apps::placement {

Units uniform(std::mt19937_64& random, Units lo, Units hi) {
  const std::uint64_t range = static_cast<std::uint64_t>(hi - lo) + 1;
  const std::uint64_t rejectBelow = (0 - range) % range;  // 2^64 mod range
  std::uint64_t draw;
  do draw = random();
  while (draw < rejectBelow);
  return lo + static_cast<Units>(draw % range);
}

Point inDisc(std::mt19937_64& random, Point centre, Units radius) {
  for (;;) {
    const Units dx = uniform(random, -radius, radius);
    const Units dy = uniform(random, -radius, radius);
    if (squared(dx) + squared(dy) <= squared(radius)) return {centre.x + dx, centre.y + dy};
  }
}

std::string metres(Units value) {
  const Units magnitude = value < 0 ? -value : value;
  return fmt::format("{}{}.{:04d}", value < 0 ? "-" : "", magnitude / 10000, magnitude % 10000);
}

std::string escapeAttribute(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::string escapeComment(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '-' && !out.empty() && out.back() == '-') out += ' ';
    out += c;
  }
  if (!out.empty() && out.back() == '-') out += ' ';
  return out;
}

std::string obstacleXml(const std::string& urdf, const std::string& role, const std::string& name,
                        const std::string& x, const std::string& y, const std::string& z) {
  return fmt::format(
      "  <Obstacle obstacle=\"{}\" role=\"{}\">\n"
      "    <KauthamName name=\"{}\"/>\n"
      "    <Home X=\"{}\" Y=\"{}\" Z=\"{}\"/>\n"
      "  </Obstacle>\n",
      urdf, role, name, x, y, z);
}

std::string tablePhysicsXml(const SolverSettings& solver) {
  const std::string overRelaxation =
      solver.overRelaxation == SolverSettings{}.overRelaxation
          ? std::string()
          : fmt::format("overRelaxation=\"{:g}\" ", solver.overRelaxation);
  return solver.comment +
         fmt::format(
             "  <Physics stepSize=\"0.01\" gravity=\"0 0 -9.81\" maxContacts=\"8\" "
             "solverIterations=\"{}\"\n"
             "           {}friction=\"0.5\" erp=\"0.2\" cfm=\"1e-5\"/>\n",
             solver.iterations, overRelaxation) +
         "  <!-- what is known only roughly: object poses to 5 mm and 0.05 rad, friction to 0.05,\n"
         "       joint speeds to 0.2 % of their limits (p-KPIECE plans for it; validate samples "
         "it;\n"
         "       docs/planners.md says why not more) -->\n"
         "  <Uncertainty x=\"0.005\" y=\"0.005\" yaw=\"0.05\" friction=\"0.05\" "
         "control=\"0.002\"/>\n"
         "  <Interaction support=\"table\" maxObjectSpeed=\"1.0\" maxDisplacement=\"0.3\" "
         "maxTilt=\"0.35\"\n"
         "               targetTolerance=\"0.005\"/>\n";
}

}  // namespace kautham::apps::placement
