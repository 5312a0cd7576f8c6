// Tests that reach an accuracy target at full scale (a Cornell box at
// thousands of samples, a solve run twice to compare thread counts) take a
// minute each under AddressSanitizer, and they run the same code as the
// smaller tests beside them. CI runs every test in the Release build and
// skips these in its sanitizer build, which would otherwise take most of
// CI's time (.ci/run).
#pragma once

#include <gtest/gtest.h>

// GCC defines __SANITIZE_ADDRESS__ under -fsanitize=address; clang 14 (CI's
// sanitizer build) only answers __has_feature(address_sanitizer).
#if defined(__SANITIZE_ADDRESS__)
#define RADIANT_UNDER_SANITIZER 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define RADIANT_UNDER_SANITIZER 1
#endif
#endif
#ifndef RADIANT_UNDER_SANITIZER
#define RADIANT_UNDER_SANITIZER 0
#endif

#if RADIANT_UNDER_SANITIZER
#define RADIANT_SKIP_UNDER_SANITIZER() \
  GTEST_SKIP() << "accuracy at full scale: run by the Release build, skipped under the sanitizer"
#else
#define RADIANT_SKIP_UNDER_SANITIZER() static_cast<void>(0)
#endif
