// The pairing of rows with columns of least total cost: the Hungarian method (Kuhn, Munkres), in
// its O(n² m) form with row and column potentials. MultiObjectTracker pairs tracks with detections
// by it; a greedy pairing (the best pair first) can take a pair that leaves two others worse off,
// which is how two objects that pass close by swap their ids.
#pragma once

#include <limits>
#include <opencv2/core.hpp>
#include <vector>

namespace apex_nodes {

/** @brief For each row of `cost` (any sizes; finite costs), the column paired with it, or -1:
 *  min(rows, cols) pairs, each row and each column in one at most, of least total cost. */
inline std::vector<int> leastCostAssignment(const cv::Mat1d& cost) {
  const int rows = cost.rows, cols = cost.cols;
  if (rows == 0 || cols == 0) return std::vector<int>(static_cast<std::size_t>(rows), -1);
  if (rows > cols) {  // the method pairs every row: pair every column of the transpose instead
    const std::vector<int> row_of = leastCostAssignment(cv::Mat1d(cost.t()));
    std::vector<int> col_of(static_cast<std::size_t>(rows), -1);
    for (int c = 0; c < cols; ++c)
      if (row_of[c] >= 0) col_of[row_of[c]] = c;
    return col_of;
  }
  // Rows and columns from 1; column 0 stands for the row being added. Costs less the potentials
  // u[row] + v[col] are never negative, and 0 on the pairs made so far.
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> u(rows + 1, 0.0), v(cols + 1, 0.0);
  std::vector<int> row_at(cols + 1, 0);  // the row paired with each column, 0: none
  std::vector<int> way(cols + 1, 0);  // the column before each on the path of least reduced cost
  for (int r = 1; r <= rows; ++r) {
    row_at[0] = r;
    int c0 = 0;
    std::vector<double> slack(cols + 1, inf);
    std::vector<bool> used(cols + 1, false);
    do {  // grow the paths from row r, column by column, until one reaches a free column
      used[c0] = true;
      const int r0 = row_at[c0];
      double delta = inf;
      int c1 = 0;
      for (int c = 1; c <= cols; ++c) {
        if (used[c]) continue;
        const double reduced = cost(r0 - 1, c - 1) - u[r0] - v[c];
        if (reduced < slack[c]) slack[c] = reduced, way[c] = c0;
        if (slack[c] < delta) delta = slack[c], c1 = c;
      }
      for (int c = 0; c <= cols; ++c) {
        if (used[c]) u[row_at[c]] += delta, v[c] -= delta;
        else slack[c] -= delta;
      }
      c0 = c1;
    } while (row_at[c0] != 0);
    do {  // shift the pairs along the path back to row r
      const int c1 = way[c0];
      row_at[c0] = row_at[c1];
      c0 = c1;
    } while (c0 != 0);
  }
  std::vector<int> col_of(static_cast<std::size_t>(rows), -1);
  for (int c = 1; c <= cols; ++c)
    if (row_at[c] != 0) col_of[row_at[c] - 1] = c - 1;
  return col_of;
}

}  // namespace apex_nodes
