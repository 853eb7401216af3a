// The committed Sobol table (assets/sampling/sobol_dirs.bin) is exactly what the generator computes, so it
// cannot go stale, and sobolDirectionNumbers() serves it without running the search.
#include <gtest/gtest.h>

#include "sampling/sobol.h"
#include "shared/random.h"

using namespace wb;

TEST(Sobol, CommittedTableMatchesGenerator) {
  const std::vector<uint32_t> committed = loadCommittedSobolDirections();
  const std::vector<uint32_t> generated = generateSobolDirectionNumbers(kSobolCommittedDims);
  ASSERT_EQ(committed.size(), generated.size());
  size_t mismatches = 0;
  for (size_t i = 0; i < committed.size(); ++i) mismatches += committed[i] != generated[i];
  EXPECT_EQ(mismatches, 0u) << "assets/sampling/sobol_dirs.bin is stale: rebuild and run wb_gen_sobol";
  EXPECT_GE(kSobolCommittedDims, static_cast<int>(WB_SOBOL_DIMS)) << "the renderer needs WB_SOBOL_DIMS dims";
}

TEST(Sobol, FastPathServesTheCommittedTable) {
  const std::vector<uint32_t> committed = loadCommittedSobolDirections();
  const std::vector<uint32_t> dirs = sobolDirectionNumbers(static_cast<int>(WB_SOBOL_DIMS));
  ASSERT_EQ(dirs.size(), size_t(WB_SOBOL_DIMS) * 32u);
  EXPECT_TRUE(std::equal(dirs.begin(), dirs.end(), committed.begin()));
  // A prefix request is a prefix of the table; more dims than committed still works (the search).
  const std::vector<uint32_t> few = sobolDirectionNumbers(7);
  EXPECT_TRUE(std::equal(few.begin(), few.end(), committed.begin()));
}
