#include "kautham/core/KauthamBenchmark.h"

#include <set>

#include "XmlReader.h"

namespace kautham::core {

namespace {

namespace fs = std::filesystem;
using tinyxml2::XMLElement;

/// The <Name> of a problem file's <Planner>: all a benchmark entry takes from its file besides
/// the planner's parameters, which `kautham plan --planner-from` reads with the whole file.
std::string plannerName(const fs::path& problem) {
  const XmlReader xml(problem);
  const XMLElement& root = xml.root("Problem");
  const XMLElement* planner = root.FirstChildElement("Planner");
  const XMLElement* parameters = planner ? planner->FirstChildElement("Parameters") : nullptr;
  const XMLElement* name = parameters ? parameters->FirstChildElement("Name") : nullptr;
  if (!name || xml.elementText(*name).empty())
    xml.fail(planner ? *planner : root,
             "a benchmark entry's problem needs <Planner><Parameters><Name>: the planner it "
             "adds to the benchmark");
  return xml.elementText(*name);
}

class BenchmarkReader {
 public:
  explicit BenchmarkReader(const fs::path& file) : xml_(file) {}

  KauthamBenchmark read() {
    const XMLElement* first = xml_.anyRoot();
    if (first && std::string(first->Name()) == "Benchmark")
      if (const XMLElement* second = first->NextSiblingElement("Benchmark"))
        xml_.fail(*second,
                  "a second <Benchmark>: Kautham runs a file's benchmarks in turn, "
                  "`kautham bench --file` runs one; put each in a file of its own");
    const XMLElement& root = xml_.root("Benchmark");
    xml_.allowAttributes(root, {"Name"});
    xml_.allowChildren(root, {"Problem", "Parameter"});
    benchmark_.name = xml_.optionalText(root, "Name").value_or("");
    benchmark_.where = xml_.at(root);
    for (const XMLElement* e = root.FirstChildElement("Problem"); e;
         e = e->NextSiblingElement("Problem"))
      readEntry(*e);
    if (benchmark_.entries.empty())
      xml_.fail(root,
                "the benchmark has no <Problem File=\"...\" PlannerAlias=\"...\"/>: "
                "nothing to run");
    std::set<std::string> given;
    for (const XMLElement* e = root.FirstChildElement("Parameter"); e;
         e = e->NextSiblingElement("Parameter"))
      readSetting(*e, given);
    return benchmark_;
  }

 private:
  void readEntry(const XMLElement& e) {
    xml_.allowAttributes(e, {"File", "PlannerAlias"});
    KauthamBenchmarkEntry entry;
    const fs::path given = xml_.requiredText(e, "File");
    // Kautham joins the benchmark's folder and File; an absolute File is taken as it is.
    entry.problem =
        given.is_absolute() ? given : (xml_.file().parent_path() / given).lexically_normal();
    entry.where = xml_.at(e);
    if (!fs::is_regular_file(entry.problem))
      xml_.fail(e, "problem file '" + given.string() + "' not found (looked for " +
                       entry.problem.string() + ")");
    entry.planner = plannerName(entry.problem);
    entry.alias = xml_.optionalText(e, "PlannerAlias").value_or("");
    benchmark_.entries.push_back(std::move(entry));
  }

  void readSetting(const XMLElement& e, std::set<std::string>& given) {
    xml_.allowAttributes(e, {"Name", "Value"});
    const std::string name = xml_.requiredText(e, "Name");
    if (!xml_.optionalText(e, "Value"))
      xml_.fail(e, "<Parameter Name=\"" + name + "\"> needs the attribute Value");
    if (!given.insert(name).second)
      xml_.fail(e, "the benchmark sets '" + name + "' twice; keep one");
    if (name == "maxTime") {
      benchmark_.maxTime = xml_.number(e, "Value", 0.0);
      if (!(benchmark_.maxTime > 0.0)) xml_.fail(e, "maxTime must be a positive number of seconds");
    } else if (name == "runCount") {
      const int runs = xml_.integer(e, "Value", 0);
      if (runs < 1) xml_.fail(e, "runCount must be a whole number of at least 1");
      benchmark_.runCount = static_cast<std::size_t>(runs);
    } else if (name == "maxMem" || name == "timeBetweenUpdates") {
      xml_.number(e, "Value", 0.0);  // checked, so that a typo is not carried on
      keep(name, e);
    } else if (name == "displayProgress" || name == "saveConsoleOutput") {
      xml_.flag(e, "Value", true);
      keep(name, e);
    } else if (name == "filename") {
      keep(name, e);
    } else {
      xml_.fail(e, "unknown benchmark parameter '" + name +
                       "'; Kautham's are maxTime, maxMem, runCount, timeBetweenUpdates, "
                       "displayProgress, saveConsoleOutput, filename");
    }
  }

  void keep(const std::string& name, const XMLElement& e) {
    benchmark_.unused.push_back({name, *xml_.optionalText(e, "Value"), xml_.at(e)});
  }

  XmlReader xml_;
  KauthamBenchmark benchmark_;
};

}  // namespace

KauthamBenchmark loadKauthamBenchmark(const std::filesystem::path& file) {
  return BenchmarkReader(file).read();
}

}  // namespace kautham::core
