#pragma once
// The SIMD kernels' tests (tests/core/*_batch_test.cpp) run their comparisons once per SIMD
// target the CPU has (AVX-512, AVX2, SSE4, SSSE3, emulated 128-bit), each forced in turn.
#include <gtest/gtest.h>
#include <hwy/targets.h>

#include <cstdio>

namespace tray::test {

/// Calls `compare` under each SIMD target (HWY_SCALAR is skipped: the kernels' callers leave
/// CPUs without SIMD to the scalar code), expecting it to return more than `atLeast` cases
/// compared; stops at the first target with a failure and restores dispatch to the best one.
template <class Compare>
void onEverySimdTarget(int atLeast, Compare compare) {
  int targets = 0;
  for (const int64_t target : hwy::SupportedAndGeneratedTargets()) {
    if (target == HWY_SCALAR) continue;
    SCOPED_TRACE(hwy::TargetName(target));
    hwy::SetSupportedTargetsForTest(target);
    EXPECT_GT(compare(), atLeast);
    ++targets;
    if (testing::Test::HasFailure()) break;
  }
  hwy::SetSupportedTargetsForTest(0);
  EXPECT_GE(targets, 1);
  std::printf("compared on %d targets\n", targets);
}

}  // namespace tray::test
