#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>

#include <contact/dual_transforms.h>
#include <qp/power_iteration.h>

#include <cmath>

namespace dualcontact
{
  namespace contact
  {
    using namespace dealii;

    LambdaMaxScaling::LambdaMaxScaling(
      const std::function<void(VectorType &, const VectorType &)> &F,
      const VectorType                                            &start)
    {
      const qp::PowerIterationResult power =
        qp::power_iteration<VectorType>(F, start, 200, 1e-6, 1.0);
      scale_      = power.estimate;
      n_products_ = power.n_products;
      AssertThrow(scale_ > 0 && std::isfinite(scale_),
                  ExcMessage("The dual operator F = B K^# B' is zero or not "
                             "finite: are there contact constraints?"));
    }


    double
    LambdaMaxScaling::scale() const
    {
      return scale_;
    }


    unsigned int
    LambdaMaxScaling::n_products() const
    {
      return n_products_;
    }


    OrthonormalEqualities::OrthonormalEqualities(
      const std::vector<VectorType> &G_rows,
      const VectorType              &e)
        : rows_(G_rows)
        , rhs_(e)
    {
      for (unsigned int k = 0; k < rows_.size(); ++k)
      {
        for (unsigned int j = 0; j < k; ++j)
        {
          const double projection = rows_[k] * rows_[j];
          rows_[k].add(-projection, rows_[j]);
          rhs_(k) -= projection * rhs_(j);
        }
        const double norm = rows_[k].l2_norm();
        AssertThrow(norm > 1e-10,
                    ExcMessage(
                      "A rigid-body motion of a body is not restrained by "
                      "any contact constraint (G = R'B' is rank deficient): "
                      "add a Dirichlet condition, a contact pair or "
                      "friction that holds it."));
        rows_[k] /= norm;
        rhs_(k) /= norm;
      }
    }


    unsigned int
    OrthonormalEqualities::n_rows() const
    {
      return rows_.size();
    }


    std::shared_ptr<qp::EqualityConstraints<OrthonormalEqualities::VectorType>>
    OrthonormalEqualities::constraints(const unsigned int n_multipliers) const
    {
      auto equality   = std::make_shared<qp::EqualityConstraints<VectorType>>();
      equality->vmult = [this](VectorType &dst, const VectorType &src)
      {
        dst.reinit(rows_.size());
        for (unsigned int k = 0; k < rows_.size(); ++k)
          dst(k) = rows_[k] * src;
      };
      equality->Tvmult =
        [this, n_multipliers](VectorType &dst, const VectorType &src)
      {
        dst.reinit(n_multipliers);
        for (unsigned int k = 0; k < rows_.size(); ++k)
          dst.add(src(k), rows_[k]);
      };
      equality->c                = rhs_;
      equality->n_constraints    = rows_.size();
      equality->norm_sq          = 1.; // ||G~||^2 = lambda_max(G~ G~') = 1
      equality->orthonormal_rows = true;
      return equality;
    }


    void
    OrthonormalEqualities::distribute(const MultiplierDistribution &owners)
    {
      const unsigned int n_modes      = rows_.size();
      const MPI_Comm     communicator = owners.communicator();
      owned_modes_                    = IndexSet(n_modes);
      if (Utilities::MPI::this_mpi_process(communicator) == 0)
        owned_modes_.add_range(0, n_modes);
      owned_modes_.compress();
      rhs_distributed_ = std::make_unique<DistributedVector>();
      rhs_distributed_->reinit(owned_modes_, communicator);
      for (unsigned int k = 0; k < rhs_distributed_->locally_owned_size(); ++k)
        rhs_distributed_->begin()[k] = rhs_(owned_modes_.nth_index_in_set(k));
    }


    std::shared_ptr<
      qp::EqualityConstraints<OrthonormalEqualities::DistributedVector>>
    OrthonormalEqualities::distributed_constraints(
      const MultiplierDistribution &owners,
      const unsigned int            n_multipliers) const
    {
      using V       = DistributedVector;
      auto equality = std::make_shared<qp::EqualityConstraints<V>>();
      // dst = G~ src: partial dot products over the owned multipliers,
      // summed; the rows live on process 0
      equality->vmult = [this, &owners](V &dst, const V &src)
      {
        const std::vector<unsigned int> &owned_rows = owners.owned_rows();
        const unsigned int               n_modes    = rows_.size();
        std::vector<double>              partial(n_modes, 0.), total(n_modes);
        for (unsigned int k = 0; k < n_modes; ++k)
          for (unsigned int l = 0; l < owned_rows.size(); ++l)
            partial[k] += rows_[k](owned_rows[l]) * src.begin()[l];
        Utilities::MPI::sum(partial, owners.communicator(), total);
        if (dst.size() != n_modes)
          dst.reinit(owned_modes_, owners.communicator());
        for (unsigned int l = 0; l < dst.locally_owned_size(); ++l)
          dst.begin()[l] = total[owned_modes_.nth_index_in_set(l)];
      };
      // dst = G~' src: the few coefficients to every process, then the
      // owned entries
      equality->Tvmult = [this, &owners, n_multipliers](V &dst, const V &src)
      {
        const std::vector<unsigned int> &owned_rows = owners.owned_rows();
        const unsigned int               n_modes    = rows_.size();
        std::vector<double>              partial(n_modes, 0.), total(n_modes);
        for (unsigned int l = 0; l < src.locally_owned_size(); ++l)
          partial[owned_modes_.nth_index_in_set(l)] = src.begin()[l];
        Utilities::MPI::sum(partial, owners.communicator(), total);
        if (dst.size() != n_multipliers)
          owners.layout().initialize(dst);
        for (unsigned int l = 0; l < owned_rows.size(); ++l)
        {
          double value = 0;
          for (unsigned int k = 0; k < n_modes; ++k)
            value += total[k] * rows_[k](owned_rows[l]);
          dst.begin()[l] = value;
        }
      };
      equality->c                = *rhs_distributed_;
      equality->n_constraints    = rows_.size();
      equality->norm_sq          = 1.;
      equality->orthonormal_rows = true;
      return equality;
    }
  } // namespace contact
} // namespace dualcontact
