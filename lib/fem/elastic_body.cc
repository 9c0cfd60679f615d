#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/distributed/tria_base.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/mapping_q.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/numerics/vector_tools.h>

#include <fem/elastic_body.h>
#include <fem/stiffness_solver.h>
#include <util/machine.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>

namespace dualcontact
{
  namespace fem
  {
    using namespace dealii;

    template <int dim>
    ElasticBody<dim>::ElasticBody(
      const std::string                                     &name,
      std::shared_ptr<Triangulation<dim>>                    triangulation,
      const unsigned int                                     fe_degree,
      const std::map<types::material_id, IsotropicMaterial> &materials,
      const unsigned int curved_mapping_degree)
        : name_(name)
        , triangulation_(std::move(triangulation))
        , cell_family_(*triangulation_, name)
        , fe_(*cell_family_.scalar_element(fe_degree), dim)
        , mapping_degree_(cell_family_.mapping_degree(fe_degree))
        // simplices: affine everywhere (see CellFamily), no curved mapping
        , curved_mapping_degree_(cell_family_.is_simplex() ?
                                   mapping_degree_ :
                                   std::max(curved_mapping_degree, 1u))
        , mapping_(cell_family_.mapping(fe_degree))
        , curved_mapping_(curved_mapping_degree_ > mapping_degree_ ?
                            cell_family_.mapping(curved_mapping_degree_) :
                            nullptr)
        , dof_handler_(*triangulation_)
        , materials_(materials)
    {
      AssertThrow(fe_degree == 1 || fe_degree == 2,
                  ExcMessage(name +
                             ": the finite element degree must be 1 or "
                             "2 (got " +
                             std::to_string(fe_degree) + ")."));
      AssertThrow(curved_mapping_degree >= 1,
                  ExcMessage(name +
                             ": the mapping degree of curved loaded faces "
                             "must be at least 1 (got 0)."));
    }


    template <int dim>
    ElasticBody<dim>::~ElasticBody()
    {
      // The DoFHandler refers to the triangulation: release it first.
      dof_handler_.clear();
    }


    template <int dim>
    void
    ElasticBody<dim>::set_dirichlet_conditions(
      const std::vector<DirichletCondition<dim>> &conditions)
    {
      dirichlet_ = conditions;
    }


    template <int dim>
    void
    ElasticBody<dim>::set_traction_conditions(
      const std::vector<TractionCondition<dim>> &conditions)
    {
      tractions_ = conditions;
    }


    template <int dim>
    void
    ElasticBody<dim>::set_body_force(std::shared_ptr<Function<dim>> body_force)
    {
      body_force_ = std::move(body_force);
    }


    template <int dim>
    void
    ElasticBody<dim>::setup()
    {
      // Consistency of the scene with the mesh, before anything is built
      // (on a distributed mesh every process decides on the largest id
      // without a material, so that all of them throw alike).
      int missing = -1;
      for (const auto &cell : triangulation_->active_cell_iterators())
        if (!cell->is_artificial() &&
            materials_.count(cell->material_id()) == 0)
          missing = std::max<int>(missing, cell->material_id());
      if (is_distributed())
        missing = Utilities::MPI::max(missing, communicator());
      AssertThrow(missing < 0,
                  ExcMessage(name_ + ": the mesh has cells with material id " +
                             std::to_string(missing) +
                             ", but no material is given for it."));
      const std::vector<types::boundary_id> ids =
        triangulation_->get_boundary_ids();
      const auto check_id =
        [&](const types::boundary_id id, const std::string &what)
      {
        AssertThrow(std::find(ids.begin(), ids.end(), id) != ids.end(),
                    ExcMessage(name_ + ": " + what + " on boundary id " +
                               std::to_string(id) +
                               ", which the mesh does not have."));
      };
      for (const auto &condition : dirichlet_)
      {
        check_id(condition.boundary_id, "a Dirichlet condition");
        AssertThrow(condition.components.size() == dim && condition.values &&
                      condition.values->n_components == dim,
                    ExcMessage(name_ +
                               ": a Dirichlet condition needs a "
                               "component mask and values with " +
                               std::to_string(dim) + " components."));
      }
      for (const auto &condition : tractions_)
      {
        check_id(condition.boundary_id, "a traction");
        AssertThrow(condition.traction &&
                      condition.traction->n_components == dim,
                    ExcMessage(name_ + ": a traction needs " +
                               std::to_string(dim) + " components."));
      }
      AssertThrow(!body_force_ || body_force_->n_components == dim,
                  ExcMessage(name_ + ": the body force needs " +
                             std::to_string(dim) + " components."));

      dof_handler_.distribute_dofs(fe_);
      make_constraints();

      // a new set of dofs: the system of the old ones is gone
      stiffness_.clear();
      sparsity_.reinit(0, 0, 0);
      load_.reinit(0);
    }


    template <int dim>
    void
    ElasticBody<dim>::assemble_load()
    {
      Assert(is_assembled(), ExcMessage(name_ + ": assemble() first."));
      load_ = 0.;
      CellScratch        scratch(*this);
      FullMatrix<double> cell_matrix;
      Vector<double>     cell_rhs;
      std::vector<types::global_dof_index> dof_indices(fe_.n_dofs_per_cell());
      for (const auto &cell : dof_handler_.active_cell_iterators())
      {
        cell_system(cell, scratch, cell_matrix, cell_rhs);
        cell->get_dof_indices(dof_indices);
        // the inhomogeneities through the cell matrix, as assemble() does
        constraints_.distribute_local_to_global(cell_rhs,
                                                dof_indices,
                                                load_,
                                                cell_matrix);
      }
    }


    template <int dim>
    struct ElasticBody<dim>::CellScratch
    {
      explicit CellScratch(const ElasticBody<dim> &body)
          : CellScratch(body.cell_family_,
                        *body.mapping_,
                        body.curved_mapping_ ? *body.curved_mapping_ :
                                               *body.mapping_,
                        body.curved_mapping_degree_,
                        body.fe_)
      {}

      CellScratch(const CellFamily<dim>    &family,
                  const Mapping<dim>       &mapping,
                  const Mapping<dim>       &curved_mapping,
                  const unsigned int        curved_mapping_degree,
                  const FiniteElement<dim> &fe)
          : quadrature(family.cell_quadrature(fe.degree + 1))
          , face_quadrature(family.face_quadrature(fe.degree + 1))
          // the integrand on a curved face is phi_i t |J| with |J| of the
          // degree of the curved mapping: Gauss exact for phi_i |J| in 2D
          , curved_face_quadrature(
              family.face_quadrature(fe.degree + curved_mapping_degree))
          , fe_values(mapping,
                      fe,
                      quadrature,
                      update_gradients | update_values |
                        update_quadrature_points | update_JxW_values)
          , fe_face_values(mapping,
                           fe,
                           face_quadrature,
                           update_values | update_quadrature_points |
                             update_JxW_values)
          , curved_fe_face_values(curved_mapping,
                                  fe,
                                  curved_face_quadrature,
                                  update_values | update_quadrature_points |
                                    update_JxW_values)
          , gradients(fe.n_dofs_per_cell())
          , component(fe.n_dofs_per_cell())
          , force(dim)
      {
        for (unsigned int i = 0; i < fe.n_dofs_per_cell(); ++i)
          component[i] = fe.system_to_component_index(i).first;
      }

      const Quadrature<dim>       quadrature;
      const Quadrature<dim - 1>   face_quadrature;
      const Quadrature<dim - 1>   curved_face_quadrature;
      FEValues<dim>               fe_values;
      FEFaceValues<dim>           fe_face_values;
      FEFaceValues<dim>           curved_fe_face_values;
      std::vector<Tensor<1, dim>> gradients;
      std::vector<unsigned int>   component;
      Vector<double>              force;
    };


    namespace
    {
      bool
      all_finite(const Vector<double> &values)
      {
        return std::all_of(values.begin(),
                           values.end(),
                           [](const double value)
                           { return std::isfinite(value); });
      }

      /**
       * Throw naming the body, the load and the point: a load evaluated at a
       * quadrature point is not finite (an expression such as `1/0' or
       * `sqrt(-1)' that muparser evaluates to inf or NaN).  Checked during
       * assembly, where every load value passes, so that nothing
       * non-finite is solved for.
       */
      template <int dim>
      void
      throw_non_finite_load(const Vector<double> &values,
                            const Point<dim>     &point,
                            const std::string    &body_name,
                            const std::string    &load_name)
      {
        std::ostringstream message;
        message << body_name << ": the " << load_name << " is not finite (";
        for (unsigned int c = 0; c < values.size(); ++c)
          message << (c == 0 ? "" : ", ") << values[c];
        message << ") at the point (" << point
                << "): check its expression (a division by zero, the square "
                   "root or logarithm of a negative number, an overflow).";
        AssertThrow(false, ExcMessage(message.str()));
      }
    } // namespace


    template <int dim>
    bool
    ElasticBody<dim>::touches_curved_manifold(
      const typename Triangulation<dim>::face_iterator &face)
    {
      if (face->manifold_id() != numbers::flat_manifold_id)
        return true;
      if constexpr (dim == 3)
        for (unsigned int l = 0; l < face->n_lines(); ++l)
          if (face->line(l)->manifold_id() != numbers::flat_manifold_id)
            return true;
      return false;
    }


    template <int dim>
    const FEFaceValues<dim> &
    ElasticBody<dim>::traction_face_values(
      const typename DoFHandler<dim>::active_cell_iterator &cell,
      const unsigned int                                    f,
      CellScratch                                          &scratch) const
    {
      FEFaceValues<dim> &values =
        curved_mapping_ && touches_curved_manifold(cell->face(f)) ?
          scratch.curved_fe_face_values :
          scratch.fe_face_values;
      values.reinit(cell, f);
      return values;
    }


    template <int dim>
    void
    ElasticBody<dim>::cell_system(
      const typename DoFHandler<dim>::active_cell_iterator &cell,
      CellScratch                                          &scratch,
      FullMatrix<double>                                   &cell_matrix,
      Vector<double>                                       &cell_rhs) const
    {
      const unsigned int dofs_per_cell = fe_.n_dofs_per_cell();
      cell_matrix.reinit(dofs_per_cell, dofs_per_cell);
      cell_rhs.reinit(dofs_per_cell);
      FEValues<dim> &fe_values = scratch.fe_values;
      fe_values.reinit(cell);
      const IsotropicMaterial &material = materials_.at(cell->material_id());
      const double             lambda   = material.lame_lambda();
      const double             mu       = material.shear_modulus();
      const auto              &c        = scratch.component;
      auto                    &g        = scratch.gradients;

      // Each shape function of FESystem(FE_Q, dim) has one nonzero component
      // c_i, so eps(phi_i) = sym(e_{c_i} (x) grad phi_i) and
      // C eps_i : eps_j = lambda g_i[c_i] g_j[c_j]
      //                 + mu (g_i[c_j] g_j[c_i] + delta_{c_i c_j} g_i . g_j),
      // far cheaper than contracting rank-4 tensors.
      for (unsigned int q = 0; q < scratch.quadrature.size(); ++q)
      {
        for (unsigned int k = 0; k < dofs_per_cell; ++k)
          g[k] = fe_values.shape_grad(k, q);
        const double JxW = fe_values.JxW(q);
        for (unsigned int i = 0; i < dofs_per_cell; ++i)
          for (unsigned int j = i; j < dofs_per_cell; ++j)
            cell_matrix(i, j) += (lambda * g[i][c[i]] * g[j][c[j]] +
                                  mu * (g[i][c[j]] * g[j][c[i]] +
                                        (c[i] == c[j] ? g[i] * g[j] : 0.))) *
                                 JxW;
        if (body_force_)
        {
          body_force_->vector_value(fe_values.quadrature_point(q),
                                    scratch.force);
          if (!all_finite(scratch.force))
            throw_non_finite_load(scratch.force,
                                  fe_values.quadrature_point(q),
                                  name_,
                                  "body force (`set Body force')");
          for (unsigned int i = 0; i < dofs_per_cell; ++i)
            cell_rhs(i) +=
              scratch.force(c[i]) * fe_values.shape_value(i, q) * JxW;
        }
      }
      for (unsigned int i = 0; i < dofs_per_cell; ++i)
        for (unsigned int j = 0; j < i; ++j)
          cell_matrix(i, j) = cell_matrix(j, i);

      if (!tractions_.empty() && cell->at_boundary())
        for (const unsigned int f : cell->face_indices())
          if (cell->face(f)->at_boundary())
            for (const auto &condition : tractions_)
              if (cell->face(f)->boundary_id() == condition.boundary_id)
              {
                const FEFaceValues<dim> &fe_face_values =
                  traction_face_values(cell, f, scratch);
                for (const unsigned int q :
                     fe_face_values.quadrature_point_indices())
                {
                  condition.traction->vector_value(
                    fe_face_values.quadrature_point(q), scratch.force);
                  if (!all_finite(scratch.force))
                    throw_non_finite_load(scratch.force,
                                          fe_face_values.quadrature_point(q),
                                          name_,
                                          "traction on boundary id " +
                                            std::to_string(
                                              condition.boundary_id) +
                                            " (`set Traction')");
                  for (unsigned int i = 0; i < dofs_per_cell; ++i)
                    cell_rhs(i) += scratch.force(c[i]) *
                                   fe_face_values.shape_value(i, q) *
                                   fe_face_values.JxW(q);
                }
              }
    }


    template <int dim>
    void
    ElasticBody<dim>::assemble()
    {
      Assert(dof_handler_.n_dofs() > 0, ExcMessage(name_ + ": setup() first."));
      AssertThrow(!is_distributed(),
                  ExcMessage(name_ + ": the whole stiffness matrix of a body "
                                     "on a distributed mesh is assembled "
                                     "nowhere (TFETI assembles subdomains)."));
      DynamicSparsityPattern dsp(dof_handler_.n_dofs());
      // every cell, also on a parallel::shared::Triangulation (where
      // DoFTools::make_sparsity_pattern would visit the locally owned cells
      // only): the body's K is the whole matrix on every process
      std::vector<types::global_dof_index> cell_dofs(fe_.n_dofs_per_cell());
      for (const auto &cell : dof_handler_.active_cell_iterators())
      {
        cell->get_dof_indices(cell_dofs);
        constraints_.add_entries_local_to_global(cell_dofs, dsp, false);
      }
      stiffness_.clear();
      sparsity_.copy_from(dsp);
      stiffness_.reinit(sparsity_);
      load_.reinit(dof_handler_.n_dofs());
      CellScratch        scratch(*this);
      FullMatrix<double> cell_matrix;
      Vector<double>     cell_rhs;
      std::vector<types::global_dof_index> dof_indices(fe_.n_dofs_per_cell());
      for (const auto &cell : dof_handler_.active_cell_iterators())
      {
        cell_system(cell, scratch, cell_matrix, cell_rhs);
        cell->get_dof_indices(dof_indices);
        constraints_.distribute_local_to_global(
          cell_matrix, cell_rhs, dof_indices, stiffness_, load_);
      }
    }


    template <int dim>
    void
    ElasticBody<dim>::assemble_cells(
      const std::vector<typename DoFHandler<dim>::active_cell_iterator> &cells,
      const std::vector<types::global_dof_index>                        &dofs,
      SparsityPattern      &sparsity,
      SparseMatrix<double> &matrix,
      Vector<double>       &load) const
    {
      Assert(std::is_sorted(dofs.begin(), dofs.end()), ExcInternalError());
      const unsigned int dofs_per_cell = fe_.n_dofs_per_cell();
      // the local indices of each cell's dofs, once
      std::vector<std::vector<types::global_dof_index>> local(cells.size());
      std::vector<types::global_dof_index> cell_dofs(dofs_per_cell);
      for (unsigned int c = 0; c < cells.size(); ++c)
      {
        cells[c]->get_dof_indices(cell_dofs);
        local[c].resize(dofs_per_cell);
        for (unsigned int i = 0; i < dofs_per_cell; ++i)
        {
          const auto it =
            std::lower_bound(dofs.begin(), dofs.end(), cell_dofs[i]);
          Assert(it != dofs.end() && *it == cell_dofs[i], ExcInternalError());
          local[c][i] = it - dofs.begin();
        }
      }
      DynamicSparsityPattern dsp(dofs.size());
      for (const auto &indices : local)
        for (const auto i : indices)
          dsp.add_entries(i, indices.begin(), indices.end());
      sparsity.copy_from(dsp);
      matrix.reinit(sparsity);
      load.reinit(dofs.size());

      CellScratch        scratch(*this);
      FullMatrix<double> cell_matrix;
      Vector<double>     cell_rhs;
      for (unsigned int c = 0; c < cells.size(); ++c)
      {
        cell_system(cells[c], scratch, cell_matrix, cell_rhs);
        for (unsigned int i = 0; i < dofs_per_cell; ++i)
        {
          for (unsigned int j = 0; j < dofs_per_cell; ++j)
            matrix.add(local[c][i], local[c][j], cell_matrix(i, j));
          load(local[c][i]) += cell_rhs(i);
        }
      }
    }


    template <int dim>
    void
    ElasticBody<dim>::solve(StiffnessSolver &solver,
                            Vector<double>  &displacement,
                            const bool       factorize) const
    {
      if (factorize)
        solver.initialize(stiffness_);
      displacement.reinit(n_dofs());
      solver.solve(displacement, load_);
      distribute(displacement);
    }


    template <int dim>
    void
    ElasticBody<dim>::distribute(Vector<double> &displacement) const
    {
      constraints_.distribute(displacement);
    }


    template <int dim>
    typename ElasticBody<dim>::Summary
    ElasticBody<dim>::summarize(const Vector<double> &displacement,
                                const Vector<double> *contact_force) const
    {
      AssertDimension(displacement.size(), n_dofs());
      Assert(contact_force == nullptr || contact_force->size() == n_dofs(),
             ExcDimensionMismatch(contact_force->size(), n_dofs()));
      Summary summary;
      // f was assembled with the constraints condensed, so the load and the
      // residual K_full u - f_full are rebuilt from the unconstrained cell
      // systems.
      CellScratch        scratch(*this);
      FullMatrix<double> cell_matrix;
      Vector<double>     cell_rhs;
      const unsigned int dofs_per_cell = fe_.n_dofs_per_cell();
      Vector<double>     local_u(dofs_per_cell);
      Vector<double>     local_Ku(dofs_per_cell);
      Vector<double>     local_w(dofs_per_cell), local_Kw(dofs_per_cell);
      Tensor<1, dim>     mean;
      std::vector<types::global_dof_index> dof_indices(dofs_per_cell);
      Vector<double>                       residual(n_dofs());
      // the vector component of every dof of the cells summed here
      std::vector<int> component_of_dof(n_dofs(), -1);
      // Support points of all components coincide: the nodal displacement
      // is gathered through the component-0 dofs of each cell.
      const unsigned int n_nodes   = fe_.base_element(0).n_dofs_per_cell();
      double             max_norm2 = 0;
      for (const auto &cell : dof_handler_.active_cell_iterators())
      {
        if (!is_counted_here(cell))
          continue;
        cell_system(cell, scratch, cell_matrix, cell_rhs);
        cell->get_dof_indices(dof_indices);
        for (unsigned int i = 0; i < dofs_per_cell; ++i)
          local_u(i) = displacement(dof_indices[i]);
        cell_matrix.vmult(local_Ku, local_u);
        // The energy of u less the cell's mean translation (K_c annihilates
        // a translation): a floating body that moved 100 m would otherwise
        // lose its few joules of strain energy to the rounding of
        // K_c u ~ eps |K_c| 100 m (tests/app/cylinder_gap_99m).
        for (unsigned int i = 0; i < dofs_per_cell; ++i)
          mean[fe_.system_to_component_index(i).first] += local_u(i);
        for (unsigned int d = 0; d < dim; ++d)
          mean[d] /= n_nodes;
        for (unsigned int i = 0; i < dofs_per_cell; ++i)
          local_w(i) =
            local_u(i) - mean[fe_.system_to_component_index(i).first];
        mean = 0;
        cell_matrix.vmult(local_Kw, local_w);
        summary.strain_energy += 0.5 * (local_w * local_Kw);
        summary.external_work += cell_rhs * local_u;
        for (unsigned int i = 0; i < dofs_per_cell; ++i)
        {
          // Shape functions of one component sum to one, so the resultant
          // is the sum of the load entries of that component.
          summary.applied_force[scratch.component[i]] += cell_rhs(i);
          residual(dof_indices[i]) += local_Ku(i) - cell_rhs(i);
          component_of_dof[dof_indices[i]] = scratch.component[i];
        }
        for (unsigned int node = 0; node < n_nodes; ++node)
        {
          double norm2 = 0;
          for (unsigned int c = 0; c < dim; ++c)
            norm2 += dealii::Utilities::fixed_power<2>(
              local_u(fe_.component_to_system_index(c, node)));
          max_norm2 = std::max(max_norm2, norm2);
        }
      }
      summary.max_displacement    = std::sqrt(max_norm2);
      summary.traction_resultants = traction_resultants(scratch);
      if (is_distributed())
      {
        // each process summed its own cells; the residual at a support
        // dof takes every cell around it
        const MPI_Comm comm = communicator();
        summary.strain_energy =
          Utilities::MPI::sum(summary.strain_energy, comm);
        summary.external_work =
          Utilities::MPI::sum(summary.external_work, comm);
        summary.applied_force =
          Utilities::MPI::sum(summary.applied_force, comm);
        summary.max_displacement =
          Utilities::MPI::max(summary.max_displacement, comm);
        Utilities::MPI::sum(residual, comm, residual);
      }
      if (contact_force != nullptr)
      {
        residual -= *contact_force;
        // each dof by the process that owns it (the owned cells hold the
        // owned dofs)
        for (types::global_dof_index i = 0; i < n_dofs(); ++i)
          if (component_of_dof[i] >= 0 && is_owned_dof(i))
            summary.contact_force[component_of_dof[i]] += (*contact_force)(i);
        if (is_distributed())
          summary.contact_force =
            Utilities::MPI::sum(summary.contact_force, communicator());
      }
      condense_hanging_nodes(residual);

      // A dof on two supports is counted once, for the first condition that
      // names it (the one that won in setup()).  Hanging dofs are not
      // supports: condense_hanging_nodes() gave their share to their parents.
      std::set<types::global_dof_index>    counted;
      std::vector<types::global_dof_index> face_dofs(fe_.n_dofs_per_face());
      for (const auto &condition : dirichlet_)
      {
        Tensor<1, dim> &reaction =
          summary.reaction_forces[condition.boundary_id];
        // on a distributed mesh: the faces of the owned and ghost cells,
        // each support dof counted by its owner (the cells around a dof
        // are owned or ghosts on its owner)
        for (const auto &cell : dof_handler_.active_cell_iterators())
          if (!cell->is_artificial() && cell->at_boundary())
            for (const unsigned int f : cell->face_indices())
              if (cell->face(f)->at_boundary() &&
                  cell->face(f)->boundary_id() == condition.boundary_id)
              {
                cell->face(f)->get_dof_indices(face_dofs);
                for (unsigned int i = 0; i < face_dofs.size(); ++i)
                {
                  const unsigned int c =
                    fe_.face_system_to_component_index(i).first;
                  if (condition.components[c] &&
                      constraints_.is_constrained(face_dofs[i]) &&
                      !hanging_node_constraints_.is_constrained(face_dofs[i]) &&
                      is_owned_dof(face_dofs[i]) &&
                      counted.insert(face_dofs[i]).second)
                    reaction[c] += residual(face_dofs[i]);
                }
              }
        if (is_distributed())
          reaction = Utilities::MPI::sum(reaction, communicator());
      }
      summary.force_imbalance = force_imbalance(summary);
      return summary;
    }


    template <int dim>
    void
    ElasticBody<dim>::condense_hanging_nodes(Vector<double> &residual) const
    {
      // r = C' r_full: the residual of a hanging dof belongs to its parents
      // with the constraint's weights (its shape function is part of
      // theirs).  Left where it is, it is lost to a support whose vertex is
      // a parent (an edge from the support into a refined zone) and the
      // reactions do not balance the loads.  Closed lines name parents only.
      for (const auto &line : hanging_node_constraints_.get_lines())
      {
        for (const auto &[parent, weight] : line.entries)
          residual(parent) += weight * residual(line.index);
        residual(line.index) = 0;
      }
    }


    template <int dim>
    double
    ElasticBody<dim>::force_imbalance(const Summary &summary)
    {
      Tensor<1, dim> sum = summary.applied_force + summary.contact_force;
      double         scale =
        std::max(summary.applied_force.norm(), summary.contact_force.norm());
      for (const auto &[id, force] : summary.reaction_forces)
      {
        sum += force;
        scale = std::max(scale, force.norm());
      }
      return scale > 0 ? sum.norm() / scale : 0.;
    }


    template <int dim>
    double
    ElasticBody<dim>::strain_energy(const Vector<double> &displacement) const
    {
      return summarize(displacement).strain_energy;
    }


    template <int dim>
    double
    ElasticBody<dim>::external_work(const Vector<double> &displacement) const
    {
      return summarize(displacement).external_work;
    }


    template <int dim>
    std::map<types::boundary_id, Tensor<1, dim>>
    ElasticBody<dim>::reaction_forces(const Vector<double> &displacement) const
    {
      return summarize(displacement).reaction_forces;
    }


    template <int dim>
    Tensor<1, dim>
    ElasticBody<dim>::applied_force() const
    {
      return summarize(Vector<double>(n_dofs())).applied_force;
    }


    template <int dim>
    std::vector<typename ElasticBody<dim>::TractionResultant>
    ElasticBody<dim>::traction_resultants() const
    {
      if (tractions_.empty())
        return {};
      CellScratch scratch(*this);
      return traction_resultants(scratch);
    }


    template <int dim>
    std::vector<typename ElasticBody<dim>::TractionResultant>
    ElasticBody<dim>::traction_resultants(CellScratch &scratch) const
    {
      std::vector<TractionResultant> resultants(tractions_.size());
      if (tractions_.empty())
        return resultants;
      const Quadrature<dim - 1> nominal_quadrature =
        cell_family_.face_quadrature(nominal_mapping_degree + 2);
      // faces without a curved manifold are exact with the isoparametric
      // mapping (and much cheaper with it)
      FEFaceValues<dim> nominal_flat_values(*mapping_,
                                            fe_,
                                            nominal_quadrature,
                                            update_quadrature_points |
                                              update_JxW_values);
      // The high-degree mapping and its face values are set up only when a
      // loaded face touches a curved manifold: their setup (shape functions
      // of (degree + 1)^dim support points at the quadrature points of every
      // face) costs seconds in 3D, whatever the number of such faces.
      std::unique_ptr<const MappingQ<dim>> nominal_mapping;
      std::unique_ptr<FEFaceValues<dim>>   nominal_curved_values;
      const auto curved_values = [&]() -> FEFaceValues<dim> &
      {
        if (!nominal_curved_values)
        {
          nominal_mapping =
            std::make_unique<const MappingQ<dim>>(nominal_mapping_degree);
          nominal_curved_values =
            std::make_unique<FEFaceValues<dim>>(*nominal_mapping,
                                                fe_,
                                                nominal_quadrature,
                                                update_quadrature_points |
                                                  update_JxW_values);
        }
        return *nominal_curved_values;
      };
      Vector<double> force(dim);
      // the integral of t over the faces of @p values; shape functions of one
      // component sum to one, so for the assembly's face values this is the
      // sum of the traction's load entries
      const auto integrate = [&](const TractionCondition<dim> &condition,
                                 const FEFaceValues<dim>      &values,
                                 Tensor<1, dim>               &sum)
      {
        for (const unsigned int q : values.quadrature_point_indices())
        {
          condition.traction->vector_value(values.quadrature_point(q), force);
          for (unsigned int d = 0; d < dim; ++d)
            sum[d] += force(d) * values.JxW(q);
        }
      };
      for (unsigned int t = 0; t < tractions_.size(); ++t)
      {
        const TractionCondition<dim> &condition = tractions_[t];
        TractionResultant            &resultant = resultants[t];
        resultant.boundary_id                   = condition.boundary_id;
        for (const auto &cell : dof_handler_.active_cell_iterators())
          if (is_counted_here(cell) && cell->at_boundary())
            for (const unsigned int f : cell->face_indices())
              if (cell->face(f)->at_boundary() &&
                  cell->face(f)->boundary_id() == condition.boundary_id)
              {
                integrate(condition,
                          traction_face_values(cell, f, scratch),
                          resultant.applied);
                // a simplex mesh is its polygon (affine, see CellFamily)
                FEFaceValues<dim> &nominal =
                  !cell_family_.is_simplex() &&
                      touches_curved_manifold(cell->face(f)) ?
                    curved_values() :
                    nominal_flat_values;
                nominal.reinit(cell, f);
                integrate(condition, nominal, resultant.nominal);
              }
        if (is_distributed())
        {
          resultant.applied =
            Utilities::MPI::sum(resultant.applied, communicator());
          resultant.nominal =
            Utilities::MPI::sum(resultant.nominal, communicator());
        }
      }
      return resultants;
    }


    template <int dim>
    double
    ElasticBody<dim>::max_displacement(const Vector<double> &displacement) const
    {
      return summarize(displacement).max_displacement;
    }


    template <int dim>
    bool
    ElasticBody<dim>::is_distributed() const
    {
      return dynamic_cast<const parallel::DistributedTriangulationBase<dim> *>(
               triangulation_.get()) != nullptr;
    }


    template <int dim>
    MPI_Comm
    ElasticBody<dim>::communicator() const
    {
      const auto *parallel =
        dynamic_cast<const parallel::TriangulationBase<dim> *>(
          triangulation_.get());
      return parallel != nullptr ? parallel->get_communicator() : MPI_COMM_SELF;
    }


    template <int dim>
    bool
    ElasticBody<dim>::is_counted_here(
      const typename DoFHandler<dim>::active_cell_iterator &cell) const
    {
      // a replicated mesh (also parallel::shared) sums every cell on every
      // process; a distributed one its owned cells, summed over processes
      return !is_distributed() || cell->is_locally_owned();
    }


    template <int dim>
    bool
    ElasticBody<dim>::is_owned_dof(const types::global_dof_index dof) const
    {
      return !is_distributed() ||
             dof_handler_.locally_owned_dofs().is_element(dof);
    }


    template <int dim>
    void
    ElasticBody<dim>::gather_constraint_lines(const bool hanging)
    {
      // the (not yet closed) lines of the owned dofs, concatenated over the
      // processes as (dof, inhomogeneity, n, (column, weight) x n): the
      // hanging ones (with entries) or the prescribed ones (without); a
      // surface's worth, and the same on every process once closed
      std::vector<double> local;
      for (const auto &line : constraints_.get_lines())
        if (line.entries.empty() != hanging &&
            dof_handler_.locally_owned_dofs().is_element(line.index))
        {
          local.push_back(line.index);
          local.push_back(line.inhomogeneity);
          local.push_back(line.entries.size());
          for (const auto &[column, weight] : line.entries)
          {
            local.push_back(column);
            local.push_back(weight);
          }
        }
      const std::vector<double> all =
        util::concatenate_over_processes(local, communicator());
      for (std::size_t i = 0; i < all.size();)
      {
        const auto        dof = static_cast<types::global_dof_index>(all[i]);
        const double      inhomogeneity = all[i + 1];
        const std::size_t n_entries     = all[i + 2];
        i += 3;
        const bool known = constraints_.is_constrained(dof);
        if (!known)
          constraints_.add_line(dof);
        for (std::size_t e = 0; e < n_entries; ++e, i += 2)
          if (!known)
            constraints_.add_entry(dof,
                                   static_cast<types::global_dof_index>(all[i]),
                                   all[i + 1]);
        if (!known)
          constraints_.set_inhomogeneity(dof, inhomogeneity);
      }
    }


    template <int dim>
    const std::string &
    ElasticBody<dim>::name() const
    {
      return name_;
    }

    template <int dim>
    const Triangulation<dim> &
    ElasticBody<dim>::triangulation() const
    {
      return *triangulation_;
    }

    template <int dim>
    const DoFHandler<dim> &
    ElasticBody<dim>::dof_handler() const
    {
      return dof_handler_;
    }

    template <int dim>
    const FESystem<dim> &
    ElasticBody<dim>::fe() const
    {
      return fe_;
    }

    template <int dim>
    const Mapping<dim> &
    ElasticBody<dim>::mapping() const
    {
      return *mapping_;
    }


    template <int dim>
    const CellFamily<dim> &
    ElasticBody<dim>::cell_family() const
    {
      return cell_family_;
    }

    template <int dim>
    const AffineConstraints<double> &
    ElasticBody<dim>::constraints() const
    {
      return constraints_;
    }


    template <int dim>
    const AffineConstraints<double> &
    ElasticBody<dim>::hanging_node_constraints() const
    {
      return hanging_node_constraints_;
    }

    template <int dim>
    const SparseMatrix<double> &
    ElasticBody<dim>::stiffness_matrix() const
    {
      Assert(is_assembled(), ExcMessage(name_ + ": assemble() first."));
      return stiffness_;
    }

    template <int dim>
    const Vector<double> &
    ElasticBody<dim>::load_vector() const
    {
      Assert(is_assembled(), ExcMessage(name_ + ": assemble() first."));
      return load_;
    }

    template <int dim>
    bool
    ElasticBody<dim>::is_assembled() const
    {
      return load_.size() > 0 && load_.size() == dof_handler_.n_dofs();
    }

    template <int dim>
    const IsotropicMaterial &
    ElasticBody<dim>::material(const types::material_id id) const
    {
      const auto it = materials_.find(id);
      AssertThrow(it != materials_.end(),
                  ExcMessage(name_ + ": no material with id " +
                             std::to_string(id) + "."));
      return it->second;
    }

    template <int dim>
    unsigned int
    ElasticBody<dim>::n_dofs() const
    {
      return dof_handler_.n_dofs();
    }

    template class ElasticBody<2>;
    template class ElasticBody<3>;
  } // namespace fem
} // namespace dualcontact
