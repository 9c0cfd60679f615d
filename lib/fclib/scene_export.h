#pragma once

#include <deal.II/lac/vector.h>

#include <contact/contact_discretization.h>
#include <contact/dual_problem.h>
#include <fclib/global_problem.h>
#include <fem/elastic_body.h>
#include <io/output_folder.h>
#include <util/enum_names.h>

#include <string>
#include <vector>

namespace dualcontact
{
  namespace fclib
  {
    /**
     * The contact problem of a scene as an FCLIB global problem, one
     * contact per slave node (unknowns [normal, tangents] in the node's
     * frame, see lib/contact/README.md):
     *
     *   M = K (the condensed stiffness matrices of all bodies, block
     *   diagonal, at ContactDiscretization::body_offset()),
     *   H = -[B_N; B_T]' (column dim*i the normal row of node i, then its
     *   tangential rows; the minus because lambda is the force on the
     *   master and the contact pushes the slave by -B'lambda),
     *   f = the condensed loads, w = [c_i; -o_T,i] per node (gap minus
     *   prescribed normal displacement; minus prescribed tangential
     *   displacement), mu_i = the pair's Coulomb coefficient (0 for
     *   frictionless pairs).
     *
     * Contact nodes whose dofs are all prescribed (e.g. on a clamped edge)
     * have zero rows in B and are left out (exported_nodes()): their u is a
     * constant and their force goes into the support; a zero diagonal block
     * of W also stops other codes (Siconos' NSGS asserts on it).
     *
     * Then u = H'v + w is the gap after deformation and minus the slip, and
     * the reduction W = H'M^-1H, q = H'M^-1 f + w is exactly F, -d of the
     * DualProblem.  Only frictionless and isotropic Coulomb pairs can be
     * written (FCLIB holds Coulomb friction), and no body may have
     * rigid-body modes (K must be positive definite); both are checked with
     * a message naming the pair / the reason.
     */
    template <int dim>
    GlobalProblem
    make_global_problem(
      const std::vector<const fem::ElasticBody<dim> *> &bodies,
      const contact::ContactDiscretization<dim>        &contact,
      const contact::DualProblem<dim>                  &dual,
      const std::string                                &title);

    /** Which FCLIB files a scene writes (`Output/FCLIB problem`). */
    enum class ExportForm
    {
      none,
      global,
      local,
      both
    };

    /** The names of ExportForm: "none", "global", "local", "both". */
    inline constexpr util::EnumNames<ExportForm, 4> export_form_names{
      "FCLIB problem form",
      {{"none", "global", "local", "both"}},
    };

    /**
     * Write the scene's contact problem into @p folder as
     * `contact_problem_global.hdf5` (M, H, f, w, mu; /solution with v, u, r)
     * and/or `contact_problem_local.hdf5` (W, q, mu; /solution with u, r),
     * the solution being @p lambda (DualProblem layout; empty: the files get
     * no /solution, e.g. when the contact solver did not converge).  The HDF5
     * file is made by libfclib in a temporary file and copied into the folder's
     * stream, so that the folder's commit/clean-up covers it.
     */
    template <int dim>
    void
    write_scene_problem(
      io::OutputFolder                                 &folder,
      const ExportForm                                  form,
      const std::vector<const fem::ElasticBody<dim> *> &bodies,
      const contact::ContactDiscretization<dim>        &contact,
      const contact::DualProblem<dim>                  &dual,
      const dealii::Vector<double>                     &lambda,
      const std::string                                &title);

    /** The contact nodes that are written (B has a nonzero normal row). */
    template <int dim>
    std::vector<unsigned int>
    exported_nodes(const contact::ContactDiscretization<dim> &contact);

    /**
     * The multipliers lambda of the DualProblem (layout [lambda_N;
     * lambda_T of frictional nodes]) in the FCLIB layout (per exported node
     * [lambda_N, lambda_T]; zero tangential force at frictionless nodes).
     */
    template <int dim>
    dealii::Vector<double>
    to_fclib_layout(const contact::ContactDiscretization<dim> &contact,
                    const contact::DualProblem<dim>           &dual,
                    const dealii::Vector<double>              &lambda);

    /** Inverse of to_fclib_layout() (tangents of frictionless nodes dropped).
     */
    template <int dim>
    dealii::Vector<double>
    to_dual_layout(const contact::ContactDiscretization<dim> &contact,
                   const contact::DualProblem<dim>           &dual,
                   const dealii::Vector<double>              &r);
  } // namespace fclib
} // namespace dualcontact
