#include <qp/solver_factory.h>
#include <qp/vector_helpers.h>

#include <deal.II/base/exceptions.h>

// ---- REGISTRATION POINT (1 of 2): include the solver headers here. ----
#include <qp/apgd.h>
#include <qp/mpgp.h>
#include <qp/mpgp_bb.h>
#include <qp/mprgp.h>
#include <qp/mwpgp.h>
#include <qp/pbbf.h>
#include <qp/solver_chain.h>
#include <qp/spg_qp.h>
// ---- end of registration point 1 ----

namespace dualcontact
{
  namespace qp
  {
    std::string
    solver_names()
    {
      // The names of the `Solver` selection, implemented or not yet: the
      // .prm pattern must not change when a solver is added.
      return "mprgp|mpgp|mpgp-bb|mwpgp|spg-qp|pbbf|apgd|auto";
    }


    namespace
    {
      template <typename VectorType>
      std::unique_ptr<SolverBase<VectorType>>
      create_solver(const std::string &name, const SolverParameters &prm)
      {
        // ---- REGISTRATION POINT (2 of 2): one branch per solver, e.g.
        //   if (name == "mprgp")
        //     return std::make_unique<MPRGP<VectorType>>(prm);
        if (name == "mprgp")
          return std::make_unique<MPRGP<VectorType>>(prm);
        if (name == "mpgp")
          return std::make_unique<MPGP<VectorType>>(prm);
        if (name == "mpgp-bb")
          return std::make_unique<MPGPBB<VectorType>>(prm);
        if (name == "mwpgp")
          return std::make_unique<MwPGP<VectorType>>(prm);
        if (name == "spg-qp")
          return std::make_unique<SPGQP<VectorType>>(prm);
        if (name == "pbbf")
          return std::make_unique<PBBf<VectorType>>(prm);
        if (name == "apgd")
          return std::make_unique<APGD<VectorType>>(prm);
        // the fall-back chain (default SMALSE-M parameters for problems
        // with equality constraints; build a SolverChain to choose them)
        if (name == "auto")
          return std::make_unique<SolverChain<VectorType>>(prm);
        // ---- end of registration point 2 ----
        return nullptr;
      }
    } // namespace


    template <typename VectorType>
    std::unique_ptr<SolverBase<VectorType>>
    create(const std::string &name, const SolverParameters &parameters)
    {
      parameters.check();
      auto solver = create_solver<VectorType>(name, parameters);
      AssertThrow(solver != nullptr,
                  dealii::ExcMessage("Unknown or unavailable QP solver '" +
                                     name +
                                     "' (`Solver' in `subsection QP "
                                     "solver'); valid names: " +
                                     solver_names() + "."));
      return solver;
    }


    template <typename VectorType>
    std::unique_ptr<SolverBase<VectorType>>
    create(const SolverParameters &parameters)
    {
      return create<VectorType>(parameters.solver, parameters);
    }


    template std::unique_ptr<SolverBase<dealii::Vector<double>>>
    create<dealii::Vector<double>>(const std::string &,
                                   const SolverParameters &);
    template std::unique_ptr<SolverBase<dealii::Vector<double>>>
    create<dealii::Vector<double>>(const SolverParameters &);
    template std::unique_ptr<SolverBase<dealii::TrilinosWrappers::MPI::Vector>>
    create<dealii::TrilinosWrappers::MPI::Vector>(const std::string &,
                                                  const SolverParameters &);
    template std::unique_ptr<SolverBase<dealii::TrilinosWrappers::MPI::Vector>>
    create<dealii::TrilinosWrappers::MPI::Vector>(const SolverParameters &);
  } // namespace qp
} // namespace dualcontact
