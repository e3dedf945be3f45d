// The stage plan (stage_plan.hpp): its phases never go back, the fixed core
// (begin_step's stages, the second kick) is listed but not walked, every
// other stage has its function, gravity's loads come first, and
// docs/architecture.md shows the plan as stage_plan_markdown prints it; the
// domain couplings' rows are whole, each point's together, and shown as
// domain_couplings_markdown prints them.
#include "gjkdem/dem/stage_plan.hpp"
#include "gjkdem/dem/domain_couplings.hpp"

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

// The text between `begin` and `end` in docs/architecture.md.
std::string doc_between(const std::string& begin, const std::string& end) {
  std::ifstream in(std::string(GJKDEM_SOURCE_DIR) + "/docs/architecture.md");
  if (!in) {
    ADD_FAILURE() << "docs/architecture.md not found";
    return "";
  }
  std::stringstream text;
  text << in.rdbuf();
  const std::string doc = text.str();
  const std::size_t from = doc.find(begin), to = doc.find(end);
  if (from == std::string::npos || to == std::string::npos || to < from) {
    ADD_FAILURE() << "no '" << begin << "' ... '" << end << "' markers";
    return "";
  }
  return doc.substr(from + begin.size(), to - from - begin.size());
}

TEST(StagePlan, TheArchitectureDocShowsThePlanAsPrinted) {
  EXPECT_EQ(doc_between("<!-- stage plan: printed by dem::stage_plan_markdown() -->\n", "<!-- end of the stage plan -->"),
            stage_plan_markdown())
      << "docs/architecture.md's stage list differs from the plan; put this there:\n"
      << stage_plan_markdown();
}

TEST(DomainCouplings, EachPointsRowsAreTogetherAndEachRowIsWhole) {
  std::set<std::string_view> names;
  const std::span<const DomainCoupling> rows = domain_couplings();
  ASSERT_FALSE(rows.empty());
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const DomainCoupling& c = rows[k];
    EXPECT_TRUE(names.insert(c.name).second) << c.name << " twice";
    if (k > 0) {
      EXPECT_LE(rows[k - 1].point, c.point) << c.name << " is listed after a later point";
    }
    EXPECT_TRUE(c.needed && c.run) << c.name;
    EXPECT_FALSE(c.needed_by.empty() || c.file.empty() || c.reads.empty() || c.writes.empty()) << c.name;
  }
}

TEST(DomainCouplings, TheArchitectureDocShowsThemAsPrinted) {
  EXPECT_EQ(doc_between("<!-- domain couplings: printed by dem::domain_couplings_markdown() -->\n",
                        "<!-- end of the domain couplings -->"),
            domain_couplings_markdown())
      << "docs/architecture.md's domain couplings differ from the table; put this there:\n"
      << domain_couplings_markdown();
}

}  // namespace
}  // namespace gjkdem::dem
