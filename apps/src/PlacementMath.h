#pragma once

// Integer geometry and text for the scene generators (ClutterGenerator, SideGraspClutter).
// Every length is a whole number of units of 0.1 mm and every computation on them is done in
// integers: a placement is then the same on every machine and standard library
// (std::mt19937_64 is specified bit for bit; std::uniform_*_distribution and floating-point
// rounding are not).

#include <cstdint>
#include <random>
#include <string>

namespace kautham::apps::placement {

using Units = std::int64_t;
constexpr double kUnit = 1e-4;  // metres per unit

struct Point {
  Units x;
  Units y;
};

inline Units squared(Units v) { return v * v; }
inline Units distanceSquared(Point a, Point b) { return squared(a.x - b.x) + squared(a.y - b.y); }

/// A whole number in [lo, hi], each equally likely: our own mapping of the generator's 64-bit
/// output, so that it does not depend on the standard library.
Units uniform(std::mt19937_64& random, Units lo, Units hi);

/// A point in the disc of the given radius about `centre`, each equally likely.
Point inDisc(std::mt19937_64& random, Point centre, Units radius);

/// A length in units as metres, exactly: "-0.1234".
std::string metres(Units value);

/// Text for an XML attribute value.
std::string escapeAttribute(const std::string& text);

/// Text for an XML comment, which may not contain "--" nor end with "-".
std::string escapeComment(const std::string& text);

/// One <Obstacle> element of a generated problem file, with its <KauthamName> and <Home>
/// position (coordinates as they are to be written).
std::string obstacleXml(const std::string& urdf, const std::string& role, const std::string& name,
                        const std::string& x, const std::string& y, const std::string& z);

/// How a generated scene asks ODE's QuickStep to solve its steps.
struct SolverSettings {
  int iterations = 20;
  double overRelaxation = 1.3;  ///< ODE's default; written only when another is asked for
  std::string comment;          ///< whole lines before the <Physics> element: why these
};

/// The <Physics>, <Uncertainty> and <Interaction> elements every generated table scene
/// shares (a commented block of the file), with the solver settings `solver`.
std::string tablePhysicsXml(const SolverSettings& solver = {});

}  // namespace kautham::apps::placement
