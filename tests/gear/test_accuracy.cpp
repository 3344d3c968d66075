// ISO 1328-1:2013's flank tolerances (gear/accuracy.hpp): the formulas of clause 5.3 evaluated by hand for one gear,
// each class √2 from the next, the scope and the refusals.
#include <gtest/gtest.h>

#include <cmath>

#include "common/error.hpp"
#include "gear/accuracy.hpp"

namespace {

using namespace sw;

// d = 50 mm, m_n = 2 mm, class 5, by hand from eqs. (5)-(9):
//   f_pT = 0.05 + 0.8 + 5 = 5.85;  F_pT = 0.1 + 0.55·√50 + 1.4 + 12 = 17.389087;  f_HαT = 0.8 + 0.05 + 4 = 4.85;
//   f_fαT = 1.1 + 5 = 6.1;  F_αT = √(4.85² + 6.1²) = 7.793106.
TEST(Iso1328, ClassFiveByHand) {
  const FlankTolerances t = iso1328_tolerances(50, 2, 5);
  EXPECT_NEAR(t.single_pitch_um, 5.85, 1e-12);
  EXPECT_NEAR(t.cumulative_pitch_um, 17.389087, 1e-6);
  EXPECT_NEAR(t.profile_slope_um, 4.85, 1e-12);
  EXPECT_NEAR(t.profile_form_um, 6.1, 1e-12);
  EXPECT_NEAR(t.profile_total_um, 7.793106, 1e-6);
}

// Clause 5.2: a class's tolerances are the next finer one's times √2; two classes double them.
TEST(Iso1328, EachClassRootTwoFromTheNext) {
  const FlankTolerances a = iso1328_tolerances(43.2, 0.216, 5), b = iso1328_tolerances(43.2, 0.216, 7),
                        c = iso1328_tolerances(43.2, 0.216, 6);
  EXPECT_NEAR(b.single_pitch_um / a.single_pitch_um, 2.0, 1e-12);
  EXPECT_NEAR(b.cumulative_pitch_um / a.cumulative_pitch_um, 2.0, 1e-12);
  EXPECT_NEAR(c.profile_form_um / a.profile_form_um, std::sqrt(2.0), 1e-12);
}

TEST(Iso1328, ScopeAndRefusals) {
  EXPECT_FALSE(iso1328_scope(50, 2));
  ASSERT_TRUE(iso1328_scope(43.2, 0.216));
  EXPECT_NE(iso1328_scope(43.2, 0.216)->find("0.5 mm"), std::string::npos);
  EXPECT_THROW(iso1328_tolerances(50, 2, 0), InputError);
  EXPECT_THROW(iso1328_tolerances(50, 2, 12), InputError);
  EXPECT_THROW(iso1328_tolerances(0, 2, 5), InputError);
}

}  // namespace
