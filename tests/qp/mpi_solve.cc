// The same QPs on dealii::TrilinosWrappers::MPI::Vector (run on 1 and 2
// ranks) and on dealii::Vector<double> (serial, on every rank): for each
// core solver and a mixed set (bound, box, disc, ellipse, cone) plus a
// bound-only set for mprgp, solved to 1e-12, the distributed answer
// matches the serial one to 1e-10 and the planted solution to 1e-8; block
// counts are global; a block straddling two ranks is rejected on both.
#include "planted_problems.h"

#include <deal.II/base/mpi.h>

#include <qp/solver_factory.h>

using namespace qptest;
using namespace dualcontact::qp;
using Vec  = dealii::Vector<double>;
using PVec = dealii::TrilinosWrappers::MPI::Vector;

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const MPI_Comm                           comm = MPI_COMM_WORLD;
  const unsigned rank = dealii::Utilities::MPI::this_mpi_process(comm);
  const unsigned size = dealii::Utilities::MPI::n_mpi_processes(comm);
  Checker        check;
  check.verbose = (rank == 0);

  struct Case
  {
    std::string            solver;
    std::vector<BlockType> types;
  };
  const std::vector<BlockType> mixed = {BlockType::bound,
                                        BlockType::box,
                                        BlockType::disc,
                                        BlockType::ellipse,
                                        BlockType::cone};
  const std::vector<Case>      cases = {{"mprgp",
                                         {BlockType::bound, BlockType::box}},
                                        {"mpgp", mixed},
                                        {"mpgp-bb", mixed},
                                        {"mwpgp", mixed}};

  for (const Case &c : cases)
  {
    const unsigned     n_blocks = 40;
    const Planted      P        = make_planted(c.types, n_blocks, 6, 99);
    const unsigned int n        = P.x_star.size();
    // rank r owns the blocks [r nb/size, (r+1) nb/size); the free
    // unknowns at the end belong to the last rank
    const unsigned   b0 = rank * n_blocks / size;
    const unsigned   b1 = (rank + 1) * n_blocks / size;
    const unsigned   i0 = P.blocks[b0].first;
    const unsigned   i1 = (rank + 1 == size) ? n : P.blocks[b1].first;
    dealii::IndexSet owned(n);
    owned.add_range(i0, i1);
    PVec layout(owned, comm);

    SolverParameters prm;
    prm.tolerance = 1e-12;

    auto       pproblem = make_problem(P.A, P.b, P.blocks, layout);
    PVec       px(layout);
    const auto ps = create<PVec>(c.solver, prm)->solve(pproblem, px);

    Vec        slayout(n);
    auto       sproblem = make_problem(P.A, P.b, P.blocks, slayout);
    Vec        sx(n);
    const auto ss = create<Vec>(c.solver, prm)->solve(sproblem, sx);

    const Vec full(px);
    Vec       diff(full);
    diff -= sx;
    const double d   = diff.l2_norm();
    const double err = distance(px, P.x_star);
    check.check(ps.converged() && ss.converged() && d <= 1e-10 &&
                  err <= 1e-8 * (1. + norm(P.x_star)),
                c.solver + " on " + std::to_string(size) +
                  " rank(s): |x_mpi - x_serial| = " + sci(d) + ", |x - x*| = " +
                  sci(err) + ", iterations " + std::to_string(ps.iterations) +
                  " (serial " + std::to_string(ss.iterations) + ")");
    const auto &set = *pproblem.constraints;
    check.check(set.n_blocks() == n_blocks &&
                  set.n_blocks(BlockType::bound) ==
                    sproblem.constraints->n_blocks(BlockType::bound),
                c.solver + ": global block counts (" +
                  std::to_string(set.n_blocks()) + " blocks)");
  }

  if (size == 2)
  {
    // a disc at unknowns 0,1 with the rank boundary between them
    dealii::IndexSet owned(4);
    owned.add_range(rank == 0 ? 0 : 1, rank == 0 ? 1 : 4);
    PVec               layout(owned, comm);
    SeparableSet<PVec> set;
    set.add_disc(0, 1.);
    bool thrown = false;
    try
    {
      set.finalize(layout);
    }
    catch (const std::exception &e)
    {
      thrown = std::string(e.what()).find("straddles") != std::string::npos;
    }
    check.check(dealii::Utilities::MPI::min(thrown ? 1 : 0, comm) == 1,
                "a disc straddling two ranks is rejected on both");
  }
  const int result = check.finish("mpi_solve");
  return dealii::Utilities::MPI::max(result, comm);
}
