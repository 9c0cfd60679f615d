#include <contact/implicit_dual_operator.h>

namespace dualcontact
{
  namespace contact
  {
    using namespace dealii;

    template <int dim>
    ImplicitDualOperator<dim>::ImplicitDualOperator(
      const ContactRows<dim>      &rows,
      const StiffnessInverse<dim> &inverse,
      const std::string           &description)
        : rows_(rows)
        , inverse_(inverse)
        , description_(description)
    {
    }


    template <int dim>
    void
    ImplicitDualOperator<dim>::vmult(VectorType       &dst,
                                     const VectorType &src) const
    {
      Vector<double> u;
      rows_.Tvmult(u, src);
      inverse_.apply(u);
      rows_.vmult(dst, u);
    }


    template <int dim>
    void
    ImplicitDualOperator<dim>::vmult(DistributedVector            &dst,
                                     const DistributedVector      &src,
                                     const MultiplierDistribution &owners) const
    {
      const std::vector<unsigned int> &owned_rows = owners.owned_rows();
      Vector<double>                   u;
      rows_.Tvmult_owned(u, src, owned_rows, owners.communicator());
      inverse_.apply(u);
      for (unsigned int k = 0; k < owned_rows.size(); ++k)
        dst.begin()[k] = rows_.row_times(owned_rows[k], u);
    }


    template <int dim>
    bool
    ImplicitDualOperator<dim>::is_assembled() const
    {
      return false;
    }


    template <int dim>
    const std::string &
    ImplicitDualOperator<dim>::description() const
    {
      return description_;
    }


    template <int dim>
    double
    ImplicitDualOperator<dim>::assembly_time() const
    {
      return 0.;
    }


    template class ImplicitDualOperator<2>;
    template class ImplicitDualOperator<3>;
  } // namespace contact
} // namespace dualcontact
