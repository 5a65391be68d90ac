#pragma once
// Sparse coding (paper 3.3): min 1/2 ||Y - D X||_F^2 subject to a cap on the non-zeros of X,
// solved by projected gradient (iterative hard thresholding): a gradient step, then keep the
// largest-magnitude entries of each group and zero the rest.
#include <Eigen/Core>
#include <vector>

namespace mostyle {

// Which entries of the code matrix X share one non-zero budget.
enum class SparseGroup {
  kColumn,  // each column x_j of X (the paper's per-signal constraint ||x_j||_0 <= s)
  kRow,     // each row of X (one component of a decomposition: how many channels it touches)
};

struct SparseCodingOptions {
  int nonzeros = 1;                          // entries kept per group, >= 1, <= group size
  SparseGroup group = SparseGroup::kColumn;  // how the budget is applied
  int max_iterations = 200;                  // passes over X (one step per group), >= 1
  // Stop early when ||X_new - X_old||_F <= tolerance * ||X_new||_F; 0 runs every iteration.
  double tolerance = 1e-12;
  // Row groups only: when given (one list of neighbouring joints per joint, the columns being
  // x, y, z triples of those joints), each row keeps whole joints that form one connected piece
  // of that graph (keep_connected) instead of its largest entries. Not owned.
  const std::vector<std::vector<int>>* joint_neighbours = nullptr;
};

// Sparse codes X of signals Y (dims x signals) in dictionary D (dims x atoms), given by the
// normal equations the decomposition already holds: gram = D^T D (atoms x atoms), correlation =
// D^T Y (atoms x signals). Updates codes (atoms x signals; the warm start, zeros for a cold one)
// in place and returns the number of passes over X taken. Each group is a block that takes a
// gradient step of length 1/(its Lipschitz constant), then keeps its largest entries:
// - kColumn: all columns together with step 1/||D^T D||_2 (not the paper's printed
//   2/||D^T D||_2, which is the stability limit; see the .cpp);
// - kRow: one row after another (block-coordinate), row i with step 1/(D^T D)_ii, which makes
//   each row update the exact best sparse row given the others.
// Either way the objective 1/2 ||Y - D X||_F^2 never increases once X is sparse. Shapes are
// asserted, not checked; the options must be in range (1 <= nonzeros <= group size,
// max_iterations >= 1, tolerance >= 0: DecompositionOptions::Validate sees to it). Cost per
// iteration: O(atoms^2 * signals); allocates O(atoms x signals) scratch once per call.
int sparse_code_normal(const Eigen::MatrixXd& gram, const Eigen::MatrixXd& correlation,
                       Eigen::MatrixXd& codes, const SparseCodingOptions& options);

// Euclidean projection onto the sparse set: keeps the `nonzeros` largest-magnitude entries of
// each group of x and zeroes the rest. Ties go to the lower index, so the result is
// deterministic and keeps exactly min(nonzeros, group size) entries per group (an entry that
// was already zero may be among them).
// scratch is resized as needed and may be reused between calls to avoid allocation.
void keep_largest(Eigen::MatrixXd& x, int nonzeros, SparseGroup group,
                  std::vector<double>& scratch);

// The local projection of one row (a component over joints' x, y, z triples): grows a connected
// set of joints from the joint with the most energy (sum of its squared entries), adding the
// neighbouring joint with the most energy (ties to the lower index) until it holds
// max(1, round(nonzeros / 3)) joints or no neighbour has any energy, and zeroes every other
// joint. neighbours: one list per joint (row.size() / 3 joints). Greedy, not the exact
// projection onto connected supports; the sparse coding keeps a row's previous value whenever
// the projected step would not lower its cost. O(joints^2) worst case.
void keep_connected(Eigen::Ref<Eigen::RowVectorXd> row, int nonzeros, const std::vector<std::vector<int>>& neighbours,
                    std::vector<char>& chosen);

// Neighbour lists of a tree given by parent indices (-1: root).
std::vector<std::vector<int>> neighbours_of(const std::vector<int>& parents);

}  // namespace mostyle
