/**
 * @file vector_helpers.h
 * The few things the QP library needs to know about a vector type beyond
 * its arithmetic: its communicator and MPI reductions of local partial
 * results.  Overloads, not a traits class, so adding a vector type is adding
 * one function.
 */
#ifndef dualcontact_qp_vector_helpers_h
#define dualcontact_qp_vector_helpers_h

#include <qp/vector_kernels.h>

#include <deal.II/base/mpi.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector.h>

#include <array>
#include <cmath>

namespace dualcontact
{
  namespace qp
  {
    namespace internal
    {
      /// A serial vector lives on this process only.
      inline MPI_Comm
      communicator(const dealii::Vector<double> &)
      {
        return MPI_COMM_SELF;
      }

      inline MPI_Comm
      communicator(const dealii::TrilinosWrappers::MPI::Vector &v)
      {
        return v.get_mpi_communicator();
      }

      /// Sum of a local value over the vector's communicator.
      template <typename VectorType>
      inline double
      sum(const double local, const VectorType &v)
      {
        return dealii::Utilities::MPI::sum(local, communicator(v));
      }

      template <typename VectorType>
      inline double
      min(const double local, const VectorType &v)
      {
        return dealii::Utilities::MPI::min(local, communicator(v));
      }

      template <typename VectorType>
      inline double
      max(const double local, const VectorType &v)
      {
        return dealii::Utilities::MPI::max(local, communicator(v));
      }

      /**
       * a'b over the vector's communicator.  Unlike the vector classes' own
       * operator*, this does not assert finiteness (deal.II debug builds
       * abort on a NaN there), so a solver can see the NaN and report
       * `non_finite` instead.
       */
      template <typename VectorType>
      inline double
      dot(const VectorType &a, const VectorType &b)
      {
        // in eight lanes (VectorKernels): a dependent sum per entry would
        // make the dot product latency-bound
        VectorKernels::Lanes s;
        VectorKernels::dot(a.locally_owned_size(), a.begin(), b.begin(), s);
        return sum(s.total(), a);
      }

      /// ||a|| without finiteness assertions (see dot()).
      template <typename VectorType>
      inline double
      norm(const VectorType &a)
      {
        return std::sqrt(dot(a, a));
      }

      /// {p'Ap, p'p, g'p} in one pass (VectorKernels::dots), one reduction.
      template <typename VectorType>
      inline std::array<double, 3>
      dots(const VectorType &p, const VectorType &Ap, const VectorType &g)
      {
        VectorKernels::Lanes pAp, pp, gp;
        VectorKernels::dots(p.locally_owned_size(),
                            p.begin(),
                            Ap.begin(),
                            g.begin(),
                            pAp,
                            pp,
                            gp);
        const double          local[3] = {pAp.total(), pp.total(), gp.total()};
        std::array<double, 3> global;
        dealii::Utilities::MPI::sum(dealii::ArrayView<const double>(local, 3),
                                    communicator(p),
                                    dealii::ArrayView<double>(global.data(),
                                                              3));
        return global;
      }

      /// The cost 1/2 y'Ay - b'y from the gradient g = Ay - b: 1/2 y'(g -
      /// b), in one pass (VectorKernels::cost).
      template <typename VectorType>
      inline double
      cost(const VectorType &y, const VectorType &g, const VectorType &b)
      {
        VectorKernels::Lanes s;
        VectorKernels::cost(
          y.locally_owned_size(), y.begin(), g.begin(), b.begin(), s);
        return 0.5 * sum(s.total(), y);
      }
    } // namespace internal
  }   // namespace qp
} // namespace dualcontact

#endif
