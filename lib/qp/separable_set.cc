/**
 * @file separable_set.cc
 * SeparableSet: building the set (add_*, finalize) and the counts of its
 * blocks, active or all.  The projections and steps are in
 * separable_set_steps.cc, the gradient splits and norms (and zero_active,
 * the free part of any vector) in separable_set_gradients.cc, the CG
 * passes in separable_set_cg_passes.cc; the arithmetic of each block kind
 * in qp/blocks/.
 */
#include <qp/separable_set.h>
#include <qp/vector_helpers.h>

#include <deal.II/base/exceptions.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

namespace dualcontact
{
  namespace qp
  {
    template <typename VectorType>
    SeparableSet<VectorType>::SeparableSet(const double active_tolerance)
        : tolerance(active_tolerance)
    {
      AssertThrow(active_tolerance >= 0. && active_tolerance < 1.,
                  dealii::ExcMessage(
                    "SeparableSet: the active tolerance must lie in [0, 1)"));
    }


    template <typename VectorType>
    void
    SeparableSet<VectorType>::add_bound(const size_type first,
                                        const double    lower)
    {
      AssertThrow(std::isfinite(lower),
                  dealii::ExcMessage("bound constraint at unknown " +
                                     std::to_string(first) +
                                     ": the lower bound must be finite"));
      added_bounds.push_back({first, {lower}});
      finalized = false;
    }


    template <typename VectorType>
    void
    SeparableSet<VectorType>::add_box(const size_type first,
                                      const double    lower,
                                      const double    upper)
    {
      AssertThrow(std::isfinite(lower) && std::isfinite(upper) &&
                    lower <= upper,
                  dealii::ExcMessage(
                    "box constraint at unknown " + std::to_string(first) +
                    ": need finite lower <= upper, got " +
                    std::to_string(lower) + ", " + std::to_string(upper)));
      added_boxes.push_back({first, {lower, upper}});
      finalized = false;
    }


    template <typename VectorType>
    void
    SeparableSet<VectorType>::add_disc(const size_type first,
                                       const double    radius)
    {
      AssertThrow(std::isfinite(radius) && radius >= 0.,
                  dealii::ExcMessage("disc constraint at unknown " +
                                     std::to_string(first) +
                                     ": the radius must be finite and >= 0"));
      added_discs.push_back({first, {radius}});
      finalized = false;
    }


    template <typename VectorType>
    void
    SeparableSet<VectorType>::add_ellipse(const size_type first,
                                          const double    a,
                                          const double    b,
                                          const double    angle)
    {
      AssertThrow(std::isfinite(a) && std::isfinite(b) && a > 0. && b > 0. &&
                    std::isfinite(angle),
                  dealii::ExcMessage(
                    "ellipse constraint at unknown " + std::to_string(first) +
                    ": the semi-axes must be finite and positive"));
      added_ellipses.push_back(
        {first, {a, b, std::cos(angle), std::sin(angle)}});
      finalized = false;
    }


    template <typename VectorType>
    void
    SeparableSet<VectorType>::add_cone(const size_type first, const double mu)
    {
      AssertThrow(std::isfinite(mu) && mu >= 0.,
                  dealii::ExcMessage("cone constraint at unknown " +
                                     std::to_string(first) +
                                     ": mu must be finite and >= 0"));
      added_cones.push_back({first, {mu}});
      finalized = false;
    }


    template <typename VectorType>
    void
    SeparableSet<VectorType>::finalize(const VectorType &layout)
    {
      owned                        = layout.locally_owned_elements();
      local_size                   = owned.n_elements();
      const size_type            n = layout.size();
      std::vector<unsigned char> used(local_size, 0);
      // one contiguous range (always in serial): membership and local
      // index by arithmetic instead of IndexSet's searches, which were a
      // tenth of a short QP's work on a small problem (fclib's loops
      // finalize a set per QP)
      const bool      contiguous = owned.is_contiguous();
      const size_type begin =
        contiguous && local_size > 0 ? owned.nth_index_in_set(0) : 0;
      const auto is_owned = [&](const size_type i)
      {
        return contiguous ? (i >= begin && i < begin + local_size) :
                            owned.is_element(i);
      };
      const auto local_index = [&](const size_type i) -> size_type
      { return contiguous ? i - begin : owned.index_within_set(i); };

      // Returns true if the block [first, first+width) is locally owned,
      // false if it is owned elsewhere; throws if it straddles, leaves the
      // vector, or overlaps a block already placed.
      const auto place = [&](const size_type    first,
                             const unsigned int width,
                             const char        *type,
                             size_type         &local) -> bool
      {
        AssertThrow(first + width <= n,
                    dealii::ExcMessage(
                      std::string(type) + " block at unknown " +
                      std::to_string(first) + " exceeds the vector size " +
                      std::to_string(n)));
        unsigned int n_owned = 0;
        for (unsigned int k = 0; k < width; ++k)
          n_owned += is_owned(first + k) ? 1 : 0;
        if (n_owned == 0)
          return false;
        AssertThrow(n_owned == width,
                    dealii::ExcMessage(std::string(type) +
                                       " block at unknown " +
                                       std::to_string(first) +
                                       " straddles two MPI ranks; "
                                       "partition so that blocks stay "
                                       "together"));
        local = local_index(first);
        for (unsigned int k = 0; k < width; ++k)
        {
          const size_type l = local_index(first + k);
          AssertThrow(l == local + k,
                      dealii::ExcMessage(
                        std::string(type) + " block at unknown " +
                        std::to_string(first) + " is not contiguous locally"));
          AssertThrow(!used[l],
                      dealii::ExcMessage(std::string(type) +
                                         " block at unknown " +
                                         std::to_string(first) +
                                         " overlaps another block (unknown " +
                                         std::to_string(first + k) + ")"));
          used[l] = 1;
        }
        return true;
      };

      // The locally owned blocks of one kind at their local offsets,
      // sorted by offset so that the passes stream through memory.
      const auto place_kind = [&](const auto &added, auto &placed)
      {
        using Kind = decltype(added[0].block);
        placed.clear();
        size_type local = 0;
        for (const auto &block : added)
          if (place(block.first,
                    Kind::n_components,
                    block_type_names.name(Kind::type),
                    local))
            placed.push_back({local, block.block});
        std::sort(placed.begin(),
                  placed.end(),
                  [](const auto &l, const auto &r)
                  { return l.first < r.first; });
      };
      place_kind(added_bounds, bounds);
      place_kind(added_boxes, boxes);
      place_kind(added_discs, discs);
      place_kind(added_ellipses, ellipses);
      place_kind(added_cones, cones);

      // runs of consecutive bound / box blocks
      const auto make_runs = [](const auto &blocks, std::vector<Run> &runs)
      {
        runs.clear();
        for (std::size_t k = 0; k < blocks.size(); ++k)
          if (!runs.empty() &&
              runs.back().begin + runs.back().count == blocks[k].first)
            ++runs.back().count;
          else
            runs.push_back({static_cast<std::size_t>(blocks[k].first), 1, k});
      };
      make_runs(bounds, bound_runs);
      make_runs(boxes, box_runs);
      bound_lower.resize(bounds.size());
      for (std::size_t k = 0; k < bounds.size(); ++k)
        bound_lower[k] = bounds[k].block.lower;
      free_ranges.clear();
      for (std::size_t i = 0; i < local_size; ++i)
        if (!used[i])
        {
          if (!free_ranges.empty() && free_ranges.back().second == i)
            ++free_ranges.back().second;
          else
            free_ranges.emplace_back(i, i + 1);
        }

      std::array<std::size_t, n_block_types> local_counts{};
      for_each_kind(
        [&](const auto &placed)
        {
          using Kind = decltype(placed[0].block);
          local_counts[static_cast<unsigned int>(Kind::type)] = placed.size();
        });
      for (unsigned int t = 0; t < n_block_types; ++t)
        global_counts[t] = static_cast<size_type>(
          internal::sum(static_cast<double>(local_counts[t]), layout) + 0.5);
      finalized = true;
    }


    namespace
    {
      /**
       * Position in @p placed (sorted by local offset in finalize()) of the
       * block added at global index @p global; placed.size() if another
       * rank owns it.
       */
      template <typename Placed>
      std::size_t
      placed_position(const std::vector<Placed>            &placed,
                      const dealii::IndexSet               &owned,
                      const dealii::types::global_dof_index global)
      {
        if (!owned.is_element(global))
          return placed.size();
        const auto local = owned.index_within_set(global);
        const auto it    = std::lower_bound(placed.begin(),
                                         placed.end(),
                                         local,
                                         [](const Placed &b, const auto l)
                                         { return b.first < l; });
        Assert(it != placed.end() && it->first == local,
               dealii::ExcInternalError());
        return it - placed.begin();
      }
    } // namespace


    template <typename VectorType>
    void
    SeparableSet<VectorType>::set_disc_radius(const size_type k,
                                              const double    radius)
    {
      Assert(finalized, dealii::ExcMessage("call finalize() first"));
      AssertThrow(k < added_discs.size(),
                  dealii::ExcMessage("set_disc_radius: disc " +
                                     std::to_string(k) + " of " +
                                     std::to_string(added_discs.size())));
      AssertThrow(radius >= 0. && std::isfinite(radius),
                  dealii::ExcMessage("disc radius must be >= 0 and finite, "
                                     "not " +
                                     std::to_string(radius)));
      added_discs[k].block.radius = radius;
      const std::size_t position =
        placed_position(discs, owned, added_discs[k].first);
      if (position < discs.size())
        discs[position].block.radius = radius;
    }


    template <typename VectorType>
    void
    SeparableSet<VectorType>::set_box_bounds(const size_type k,
                                             const double    lower,
                                             const double    upper)
    {
      Assert(finalized, dealii::ExcMessage("call finalize() first"));
      AssertThrow(k < added_boxes.size(),
                  dealii::ExcMessage("set_box_bounds: box " +
                                     std::to_string(k) + " of " +
                                     std::to_string(added_boxes.size())));
      AssertThrow(lower <= upper,
                  dealii::ExcMessage("box bounds need lower <= upper, not " +
                                     std::to_string(lower) + " > " +
                                     std::to_string(upper)));
      added_boxes[k].block = {lower, upper};
      const std::size_t position =
        placed_position(boxes, owned, added_boxes[k].first);
      if (position < boxes.size())
        boxes[position].block = {lower, upper};
    }


    template <typename VectorType>
    bool
    SeparableSet<VectorType>::is_finalized() const
    {
      return finalized;
    }


    template <typename VectorType>
    double
    SeparableSet<VectorType>::active_tolerance() const
    {
      return tolerance;
    }


    template <typename VectorType>
    typename SeparableSet<VectorType>::size_type
    SeparableSet<VectorType>::n_blocks() const
    {
      Assert(finalized, dealii::ExcMessage("call finalize() first"));
      return std::accumulate(global_counts.begin(),
                             global_counts.end(),
                             size_type(0));
    }


    template <typename VectorType>
    typename SeparableSet<VectorType>::size_type
    SeparableSet<VectorType>::n_blocks(const BlockType type) const
    {
      Assert(finalized, dealii::ExcMessage("call finalize() first"));
      return global_counts[static_cast<unsigned int>(type)];
    }


    template <typename VectorType>
    bool
    SeparableSet<VectorType>::only_bounds_and_boxes() const
    {
      return n_blocks(BlockType::disc) + n_blocks(BlockType::ellipse) +
               n_blocks(BlockType::cone) ==
             0;
    }


    template <typename VectorType>
    typename SeparableSet<VectorType>::size_type
    SeparableSet<VectorType>::n_constrained_unknowns() const
    {
      return n_blocks(BlockType::bound) * blocks::Bound::n_components +
             n_blocks(BlockType::box) * blocks::Box::n_components +
             n_blocks(BlockType::disc) * blocks::Disc::n_components +
             n_blocks(BlockType::ellipse) * blocks::Ellipse::n_components +
             n_blocks(BlockType::cone) * blocks::Cone::n_components;
    }


    // ======================== the active set ============================

    template <typename VectorType>
    std::array<typename SeparableSet<VectorType>::size_type, n_block_types>
    SeparableSet<VectorType>::n_active_blocks(const VectorType &x) const
    {
      Assert(finalized, dealii::ExcMessage("call finalize() first"));
      const double *v                    = x.begin();
      double        local[n_block_types] = {0., 0., 0., 0., 0.};
      for_each_kind(
        [&](const auto &placed_blocks)
        {
          for (const auto &placed : placed_blocks)
            local[static_cast<unsigned int>(placed.block.type)] +=
              placed.block.classify(v + placed.first, tolerance).active ? 1 : 0;
        });
      double global[n_block_types];
      dealii::Utilities::MPI::sum(
        dealii::ArrayView<const double>(local, n_block_types),
        internal::communicator(x),
        dealii::ArrayView<double>(global, n_block_types));
      std::array<size_type, n_block_types> result;
      for (unsigned int t = 0; t < n_block_types; ++t)
        result[t] = static_cast<size_type>(global[t] + 0.5);
      return result;
    }


    template <typename VectorType>
    bool
    SeparableSet<VectorType>::is_active(const VectorType &x,
                                        const size_type   first) const
    {
      Assert(finalized, dealii::ExcMessage("call finalize() first"));
      AssertThrow(owned.is_element(first),
                  dealii::ExcMessage("is_active: unknown " +
                                     std::to_string(first) +
                                     " is not locally owned"));
      const size_type off    = owned.index_within_set(first);
      const double   *v      = x.begin();
      bool            found  = false;
      bool            active = false;
      for_each_kind(
        [&](const auto &placed_blocks)
        {
          for (const auto &placed : placed_blocks)
            if (!found && placed.first == off)
            {
              found  = true;
              active = placed.block.classify(v + off, tolerance).active;
              return;
            }
        });
      AssertThrow(found,
                  dealii::ExcMessage("is_active: no block starts at unknown " +
                                     std::to_string(first)));
      return active;
    }


#define DUALCONTACT_INSTANTIATE_SET(V) template class SeparableSet<V>;

    DUALCONTACT_INSTANTIATE_SET(dealii::Vector<double>)
    DUALCONTACT_INSTANTIATE_SET(dealii::TrilinosWrappers::MPI::Vector)
  } // namespace qp
} // namespace dualcontact
