// Parameter tables (util/parameters.h) and the registries' use of them: a
// value is read as declared, a misplaced or misspelt one is refused with the
// methods that take it, and one name means one thing in every table.
#include "util/parameters.h"

#include <gtest/gtest.h>

#include <map>

#include "display/tone_operator.h"
#include "input_errors.h"
#include "radiosity/solver.h"
#include "render/registry.h"

namespace radiant {
namespace {

const ParameterTable &table() {
  static const ParameterTable t = {
      {"sources", ParameterType::Integer, "4", "patches", 0, 100},
      {"fraction", ParameterType::Real, "0.5", "share", 0, 1},
      {"ff", ParameterType::Choice, "mc", "visibility", 0, 0, {"point", "mc"}},
      {"selective", ParameterType::Flag, "false", "re-evaluate"},
  };
  return t;
}

ParameterValues given(std::initializer_list<std::pair<std::string, std::string>> values) {
  ParameterValues v;
  for (const auto &[name, text] : values) v.set(name, text, InputLocation{"--" + name});
  return v;
}

TEST(Parameters, ReadTheGivenValueOrTheTablesDefault) {
  const Parameters p(table(), given({{"sources", "7"}, {"selective", "true"}}));
  EXPECT_EQ(p.integer("sources"), 7);
  EXPECT_TRUE(p.given("sources"));
  EXPECT_DOUBLE_EQ(p.real("fraction"), 0.5);
  EXPECT_FALSE(p.given("fraction"));
  EXPECT_EQ(p.choice("ff"), "mc");
  EXPECT_TRUE(p.flag("selective"));
  EXPECT_THROW(p.integer("undeclared"), std::logic_error);  // a method reading what it did not declare
}

TEST(Parameters, RefuseValuesOfTheWrongTypeOrOutOfRangeAtTheirOrigin) {
  auto check = [](std::initializer_list<std::pair<std::string, std::string>> values) {
    return test::inputErrorOf([&] { checkParameters(table(), given(values), "method m", {}); });
  };
  EXPECT_NE(check({{"sources", "2.5"}}).find("--sources: expected an integer"), std::string::npos);
  EXPECT_NE(check({{"sources", "101"}}).find("--sources: must be in 0…100"), std::string::npos);
  EXPECT_NE(check({{"fraction", "nan"}}).find("--fraction: expected a number"), std::string::npos);
  EXPECT_NE(check({{"fraction", "1e999"}}).find("--fraction"), std::string::npos);
  EXPECT_NE(check({{"ff", "pt"}}).find("--ff: expected one of point, mc"), std::string::npos);
  EXPECT_NE(check({{"selective", "maybe"}}).find("--selective: expected true or false"), std::string::npos);
  EXPECT_EQ(check({{"sources", "100"}, {"fraction", "0"}, {"ff", "point"}}), "");
}

TEST(Parameters, AnIntegerThatMustBeAMultipleIsRefusedOtherwiseWhenRead) {
  // bump-orientations (two tilts × azimuths): an odd count was refused only
  // after the solve; the table now says it, and reading the value refuses it.
  ParameterSpec even{"orientations", ParameterType::Integer, "16", "", 4, 64};
  even.multipleOf = 2;
  ParameterSpec third = even;
  third.multipleOf = 3;
  EXPECT_EQ(even.describeRange(), "4…64, even");
  EXPECT_EQ(third.describeRange(), "4…64, a multiple of 3");
  const InputLocation where{"--orientations"};
  EXPECT_EQ(parseParameter(even, "8", where), 8);
  EXPECT_EQ(parseParameter(third, "9", where), 9);
  EXPECT_NE(test::inputErrorOf([&] { parseParameter(even, "9", where); }).find("--orientations: must be even, got 9"),
            std::string::npos);
  EXPECT_NE(test::inputErrorOf([&] { parseParameter(third, "8", where); }).find("must be a multiple of 3, got 8"),
            std::string::npos);
  EXPECT_NE(test::inputErrorOf([&] { parseParameter(even, "66", where); }).find("must be in 4…64, even, got 66"),
            std::string::npos);
}

TEST(Parameters, AMisplacedParameterNamesTheMethodsThatTakeIt) {
  const ParameterTable other = {{"radius", ParameterType::Real, "1", "r"}};
  const std::string misplaced = test::inputErrorOf([&] {
    checkParameters(other, given({{"sources", "3"}}), "method disc", {{"kok", &table()}});
  });
  EXPECT_NE(misplaced.find("--sources: method disc does not use it (used by kok)"), std::string::npos) << misplaced;
  const std::string misspelt = test::inputErrorOf([&] {
    checkParameters(table(), given({{"sorces", "3"}}), "method kok", {{"kok", &table()}});
  });
  EXPECT_NE(misspelt.find("unknown parameter 'sorces' (did you mean 'sources'?)"), std::string::npos) << misspelt;
}

/// Every table of the registries: names unique within a table, and a name
/// shared by several (selective, max-depth, mesh-size…) declared identically,
/// so that one flag means one thing; defaults parse as their own type.
TEST(Parameters, EveryRegistryTableIsConsistent) {
  std::vector<std::pair<std::string, const ParameterTable *>> tables;
  for (const RendererInfo &info : rendererRegistry()) tables.push_back({info.name, &info.parameters});
  for (const char *solver : {"auto", "gauss-seidel", "progressive", "hierarchical", "stochastic", "hierarchical-exact"})
    tables.push_back({solver, &solverParameters(solver)});
  for (const ToneOperatorInfo &info : toneOperatorRegistry()) tables.push_back({info.name, &info.parameters});
  for (const FormFactorEstimatorInfo &e : formFactorEstimators()) tables.push_back({e.name, &e.parameters});
  std::map<std::string, const ParameterSpec *> byName;
  for (const auto &[owner, t] : tables) {
    std::map<std::string, int> seen;
    for (const ParameterSpec &spec : *t) {
      EXPECT_EQ(++seen[spec.name], 1) << owner << " declares " << spec.name << " twice";
      EXPECT_FALSE(spec.documentation.empty()) << owner << ": " << spec.name;
      if (!spec.defaultValue.empty())
        EXPECT_NO_THROW(parseParameter(spec, spec.defaultValue, InputLocation::ofParameter(spec.name)))
            << owner << ": " << spec.name << "'s default";
      else
        EXPECT_FALSE(spec.defaultDescription.empty()) << owner << ": " << spec.name << " has no default";
      auto [it, added] = byName.emplace(spec.name, &spec);
      if (!added) {
        EXPECT_EQ(int(it->second->type), int(spec.type)) << spec.name;
        EXPECT_EQ(it->second->defaultValue, spec.defaultValue) << spec.name;
        EXPECT_EQ(it->second->documentation, spec.documentation) << spec.name;
      }
    }
  }
  // A renderer parameter and a solver parameter never share a name: the command line has one flag for both.
  for (const RendererInfo &info : rendererRegistry())
    for (const ParameterSpec &spec : info.parameters)
      for (const ParameterSpec &solverSpec : solverParameters("auto")) EXPECT_NE(spec.name, solverSpec.name);
}

TEST(Parameters, AMethodTakesOnlyWhatItsTableDeclares) {
  const std::string error = test::inputErrorOf([] {
    methodParameters(findRenderer("path"), given({{"sources", "2"}}));
  });
  EXPECT_NE(error.find("method path does not use it (used by kok, multipass)"), std::string::npos) << error;
  const std::string both = test::inputErrorOf([] {
    methodParameters(findRenderer("kok"), given({{"sources", "2"}, {"source-fraction", "0.5"}}));
  });
  EXPECT_NE(both.find("--source-fraction: give sources or source-fraction, not both"), std::string::npos) << both;
  const std::string solverError = test::inputErrorOf([] {
    checkSolverParameters("stochastic", given({{"quality", "low"}}));
  });
  EXPECT_NE(solverError.find("solver stochastic does not use it (used by auto, hierarchical-exact)"), std::string::npos)
      << solverError;
}

}  // namespace
}  // namespace radiant
