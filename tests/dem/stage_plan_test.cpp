// The stage plan (stage_plan.hpp): its phases never go back, the fixed core
// (begin_step's stages, the second kick) is listed but not walked, every
// other stage has its function, gravity's loads come first, and
// docs/architecture.md shows the plan as stage_plan_markdown prints it.
#include "gjkdem/dem/stage_plan.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

namespace gjkdem::dem {
namespace {

TEST(StagePlan, PhasesGoForwardAndOnlyTheFixedCoreIsNotWalked) {
  const std::span<const Stage> plan = stage_plan();
  ASSERT_FALSE(plan.empty());
  std::set<std::string_view> names;
  for (std::size_t k = 0; k < plan.size(); ++k) {
    const Stage& s = plan[k];
    EXPECT_TRUE(names.insert(s.name).second) << s.name << " twice";
    if (k > 0) {
      EXPECT_LE(plan[k - 1].phase, s.phase) << s.name << " comes after a later phase";
    }
    const bool core = s.phase == StagePhase::Integrate || s.phase == StagePhase::AfterForces;
    EXPECT_EQ(s.run == nullptr, core) << s.name;
    EXPECT_FALSE(s.file.empty() || s.reads.empty() || s.writes.empty()) << s.name;
  }
  const auto first = std::find_if(plan.begin(), plan.end(), [](const Stage& s) { return s.run != nullptr; });
  ASSERT_NE(first, plan.end());
  EXPECT_EQ(first->name, "loads");  // gravity and the applied loads, before any contact adds its force
}

TEST(StagePlan, TheArchitectureDocShowsThePlanAsPrinted) {
  std::ifstream in(std::string(GJKDEM_SOURCE_DIR) + "/docs/architecture.md");
  ASSERT_TRUE(in) << "docs/architecture.md not found";
  std::stringstream text;
  text << in.rdbuf();
  const std::string doc = text.str();
  const std::string begin = "<!-- stage plan: printed by dem::stage_plan_markdown() -->\n";
  const std::string end = "<!-- end of the stage plan -->";
  const std::size_t from = doc.find(begin), to = doc.find(end);
  ASSERT_NE(from, std::string::npos) << "no '" << begin << "' marker";
  ASSERT_NE(to, std::string::npos) << "no '" << end << "' marker";
  EXPECT_EQ(doc.substr(from + begin.size(), to - from - begin.size()), stage_plan_markdown())
      << "docs/architecture.md's stage list differs from the plan; put this there:\n"
      << stage_plan_markdown();
}

}  // namespace
}  // namespace gjkdem::dem
