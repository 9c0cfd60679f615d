#include <deal.II/base/exceptions.h>

#include <qp/smalse_m.h>
#include <qp/solver_chain.h>
#include <qp/solver_factory.h>
#include <qp/solver_registry.h>

namespace dualcontact
{
  namespace qp
  {
    std::string
    solver_names()
    {
      return join_names(SolverRegistry::instance().names());
    }


    template <typename VectorType>
    std::unique_ptr<SolverBase<VectorType>>
    create(const std::string &name, const SolverParameters &parameters)
    {
      parameters.check();
      const SolverEntry *entry = SolverRegistry::instance().find(name);
      AssertThrow(entry != nullptr,
                  dealii::ExcMessage("Unknown or unavailable QP solver '" +
                                     name +
                                     "' (`Solver' in `subsection QP "
                                     "solver'); valid names: " +
                                     solver_names() + "."));
      return entry->creator<VectorType>()(parameters);
    }


    template <typename VectorType>
    std::unique_ptr<SolverBase<VectorType>>
    create(const SolverParameters &parameters)
    {
      return create<VectorType>(parameters.solver, parameters);
    }


    template <typename VectorType>
    std::unique_ptr<SolverBase<VectorType>>
    make_solver(const SolverParameters  &parameters,
                const SMALSEMParameters &smalse_parameters,
                const bool               with_equality)
    {
      // the chain wraps SMALSE-M around each of its solvers itself
      if (parameters.solver == "auto")
        return std::make_unique<SolverChain<VectorType>>(parameters,
                                                         smalse_parameters);
      if (with_equality)
        return std::make_unique<SMALSEM<VectorType>>(parameters,
                                                     smalse_parameters);
      return create<VectorType>(parameters);
    }


    template <typename VectorType>
    std::unique_ptr<SolverBase<VectorType>>
    make_solver(const SolverParameters    &parameters,
                const SMALSEMParameters   &smalse_parameters,
                const Problem<VectorType> &problem)
    {
      return make_solver<VectorType>(parameters,
                                     smalse_parameters,
                                     problem.equality != nullptr);
    }


#define DUALCONTACT_INSTANTIATE_FACTORY(V)                                     \
  template std::unique_ptr<SolverBase<V>> create<V>(const std::string &,       \
                                                    const SolverParameters &); \
  template std::unique_ptr<SolverBase<V>> create<V>(const SolverParameters &); \
  template std::unique_ptr<SolverBase<V>> make_solver<V>(                      \
    const SolverParameters &, const SMALSEMParameters &, bool);                \
  template std::unique_ptr<SolverBase<V>> make_solver<V>(                      \
    const SolverParameters &, const SMALSEMParameters &, const Problem<V> &);

    DUALCONTACT_INSTANTIATE_FACTORY(dealii::Vector<double>)
    DUALCONTACT_INSTANTIATE_FACTORY(dealii::TrilinosWrappers::MPI::Vector)
#undef DUALCONTACT_INSTANTIATE_FACTORY
  } // namespace qp
} // namespace dualcontact
