#pragma once

#include <deal.II/lac/vector.h>

#include <fclib/contact_list.h>
#include <fclib/delassus_operator.h>
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
     *
     * W is kept by a DelassusOperator: dense (BLAS) when it is dense, sparse
     * otherwise, with its symmetric part formed once.
     */
    class LocalProblem : public ContactList
    {
    public:
      LocalProblem() = default;
      /**
       * @p spacedim 2 or 3; @p W square of size spacedim * mu.size();
       * @p q of that size; @p storage of W for the products.
       */
      LocalProblem(const unsigned int            spacedim,
                   const Triplets               &W,
                   const dealii::Vector<double> &q,
                   const std::vector<double>    &mu,
                   const std::string            &title   = "",
                   const Storage                 storage = Storage::automatic);

      /** spacedim * n_contacts(). */
      unsigned int
      size() const;
      /** W as read (writing, entries); products go through delassus(). */
      const dealii::SparseMatrix<double> &
      W() const;
      /** The products with W (dense or sparse storage). */
      const DelassusOperator &
      delassus() const;
      const dealii::Vector<double> &
      q() const;

      /** u = W r + q. */
      void
      velocity(dealii::Vector<double>       &u,
               const dealii::Vector<double> &r) const;

    private:
      DelassusOperator       W_;
      dealii::Vector<double> q_;
    };
  } // namespace fclib
} // namespace dualcontact
