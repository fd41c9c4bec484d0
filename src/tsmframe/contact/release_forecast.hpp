#pragma once
// Which contacts let go together at a converged iterate where some pull (Newton's look-ahead):
// a linearised active-set iteration on the tangent there. Letting go of a set S takes S's point
// loads Y_S u_S off the nodes and their stiffness k u uᵀ out of the tangent K, so the forces S's
// contacts would have at the new state solve (I − K_S G_SS) Y'_S = Y_S, and every other
// contact's is Y_i + k_i G_iS Y'_S, with G = Uᵀ K⁻¹ U over the contacts' point-load directions u
// (assembly::ContactDirection). S starts as the contacts that pull and grows by those that would
// (and loses those that would press again, except the first) until it no longer changes. Only
// G's columns of contacts in S are ever needed: one solve each, asked for as S grows.

#include <Eigen/Core>
#include <functional>
#include <vector>

namespace tsm::contact {

/// G's column j, Uᵀ K⁻¹ u_j (one entry per contact).
using ForecastColumn = std::function<Eigen::VectorXd(int j)>;

/// The points' stiffness: block diagonal, one block per contact element (its points coupled
/// through the beam, C⁻¹ of the k-point law; 1/c for one point). Entries of a block are
/// consecutive: block b holds entries first[b] … first[b + 1] − 1.
struct PointStiffness {
  std::vector<int> first{0};
  std::vector<Eigen::MatrixXd> blocks;
  /// One point per element: the blocks 1×1.
  static PointStiffness diagonal(const Eigen::VectorXd& stiffness);
  void add(const Eigen::MatrixXd& block);
};

/// Per contact entry whether it lets go: compression is −side · Y; `may_join` false keeps an
/// entry out of S whatever it does (a vertex's two elements). Where the iteration has not
/// settled after `rounds`, or S would grow beyond `largest_set` (its dense solve, |S|³, and one
/// solve with K per member), only the entries that pull now.
///
/// Points coupled on an element: letting go of some of them, R, changes the law of the others,
/// Q (their stiffness becomes C_QQ⁻¹): the state after it is the one where R's points stay in
/// the model with a separation s_R each and zero force. With ψ = Z s over the elements that
/// lose a point (Z their blocks), ΔD = −K⁻¹ U ψ and the forces become Y + ψ − Z G ψ; ψ solves
/// (Y + ψ − Z G ψ)_S = 0 and (Z⁻¹ ψ)_Q = 0. A point of S stays let go where it separates
/// (side · s < 0), another joins where its force Y + ψ − Z G ψ would pull. One point per element:
/// ψ_S = −Y'_S above.
std::vector<char> forecast_releases(const ForecastColumn& column, const PointStiffness& stiffness,
                                    const Eigen::VectorXd& Y, const std::vector<int>& side,
                                    const std::vector<char>& may_join, int rounds = 50, int largest_set = 400);
std::vector<char> forecast_releases(const ForecastColumn& column, const Eigen::VectorXd& stiffness,
                                    const Eigen::VectorXd& Y, const std::vector<int>& side,
                                    const std::vector<char>& may_join, int rounds = 50, int largest_set = 400);
/// The same with G given whole.
std::vector<char> forecast_releases(const Eigen::MatrixXd& G, const Eigen::VectorXd& stiffness, const Eigen::VectorXd& Y,
                                    const std::vector<int>& side, const std::vector<char>& may_join, int rounds = 50,
                                    int largest_set = 400);

}  // namespace tsm::contact
