#include <deal.II/base/exceptions.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/lac/full_matrix.h>

#include <fem/rigid_body_modes.h>

#include <cmath>

namespace dualcontact
{
  namespace fem
  {
    using namespace dealii;

    namespace
    {
      /** MtM := diag(eigenvalues) of the symmetric @p MtM and V its
       *  eigenvectors, by cyclic Jacobi rotations (n <= 6). */
      void
      diagonalize(FullMatrix<double> &MtM, FullMatrix<double> &V)
      {
        const unsigned int n_rigid = MtM.m();
        V.reinit(n_rigid, n_rigid);
        for (unsigned int k = 0; k < n_rigid; ++k)
          V(k, k) = 1.;
        for (unsigned int sweep = 0; sweep < 50; ++sweep)
        {
          double off = 0;
          for (unsigned int p = 0; p < n_rigid; ++p)
            for (unsigned int q = p + 1; q < n_rigid; ++q)
              off += MtM(p, q) * MtM(p, q);
          if (off < 1e-30 * (1. + MtM.frobenius_norm()))
            break;
          for (unsigned int p = 0; p < n_rigid; ++p)
            for (unsigned int q = p + 1; q < n_rigid; ++q)
              if (MtM(p, q) != 0.)
              {
                const double theta =
                  0.5 * std::atan2(2 * MtM(p, q), MtM(q, q) - MtM(p, p));
                const double c = std::cos(theta), s = std::sin(theta);
                for (unsigned int k = 0; k < n_rigid; ++k)
                {
                  const double kp = MtM(k, p), kq = MtM(k, q);
                  MtM(k, p) = c * kp - s * kq;
                  MtM(k, q) = s * kp + c * kq;
                }
                for (unsigned int k = 0; k < n_rigid; ++k)
                {
                  const double pk = MtM(p, k), qk = MtM(q, k);
                  MtM(p, k) = c * pk - s * qk;
                  MtM(q, k) = s * pk + c * qk;
                }
                for (unsigned int k = 0; k < n_rigid; ++k)
                {
                  const double kp = V(k, p), kq = V(k, q);
                  V(k, p) = c * kp - s * kq;
                  V(k, q) = s * kp + c * kq;
                }
              }
        }
      }


      /** Rigid motion @p k of a body with centroid @p centroid at @p x,
       *  component @p c: translations first, then rotations. */
      template <int dim>
      double
      rigid_motion(const unsigned int k,
                   const Point<dim>  &centroid,
                   const Point<dim>  &x,
                   const unsigned int c)
      {
        if (k < dim)
          return c == k ? 1. : 0.;
        const Tensor<1, dim> r = x - centroid;
        if (dim == 2)
          return c == 0 ? -r[1] : r[0];
        // 3D: rotation about axis a = k - 3: (e_a x r)_c
        const unsigned int a = k - dim;
        const unsigned int b = (a + 1) % 3, d = (a + 2) % 3;
        if (c == b)
          return -r[d];
        if (c == d)
          return r[b];
        return 0.;
      }
    } // namespace


    template <int dim>
    RigidBodyModes<dim>::RigidBodyModes(const ElasticBody<dim> &body)
    {
      const unsigned int      n_dofs = body.n_dofs();
      std::vector<Point<dim>> points(n_dofs);
      DoFTools::map_dofs_to_support_points(body.mapping(),
                                           body.dof_handler(),
                                           points);
      std::vector<unsigned int> component(n_dofs);
      {
        std::vector<types::global_dof_index> dofs(body.fe().n_dofs_per_cell());
        for (const auto &cell : body.dof_handler().active_cell_iterators())
        {
          cell->get_dof_indices(dofs);
          for (unsigned int i = 0; i < dofs.size(); ++i)
            component[dofs[i]] = body.fe().system_to_component_index(i).first;
        }
      }
      std::vector<types::global_dof_index> all(n_dofs);
      for (unsigned int i = 0; i < n_dofs; ++i)
        all[i] = i;
      build(points, component, all, &body.constraints(), body.name());
    }


    template <int dim>
    RigidBodyModes<dim>::RigidBodyModes(
      const std::vector<Point<dim>>              &support_points,
      const std::vector<unsigned int>            &components,
      const std::vector<types::global_dof_index> &dofs,
      const std::string                          &name)
    {
      std::vector<Point<dim>>   points(dofs.size());
      std::vector<unsigned int> component(dofs.size());
      for (unsigned int i = 0; i < dofs.size(); ++i)
      {
        points[i]    = support_points[dofs[i]];
        component[i] = components[dofs[i]];
      }
      build(points, component, dofs, nullptr, name);
    }


    template <int dim>
    void
    RigidBodyModes<dim>::build(const std::vector<Point<dim>>   &points,
                               const std::vector<unsigned int> &component,
                               const std::vector<types::global_dof_index> &dofs,
                               const AffineConstraints<double> *constraints,
                               const std::string               &name)
    {
      const unsigned int n_dofs = dofs.size();
      // constrained by a Dirichlet condition (no constraint entries, as
      // opposed to hanging nodes), and constrained at all
      const auto is_dirichlet = [&](const unsigned int i)
      {
        return constraints != nullptr && constraints->is_constrained(dofs[i]) &&
               (constraints->get_constraint_entries(dofs[i]) == nullptr ||
                constraints->get_constraint_entries(dofs[i])->empty());
      };
      const auto is_constrained = [&](const unsigned int i) {
        return constraints != nullptr && constraints->is_constrained(dofs[i]);
      };
      Point<dim>   centroid;
      unsigned int n_nodes = 0;
      for (unsigned int i = 0; i < n_dofs; ++i)
        if (component[i] == 0)
        {
          centroid += points[i];
          ++n_nodes;
        }
      centroid /= n_nodes;

      const auto mode_value =
        [&](const unsigned int k, const Point<dim> &x, const unsigned int c)
      { return rigid_motion(k, centroid, x, c); };

      // Raw motions, each scaled to unit norm over all dofs.
      const unsigned int  n_rigid = dim * (dim + 1) / 2;
      std::vector<double> scale(n_rigid, 0.);
      for (unsigned int k = 0; k < n_rigid; ++k)
      {
        for (unsigned int i = 0; i < n_dofs; ++i)
          scale[k] += std::pow(mode_value(k, points[i], component[i]), 2);
        scale[k] = 1. / std::sqrt(scale[k]);
      }

      // The motions that the Dirichlet conditions allow: the kernel of M'M,
      // M the raw motions at the Dirichlet-constrained dofs (constrained
      // without constraint entries, as opposed to hanging nodes).
      FullMatrix<double> MtM(n_rigid, n_rigid);
      double             n_dirichlet = 0;
      for (unsigned int i = 0; i < n_dofs; ++i)
        if (is_dirichlet(i))
        {
          ++n_dirichlet;
          for (unsigned int k = 0; k < n_rigid; ++k)
            for (unsigned int l = 0; l < n_rigid; ++l)
              MtM(k, l) += mode_value(k, points[i], component[i]) * scale[k] *
                           mode_value(l, points[i], component[i]) * scale[l];
        }
      FullMatrix<double> V;
      diagonalize(MtM, V);
      // A direction is held when M'M "sees" it at about the level of a
      // single supported node; far below that it is a kernel vector.
      const double threshold = 1e-8 * std::max(n_dirichlet, 1.) / n_dofs;
      for (unsigned int j = 0; j < n_rigid; ++j)
        if (n_dirichlet == 0 || MtM(j, j) < threshold)
        {
          Vector<double> mode(n_dofs);
          for (unsigned int i = 0; i < n_dofs; ++i)
            if (!is_constrained(i))
              for (unsigned int k = 0; k < n_rigid; ++k)
                mode(i) +=
                  V(k, j) * scale[k] * mode_value(k, points[i], component[i]);
          modes_.push_back(mode);
        }
      const unsigned int n_kernel = modes_.size();

      // Modified Gram-Schmidt, twice for round-off.
      for (unsigned int pass = 0; pass < 2; ++pass)
        for (unsigned int k = 0; k < n_kernel; ++k)
        {
          for (unsigned int j = 0; j < k; ++j)
            modes_[k].add(-(modes_[k] * modes_[j]), modes_[j]);
          const double norm = modes_[k].l2_norm();
          AssertThrow(norm > 0,
                      ExcMessage(name +
                                 ": the rigid-body modes are degenerate."));
          modes_[k] /= norm;
        }
      if (n_kernel == 0)
        return;

      // Fixing dofs: node A farthest from the centroid, B farthest from A,
      // C (3D) farthest from the line AB; only unconstrained nodes.
      std::vector<unsigned int> node_dof0;
      for (unsigned int i = 0; i < n_dofs; ++i)
        if (component[i] == 0 && !is_constrained(i))
          node_dof0.push_back(i);
      const auto farthest = [&](const auto &distance)
      {
        unsigned int best = node_dof0[0];
        double       max  = -1;
        for (const unsigned int i : node_dof0)
          if (distance(points[i]) > max)
          {
            max  = distance(points[i]);
            best = i;
          }
        return best;
      };
      const unsigned int a =
        farthest([&](const Point<dim> &x) { return x.distance(centroid); });
      const unsigned int b =
        farthest([&](const Point<dim> &x) { return x.distance(points[a]); });
      const Tensor<1, dim> ab =
        (points[b] - points[a]) / points[b].distance(points[a]);
      const unsigned int c = farthest(
        [&](const Point<dim> &x)
        {
          const Tensor<1, dim> ax = x - points[a];
          return (ax - (ax * ab) * ab).norm();
        });

      // The dofs of a node: those with the same support point (dofs of one
      // node are not consecutive in general), in component order.
      const auto dofs_of_node = [&](const unsigned int dof0)
      {
        std::vector<types::global_dof_index> result(dim, n_dofs);
        for (unsigned int i = 0; i < n_dofs; ++i)
          if (points[i] == points[dof0])
            result[component[i]] = i;
        for (const auto dof : result)
          AssertThrow(dof < n_dofs,
                      ExcMessage(name + ": a node without all " +
                                 std::to_string(dim) + " components."));
        return result;
      };

      // Choose greedily the dofs that keep R restricted to them of full
      // rank, candidates in the order A (all), B, C.
      std::vector<types::global_dof_index> candidates;
      for (const unsigned int node : {a, b, c})
        for (const auto dof : dofs_of_node(node))
          candidates.push_back(dof);
      std::vector<Vector<double>> rows; // orthonormalized rows of R(fixed, :)
      for (const auto dof : candidates)
      {
        if (fixing_dofs_.size() == n_kernel)
          break;
        Vector<double> row(n_kernel);
        for (unsigned int k = 0; k < n_kernel; ++k)
          row(k) = modes_[k](dof);
        const double original = row.l2_norm();
        for (const auto &q : rows)
          row.add(-(row * q), q);
        if (row.l2_norm() > 1e-3 * original && original > 0)
        {
          row /= row.l2_norm();
          rows.push_back(row);
          fixing_dofs_.push_back(dof);
        }
      }
      AssertThrow(fixing_dofs_.size() == n_kernel,
                  ExcMessage(name + ": could not choose fixing nodes for the "
                                    "generalized inverse (degenerate mesh?)."));
    }


    template <int dim>
    unsigned int
    RigidBodyModes<dim>::n_free_motions(
      const std::vector<Point<dim>>   &points,
      const std::vector<unsigned int> &components)
    {
      const unsigned int n_rigid = dim * (dim + 1) / 2;
      if (points.empty())
        return n_rigid;
      Point<dim>   centroid;
      unsigned int n_nodes = 0;
      for (unsigned int i = 0; i < points.size(); ++i)
        if (components[i] == 0)
        {
          centroid += points[i];
          ++n_nodes;
        }
      // a support holding only other components has no component-0 dof
      if (n_nodes == 0)
        for (const Point<dim> &x : points)
          centroid += x / static_cast<double>(points.size());
      else
        centroid /= n_nodes;
      std::vector<double> scale(n_rigid, 0.);
      for (unsigned int k = 0; k < n_rigid; ++k)
      {
        for (unsigned int i = 0; i < points.size(); ++i)
          scale[k] +=
            std::pow(rigid_motion(k, centroid, points[i], components[i]), 2);
        scale[k] = scale[k] > 0 ? 1. / std::sqrt(scale[k]) : 0.;
      }
      FullMatrix<double> MtM(n_rigid, n_rigid), V;
      for (unsigned int i = 0; i < points.size(); ++i)
        for (unsigned int k = 0; k < n_rigid; ++k)
          for (unsigned int l = 0; l < n_rigid; ++l)
            MtM(k, l) +=
              rigid_motion(k, centroid, points[i], components[i]) * scale[k] *
              rigid_motion(l, centroid, points[i], components[i]) * scale[l];
      diagonalize(MtM, V);
      // every point is a supported one: the threshold of the constructors
      // with n_dirichlet = n_dofs
      unsigned int n_free = 0;
      for (unsigned int j = 0; j < n_rigid; ++j)
        n_free += MtM(j, j) < 1e-8 ? 1 : 0;
      return n_free;
    }


    template <int dim>
    unsigned int
    RigidBodyModes<dim>::n_modes() const
    {
      return modes_.size();
    }


    template <int dim>
    const std::vector<Vector<double>> &
    RigidBodyModes<dim>::modes() const
    {
      return modes_;
    }


    template <int dim>
    const std::vector<types::global_dof_index> &
    RigidBodyModes<dim>::fixing_dofs() const
    {
      return fixing_dofs_;
    }


    template class RigidBodyModes<2>;
    template class RigidBodyModes<3>;
  } // namespace fem
} // namespace dualcontact
