#include "tsmframe/contact/release_forecast.hpp"

#include <Eigen/LU>

namespace tsm::contact {

PointStiffness PointStiffness::diagonal(const Eigen::VectorXd& stiffness) {
  PointStiffness z;
  for (Eigen::Index i = 0; i < stiffness.size(); ++i) z.add(Eigen::MatrixXd::Constant(1, 1, stiffness[i]));
  return z;
}

void PointStiffness::add(const Eigen::MatrixXd& block) {
  blocks.push_back(block);
  first.push_back(first.back() + static_cast<int>(block.rows()));
}

std::vector<char> forecast_releases(const ForecastColumn& column, const PointStiffness& stiffness,
                                    const Eigen::VectorXd& Y, const std::vector<int>& side,
                                    const std::vector<char>& may_join, int rounds, int largest_set) {
  const int n = static_cast<int>(Y.size());
  std::vector<int> block_of(n);
  for (size_t b = 0; b + 1 < stiffness.first.size(); ++b)
    for (int i = stiffness.first[b]; i < stiffness.first[b + 1]; ++i) block_of[i] = static_cast<int>(b);
  const auto Z = [&](int i, int j) { return stiffness.blocks[block_of[i]](i - stiffness.first[block_of[i]], j - stiffness.first[block_of[i]]); };
  std::vector<Eigen::VectorXd> columns(n);  // G's columns asked for so far
  const auto G = [&](int i, int j) -> double {
    if (columns[j].size() == 0) columns[j] = column(j);
    return columns[j][i];
  };
  // (Z G)_ij: entry i's block row against G's column j.
  const auto ZG = [&](int i, int j) {
    const int b = block_of[i];
    double sum = 0.0;
    for (int c = stiffness.first[b]; c < stiffness.first[b + 1]; ++c) sum += Z(i, c) * G(c, j);
    return sum;
  };
  std::vector<char> pulling(n, 0);
  for (int i = 0; i < n; ++i) pulling[i] = may_join[i] && -side[i] * Y[i] < 0.0;
  std::vector<char> released = pulling;
  for (int round = 0; round < rounds; ++round) {
    // E: every point of an element that loses one, S's first (in order), then the others (Q).
    std::vector<int> E, place(n, -1);  // place: an entry's index in E, −1 outside
    for (int i = 0; i < n; ++i)
      if (released[i]) place[i] = static_cast<int>(E.size()), E.push_back(i);
    const int m_S = static_cast<int>(E.size());
    if (m_S > largest_set) break;
    for (int a = 0; a < m_S; ++a) {
      const int b = block_of[E[a]];
      for (int c = stiffness.first[b]; c < stiffness.first[b + 1]; ++c)
        if (place[c] < 0) place[c] = static_cast<int>(E.size()), E.push_back(c);
    }
    const int m = static_cast<int>(E.size());
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(m, m);
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(m);
    for (int a = 0; a < m_S; ++a) {  // (Y + ψ − Z G ψ)_a = 0
      rhs[a] = -Y[E[a]];
      for (int b = 0; b < m; ++b) A(a, b) = (a == b ? 1.0 : 0.0) - ZG(E[a], E[b]);
    }
    std::vector<Eigen::MatrixXd> compliance(stiffness.blocks.size());  // Z⁻¹ of the blocks met
    for (int a = m_S; a < m; ++a) {  // (Z⁻¹ ψ)_a = 0: no separation where the point stays
      const int blk = block_of[E[a]];
      if (compliance[blk].size() == 0) compliance[blk] = stiffness.blocks[blk].inverse();
      for (int b = 0; b < m; ++b)
        if (block_of[E[b]] == blk) A(a, b) = compliance[blk](E[a] - stiffness.first[blk], E[b] - stiffness.first[blk]);
    }
    const Eigen::VectorXd psi = A.partialPivLu().solve(rhs);
    if (!psi.allFinite()) break;
    std::vector<char> next(n, 0);
    for (int a = 0; a < m_S; ++a) {
      const int i = E[a], blk = block_of[i];
      double separation = psi[a];  // one point: s = ψ/k, of ψ's sign
      if (stiffness.blocks[blk].size() > 1) {
        if (compliance[blk].size() == 0) compliance[blk] = stiffness.blocks[blk].inverse();
        separation = 0.0;
        for (int b = 0; b < m; ++b)
          if (block_of[E[b]] == blk) separation += compliance[blk](i - stiffness.first[blk], E[b] - stiffness.first[blk]) * psi[b];
      }
      next[i] = pulling[i] || side[i] * separation < 0.0;
    }
    for (int i = 0; i < n; ++i) {
      if (released[i] || !may_join[i]) continue;
      double y = Y[i];
      for (int b = 0; b < m; ++b) y -= ZG(i, E[b]) * psi[b];
      if (place[i] >= 0) y += psi[place[i]];
      next[i] = -side[i] * y < 0.0;
    }
    if (next == released) return released;
    released = next;
  }
  return pulling;
}

std::vector<char> forecast_releases(const ForecastColumn& column, const Eigen::VectorXd& stiffness,
                                    const Eigen::VectorXd& Y, const std::vector<int>& side,
                                    const std::vector<char>& may_join, int rounds, int largest_set) {
  return forecast_releases(column, PointStiffness::diagonal(stiffness), Y, side, may_join, rounds, largest_set);
}

std::vector<char> forecast_releases(const Eigen::MatrixXd& G, const Eigen::VectorXd& stiffness, const Eigen::VectorXd& Y,
                                    const std::vector<int>& side, const std::vector<char>& may_join, int rounds,
                                    int largest_set) {
  return forecast_releases([&](int j) -> Eigen::VectorXd { return G.col(j); }, stiffness, Y, side, may_join, rounds,
                           largest_set);
}

}  // namespace tsm::contact
