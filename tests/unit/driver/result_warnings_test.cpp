// driver::result_warnings: what a result's status does not say is a warning, in the report
// (RunReport::warnings, printed by the command line in the summary and on stderr):
//   - an agglomerate partition coarsened to pass condition (5.1), with the patches and ratios
//     before and after (ContactDiscretization::partition_note);
//   - a pair whose slips left small sliding, with the step of a path at which they did;
//   - a master that penetrates its slave beyond kMasterPenetrationShare of the normal
//     displacement.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "fricon/driver/run.hpp"

using namespace fricon;
using namespace fricon::driver;
using testing::HasSubstr;

TEST(ResultWarnings, NoneWithoutContactOrWhenAllIsWell) {
  RunReport r;
  EXPECT_TRUE(result_warnings(r).empty());
  r.contact = ContactReport{};
  r.contact->pairs.push_back(PairReport{});
  EXPECT_TRUE(result_warnings(r).empty());
}

TEST(ResultWarnings, ACoarsenedPartitionIsAWarningWithItsRatios) {
  RunReport r;
  r.contact = ContactReport{};
  r.contact->partition_note =
      "agglomerate partition coarsened (unstable: patch_size 0.001 m: 120 patches, ratio "
      "3.10e-17) to patch_size 0.0041 m: 14 patches, ratio 2.50e-02";
  const std::vector<std::string> w = result_warnings(r);
  ASSERT_EQ(w.size(), 1u);
  EXPECT_THAT(w[0], HasSubstr("condition (5.1)"));
  EXPECT_THAT(w[0], HasSubstr("120 patches, ratio 3.10e-17"));
  EXPECT_THAT(w[0], HasSubstr("14 patches, ratio 2.50e-02"));
}

TEST(ResultWarnings, SlidingAndPenetrationArePerPair) {
  RunReport r;
  r.contact = ContactReport{};
  PairReport p;
  p.info.key = "contact[1]";
  p.info.master = "lower_top";
  p.info.boundary = "upper_bottom";
  p.info.master_element_size = 1e-3;
  p.max_slip = 4e-3;
  p.max_slip_step = 2;
  p.small_sliding = false;
  p.master_penetration = 1e-5;
  p.normal_displacement = 1e-4;
  p.master_kept_out = false;
  r.contact->pairs = {PairReport{}, p};
  const std::vector<std::string> w = result_warnings(r);
  ASSERT_EQ(w.size(), 2u);
  EXPECT_THAT(w[0], HasSubstr("contact[1]: the largest relative slip 4.000e-03 m (at step 2)"));
  EXPECT_THAT(w[1], HasSubstr("the master 'lower_top' penetrates the contact surface"));
  EXPECT_THAT(w[1], HasSubstr("1.000e-05 m"));
}
