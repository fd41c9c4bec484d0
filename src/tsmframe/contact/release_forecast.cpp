#include "tsmframe/contact/release_forecast.hpp"

#include <Eigen/LU>

namespace tsm::contact {

std::vector<char> forecast_releases(const ForecastColumn& column, const Eigen::VectorXd& stiffness,
                                    const Eigen::VectorXd& Y, const std::vector<int>& side,
                                    const std::vector<char>& may_join, int rounds, int largest_set) {
  const int n = static_cast<int>(Y.size());
  std::vector<Eigen::VectorXd> columns(n);  // G's columns asked for so far
  const auto G = [&](int i, int j) -> double {
    if (columns[j].size() == 0) columns[j] = column(j);
    return columns[j][i];
  };
  std::vector<char> pulling(n, 0);
  for (int i = 0; i < n; ++i) pulling[i] = may_join[i] && -side[i] * Y[i] < 0.0;
  std::vector<char> released = pulling;
  for (int round = 0; round < rounds; ++round) {
    std::vector<int> S;
    for (int i = 0; i < n; ++i)
      if (released[i]) S.push_back(i);
    const int m = static_cast<int>(S.size());
    if (m > largest_set) break;
    Eigen::MatrixXd A(m, m);
    Eigen::VectorXd Y_S(m);
    for (int a = 0; a < m; ++a) {
      Y_S[a] = Y[S[a]];
      for (int b = 0; b < m; ++b) A(a, b) = (a == b ? 1.0 : 0.0) - stiffness[S[a]] * G(S[a], S[b]);
    }
    const Eigen::VectorXd would = A.partialPivLu().solve(Y_S);  // Y'_S
    if (!would.allFinite()) break;
    std::vector<char> next(n, 0);
    for (int a = 0; a < m; ++a) next[S[a]] = pulling[S[a]] || -side[S[a]] * would[a] < 0.0;
    for (int i = 0; i < n; ++i) {
      if (released[i] || !may_join[i]) continue;
      double y = Y[i];
      for (int a = 0; a < m; ++a) y += stiffness[i] * G(i, S[a]) * would[a];
      next[i] = -side[i] * y < 0.0;
    }
    if (next == released) return released;
    released = next;
  }
  return pulling;
}

std::vector<char> forecast_releases(const Eigen::MatrixXd& G, const Eigen::VectorXd& stiffness, const Eigen::VectorXd& Y,
                                    const std::vector<int>& side, const std::vector<char>& may_join, int rounds,
                                    int largest_set) {
  return forecast_releases([&](int j) -> Eigen::VectorXd { return G.col(j); }, stiffness, Y, side, may_join, rounds,
                           largest_set);
}

}  // namespace tsm::contact
