#pragma once
// Optimal assignment (Kuhn-Munkres with potentials, O(n^2 m)) for rectangular cost matrices.
#include <Eigen/Core>
#include <vector>

namespace makeway::tracking {

/// The assignment of rows to columns with the least total cost, every row or every column (the
/// fewer) assigned once. Returns the column of each row, -1 where a row is left out (more rows
/// than columns). Costs must be finite.
std::vector<int> min_cost_assignment(const Eigen::MatrixXd& cost);

}  // namespace makeway::tracking
