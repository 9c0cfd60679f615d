#pragma once

#include <deal.II/lac/vector.h>

#include <fclib/triplets.h>

#include <string>
#include <vector>

namespace dualcontact
{
  namespace fclib
  {
    /**
     * The local frictional contact problem of FCLIB: find r and u = W r + q
     * such that, for every contact i (unknowns [n, t_1(, t_2)], normal
     * first), r_i lies in the Coulomb cone K_i of aperture mu_i and De
     * Saxce's modified velocity u_i + mu_i ||u_t,i|| e_n lies in its dual
     * cone, orthogonal to r_i.
     *
     * In dualcontact's terms (lib/contact): W = F, the Delassus operator
     * B K^-1 B' in the contact frames, r the nodal contact forces lambda and
     * q = -d, so that u = F lambda - d is the gap after deformation (normal)
     * and minus the slip (tangential).
     */
    class LocalProblem
    {
    public:
      LocalProblem() = default;
      /**
       * @p spacedim 2 or 3; @p W square of size spacedim * mu.size();
       * @p q of that size.
       */
      LocalProblem(const unsigned int            spacedim,
                   const Triplets               &W,
                   const dealii::Vector<double> &q,
                   const std::vector<double>    &mu,
                   const std::string            &title = "");

      unsigned int
      spacedim() const;
      unsigned int
      n_contacts() const;
      /** spacedim * n_contacts(). */
      unsigned int
      size() const;
      const dealii::SparseMatrix<double> &
      W() const;
      const dealii::Vector<double> &
      q() const;
      const std::vector<double> &
      mu() const;
      const std::string &
      title() const;

      /** u = W r + q. */
      void
      velocity(dealii::Vector<double>       &u,
               const dealii::Vector<double> &r) const;

      /** dst = (W + W')/2 src, the Hessian of 1/2 r'W r. */
      void
      symmetric_vmult(dealii::Vector<double>       &dst,
                      const dealii::Vector<double> &src) const;

      /** dst = (W - W')/2 src, the part of W that 1/2 r'W r does not see. */
      void
      antisymmetric_vmult(dealii::Vector<double>       &dst,
                          const dealii::Vector<double> &src) const;

      /**
       * max |W_ij - W_ji| / max |W_ij|: how far W is from symmetric (some
       * distributed files are slightly non-symmetric).
       */
      double
      asymmetry() const;

    private:
      unsigned int                   spacedim_ = 3;
      OwnedSparseMatrix              W_;
      dealii::Vector<double>         q_;
      std::vector<double>            mu_;
      std::string                    title_;
      mutable dealii::Vector<double> work_;
    };
  } // namespace fclib
} // namespace dualcontact
