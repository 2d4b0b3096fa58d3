// Repeated measurements of one variant: median and range. Benchmarks run their
// variants interleaved (A B C A B C ...) so that a slow moment of the machine
// hits every variant alike, and report medians with min–max.
#pragma once

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

namespace apex_bench {

struct Spread {
  std::vector<double> v;
  void add(double x) { v.push_back(x); }
  bool empty() const { return v.empty(); }
  double median() const {
    auto s = v;
    std::sort(s.begin(), s.end());
    return s.empty() ? 0 : s[s.size() / 2];
  }
  double min() const { return v.empty() ? 0 : *std::min_element(v.begin(), v.end()); }
  double max() const { return v.empty() ? 0 : *std::max_element(v.begin(), v.end()); }
  /** "12.3 (11.9–13.0)" with printf format `fmt` for each number. */
  std::string text(const char* fmt = "%.0f") const {
    char a[32], b[32], c[32];
    std::snprintf(a, sizeof a, fmt, median());
    std::snprintf(b, sizeof b, fmt, min());
    std::snprintf(c, sizeof c, fmt, max());
    return std::string(a) + " (" + b + "–" + c + ")";
  }
};

}  // namespace apex_bench
