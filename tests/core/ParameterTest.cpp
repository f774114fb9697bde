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
  for (const std::string text : {"abc", "nan", "NaN", "inf", "-inf", "", "0.5x", "0.5 0.6"}) {
    SCOPED_TRACE(text);
    expectInvalidArgument([&] { set.set("goal_bias", text); },
                          {"goal_bias", "expects a number", "'" + text + "'"});
  }
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
