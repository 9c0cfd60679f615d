#pragma once

#include <deal.II/lac/vector.h>

#include <fclib/contact_list.h>
#include <fclib/local_problem.h>
#include <fclib/triplets.h>
#include <fem/stiffness_solver.h>

#include <memory>
#include <string>
#include <vector>

namespace dualcontact
{
  namespace fclib
  {
    /**
     * The global frictional contact problem of FCLIB: M v = H r + f,
     * u = H' v + w, with the local Coulomb conditions between r and u
     * (LocalProblem).  M is n x n symmetric positive definite, H is n x m,
     * m = spacedim * (number of contacts).
     *
     * In dualcontact's terms (lib/contact): M = K (condensed stiffness of all
     * bodies), v the displacement, r = lambda the nodal contact forces in
     * the contact frames, H = -B' (the force of the contacts on the slave
     * bodies is -B'lambda), w = [c; -o_T] (gap minus prescribed normal
     * displacement; minus the prescribed tangential displacement), so that
     * u = -B v + w is the gap after deformation and minus the slip.
     *
     * Equality constraints (G, b of the format) are not supported.
     */
    class GlobalProblem : public ContactList
    {
    public:
      GlobalProblem() = default;
      /** M may be given as its upper triangle only (it is mirrored). */
      GlobalProblem(const unsigned int            spacedim,
                    Triplets                      M,
                    const Triplets               &H,
                    const dealii::Vector<double> &f,
                    const dealii::Vector<double> &w,
                    const std::vector<double>    &mu,
                    const std::string            &title = "");
      ~GlobalProblem();
      GlobalProblem(GlobalProblem &&) = default;
      GlobalProblem &
      operator=(GlobalProblem &&) = default;

      unsigned int
      n_dofs() const;
      const dealii::SparseMatrix<double> &
      M() const;
      const dealii::SparseMatrix<double> &
      H() const;
      const dealii::Vector<double> &
      f() const;
      const dealii::Vector<double> &
      w() const;
      /** Whether M was stored as its upper triangle only (then mirrored). */
      bool
      M_was_upper_triangle() const;

      /**
       * The local form: W = H' M^-1 H (dense, m solves with the
       * factorization of M), q = H' M^-1 f + w.  M is factorized by CHOLMOD
       * (sparse Cholesky); if CHOLMOD finds M not positive definite, by
       * UMFPACK (sparse LU), and the name of the one used is in
       * factorization_name().
       */
      LocalProblem
      reduce_to_local(const Storage storage = Storage::automatic) const;

      /** v = M^-1 (H r + f), the global velocity for contact forces r. */
      void
      velocity(dealii::Vector<double>       &v,
               const dealii::Vector<double> &r) const;

      /** "cholmod" or "umfpack" once M has been factorized, else "". */
      std::string
      factorization_name() const;

    private:
      void
      factorize() const;

      OwnedSparseMatrix                             M_, H_;
      dealii::Vector<double>                        f_, w_;
      bool                                          M_upper_ = false;
      mutable std::unique_ptr<fem::StiffnessSolver> factorization_;
    };
  } // namespace fclib
} // namespace dualcontact
