// Total FETI with the multipliers shared out over processes (docs/theory.md §8.8), without MPI:
// P threads play P processes (ThreadRanks below: sums, gathers and messages through shared
// memory and a barrier), each running the whole solve with its share of the subdomains and of
// the multipliers, as MPI ranks do. Checked against one process holding everything:
//   - the rows of B shared out: every row on one process, the contact rows on process 0, the
//     rows that share a torn dof on one process (B_E B_E^T stays local), the messages of a
//     product matching between every pair;
//   - F x and M_E x assembled from the shares equal the whole products;
//   - the paper's brick with contact, and the elastic brick, solved on 2 and 3 processes give the
//     answer of 1 process (peak pressure and max |u| to 1e-6; the elastic brick to 1e-8).
#include <gtest/gtest.h>

#include <algorithm>
#include <barrier>
#include <cmath>
#include <functional>
#include <memory>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "common/fixtures.hpp"
#include "fricon/driver/model.hpp"
#include "fricon/driver/run.hpp"
#include "fricon/driver/tfeti_solve.hpp"
#include "fricon/feti/dual_rows.hpp"
#include "fricon/feti/feti_operator.hpp"
#include "fricon/io/problem_file.hpp"

// A namespace of its own (not an anonymous one): the unity build puts this file beside
// tfeti_test.cpp, whose helpers have the same names.
namespace tfeti_share_test {

using namespace fricon;
using namespace fricon::driver;

constexpr Real kSameAnswer = 1e-6;
constexpr Real kGluing = 1e-8;
const std::vector<std::string> kTight = {"solver.qp_rtol=1e-9", "solver.outer_tol=1e-8",
                                         "solver.outer_max=100"};

// What the threads share: a slot per process and a barrier.
struct Exchange {
  explicit Exchange(int n) : barrier(n), slots(static_cast<size_t>(n)) {
    for (auto& row : slots)
      row.resize(static_cast<size_t>(n));
  }
  std::barrier<> barrier;
  std::vector<std::vector<VectorXd>> slots;  ///< slots[from][to]
};

// Process `rank` of `size`, played by a thread.
class ThreadRanks final : public feti::Ranks {
 public:
  ThreadRanks(int rank, int size, Exchange& exchange) : rank_(rank), size_(size), ex_(exchange) {}
  int rank() const override { return rank_; }
  int size() const override { return size_; }

  void sum(Eigen::Ref<VectorXd> x) const override {
    const std::vector<VectorXd> all = post_to_all(VectorXd(x));
    x.setZero();
    for (const VectorXd& part : all)
      x += part;  // rank order on every process: the same bits
  }
  std::vector<double> gather(double value) const override {
    std::vector<double> values;
    for (const VectorXd& v : post_to_all(VectorXd::Constant(1, value)))
      values.push_back(v(0));
    return values;
  }
  VectorXd concat(const VectorXd& local) const override {
    const std::vector<VectorXd> all = post_to_all(local);
    Index n = 0;
    for (const VectorXd& v : all)
      n += v.size();
    VectorXd joined(n);
    n = 0;
    for (const VectorXd& v : all) {
      joined.segment(n, v.size()) = v;
      n += v.size();
    }
    return joined;
  }
  void exchange(const std::vector<VectorXd>& out, std::vector<VectorXd>& in) const override {
    ex_.slots[static_cast<size_t>(rank_)] = out;
    ex_.barrier.arrive_and_wait();
    for (int q = 0; q < size_; ++q) {
      const VectorXd& sent = ex_.slots[static_cast<size_t>(q)][static_cast<size_t>(rank_)];
      EXPECT_EQ(sent.size(), in[static_cast<size_t>(q)].size())
          << "process " << q << " sent " << sent.size() << " to " << rank_;
      in[static_cast<size_t>(q)] = sent;
    }
    ex_.barrier.arrive_and_wait();
  }

 private:
  // Every process's v, on every process.
  std::vector<VectorXd> post_to_all(const VectorXd& v) const {
    ex_.slots[static_cast<size_t>(rank_)].assign(static_cast<size_t>(size_), v);
    ex_.barrier.arrive_and_wait();
    std::vector<VectorXd> all;
    for (int q = 0; q < size_; ++q)
      all.push_back(ex_.slots[static_cast<size_t>(q)][static_cast<size_t>(rank_)]);
    ex_.barrier.arrive_and_wait();
    return all;
  }

  int rank_, size_;
  Exchange& ex_;
};

// body(ranks) on `n` threads, one process each: every process's result, in rank order.
template <class Result>
std::vector<Result> on_processes(int n, const std::function<Result(const feti::Ranks&)>& body) {
  Exchange exchange(n);
  std::vector<Result> results(static_cast<size_t>(n));
  std::vector<std::thread> threads;
  for (int r = 0; r < n; ++r)
    threads.emplace_back([&, r] {
      const ThreadRanks ranks(r, n, exchange);
      results[static_cast<size_t>(r)] = body(ranks);
    });
  for (std::thread& t : threads)
    t.join();
  return results;
}

Model model_of(const Problem& p) {
  PhaseTimes times;
  return assemble_loads(p, times);
}

// F of the problem's model on the processes of `ranks` (this process's part).
std::unique_ptr<feti::FetiOperator> operator_of(const Problem& p, const Model& model,
                                                const feti::Ranks& ranks) {
  RunOptions options;
  options.feti_ranks = &ranks;
  RunReport report;
  return make_feti_operator(p, model, nullptr, options, report);
}

Problem example(const std::string& file, std::vector<std::string> sets) {
  sets.insert(sets.begin(), "solver.backend=\"tfeti\"");
  sets.insert(sets.end(), kTight.begin(), kTight.end());
  return io::read_problem(test::source_path(file), sets);
}

RunResult run_on(const Problem& p, const feti::Ranks& ranks) {
  RunOptions options;
  options.feti_ranks = &ranks;
  return run(p, options);
}

// max |u_i| over the nodes and components of a displacement (3 x n_nodes).
Real max_abs(const fe::NodalField& u) {
  return u.size() > 0 ? u.cwiseAbs().maxCoeff() : 0.0;
}

Real peak_pressure(const RunResult& r) {
  Real peak = 0.0;
  for (Index p = 0; p < r.contact->lambda.size() / 3; ++p)
    peak = std::max(peak, r.contact->lambda(3 * p));
  return peak;
}

TEST(TfetiShare, EveryRowIsOneProcesssAndRowsSharingADofStayTogether) {
  const Problem p =
      example("examples/elastic-brick.toml", {"mesh.cells=[8,4,4]", "solver.subdomains=12"});
  const Model model = model_of(p);
  const auto whole = operator_of(p, model, feti::this_process());
  const SparseMatrix& B = whole->rows().B;
  const std::vector<std::vector<Index>> owned =
      on_processes<std::vector<Index>>(3, [&](const feti::Ranks& ranks) {
        const auto F = operator_of(p, model, ranks);
        EXPECT_EQ(F->dual_rows().n_local_contact(), ranks.rank() == 0 ? F->n_contact() : 0);
        return F->dual_rows().owned();
      });
  std::vector<int> owner(static_cast<size_t>(B.rows()), -1);
  for (std::size_t q = 0; q < owned.size(); ++q) {
    EXPECT_FALSE(owned[q].empty()) << "process " << q << " holds no row";
    EXPECT_TRUE(std::is_sorted(owned[q].begin(), owned[q].end()));
    for (Index r : owned[q]) {
      EXPECT_EQ(owner[static_cast<size_t>(r)], -1) << "row " << r << " held twice";
      owner[static_cast<size_t>(r)] = static_cast<int>(q);
    }
  }
  EXPECT_EQ(std::count(owner.begin(), owner.end(), -1), 0) << "a row nobody holds";
  // Rows that share a torn dof are one process's: B_E B_E^T has no entry between processes.
  for (Index j = 0; j < B.outerSize(); ++j) {
    int first = -1;
    for (SparseMatrix::InnerIterator it(B, j); it; ++it) {
      const int q = owner[static_cast<size_t>(it.row())];
      if (first < 0) first = q;
      EXPECT_EQ(q, first) << "torn dof " << j << " on the rows of two processes";
    }
  }
}

TEST(TfetiShare, ProductsAssembledFromTheSharesAreTheWholeOnes) {
  const Problem p =
      example("examples/paper-brick.toml", {"mesh.cells=[12,4,4]", "solver.subdomains=8"});
  const Model model = model_of(p);
  const auto whole = operator_of(p, model, feti::this_process());
  const VectorXd x = VectorXd::Random(whole->size());
  VectorXd Fx(x.size());
  whole->apply(x, Fx);
  const VectorXd x_E = x.tail(whole->n_equality());
  VectorXd Mx;
  whole->equality_preconditioner()(x_E, Mx);
  for (int n : {2, 3}) {
    using Pair = std::pair<VectorXd, VectorXd>;
    const Pair shared = on_processes<Pair>(n, [&](const feti::Ranks& ranks) {
      const auto F = operator_of(p, model, ranks);
      const dual::DualShare& share = F->share();
      VectorXd y;
      share.apply(share.restrict(x), y);
      const VectorXd x_share = share.restrict(x);
      VectorXd m;
      share.equality_preconditioner()(VectorXd(x_share.tail(share.size() - share.n_contact())), m);
      VectorXd m_all = VectorXd::Zero(share.size());
      m_all.tail(m.size()) = m;
      return Pair{share.assemble(y), share.assemble(m_all)};
    })[0];
    EXPECT_LE((shared.first - Fx).norm(), 1e-12 * Fx.norm()) << n << " processes";
    EXPECT_LE((VectorXd(shared.second.tail(Mx.size())) - Mx).norm(), 1e-12 * Mx.norm())
        << n << " processes";
  }
}

TEST(TfetiShare, TheBrickOnTwoAndThreeProcessesHasTheAnswerOfOne) {
  const Problem p =
      example("examples/paper-brick.toml", {"mesh.cells=[12,4,4]", "solver.subdomains=8"});
  const RunResult one = run(p);
  ASSERT_EQ(one.report.status, RunStatus::Converged) << one.report.message;
  for (int n : {2, 3}) {
    const RunResult shared = std::move(
        on_processes<RunResult>(n, [&](const feti::Ranks& ranks) { return run_on(p, ranks); })[0]);
    ASSERT_EQ(shared.report.status, RunStatus::Converged)
        << n << " processes: " << shared.report.message;
    EXPECT_LE(std::abs(peak_pressure(shared) - peak_pressure(one)),
              kSameAnswer * peak_pressure(one));
    EXPECT_LE(std::abs(max_abs(shared.displacement) - max_abs(one.displacement)),
              kSameAnswer * max_abs(one.displacement));
  }
}

TEST(TfetiShare, TheElasticBrickOnThreeProcessesHasTheAnswerOfOne) {
  const Problem p =
      example("examples/elastic-brick.toml", {"mesh.cells=[8,4,4]", "solver.subdomains=12"});
  const RunResult one = run(p);
  const RunResult shared = std::move(
      on_processes<RunResult>(3, [&](const feti::Ranks& ranks) { return run_on(p, ranks); })[0]);
  ASSERT_EQ(shared.report.status, RunStatus::Converged) << shared.report.message;
  EXPECT_LE((shared.displacement - one.displacement).cwiseAbs().maxCoeff(),
            kGluing * max_abs(one.displacement));
}

}  // namespace tfeti_share_test
