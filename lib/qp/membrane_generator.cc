#include <qp/membrane_generator.h>

#include <deal.II/base/exceptions.h>

#include <cmath>
#include <vector>

namespace dualcontact
{
  namespace qp
  {
    MembraneGenerator::MembraneGenerator(const Parameters &parameters)
        : parameters(parameters)
    {
      AssertThrow(parameters.h >= 1,
                  dealii::ExcMessage("membrane: h must be at least 1"));
      AssertThrow(parameters.load_scale > 0.,
                  dealii::ExcMessage("membrane: load scale must be > 0"));
    }


    unsigned int
    MembraneGenerator::n_unknowns() const
    {
      const unsigned int h = parameters.h;
      return parameters.variant == Variant::thesis ? h * h : h * (h + 1);
    }


    std::pair<double, double>
    MembraneGenerator::exact_extreme_eigenvalues() const
    {
      if (parameters.variant != Variant::thesis)
        return {0., 0.};
      const double theta = M_PI / (parameters.h + 1);
      return {4. - 4. * std::cos(theta), 4. + 4. * std::cos(theta)};
    }


    std::unique_ptr<ProblemData>
    MembraneGenerator::generate() const
    {
      const bool         thesis = (parameters.variant == Variant::thesis);
      const unsigned int h      = parameters.h;
      // grid of unknowns: n_x columns (x1 direction) times n_y rows
      const unsigned int n_x  = h;
      const unsigned int n_y  = thesis ? h : h + 1;
      const double       step = thesis ? 1. / (h + 1) : 1. / h;
      const unsigned int n    = n_x * n_y;
      // x1 coordinate of column i; the thesis grid starts at H, the permon
      // grid at H too (the column x1 = 0 is clamped and removed)
      const auto x1    = [&](unsigned int i) { return (i + 1) * step; };
      const auto index = [&](unsigned int i, unsigned int j)
      { return j * n_x + i; };

      // Edge assembly: K = sum_e w_e (e_a - e_b)(e_a - e_b)'.  An edge to a
      // clamped node contributes w_e to the diagonal only.
      std::vector<double>                                       diagonal(n, 0.);
      std::vector<std::vector<std::pair<unsigned int, double>>> offdiag(n);
      const auto add_edge = [&](long a, long b, double w)
      {
        // a, b: unknown indices, -1 for a clamped node
        if (a >= 0)
          diagonal[a] += w;
        if (b >= 0)
          diagonal[b] += w;
        if (a >= 0 && b >= 0)
        {
          offdiag[a].emplace_back(b, -w);
          offdiag[b].emplace_back(a, -w);
        }
      };

      if (thesis)
      {
        // every unknown has 4 neighbours; missing ones are clamped
        for (unsigned int j = 0; j < n_y; ++j)
          for (unsigned int i = 0; i < n_x; ++i)
          {
            const long me = index(i, j);
            // right and up edges, plus the left/bottom edges to the
            // boundary (each interior edge is visited once)
            add_edge(me, i + 1 < n_x ? long(index(i + 1, j)) : -1, 1.);
            add_edge(me, j + 1 < n_y ? long(index(i, j + 1)) : -1, 1.);
            if (i == 0)
              add_edge(me, -1, 1.);
            if (j == 0)
              add_edge(me, -1, 1.);
          }
      }
      else
      {
        // nodes (c, j), c = 0..h (c = 0 clamped), j = 0..h; unknown
        // (c-1, j).  Edges on the boundary lines y = 0, y = 1, x = 1 have
        // one adjacent triangle: weight 1/2.
        const auto node = [&](unsigned int c, unsigned int j) -> long
        { return c == 0 ? -1 : long(index(c - 1, j)); };
        for (unsigned int j = 0; j <= h; ++j)
          for (unsigned int c = 0; c <= h; ++c)
          {
            if (c < h) // horizontal edge (c,j)-(c+1,j)
              add_edge(node(c, j),
                       node(c + 1, j),
                       (j == 0 || j == h) ? 0.5 : 1.);
            if (j < h && c > 0) // vertical edge (c,j)-(c,j+1)
              add_edge(node(c, j), node(c, j + 1), c == h ? 0.5 : 1.);
          }
      }

      auto problem = std::make_unique<ProblemData>();
      {
        std::vector<unsigned int> row_length(n);
        for (unsigned int r = 0; r < n; ++r)
          row_length[r] = 1 + offdiag[r].size();
        problem->hessian_pattern.reinit(n, n, row_length);
        for (unsigned int r = 0; r < n; ++r)
          for (const auto &entry : offdiag[r])
            problem->hessian_pattern.add(r, entry.first);
        problem->hessian_pattern.compress();
        problem->hessian.reinit(problem->hessian_pattern);
        for (unsigned int r = 0; r < n; ++r)
        {
          problem->hessian.set(r, r, diagonal[r]);
          for (const auto &entry : offdiag[r])
            problem->hessian.add(r, entry.first, entry.second);
        }
      }

      problem->rhs.reinit(n);
      ProblemData::ConstraintBlock bound;
      bound.type  = "bound";
      bound.first = 0;
      bound.count = n;
      bound.lower.resize(n);
      const double load = -parameters.load_scale * step * step;
      for (unsigned int j = 0; j < n_y; ++j)
        for (unsigned int i = 0; i < n_x; ++i)
        {
          double weight = 1.;
          if (!thesis)
          {
            if (j == 0 || j == h)
              weight *= 0.5;
            if (i + 1 == n_x)
              weight *= 0.5;
          }
          problem->rhs[index(i, j)] = load * weight;
          bound.lower[index(i, j)]  = x1(i) <= parameters.p + 1e-12 ?
                                        parameters.upper_obstacle :
                                        parameters.lower_obstacle;
        }
      problem->constraints.push_back(std::move(bound));
      problem->source = std::string("membrane (") +
                        (thesis ? "thesis" : "permon") +
                        ", h = " + std::to_string(h) +
                        ", p = " + std::to_string(parameters.p) + ")";
      return problem;
    }
  } // namespace qp
} // namespace dualcontact
