#include <contact/stiffness_inverse.h>

namespace dualcontact
{
  namespace contact
  {
    using namespace dealii;

    template <int dim>
    StiffnessInverse<dim>::StiffnessInverse(
      const std::vector<const fem::ElasticBody<dim> *> &bodies,
      const ContactDiscretization<dim>                 &contact)
        : bodies_(bodies)
        , contact_(contact)
    {
    }


    template <int dim>
    void
    StiffnessInverse<dim>::add(std::unique_ptr<fem::StiffnessSolver> solver)
    {
      solvers_.push_back(std::move(solver));
    }


    template <int dim>
    void
    StiffnessInverse<dim>::apply(Vector<double> &x) const
    {
      Vector<double> in, out;
      for (unsigned int b = 0; b < bodies_.size(); ++b)
      {
        const types::global_dof_index offset = contact_.body_offset(b);
        const unsigned int            n      = bodies_[b]->n_dofs();
        in.reinit(n, true);
        for (unsigned int i = 0; i < n; ++i)
          in(i) = x(offset + i);
        solvers_[b]->solve(out, in);
        for (unsigned int i = 0; i < n; ++i)
          x(offset + i) = out(i);
      }
      ++n_solves_;
    }


    template <int dim>
    bool
    StiffnessInverse<dim>::is_distributed() const
    {
      for (const auto &solver : solvers_)
        if (solver->is_distributed())
          return true;
      return false;
    }


    template <int dim>
    unsigned long
    StiffnessInverse<dim>::n_solves() const
    {
      return n_solves_;
    }


    template <int dim>
    double
    StiffnessInverse<dim>::setup_time() const
    {
      double time = 0;
      for (const auto &solver : solvers_)
        time += solver->statistics().setup_time;
      return time;
    }


    template <int dim>
    double
    StiffnessInverse<dim>::solve_time() const
    {
      double time = 0;
      for (const auto &solver : solvers_)
        time += solver->statistics().solve_time;
      return time;
    }


    template class StiffnessInverse<2>;
    template class StiffnessInverse<3>;
  } // namespace contact
} // namespace dualcontact
