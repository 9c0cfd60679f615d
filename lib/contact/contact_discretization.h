#pragma once

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>
#include <deal.II/lac/vector.h>

#include <contact/contact_pair.h>
#include <fem/elastic_body.h>

#include <array>
#include <map>
#include <string>
#include <vector>

namespace dualcontact
{
  namespace contact
  {
    /**
     * One slave node of a contact pair: where it is, its contact frame, its
     * initial gap and its share of the contact area.
     */
    template <int dim>
    struct ContactNode
    {
      unsigned int pair = 0;
      unsigned int body = 0;
      /** The node's dofs in its body's numbering, one per component. */
      std::array<dealii::types::global_dof_index, dim> dofs;
      dealii::Point<dim>                               position;
      /** Closest point of the master surface (reference configuration). */
      dealii::Point<dim> master_point;
      /** Unit normal, pointing from the slave into the master. */
      dealii::Tensor<1, dim> normal;
      /** Unit tangents; (normal, tangents) is orthonormal. */
      std::array<dealii::Tensor<1, dim>, dim - 1> tangents;
      /** Initial normal gap (master_point - position) . normal [m]. */
      double gap = 0;
      /** Contact area weight: int phi_i ds over the slave surface [m^2]. */
      double weight = 0;
    };


    /**
     * One slave face (an edge in 2D) of a contact pair: the contact nodes
     * on it with their shares w_{f,i} = int_f phi_i ds of the face [m^2; m
     * in 2D] (summed over the faces of a node they give its weight).  The
     * report's friction multipliers are piecewise constant on these faces.
     */
    struct ContactFace
    {
      unsigned int pair = 0;
      /** (index into nodes(), w_{f,i}) */
      std::vector<std::pair<unsigned int, double>> nodes;
    };


    /**
     * Node-to-surface contact discretization (small displacements, reference
     * configuration) of all contact pairs of a scene.
     *
     * The displacements of all bodies form one vector, body b's dofs at
     * offset body_offset(b).  Per slave node i the relative displacement
     * u_s - u_m (u_m interpolated at the slave node's closest point on the
     * master surface; zero for a rigid obstacle) gives one normal row of B_N
     * and dim - 1 tangential rows of B_T:
     *   (B_N u)_i = n_i . (u_s - u_m),   (B_T u)_{(dim-1) i + k} = t_ik . (u_s
     * - u_m), and non-penetration reads B_N u <= gap.
     *
     * The matrices act on the *condensed* displacements: entries at dofs
     * constrained by a body's AffineConstraints (Dirichlet, hanging nodes)
     * are expanded through the constraint lines, and the inhomogeneities move
     * into normal_offset() / tangential_offset(), so that for u satisfying
     * the constraints  B_full u = B u + offset.  Hence normal_bound() =
     * gap - normal_offset is the right-hand side of B_N u <= c for the
     * condensed stiffness matrices.
     *
     * Master faces are projected onto by their vertices (bilinear/straight
     * geometry); curved Q2 master faces are approximated by that.
     */
    template <int dim>
    class ContactDiscretization
    {
    public:
      /** Per pair: what the log reports. */
      struct PairSummary
      {
        std::string  name;
        unsigned int n_nodes = 0;
        double       min_gap = 0;
        double       max_gap = 0;
        double       area    = 0; ///< sum of the weights [m^2]
      };

      ContactDiscretization(
        const std::vector<const fem::ElasticBody<dim> *> &bodies,
        const std::vector<ContactPair<dim>>              &pairs);

      unsigned int
      n_nodes() const;
      const std::vector<ContactNode<dim>> &
      nodes() const;
      const std::vector<PairSummary> &
      pair_summaries() const;
      /** The slave faces of every pair with their contact nodes (nodes
       * without a master within the search distance left out; faces left
       * with no node dropped). */
      const std::vector<ContactFace> &
      faces() const;
      const std::vector<ContactPair<dim>> &
      pairs() const;

      /** Total number of displacement dofs of all bodies. */
      dealii::types::global_dof_index
      n_dofs() const;
      dealii::types::global_dof_index
      body_offset(const unsigned int body) const;
      /** The body whose stacked dofs hold @p dof: body_offset(b) <= dof <
       *  body_offset(b + 1). */
      unsigned int
      body_of_dof(const dealii::types::global_dof_index dof) const;

      /** B_N: n_nodes() x n_dofs(). */
      const dealii::SparseMatrix<double> &
      normal_matrix() const;
      /** B_T: (dim - 1) n_nodes() x n_dofs(). */
      const dealii::SparseMatrix<double> &
      tangential_matrix() const;
      /** The initial gaps of the nodes [m]. */
      const dealii::Vector<double> &
      gaps() const;
      /** B_N applied to the prescribed (inhomogeneous) displacements. */
      const dealii::Vector<double> &
      normal_offset() const;
      /** B_T applied to the prescribed displacements. */
      const dealii::Vector<double> &
      tangential_offset() const;
      /** c = gap - normal_offset: B_N u <= c on condensed displacements. */
      dealii::Vector<double>
      normal_bound() const;

      /**
       * normal_offset() and tangential_offset() again from the bodies'
       * current constraints (the prescribed values of a new load step,
       * fem::ElasticBody::set_load_time()); the constraint lines, and hence
       * B, must be those of the construction.
       */
      void
      update_offsets(const std::vector<const fem::ElasticBody<dim> *> &bodies);

      /**
       * The forces the contact exerts on the bodies' nodes [N; N/m in 2D]
       * for the multipliers @p normal_multipliers (lambda_N, one per node)
       * and @p tangential_multipliers (lambda_T, dim - 1 per node, zero at a
       * frictionless node): -B_full' lambda on the stacked dofs of all
       * bodies, with B_full the rows before condensation.  Unlike B' lambda
       * it has the entries at prescribed dofs (a slave node on a support or
       * a symmetry plane), which belong to the contact force and not to the
       * support's reaction, and at hanging nodes (which the bodies'
       * reactions condense to their parents as the rest of the residual).
       */
      dealii::Vector<double>
      nodal_contact_forces(
        const dealii::Vector<double> &normal_multipliers,
        const dealii::Vector<double> &tangential_multipliers) const;

    private:
      /// Adds the faces of pair @p pair: per slave face, the weights of
      /// its nodes that became contact nodes (@p node_of_key: a slave
      /// node's key, its first-component dof, to its index in nodes_).
      void
      add_faces(
        const unsigned int pair,
        const std::vector<std::map<dealii::types::global_dof_index, double>>
          &face_weights,
        const std::map<dealii::types::global_dof_index, unsigned int>
          &node_of_key);

      std::vector<ContactPair<dim>>                pairs_;
      std::vector<dealii::types::global_dof_index> offsets_;
      std::vector<ContactNode<dim>>                nodes_;
      std::vector<PairSummary>                     summaries_;
      std::vector<ContactFace>                     faces_;
      dealii::SparsityPattern                      normal_pattern_;
      dealii::SparsityPattern                      tangential_pattern_;
      dealii::SparseMatrix<double>                 normal_matrix_;
      dealii::SparseMatrix<double>                 tangential_matrix_;
      /** The rows before condensation (nodal_contact_forces()). */
      dealii::SparsityPattern      full_normal_pattern_;
      dealii::SparsityPattern      full_tangential_pattern_;
      dealii::SparseMatrix<double> full_normal_matrix_;
      dealii::SparseMatrix<double> full_tangential_matrix_;
      dealii::Vector<double>       gaps_;
      dealii::Vector<double>       normal_offset_;
      dealii::Vector<double>       tangential_offset_;
    };
  } // namespace contact
} // namespace dualcontact
