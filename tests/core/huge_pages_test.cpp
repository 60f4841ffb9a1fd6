// When the process asks malloc for huge pages (core/huge_pages.h): only where the kernel
// hands them out on request, never twice, keeping the tunables already set.
#include "core/huge_pages.h"

#include <gtest/gtest.h>

namespace photovr {
namespace {

const std::string kOnRequest = "always [madvise] never";

TEST(HugePages, AskedForWhereTheKernelGivesThemOnRequestOnly) {
  EXPECT_EQ(tunablesWithHugePages(nullptr, kOnRequest), "glibc.malloc.hugetlb=1");
  EXPECT_EQ(tunablesWithHugePages("", kOnRequest), "glibc.malloc.hugetlb=1");
  EXPECT_EQ(tunablesWithHugePages(nullptr, "[always] madvise never"), "");  // already given
  EXPECT_EQ(tunablesWithHugePages(nullptr, "always madvise [never]"), "");  // never given
  EXPECT_EQ(tunablesWithHugePages(nullptr, ""), "");                        // no THP in this kernel
}

TEST(HugePages, KeepsOtherTunablesAndNeverAddsItTwice) {
  EXPECT_EQ(tunablesWithHugePages("glibc.malloc.arena_max=2", kOnRequest),
            "glibc.malloc.arena_max=2:glibc.malloc.hugetlb=1");
  EXPECT_EQ(tunablesWithHugePages("glibc.malloc.hugetlb=0", kOnRequest), "");  // user's choice
  EXPECT_EQ(tunablesWithHugePages("glibc.malloc.hugetlb=1", kOnRequest), "");
}

}  // namespace
}  // namespace photovr
