#include "makeway/tracking/hungarian.hpp"

#include <limits>

namespace makeway::tracking {

std::vector<int> min_cost_assignment(const Eigen::MatrixXd& cost_in) {
    const bool transposed = cost_in.rows() > cost_in.cols();
    const Eigen::MatrixXd cost = transposed ? Eigen::MatrixXd(cost_in.transpose()) : cost_in;
    const int n = static_cast<int>(cost.rows()), m = static_cast<int>(cost.cols());
    std::vector<int> row_of_col(static_cast<std::size_t>(m) + 1, 0);  // 1-based rows, 0 = free
    if (n > 0) {
        // Shortest augmenting paths with row potentials u and column potentials v; column 0 is
        // the virtual start of each path.
        const double inf = std::numeric_limits<double>::infinity();
        std::vector<double> u(static_cast<std::size_t>(n) + 1, 0.0),
            v(static_cast<std::size_t>(m) + 1, 0.0);
        std::vector<int> way(static_cast<std::size_t>(m) + 1, 0);
        for (int i = 1; i <= n; ++i) {
            row_of_col[0] = i;
            int j0 = 0;
            std::vector<double> minv(static_cast<std::size_t>(m) + 1, inf);
            std::vector<char> used(static_cast<std::size_t>(m) + 1, 0);
            do {
                used[static_cast<std::size_t>(j0)] = 1;
                const int i0 = row_of_col[static_cast<std::size_t>(j0)];
                double delta = inf;
                int j1 = 0;
                for (int j = 1; j <= m; ++j) {
                    const auto sj = static_cast<std::size_t>(j);
                    if (used[sj]) continue;
                    const double cur =
                        cost(i0 - 1, j - 1) - u[static_cast<std::size_t>(i0)] - v[sj];
                    if (cur < minv[sj]) minv[sj] = cur, way[sj] = j0;
                    if (minv[sj] < delta) delta = minv[sj], j1 = j;
                }
                for (int j = 0; j <= m; ++j) {
                    const auto sj = static_cast<std::size_t>(j);
                    if (used[sj]) {
                        u[static_cast<std::size_t>(row_of_col[sj])] += delta;
                        v[sj] -= delta;
                    } else {
                        minv[sj] -= delta;
                    }
                }
                j0 = j1;
            } while (row_of_col[static_cast<std::size_t>(j0)] != 0);
            do {  // augment along the path
                const int j1 = way[static_cast<std::size_t>(j0)];
                row_of_col[static_cast<std::size_t>(j0)] = row_of_col[static_cast<std::size_t>(j1)];
                j0 = j1;
            } while (j0 != 0);
        }
    }
    std::vector<int> col_of_row(static_cast<std::size_t>(n), -1);
    for (int j = 1; j <= m; ++j) {
        if (row_of_col[static_cast<std::size_t>(j)] > 0)
            col_of_row[static_cast<std::size_t>(row_of_col[static_cast<std::size_t>(j)] - 1)] =
                j - 1;
    }
    if (!transposed) return col_of_row;
    std::vector<int> out(static_cast<std::size_t>(cost_in.rows()), -1);
    for (int r = 0; r < n; ++r) {
        if (col_of_row[static_cast<std::size_t>(r)] >= 0)
            out[static_cast<std::size_t>(col_of_row[static_cast<std::size_t>(r)])] = r;
    }
    return out;
}

}  // namespace makeway::tracking
