// Tests of typed parameters (core::ParameterSet) and of the registry of factories that uses
// them (core::FactoryRegistry).

#include <gtest/gtest.h>

#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "kautham/core/FactoryRegistry.h"
#include "kautham/core/Parameter.h"

namespace kautham::core {
namespace {

/// Expects `call` to throw std::invalid_argument whose message contains every one of `phrases`.
template <typename Call>
void expectInvalidArgument(Call call, const std::vector<std::string>& phrases) {
  try {
    call();
    ADD_FAILURE() << "no exception";
  } catch (const std::invalid_argument& error) {
    const std::string message = error.what();
    for (const std::string& phrase : phrases)
      EXPECT_NE(message.find(phrase), std::string::npos)
          << "expected \"" << phrase << "\" in: " << message;
  }
}

std::vector<ParameterSpec> someSpecs() {
  return {
      {"goal_bias",
       ParameterType::Real,
       0.05,
       0.0,
       1.0,
       "chance of sampling the goal",
       {"Goal Bias", "goalBias"}},
      {"max_steps",
       ParameterType::Integer,
       20,
       1,
       1000,
       "most steps a control is held",
       {"Max Control Steps"}},
      {"use_projection", ParameterType::Boolean, 1, 0, 1, "project states", {}},
      {"cfm", ParameterType::Real, 1e-5, 0.0, 1.0, "constraint force mixing", {}},
  };
}

// ----- ParameterSet -----

TEST(ParameterSet, StartsWithTheDefaults) {
  const ParameterSet set(someSpecs());
  EXPECT_DOUBLE_EQ(set.real("goal_bias"), 0.05);
  EXPECT_EQ(set.integer("max_steps"), 20);
  EXPECT_TRUE(set.boolean("use_projection"));
  EXPECT_DOUBLE_EQ(set.real("cfm"), 1e-5);
  EXPECT_EQ(set.specs().size(), 4u);
}

TEST(ParameterSet, KnowsCanonicalNamesAndAliases) {
  const ParameterSet set(someSpecs());
  EXPECT_TRUE(set.has("goal_bias"));
  EXPECT_TRUE(set.has("Goal Bias"));
  EXPECT_TRUE(set.has("goalBias"));
  EXPECT_TRUE(set.has("Max Control Steps"));
  EXPECT_FALSE(set.has("Min Control Steps"));
  EXPECT_FALSE(set.has("goal bias"));  // names are exact
  EXPECT_FALSE(ParameterSet().has("goal_bias"));
}

TEST(ParameterSet, SetByAliasChangesTheCanonicalValue) {
  ParameterSet set(someSpecs());
  set.set("Goal Bias", "0.2");
  EXPECT_DOUBLE_EQ(set.real("goal_bias"), 0.2);
  EXPECT_DOUBLE_EQ(set.real("goalBias"), 0.2);
  set.set("Max Control Steps", "35");
  EXPECT_EQ(set.integer("max_steps"), 35);
  EXPECT_EQ(set.values().at("goal_bias"), "0.2");
  EXPECT_EQ(set.values().count("Goal Bias"), 0u);  // values are listed by canonical name
}

TEST(ParameterSet, IntegerRejectsFractions) {
  ParameterSet set(someSpecs());
  expectInvalidArgument([&] { set.set("max_steps", "1.5"); }, {"max_steps", "whole number", "1.5"});
  expectInvalidArgument([&] { set.set("max_steps", "ten"); }, {"max_steps", "number", "ten"});
  EXPECT_EQ(set.integer("max_steps"), 20);
  set.set("max_steps", "7");
  EXPECT_EQ(set.integer("max_steps"), 7);
  set.set("max_steps", "1e2");
  EXPECT_EQ(set.integer("max_steps"), 100);
}

TEST(ParameterSet, BooleanAcceptsTrueFalseOneZero) {
  ParameterSet set(someSpecs());
  const std::vector<std::pair<std::string, bool>> accepted = {
      {"false", false}, {"true", true}, {"0", false},  {"1", true},
      {"FALSE", false}, {"True", true}, {"no", false}, {"yes", true}};
  for (const auto& [text, value] : accepted) {
    SCOPED_TRACE(text);
    set.set("use_projection", text);
    EXPECT_EQ(set.boolean("use_projection"), value);
  }
  for (const std::string text : {"maybe", "2", "", "0.5", "truee"}) {
    SCOPED_TRACE(text);
    expectInvalidArgument([&] { set.set("use_projection", text); },
                          {"use_projection", "true or false", "'" + text + "'"});
  }
}

TEST(ParameterSet, RealRejectsTextNanAndInfinity) {
  ParameterSet set(someSpecs());
  for (const std::string text :
       {"abc", "nan", "NaN", "inf", "-inf", "", "0.5x", "0.5 0.6", "0x0.1p0", "0x1"}) {
    SCOPED_TRACE(text);
    expectInvalidArgument([&] { set.set("goal_bias", text); },
                          {"goal_bias", "expects a number", "'" + text + "'"});
  }
  EXPECT_DOUBLE_EQ(set.real("goal_bias"), 0.05);
}

TEST(ParameterSet, ANumberBeyondADoubleIsOutOfRangeNotNotANumber) {
  ParameterSet set(someSpecs());
  for (const std::string text : {"1e400", "-1e400", "+2e308"}) {
    SCOPED_TRACE(text);
    expectInvalidArgument([&] { set.set("Goal Bias", text); },
                          {"parameter 'goal_bias' is out of range: " + text +
                               " is beyond the largest number a double holds",
                           "it must be in [0, 1]"});
    expectInvalidArgument([&] { set.set("max_steps", text); }, {"out of range", "[1, 1000]"});
  }
  EXPECT_FALSE(beyondDouble("1e300"));
  EXPECT_FALSE(beyondDouble("1e-400"));  // underflows to zero: a number, and a small one
  EXPECT_FALSE(beyondDouble("inf"));
  EXPECT_FALSE(beyondDouble("1e400x"));
  EXPECT_DOUBLE_EQ(set.real("goal_bias"), 0.05);
}

TEST(ParameterSet, RangeIsChecked) {
  ParameterSet set(someSpecs());
  expectInvalidArgument([&] { set.set("goal_bias", "1.5"); }, {"goal_bias", "[0, 1]", "1.5"});
  expectInvalidArgument([&] { set.set("Goal Bias", "-0.1"); }, {"goal_bias", "[0, 1]"});
  expectInvalidArgument([&] { set.set("max_steps", "0"); }, {"max_steps", "[1, 1000]"});
  expectInvalidArgument([&] { set.set("max_steps", "1001"); }, {"max_steps", "[1, 1000]"});
  // The bounds themselves are in range.
  set.set("goal_bias", "0");
  EXPECT_DOUBLE_EQ(set.real("goal_bias"), 0.0);
  set.set("goal_bias", "1");
  EXPECT_DOUBLE_EQ(set.real("goal_bias"), 1.0);
  set.set("max_steps", "1000");
  EXPECT_EQ(set.integer("max_steps"), 1000);
}

TEST(ParameterSet, RejectedValueLeavesThePreviousOne) {
  ParameterSet set(someSpecs());
  set.set("goal_bias", "0.3");
  EXPECT_THROW(set.set("goal_bias", "3"), std::invalid_argument);
  EXPECT_THROW(set.set("goal_bias", "abc"), std::invalid_argument);
  EXPECT_DOUBLE_EQ(set.real("goal_bias"), 0.3);
}

TEST(ParameterSet, UnknownNameListsTheKnownOnes) {
  ParameterSet set(someSpecs());
  const std::vector<std::string> phrases = {"unknown parameter 'Goal Biass'",
                                            "known: goal_bias, max_steps, use_projection, cfm"};
  expectInvalidArgument([&] { set.set("Goal Biass", "0.1"); }, phrases);
  expectInvalidArgument([&] { set.real("Goal Biass"); }, phrases);
  expectInvalidArgument([&] { set.integer("Goal Biass"); }, phrases);
  expectInvalidArgument([&] { set.boolean("Goal Biass"); }, phrases);
  expectInvalidArgument([&] { ParameterSet().set("x", "1"); }, {"unknown parameter 'x'", "none"});
}

TEST(ParameterSet, ValuesAreFormattedByType) {
  ParameterSet set(someSpecs());
  EXPECT_EQ(set.values(), (std::map<std::string, std::string>{{"goal_bias", "0.05"},
                                                              {"max_steps", "20"},
                                                              {"use_projection", "true"},
                                                              {"cfm", "1e-05"}}));
  set.set("goal_bias", "0.1");  // not 0.1000000000000000055511
  set.set("max_steps", "3");
  set.set("use_projection", "0");
  set.set("cfm", "0.125");
  EXPECT_EQ(set.values(), (std::map<std::string, std::string>{{"goal_bias", "0.1"},
                                                              {"max_steps", "3"},
                                                              {"use_projection", "false"},
                                                              {"cfm", "0.125"}}));
}

TEST(ParameterSpec, AnswersToItsNameAndAliasesOnly) {
  const ParameterSpec spec = someSpecs()[0];
  EXPECT_TRUE(spec.answersTo("goal_bias"));
  EXPECT_TRUE(spec.answersTo("Goal Bias"));
  EXPECT_FALSE(spec.answersTo("bias"));
  EXPECT_EQ(spec.formatValue(0.25), "0.25");
  EXPECT_EQ(someSpecs()[1].formatValue(42), "42");
  EXPECT_EQ(someSpecs()[2].formatValue(0), "false");
}

// ----- Parameter (named builders) and checkSpec -----

TEST(Parameter, BuildsTheSpecItNames) {
  const ParameterSpec real = Parameter::real("goal_bias")
                                 .byDefault(0.05)
                                 .range(0.0, 1.0)
                                 .describe("chance of sampling the goal")
                                 .alias("Goal Bias")
                                 .alias("goalBias");
  EXPECT_EQ(real.name, "goal_bias");
  EXPECT_EQ(real.type, ParameterType::Real);
  EXPECT_DOUBLE_EQ(real.defaultValue, 0.05);
  EXPECT_DOUBLE_EQ(real.min, 0.0);
  EXPECT_DOUBLE_EQ(real.max, 1.0);
  EXPECT_EQ(real.description, "chance of sampling the goal");
  EXPECT_EQ(real.aliases, (std::vector<std::string>{"Goal Bias", "goalBias"}));

  const ParameterSpec integer =
      Parameter::integer("max_steps").byDefault(20).range(1, 1000).describe("most steps");
  EXPECT_EQ(integer.type, ParameterType::Integer);
  EXPECT_DOUBLE_EQ(integer.max, 1000);

  const ParameterSpec flag = Parameter::flag("use_projection").byDefault(1).describe("project");
  EXPECT_EQ(flag.type, ParameterType::Boolean);
  EXPECT_DOUBLE_EQ(flag.min, 0.0);  // a flag's range needs no saying
  EXPECT_DOUBLE_EQ(flag.max, 1.0);
  EXPECT_NO_THROW(checkSpecs({real, integer, flag}));
}

TEST(Parameter, BuildersDoNotChangeWhatTheyStartFrom) {
  const Parameter base = Parameter::real("x").range(0, 1).describe("an x");
  const ParameterSpec a = base.byDefault(0.25);
  const ParameterSpec b = base.byDefault(0.75);
  EXPECT_DOUBLE_EQ(a.defaultValue, 0.25);
  EXPECT_DOUBLE_EQ(b.defaultValue, 0.75);
}

/// Expects checkSpecs to reject the specs with a message containing `phrase`.
void expectRejected(const std::vector<ParameterSpec>& specs, const std::string& phrase) {
  try {
    checkSpecs(specs);
    ADD_FAILURE() << "accepted; expected: " << phrase;
  } catch (const std::logic_error& error) {
    EXPECT_NE(std::string(error.what()).find(phrase), std::string::npos) << error.what();
  }
}

TEST(Parameter, MalformedSpecsAreRejectedByName) {
  const Parameter ok = Parameter::real("x").byDefault(0.5).range(0, 1).describe("an x");
  expectRejected({ok.byDefault(2)}, "'x': its default 2 is outside [0, 1]");
  expectRejected({ok.range(1, 0)}, "min > max");
  expectRejected({ok.describe("")}, "'x': no description");
  expectRejected({Parameter::real("Goal Bias").range(0, 1).describe("d")}, "snake_case");
  expectRejected({Parameter::integer("n").byDefault(1.5).range(0, 3).describe("d")},
                 "whole numbers");
  expectRejected({Parameter::flag("f").byDefault(1).range(0, 2).describe("d")}, "a flag's range");
  expectRejected({ok, Parameter::real("x").range(0, 1).describe("again")}, "'x' is declared twice");
  expectRejected({ok.alias("k"), Parameter::integer("n").range(0, 3).describe("d").alias("k")},
                 "both answer to 'k'");
  expectRejected({ok.alias("x")}, "the name itself");
}

TEST(FactoryRegistry, AddRejectsMalformedParameters) {
  FactoryRegistry<int> registry;
  try {
    registry.add({"broken",
                  "a broken entry",
                  {Parameter::real("x").byDefault(3).range(0, 1).describe("an x")},
                  [](const ParameterSet&) { return 1; }});
    ADD_FAILURE() << "a default outside its range was registered";
  } catch (const std::logic_error& error) {
    EXPECT_NE(std::string(error.what()).find("'broken': parameter 'x'"), std::string::npos)
        << error.what();
  }
  EXPECT_EQ(registry.find("broken"), nullptr);
  EXPECT_THROW(registry.add({"", "no name", {}, [](const ParameterSet&) { return 1; }}),
               std::logic_error);
  EXPECT_THROW(registry.add({"nofactory", "no factory", {}, nullptr}), std::logic_error);
}

// ----- SettingsParameters: one declaration per field, no copy by hand -----

struct DemoSettings {
  double bias;
  unsigned candidates;
  int offset;
  bool verbose;
};

SettingsParameters<DemoSettings> demoTable() {
  return SettingsParameters<DemoSettings>()
      .add(&DemoSettings::bias,
           Parameter::real("bias").byDefault(0.2).range(0, 1).describe("a bias").alias("b"))
      .add(&DemoSettings::candidates,
           Parameter::integer("candidates").byDefault(5).range(1, 100).describe("k").alias("k"))
      .add(&DemoSettings::offset,
           Parameter::integer("offset").byDefault(-3).range(-10, 10).describe("an offset"))
      .add(&DemoSettings::verbose, Parameter::flag("verbose").byDefault(0).describe("talk"))
      .add(Parameter::real("cell_size").byDefault(0.05).range(0.001, 1).describe("no field"));
}

TEST(SettingsParameters, ListsTheSpecsInDeclarationOrder) {
  const auto table = demoTable();
  std::vector<std::string> names;
  for (const ParameterSpec& spec : table.specs()) names.push_back(spec.name);
  EXPECT_EQ(names,
            (std::vector<std::string>{"bias", "candidates", "offset", "verbose", "cell_size"}));
}

TEST(SettingsParameters, FillsEveryFieldFromTheValues) {
  const auto table = demoTable();
  const DemoSettings defaults = table.defaults();
  EXPECT_DOUBLE_EQ(defaults.bias, 0.2);
  EXPECT_EQ(defaults.candidates, 5u);
  EXPECT_EQ(defaults.offset, -3);
  EXPECT_FALSE(defaults.verbose);

  ParameterSet values(table.specs());
  values.set("b", "0.125");
  values.set("k", "9");
  values.set("offset", "7");
  values.set("verbose", "true");
  const DemoSettings set = table.read(values);
  EXPECT_DOUBLE_EQ(set.bias, 0.125);
  EXPECT_EQ(set.candidates, 9u);
  EXPECT_EQ(set.offset, 7);
  EXPECT_TRUE(set.verbose);
}

struct WrappingSettings {
  DemoSettings demo;
  unsigned extra;
};

TEST(SettingsParameters, IncludesAnotherTablesParametersForAMemberOfItsOwn) {
  const auto table =
      SettingsParameters<WrappingSettings>()
          .include(&WrappingSettings::demo, demoTable())
          .add(&WrappingSettings::extra,
               Parameter::integer("extra").byDefault(2).range(0, 10).describe("its own"));
  std::vector<std::string> names;
  for (const ParameterSpec& spec : table.specs()) names.push_back(spec.name);
  EXPECT_EQ(names, (std::vector<std::string>{"bias", "candidates", "offset", "verbose", "cell_size",
                                             "extra"}));
  ParameterSet values(table.specs());
  values.set("k", "9");
  values.set("extra", "4");
  const WrappingSettings set = table.read(values);
  EXPECT_EQ(set.demo.candidates, 9u);
  EXPECT_DOUBLE_EQ(set.demo.bias, 0.2);
  EXPECT_EQ(set.extra, 4u);
  // A name the included table declares already is refused, as a name declared twice.
  SettingsParameters<WrappingSettings> twice;
  twice.add(&WrappingSettings::extra,
            Parameter::integer("offset").byDefault(0).range(0, 1).describe("taken"));
  EXPECT_THROW(twice.include(&WrappingSettings::demo, demoTable()), std::logic_error);
  EXPECT_EQ(twice.specs().size(), 1u);  // unchanged
}

TEST(SettingsParameters, FieldTypeMustMatchTheParameterType) {
  SettingsParameters<DemoSettings> table;
  EXPECT_THROW(table.add(&DemoSettings::bias,
                         Parameter::integer("bias").byDefault(1).range(0, 2).describe("d")),
               std::logic_error);
  EXPECT_THROW(table.add(&DemoSettings::verbose,
                         Parameter::real("verbose").byDefault(0).range(0, 1).describe("d")),
               std::logic_error);
  EXPECT_THROW(table.add(&DemoSettings::candidates,
                         Parameter::integer("candidates").byDefault(0).range(-1, 2).describe("d")),
               std::logic_error);  // an unsigned field cannot take -1
  EXPECT_THROW(demoTable().add(&DemoSettings::offset,
                               Parameter::integer("bias").range(0, 1).describe("twice")),
               std::logic_error);
}

// ----- FactoryRegistry -----

/// A registry whose products are strings built from a parameter and an extra argument.
using TestRegistry = FactoryRegistry<std::string, const std::string&>;

TestRegistry::Entry entry(const std::string& name, const std::string& summary) {
  return {name,
          summary,
          {{"count", ParameterType::Integer, 2, 1, 10, "how many", {"Count"}}},
          [name](const ParameterSet& parameters, const std::string& suffix) {
            return name + "x" + std::to_string(parameters.integer("count")) + suffix;
          }};
}

TestRegistry twoEntries() {
  TestRegistry registry;
  registry.add(entry("beta", "the second"));
  registry.add(entry("alpha", "the first"));
  return registry;
}

TEST(FactoryRegistry, FindsWhatWasAdded) {
  const TestRegistry registry = twoEntries();
  const TestRegistry::Entry* beta = registry.find("beta");
  ASSERT_NE(beta, nullptr);
  EXPECT_EQ(beta->name, "beta");
  EXPECT_EQ(beta->summary, "the second");
  EXPECT_EQ(registry.find("gamma"), nullptr);
  EXPECT_EQ(registry.find("Beta"), nullptr);
  EXPECT_EQ(&registry.at("alpha"), registry.find("alpha"));
  EXPECT_EQ(registry.at("alpha").summary, "the first");
}

TEST(FactoryRegistry, EntriesAreListedByName) {
  const TestRegistry registry = twoEntries();
  const auto entries = registry.entries();
  ASSERT_EQ(entries.size(), 2u);
  EXPECT_EQ(entries[0]->name, "alpha");
  EXPECT_EQ(entries[1]->name, "beta");
  EXPECT_TRUE(TestRegistry().entries().empty());
}

TEST(FactoryRegistry, UnknownNameListsTheKnownOnes) {
  const TestRegistry registry = twoEntries();
  expectInvalidArgument([&] { registry.at("gamma"); }, {"unknown", "'gamma'", "alpha, beta"});
  expectInvalidArgument([&] { registry.defaults("gamma"); }, {"'gamma'", "alpha, beta"});
}

TEST(FactoryRegistry, DuplicateAddThrowsAndKeepsTheFirst) {
  TestRegistry registry = twoEntries();
  try {
    registry.add(entry("alpha", "an impostor"));
    ADD_FAILURE() << "a second 'alpha' was accepted";
  } catch (const std::logic_error& error) {
    EXPECT_NE(std::string(error.what()).find("'alpha'"), std::string::npos) << error.what();
  }
  EXPECT_EQ(registry.at("alpha").summary, "the first");
  EXPECT_EQ(registry.entries().size(), 2u);
}

TEST(FactoryRegistry, DefaultsAndCreateUseTheEntrysParameters) {
  const TestRegistry registry = twoEntries();
  ParameterSet parameters = registry.defaults("beta");
  EXPECT_EQ(parameters.integer("count"), 2);
  EXPECT_EQ(registry.at("beta").create(parameters, "!"), "betax2!");
  parameters.set("Count", "7");
  EXPECT_EQ(registry.at("beta").create(parameters, "?"), "betax7?");
  EXPECT_THROW(parameters.set("count", "11"), std::invalid_argument);
}

}  // namespace
}  // namespace kautham::core
